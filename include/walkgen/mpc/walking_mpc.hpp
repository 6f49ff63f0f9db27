#pragma once
/// @file
/// The NMPC walking pattern generator of thesis §2.2 and §6: a linear inverted pendulum preview
/// over N samples, CoM jerks and footsteps (position and yaw) as decision variables, and a
/// Gauss–Newton SQP (one step per tick: the real-time iteration) around walkgen's DenseQp.
///
/// This header is the driver: state, plan, result, the SQP loop and the shifts of the receding
/// horizon. The formulation is mpc/walking_model.hpp: the constraint blocks (mpc/constraints/:
/// ZMP polygon, footstep feasibility, relative yaw and its rate, obstacles, terminal capture
/// point), the cost terms (mpc/costs/), the one row layout (mpc/walking_layout.hpp, also the
/// decision vector's) and the schedule (mpc/walking_schedule.hpp: which step each horizon
/// sample belongs to, the references).
///
/// Use (convention 13: the block steps, the application owns the loop):
/// @code
///   walkgen::WalkingMpc<double, 16> mpc(walkgen::hrp2_settings());
///   if (mpc.set_command({0.1, 0.0, 0.0}) != walkgen::CommandStatus::accepted) {
///     /* NaN: rejected, the previous one stays; beyond max_command: clamped to it */
///   }                                          // v_x, v_y [m/s], ω_z [rad/s], robot frame
///   for (;;) {
///     const auto& r = mpc.solve();             // r.status: solved / qp_failed (safe plan kept)
///     interpolator.interpolate(mpc.tick_plan(), samples);  // this tick's command samples
///     mpc.advance();                           // state moves one t forward along the plan
///   }
/// @endcode
/// Allocation: the constructor sizes everything; solve(), advance(), set_command(), set_state()
/// and set_obstacles() never touch the heap (tests/mpc/test_walking_mpc_no_alloc.cpp).
/// Compile time: mpc/walking_mpc_16.hpp and the library walkgen::walking_mpc_16 give a
/// precompiled WalkingMpc<double, 16> (docs/walking.md, "Compile time").

#include <Eigen/Core>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "walkgen/core/foot.hpp"
#include "walkgen/interpolation/swing_foot.hpp"
#include "walkgen/interpolation/trajectory.hpp"
#include "walkgen/mpc/settings.hpp"
#include "walkgen/mpc/walking_layout.hpp"
#include "walkgen/mpc/walking_model.hpp"
#include "walkgen/mpc/walking_result.hpp"
#include "walkgen/mpc/walking_schedule.hpp"
#include "walkgen/qp/dense_qp.hpp"

namespace walkgen {

/// The generator.
/// @tparam Scalar    floating-point type
/// @tparam N         preview samples (WalkingSettings::n), or Eigen::Dynamic: fixes the LIPM
///                   preview's size only (docs/walking.md, "Fixed or dynamic sizes")
/// @tparam FootEdges edges of the ZMP support polygon (4 for the rectangular sole), or Dynamic
/// @tparam HullEdges edges of the footstep feasibility polygons, or Eigen::Dynamic
template <typename Scalar = double, int N = Eigen::Dynamic, int FootEdges = 4, int HullEdges = 5>
class WalkingMpc {
  static_assert(std::is_floating_point<Scalar>::value,
                "walkgen: WalkingMpc needs a floating-point Scalar");
  static_assert(N > 0 || N == Eigen::Dynamic,
                "walkgen: WalkingMpc's horizon N must be positive or Eigen::Dynamic");
  static_assert(FootEdges >= 3 || FootEdges == Eigen::Dynamic,
                "walkgen: WalkingMpc's FootEdges must be >= 3 or Eigen::Dynamic");
  static_assert(HullEdges >= 3 || HullEdges == Eigen::Dynamic,
                "walkgen: WalkingMpc's HullEdges must be >= 3 or Eigen::Dynamic");

 public:
  using Index = Eigen::Index;
  using Settings = WalkingSettings<Scalar>;
  using State = WalkingState<Scalar>;
  using Plan = WalkingPlan<Scalar>;
  using Result = MpcResult<Scalar>;
  using Obstacle = CircleObstacle<Scalar>;
  using Model = WalkingModel<Scalar, N, FootEdges, HullEdges>;
  using Workspace = WalkingWorkspace<Scalar>;
  using Vector3 = Eigen::Matrix<Scalar, 3, 1>;
  using VectorX = MpcVector<Scalar>;
  using RowMatrixX = MpcRowMatrix<Scalar>;

  /// Builds the generator: validates the settings, builds the formulation (WalkingModel:
  /// preview matrices, polygons' half-planes, constant Hessian), sizes the workspace and QP.
  /// @param obstacle_capacity most obstacles set_obstacles() will be given (at least the
  ///        settings' own); rows for them are reserved now so that no tick allocates.
  /// @throws walkgen::invalid_argument on invalid settings or sizes that contradict N,
  ///         FootEdges or HullEdges.
  explicit WalkingMpc(const Settings& settings, Index obstacle_capacity = 0);

  // --- Sizes -------------------------------------------------------------------------------------
  Index horizon() const { return layout().dims().N; }
  Index planned_steps() const { return layout().dims().nf; }
  Index samples_per_step() const { return layout().dims().S; }
  Index num_vars() const { return layout().num_vars(); }
  Index num_rows() const { return layout().num_rows(); }
  Index obstacle_capacity() const { return layout().dims().obstacles; }

  // --- Inputs ------------------------------------------------------------------------------------
  /// Velocity command (v_x, v_y [m/s], ω_z [rad/s]) in the robot's frame (the heading).
  /// A non-finite command is rejected (the previous one stays); components beyond
  /// settings().max_command are clamped to it and walked (CommandStatus::clamped).
  [[nodiscard]] CommandStatus set_command(const Vector3& command) {
    CommandStatus status = CommandStatus::accepted;
    if (!command.allFinite()) {
      status = CommandStatus::non_finite;
    } else {
      const Vector3& limit = settings().max_command;
      command_ = command.cwiseMax(-limit).cwiseMin(limit);
      if (command_ != command) status = CommandStatus::clamped;
    }
    result_.last_command = status;
    result_.command = command_;
    return status;
  }
  const Vector3& command() const { return command_; }

  /// Overwrites the state (feedback, section 6.3).
  /// @throws walkgen::invalid_argument if a value is non-finite, the phase is out of range, or
  ///         the state is implausible: the CoM, the swing foot or its origin farther than
  ///         settings().max_state_distance from the support foot, the CoM faster than
  ///         max_com_speed or accelerating more than max_com_acceleration (a feedback glitch;
  ///         the state is left unchanged).
  void set_state(const State& state);
  /// Restarts from `state`: also forgets the plan and the QP's warm start, and takes the
  /// state's heading (the mean of its feet's yaws) as the reference heading.
  void reset(const State& state);
  /// The reference heading [rad]: the heading at the last reset() plus the commanded yaw rate
  /// integrated over every advance() since. The footsteps' yaws track it (costs/heading.hpp) and
  /// the velocity command is turned by it, so a straight command walks straight even when
  /// feedback (set_state()) reports the feet turned.
  Scalar reference_heading() const { return heading_; }

  /// Replaces the obstacles (world frame). No allocation up to obstacle_capacity().
  /// @throws walkgen::invalid_argument beyond the capacity or on invalid obstacles.
  template <typename Container>
  void set_obstacles(const Container& obstacles) {
    Obstacles<Scalar>::check("WalkingMpc::set_obstacles", obstacles, obstacle_capacity());
    obstacles_.assign(obstacles.begin(), obstacles.end());
  }
  const std::vector<Obstacle>& obstacles() const { return obstacles_; }

  // --- Tick --------------------------------------------------------------------------------------
  /// Plans from the current state: sqp_iterations Gauss–Newton steps (eq. 2.83–2.89), each a QP
  /// linearised at the current iterate (the previous plan, shifted, on the first), plus at most
  /// sqp_corrections while the plan violates its nonlinear constraints beyond sqp_tolerance. A
  /// failed QP is never applied: the plan stays the previous iterate and the status says so.
  [[nodiscard]] const Result& solve();

  /// Moves the state one preview period t forward along the plan: CoM by the LIPM with the
  /// first jerk, the swing foot along its polynomials; at the end of a step the swing foot lands
  /// on the first planned footstep, which becomes the support foot, and the plan shifts.
  void advance();

  // --- Outputs -----------------------------------------------------------------------------------
  const State& state() const { return state_; }
  const Plan& plan() const { return plan_; }
  const Result& result() const { return result_; }
  const Settings& settings() const { return model_.settings(); }
  /// The formulation (layout, preview, constraint blocks, cost terms, constant Hessian).
  const Model& model() const { return model_; }
  /// What the last tick computed: the schedule and the QP of the last SQP iteration (H, g, A,
  /// lb ≤ A U ≤ ub, l ≤ U ≤ u), e.g. for tests and diagnostics.
  const Workspace& workspace() const { return ws_; }
  const WalkingLayout& layout() const { return model_.layout(); }
  const LipmPreview<Scalar, N>& preview() const { return model_.preview(); }
  StepTiming<Scalar> step_timing() const {
    return {settings().t_ds, settings().t_step, settings().step_height};
  }
  /// What the interpolator needs of this tick (interpolation/trajectory.hpp): the state planned
  /// from and the plan's first jerks and next footstep. Valid after solve(), before advance().
  TickPlan<Scalar> tick_plan() const {
    TickPlan<Scalar> p;
    p.time = state_.time;
    p.step_time = Scalar(state_.phase) * settings().t;
    p.com_x = state_.com_x;
    p.com_y = state_.com_y;
    p.jerk_x = plan_.jerk_x(0);
    p.jerk_y = plan_.jerk_y(0);
    p.support_foot = state_.support_foot;
    p.support = state_.support;
    p.swing = state_.swing;
    p.landing = plan_.footstep(1);
    p.timing = step_timing();
    return p;
  }
  /// Step of horizon sample j (0 = current support, i = i-th planned footstep); valid after
  /// solve() for the state it planned from.
  int step_of_sample(Index j) const { return ws_.schedule.step_of[j]; }
  /// Which foot stands in step i (0 = current support).
  Foot foot_of_step(Index i) const { return state_.foot_of_step(i); }

  /// The nonlinear constraint functions c(U) of eq. 2.65–2.82 for the current state, written as
  /// lb_c ≤ c(U) ≤ ub_c with the same rows as the QP: the QP's rows are their Gauss–Newton
  /// linearisation at the iterate, A = ∂c/∂U. For tests; allocation-free.
  void constraint_values(const VectorX& U, VectorX& c, VectorX& lower, VectorX& upper) const;
  /// The Jacobian ∂c/∂U at U (the QP's constraint matrix when U is the iterate); lower/upper
  /// receive the QP's row bounds for that linearisation.
  void constraint_jacobian(const VectorX& U, RowMatrixX& J, VectorX& lower, VectorX& upper) const;

  /// After a tick whose QP was infeasible (result().qp_status, or result().soft_fallback): which
  /// constraint blocks the tick's last hard QP conflicts in. Bit k is set when dropping row
  /// block k (layout().rows(k).name) alone makes it feasible; 0 when no single block does
  /// (several conflict together), or when that QP is not infeasible (e.g. the fallback's
  /// corrections moved the linearisation). Re-solves the QP once per block with its rows free,
  /// so it is for diagnostics after a failure, not for every tick; the workspace's QP keeps its
  /// data but its result is that of the last trial, and the workspace's c_lower and c_upper
  /// (scratch here) no longer hold the last plan's bounds. Allocation-free.
  std::uint32_t conflicting_blocks();
  /// The names of the blocks in a conflicting_blocks() mask, joined by '+' ("" for 0).
  std::string block_names(std::uint32_t mask) const {
    std::string names;
    for (int k = 0; k < layout().num_row_blocks(); ++k) {
      if ((mask >> k & 1u) == 0) continue;
      if (!names.empty()) names += '+';
      names += layout().rows(k).name;
    }
    return names;
  }

  /// The initial state of a settings set: CoM from com_x/com_y, support foot at
  /// (foot_x, foot_y, foot_q), the other foot foot_distance beside it, standing.
  static State initial_state(const Settings& s) { return State::initial(s); }

 private:
  typename Model::Tick tick(const VectorX& iterate) const {
    return model_.tick(state_, obstacles_, ws_.schedule, iterate);
  }

  /// A plan standing in place: zero jerks, footsteps alternating on the two current feet.
  void initial_plan();

  void shift_jerks();

  /// A correction iteration's proximal term on the footstep yaws toward the iterate, weighted as
  /// the heading term (costs/heading.hpp): μ/2 ‖θ − θ_iterate‖². It vanishes at a converged
  /// plan, so it changes no solution, but it stops the Gauss–Newton steps from jumping between
  /// the two mirror-image yaws that widen a ZMP polygon's reach along its diagonal (after a 0.1
  /// m/s push, HRP-2's first step swung ±0.038 rad at every correction and never converged).
  template <typename H, typename G>
  void damp_yaws(H& hessian, G& gradient) const {
    const Scalar mu = std::get<Heading<Scalar>>(model_.costs()).weight();
    for (Index i = 0; i < planned_steps(); ++i) {
      const Index c = layout().step_q() + i;
      hessian(c, c) += mu;
      gradient[c] -= mu * ws_.iterate[c];
    }
  }

  /// After a landing: footstep i+1 becomes i. The new last footstep is guessed where the step
  /// velocity target puts it (the Gauss–Newton rows are linearised there: a guess far from the
  /// solution makes the rotated rows' linearisation error large).
  void shift_footsteps();

  /// Moves the QP's warm-start active set along with the plan: advance() shifted the horizon by
  /// shifted_samples_ samples and shifted_steps_ landings; the layout renames every row and
  /// bound by its block's shift rule (WalkingLayout::renamed).
  void shift_warm_start();

  Model model_;
  Workspace ws_;
  std::vector<Obstacle> obstacles_;
  State state_;
  Plan plan_;
  Result result_;
  Vector3 command_ = Vector3::Zero();
  Scalar heading_ = Scalar(0);  // the reference heading: reset()'s feet, + ω t per advance()
  Index shifted_samples_ = 0, shifted_steps_ = 0;  // advance()s since the last solve()
};

// ------------------------------------------------------------------------------------------------
// Implementation. The members that build, solve and shift are defined here, outside the class, so
// that they are not implicitly inline: a translation unit that declares their instantiation
// extern (mpc/walking_mpc_16.hpp) then compiles none of them.

template <typename Scalar, int N, int FootEdges, int HullEdges>
WalkingMpc<Scalar, N, FootEdges, HullEdges>::WalkingMpc(const Settings& settings,
                                                        Index obstacle_capacity)
    : model_(settings, obstacle_capacity), ws_(model_.layout(), model_.soft_rows()) {
  obstacles_.reserve(static_cast<std::size_t>(layout().dims().obstacles));
  obstacles_ = model_.settings().obstacles;
  ws_.qp.settings().max_iterations = model_.settings().nwsr;
  reset(initial_state(model_.settings()));
}

template <typename Scalar, int N, int FootEdges, int HullEdges>
void WalkingMpc<Scalar, N, FootEdges, HullEdges>::set_state(const State& state) {
  check_walking_state("WalkingMpc::set_state", settings(), state);
  state_ = state;
}

template <typename Scalar, int N, int FootEdges, int HullEdges>
void WalkingMpc<Scalar, N, FootEdges, HullEdges>::reset(const State& state) {
  set_state(state);
  heading_ = state.heading();
  initial_plan();
  ws_.qp.reset_warm_start();
  shifted_samples_ = shifted_steps_ = 0;
}

template <typename Scalar, int N, int FootEdges, int HullEdges>
auto WalkingMpc<Scalar, N, FootEdges, HullEdges>::solve() -> const Result& {
  const Settings& s = settings();
  result_.status = MpcStatus::solved;
  result_.sqp_iterations = 0;
  result_.qp_iterations = 0;
  result_.message = "";
  result_.relaxed_blocks = 0;
  result_.soft_fallback = false;
  model_.prepare(state_, command_, heading_, plan_.U, ws_);
  shift_warm_start();
  // The soft fallback: from the QP that was infeasible (or reached nwsr) on, every QP of this
  // tick is the elastic one, warm-started from the one before.
  bool elastic = false;
  typename Model::Violation split;  // with the fallback: hard and soft blocks apart
  for (int it = 0; it < s.sqp_iterations + s.sqp_corrections; ++it) {
    if (it >= s.sqp_iterations) {
      // Converged: within sqp_tolerance; with the fallback, the hard blocks within it and the
      // soft blocks' violation settled (a relaxed plan keeps some by design).
      if (!elastic && result_.constraint_violation <= s.sqp_tolerance) break;
      if (elastic && split.hard <= s.sqp_tolerance && split.soft_change <= s.sqp_tolerance) break;
    }
    ws_.iterate = plan_.U;
    const auto t = tick(ws_.iterate);
    auto& qp = ws_.qp.problem();  // assembled in place: the solver owns the data
    model_.assemble_cost(t, qp.H, qp.g, ws_.scratch);
    if (it >= s.sqp_iterations) damp_yaws(qp.H, qp.g);
    model_.linearise(t, ws_.iterate, qp.A, qp.lb, qp.ub);
    QpStatus st = QpStatus::infeasible;
    if (!elastic) {
      st = ws_.qp.init();
      if (st != QpStatus::invalid_input) st = ws_.qp.solve().status;
    }
    if ((st == QpStatus::infeasible || st == QpStatus::max_iterations) && ws_.elastic) {
      if (!elastic) {
        ws_.qp.reset_warm_start();
        ws_.elastic->reset_warm_start();
        ws_.elastic->settings().max_iterations = 10 * s.nwsr;
        elastic = true;
      }
      model_.soften(qp, ws_.elastic->problem());
      st = ws_.elastic->init();
      if (st != QpStatus::invalid_input) st = ws_.elastic->solve().status;
    }
    const auto& qr = elastic ? ws_.elastic->result() : ws_.qp.result();
    result_.qp_status = st;
    result_.qp_iterations += qr.iterations;
    result_.primal_residual = qr.primal_residual;
    ++result_.sqp_iterations;
    if (st != QpStatus::solved) {
      // A failed correction keeps the solved plan of the iteration before; only a failure
      // within the first sqp_iterations fails the tick.
      if (it < s.sqp_iterations) {
        result_.status = MpcStatus::qp_failed;
        result_.message = qr.message;
      }
      ws_.qp.reset_warm_start();
      if (elastic) ws_.elastic->reset_warm_start();
      break;
    }
    plan_.U = qr.x.head(num_vars());
    result_.constraint_violation =
        model_.violation(tick(plan_.U), plan_.U, ws_.c, ws_.c_lower, ws_.c_upper);
    if (elastic)
      split = model_.split_violation(ws_.c, ws_.c_lower, ws_.c_upper, split, s.sqp_tolerance);
  }
  result_.soft_fallback = elastic;
  if (elastic && result_.status == MpcStatus::solved) {
    // The fallback may only have undone a poor linearisation: then the plan meets every
    // constraint (solved, below). Otherwise it is relaxed if the hard blocks hold.
    result_.relaxed_blocks = split.soft_blocks;
    if (split.hard > s.sqp_tolerance) {
      result_.status = MpcStatus::not_converged;
      result_.message = "the plan violates its hard constraints beyond sqp_tolerance";
    } else if (split.soft_blocks != 0) {
      result_.status = MpcStatus::relaxed;
      result_.message = "the QP was infeasible: the plan violates the soft constraints least";
    }
    return result_;
  }
  // Solved is a promise: the plan meets its nonlinear constraints within sqp_tolerance.
  if (result_.status == MpcStatus::solved && !(result_.constraint_violation <= s.sqp_tolerance)) {
    result_.status = MpcStatus::not_converged;
    result_.message = "the plan violates its nonlinear constraints beyond sqp_tolerance";
  }
  return result_;
}

template <typename Scalar, int N, int FootEdges, int HullEdges>
void WalkingMpc<Scalar, N, FootEdges, HullEdges>::advance() {
  const Scalar t = settings().t;
  state_.com_x = model_.lipm_step().advance(state_.com_x, plan_.jerk_x(0));
  state_.com_y = model_.lipm_step().advance(state_.com_y, plan_.jerk_y(0));
  const Scalar tau0 = Scalar(state_.phase) * t;
  const FootPose<Scalar> target = plan_.footstep(1);
  state_.swing = swing_foot_sample(step_timing(), state_.swing, tau0, target, tau0 + t).motion;
  state_.time += t;
  heading_ += command_[2] * t;
  shift_jerks();
  ++shifted_samples_;
  if (++state_.phase < samples_per_step()) return;
  ++shifted_steps_;
  // The swing foot lands: it supports the next step; the old support foot will swing.
  state_.phase = 0;
  ++state_.step_count;
  state_.swing_origin = state_.support;
  state_.swing = FootMotion<Scalar>::at_rest(state_.support);
  state_.support = target;
  state_.support_foot = other(state_.support_foot);
  shift_footsteps();
}

template <typename Scalar, int N, int FootEdges, int HullEdges>
void WalkingMpc<Scalar, N, FootEdges, HullEdges>::constraint_values(const VectorX& U, VectorX& c,
                                                                    VectorX& lower,
                                                                    VectorX& upper) const {
  model_.template constraint_values<Scalar>(tick(U), U, c);
  model_.constraint_bounds(tick(U), lower, upper);
}

template <typename Scalar, int N, int FootEdges, int HullEdges>
void WalkingMpc<Scalar, N, FootEdges, HullEdges>::constraint_jacobian(const VectorX& U,
                                                                      RowMatrixX& J, VectorX& lower,
                                                                      VectorX& upper) const {
  model_.linearise(tick(U), U, J, lower, upper);
}

template <typename Scalar, int N, int FootEdges, int HullEdges>
std::uint32_t WalkingMpc<Scalar, N, FootEdges, HullEdges>::conflicting_blocks() {
  if (result_.qp_status != QpStatus::infeasible && !result_.soft_fallback) return 0;
  // The hard QP as the tick last assembled it, factorised afresh (after the fallback took over
  // it was assembled but not factorised): is it infeasible?
  const auto infeasible = [&] {
    ws_.qp.reset_warm_start();
    return ws_.qp.init() == QpStatus::unsolved && ws_.qp.solve().status == QpStatus::infeasible;
  };
  const auto solved = [&] {
    ws_.qp.reset_warm_start();
    return ws_.qp.update() == QpStatus::unsolved && ws_.qp.solve().status == QpStatus::solved;
  };
  std::uint32_t mask = 0;
  if (infeasible()) {
    constexpr Scalar inf = std::numeric_limits<Scalar>::infinity();
    auto& qp = ws_.qp.problem();
    for (int k = 0; k < layout().num_row_blocks(); ++k) {
      const LayoutBlock& b = layout().rows(k);
      const Index o = b.offset, n = b.count();
      if (n == 0) continue;
      ws_.c_lower.segment(o, n) = qp.lb.segment(o, n);  // saved: c_lower/upper are scratch here
      ws_.c_upper.segment(o, n) = qp.ub.segment(o, n);
      qp.lb.segment(o, n).setConstant(-inf);
      qp.ub.segment(o, n).setConstant(inf);
      if (solved()) mask |= 1u << k;  // only bounds changed since init(): update() suffices
      qp.lb.segment(o, n) = ws_.c_lower.segment(o, n);
      qp.ub.segment(o, n) = ws_.c_upper.segment(o, n);
    }
  }
  ws_.qp.reset_warm_start();
  return mask;
}

template <typename Scalar, int N, int FootEdges, int HullEdges>
void WalkingMpc<Scalar, N, FootEdges, HullEdges>::initial_plan() {
  const WalkingLayout& L = layout();
  plan_.N = int(horizon());
  plan_.nf = int(planned_steps());
  plan_.U.setZero(num_vars());
  for (Index i = 1; i <= planned_steps(); ++i) {
    const FootPose<Scalar>& p = (i % 2 == 1) ? state_.swing_origin : state_.support;
    plan_.U[L.step_x() + i - 1] = p.x;
    plan_.U[L.step_y() + i - 1] = p.y;
    plan_.U[L.step_q() + i - 1] = p.q;
  }
}

template <typename Scalar, int N, int FootEdges, int HullEdges>
void WalkingMpc<Scalar, N, FootEdges, HullEdges>::shift_jerks() {
  const Index n = horizon();
  for (Index base : {layout().jerk_x(), layout().jerk_y()}) {
    for (Index j = 0; j + 1 < n; ++j) plan_.U[base + j] = plan_.U[base + j + 1];
    plan_.U[base + n - 1] = Scalar(0);
  }
}

template <typename Scalar, int N, int FootEdges, int HullEdges>
void WalkingMpc<Scalar, N, FootEdges, HullEdges>::shift_footsteps() {
  const WalkingLayout& L = layout();
  const Index nf = planned_steps();
  for (Index base : {L.step_x(), L.step_y(), L.step_q()}) {
    for (Index i = 1; i < nf; ++i) plan_.U[base + i - 1] = plan_.U[base + i];
  }
  const FootPose<Scalar> last = nf >= 2 ? plan_.footstep(int(nf - 1)) : state_.support;
  Scalar dx, dy;
  step_displacement(settings(), state_, command_, heading_, nf, dx, dy);
  plan_.U[L.step_x() + nf - 1] = last.x + dx;
  plan_.U[L.step_y() + nf - 1] = last.y + dy;
  plan_.U[L.step_q() + nf - 1] = yaw_of_step(settings(), state_, command_[2], heading_, nf);
}

template <typename Scalar, int N, int FootEdges, int HullEdges>
void WalkingMpc<Scalar, N, FootEdges, HullEdges>::shift_warm_start() {
  const Index ds = shifted_samples_, di = shifted_steps_;
  shifted_samples_ = shifted_steps_ = 0;
  if (ds == 0) return;
  ws_.qp.rename_warm_start([&](int c) { return int(layout().renamed(c, ds, di)); });
}

}  // namespace walkgen
