#pragma once
/// @file
/// The NMPC walking pattern generator of thesis §2.2 and §6: a linear inverted pendulum preview
/// over N samples, CoM jerks and footsteps (position and yaw) as decision variables, the ZMP in
/// the rotated, margin-shrunk support polygon, footsteps in the feasibility polygon of the
/// foot they are planned from, relative foot yaw and yaw-rate limits, circular obstacles, and a
/// Gauss–Newton SQP (one step per tick: the real-time iteration) around walkgen's DenseQp.
///
/// Decision vector (one tick, n = 2(N + N_f) + N_f):
///   U = ( jerk_x[0..N) | F_x[1..N_f] | jerk_y[0..N) | F_y[1..N_f] | F_q[1..N_f] )
/// CoM jerks as in eq. 2.53; footstep yaws F_q are the foot orientations (see docs/thesis-map.md
/// for how they relate to the thesis's foot-yaw jerks of eq. 2.54).
///
/// Timing: a step of S = t_step / t samples begins with double support. With `phase` p samples
/// of the current step elapsed, horizon sample j (0-based, time t_k + (j+1)t) belongs to step
/// ⌊(p + j) / S⌋: step 0 is the current support foot, step i ≥ 1 the i-th planned footstep
/// (the selection v/V of eq. 2.47–2.49). The ZMP therefore moves onto a new foot during the
/// first interval of every step, inside double support (t_ds ≥ t is validated).
///
/// Use (convention 13: the block steps, the application owns the loop):
/// @code
///   walkgen::WalkingMpc<double, 16> mpc(walkgen::hrp2_settings());
///   if (mpc.set_command({0.1, 0.0, 0.0}) != walkgen::CommandStatus::accepted) {
///     /* NaN or beyond max_command: rejected, the previous command stays */
///   }                                          // v_x, v_y [m/s], ω_z [rad/s], robot frame
///   for (;;) {
///     const auto& r = mpc.solve();             // r.status: solved / qp_failed (safe plan kept)
///     interpolator.interpolate(mpc, samples);  // command-period samples of this tick
///     mpc.advance();                           // state moves one t forward along the plan
///   }
/// @endcode
/// Allocation: the constructor sizes everything; solve(), advance(), set_command(), set_state()
/// and set_obstacles() never touch the heap (tests/mpc/test_walking_mpc_no_alloc.cpp).

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <sstream>
#include <vector>

#include "walkgen/core/exceptions.hpp"
#include "walkgen/core/foot.hpp"
#include "walkgen/interpolation/swing_foot.hpp"
#include "walkgen/model/lipm.hpp"
#include "walkgen/model/support_polygon.hpp"
#include "walkgen/mpc/settings.hpp"
#include "walkgen/qp/dense_qp.hpp"

namespace walkgen {

/// Outcome of one generator tick.
enum class MpcStatus : std::uint8_t {
  /// Every SQP iteration's QP solved and the plan meets the nonlinear constraints within
  /// sqp_tolerance (Result::constraint_violation); the plan is the new solution.
  solved,
  qp_failed,  ///< a QP failed (see Result::qp_status); the plan is the previous one, shifted
  /// Every QP solved, but after sqp_iterations + sqp_corrections Gauss–Newton iterations the
  /// plan still violates the nonlinear constraints (rotated polygons, obstacle margins) by
  /// Result::constraint_violation > sqp_tolerance. The plan is that last iterate: the best
  /// available and executable, but outside its constraints by that much.
  not_converged,
};

/// What happened to a velocity command.
enum class CommandStatus : std::uint8_t {
  accepted,      ///< in use from the next solve()
  non_finite,    ///< NaN or inf: rejected, the previous command stays
  out_of_range,  ///< beyond WalkingSettings::max_command: rejected, the previous command stays
};

/// The enumerator's name ("solved", ...), e.g. for logs; "unknown" out of range.
constexpr const char* to_string(MpcStatus s) noexcept {
  switch (s) {
    case MpcStatus::solved:
      return "solved";
    case MpcStatus::qp_failed:
      return "qp_failed";
    case MpcStatus::not_converged:
      return "not_converged";
  }
  return "unknown";
}

/// The enumerator's name ("accepted", ...), e.g. for logs; "unknown" for a value out of range.
constexpr const char* to_string(CommandStatus s) noexcept {
  switch (s) {
    case CommandStatus::accepted:
      return "accepted";
    case CommandStatus::non_finite:
      return "non_finite";
    case CommandStatus::out_of_range:
      return "out_of_range";
  }
  return "unknown";
}

/// The generator's state at a tick (section 6.3's PatternGeneratorState). Feedback may overwrite
/// it between ticks with set_state(), e.g. the CoM from forward kinematics.
template <typename Scalar = double>
struct WalkingState {
  using Vector3 = Eigen::Matrix<Scalar, 3, 1>;
  Vector3 com_x = Vector3::Zero();  ///< CoM x, ẋ, ẍ [m, m/s, m/s²], world frame
  Vector3 com_y = Vector3::Zero();  ///< CoM y, ẏ, ÿ
  Foot support_foot = Foot::left;   ///< the foot on the ground in single support
  FootPose<Scalar> support;         ///< its pose
  FootPose<Scalar> swing_origin;    ///< where the swing foot lifts off (stands in double support)
  FootMotion<Scalar> swing;         ///< the swing foot's motion now
  int phase = 0;                    ///< samples of the current step elapsed, 0 ≤ phase < S
  Scalar time = Scalar(0);          ///< [s] since the start
  long step_count = 0;              ///< steps completed since the start

  /// Heading of the robot [rad]: the mean of the two feet's yaws.
  Scalar heading() const { return (support.q + swing.q.position) / Scalar(2); }
};

/// The plan of the last solve(): the decision vector U and views on its parts.
template <typename Scalar = double>
struct WalkingPlan {
  using VectorX = Eigen::Matrix<Scalar, Eigen::Dynamic, 1>;
  VectorX U;  ///< see the file comment for the layout
  int N = 0, nf = 0;

  Scalar jerk_x(int j) const { return U[j]; }
  Scalar jerk_y(int j) const { return U[N + nf + j]; }
  /// Planned footstep i = 1..nf.
  FootPose<Scalar> footstep(int i) const {
    return {U[N + i - 1], U[2 * N + nf + i - 1], U[2 * (N + nf) + i - 1]};
  }
};

/// Result of solve().
template <typename Scalar = double>
struct MpcResult {
  MpcStatus status = MpcStatus::solved;
  QpStatus qp_status = QpStatus::unsolved;  ///< status of the last QP solved in this tick
  const char* message = "";                 ///< the QP's message when it failed
  int sqp_iterations = 0;                   ///< Gauss–Newton iterations done
  int qp_iterations = 0;                    ///< active-set changes, summed over the iterations
  Scalar primal_residual = Scalar(0);       ///< of the last QP (linearised constraints)
  /// Largest violation of the nonlinear constraints (eq. 2.65–2.82) by the plan [m or rad]:
  /// the linearisation error that sqp_corrections iterations bring below sqp_tolerance.
  Scalar constraint_violation = Scalar(0);
  CommandStatus last_command = CommandStatus::accepted;  ///< the last set_command() outcome
  Eigen::Matrix<Scalar, 3, 1> command = Eigen::Matrix<Scalar, 3, 1>::Zero();  ///< in use
};

/// The generator.
/// @tparam Scalar    floating-point type
/// @tparam N         preview samples (WalkingSettings::n), or Eigen::Dynamic
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
  using Vector3 = Eigen::Matrix<Scalar, 3, 1>;
  using VectorX = Eigen::Matrix<Scalar, Eigen::Dynamic, 1>;
  using MatrixX = Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>;
  using RowMatrixX = Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
  using FootPolygon = Eigen::Matrix<Scalar, FootEdges, 2>;
  using FootRhs = Eigen::Matrix<Scalar, FootEdges, 1>;
  using HullPolygon = Eigen::Matrix<Scalar, HullEdges, 2>;
  using HullRhs = Eigen::Matrix<Scalar, HullEdges, 1>;

  /// Builds the generator: validates the settings, precomputes the preview matrices and the
  /// polygons' half-planes, sizes the QP.
  /// @param obstacle_capacity most obstacles set_obstacles() will be given (at least the
  ///        settings' own); rows for them are reserved now so that no tick allocates.
  /// @throws walkgen::invalid_argument on invalid settings or sizes that contradict N,
  ///         FootEdges or HullEdges.
  explicit WalkingMpc(const Settings& settings, Index obstacle_capacity = 0)
      : s_(checked(settings)),
        S_(s_.samples_per_step()),
        N_(s_.n),
        nf_(s_.planned_steps()),
        cap_obstacles_(std::max<Index>(obstacle_capacity, Index(s_.obstacles.size()))),
        foot_edges_(s_.zmp_polygon.rows() > 0 ? s_.zmp_polygon.rows() : 4),
        hull_edges_(s_.left_foot_convex_hull.rows()),
        lipm_(s_.t, s_.com_z, s_.gravity, s_.n),
        step_(s_.t),
        qp_(num_vars(), num_rows()) {
    set_polygons();
    const Index n = num_vars(), m = num_rows();
    H_.setZero(n, n);
    g_.setZero(n);
    A_.setZero(m, n);
    lb_.setZero(m);
    ub_.setZero(m);
    l_.setConstant(n, -kInf);
    u_.setConstant(n, kInf);
    Zx_.setZero(N_);
    Zy_.setZero(N_);
    U_prev_.setZero(n);
    c_.setZero(m);
    c_lower_.setZero(m);
    c_upper_.setZero(m);
    step_of_.resize(N_);
    obstacles_.reserve(static_cast<std::size_t>(cap_obstacles_));
    obstacles_ = s_.obstacles;
    // Constant Hessian blocks (eq. 2.56): α P_vuᵀP_vu + β P_zuᵀP_zu + γ I and the yaw block.
    ref_x_.setZero(N_);
    ref_y_.setZero(N_);
    HUU_ = s_.alpha * lipm_.P_vu.transpose() * lipm_.P_vu +
           s_.beta * lipm_.P_zu.transpose() * lipm_.P_zu;
    HUU_.diagonal().array() += s_.gamma;
    D_.setZero(nf_, nf_);  // (Dθ)_i = θ_i − θ_{i−1}
    for (Index i = 0; i < nf_; ++i) {
      D_(i, i) = Scalar(1);
      if (i > 0) D_(i, i - 1) = Scalar(-1);
    }
    DtD_ = D_.transpose() * D_;
    Hqq_ = yaw_weight() * DtD_;
    Hqq_.diagonal().array() += s_.footstep_regularization;
    yaw_target_.setZero(nf_);
    {  // capture point at the end of the horizon: ξ_N = C_N + Ċ_N / ω
      const Scalar w = std::sqrt(s_.gravity / s_.com_z);
      xi_s_ = lipm_.P_ps.row(N_ - 1) + lipm_.P_vs.row(N_ - 1) / w;
      xi_u_ = lipm_.P_pu.row(N_ - 1) + lipm_.P_vu.row(N_ - 1) / w;
    }
    step_target_x_.setZero(nf_);
    step_target_y_.setZero(nf_);
    qp_.settings().max_iterations = s_.nwsr;
    reset(initial_state(s_));
  }

  // --- Sizes -------------------------------------------------------------------------------------
  Index horizon() const { return N_; }
  Index planned_steps() const { return nf_; }
  Index samples_per_step() const { return S_; }
  Index num_vars() const { return 2 * (N_ + nf_) + nf_; }
  Index num_rows() const {
    return N_ * foot_edges() + nf_ * hull_edges() + 2 * nf_ + nf_ * cap_obstacles_ + foot_edges();
  }
  Index obstacle_capacity() const { return cap_obstacles_; }

  // --- Inputs ------------------------------------------------------------------------------------
  /// Velocity command (v_x, v_y [m/s], ω_z [rad/s]) in the robot's frame (the heading).
  /// Non-finite or out-of-range commands are rejected (the previous one stays) and reported.
  [[nodiscard]] CommandStatus set_command(const Vector3& command) {
    CommandStatus status = CommandStatus::accepted;
    if (!command.allFinite()) {
      status = CommandStatus::non_finite;
    } else if ((command.cwiseAbs().array() > s_.max_command.array()).any()) {
      status = CommandStatus::out_of_range;
    } else {
      command_ = command;
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
  void set_state(const State& state) {
    if (state.phase < 0 || state.phase >= S_) {  // the message is built only on failure
      check_argument(false, "WalkingMpc::set_state: phase",
                     "0 <= phase < samples_per_step() = " + std::to_string(S_), state.phase);
    }
    check_argument(finite_state(state), "WalkingMpc::set_state", "finite values", "NaN or inf",
                   "check the feedback (forward kinematics) that produced the state");
    if (const char* what = implausible(state)) {
      std::ostringstream got;
      got << what << " (CoM at (" << state.com_x[0] << ", " << state.com_y[0]
          << ") m, support foot at (" << state.support.x << ", " << state.support.y << ") m)";
      check_argument(false, "WalkingMpc::set_state", "a plausible walking state", got.str(),
                     "check the feedback; the limits are WalkingSettings::max_state_distance, "
                     "max_com_speed and max_com_acceleration");
    }
    state_ = state;
  }
  /// Restarts from `state`: also forgets the plan and the QP's warm start.
  void reset(const State& state) {
    set_state(state);
    initial_plan();
    qp_.reset_warm_start();
    shifted_samples_ = shifted_steps_ = 0;
  }

  /// Replaces the obstacles (world frame). No allocation up to obstacle_capacity().
  /// @throws walkgen::invalid_argument beyond the capacity or on invalid obstacles.
  template <typename Container>
  void set_obstacles(const Container& obstacles) {
    if (Index(obstacles.size()) > cap_obstacles_) {  // the message is built only on failure
      check_argument(false, "WalkingMpc::set_obstacles",
                     "at most obstacle_capacity() = " + std::to_string(cap_obstacles_),
                     obstacles.size(), "pass a larger obstacle_capacity to the constructor");
    }
    for (const auto& o : obstacles) {
      check_argument(std::isfinite(o.x) && std::isfinite(o.y) && std::isfinite(o.radius) &&
                         o.radius > Scalar(0) && std::isfinite(o.margin) && o.margin >= Scalar(0),
                     "WalkingMpc::set_obstacles", "finite centres, radius > 0, margin >= 0",
                     "an invalid obstacle");
    }
    obstacles_.assign(obstacles.begin(), obstacles.end());
  }
  const std::vector<Obstacle>& obstacles() const { return obstacles_; }

  // --- Tick --------------------------------------------------------------------------------------
  /// Plans from the current state: sqp_iterations Gauss–Newton steps (eq. 2.83–2.89), each a QP
  /// linearised at the current iterate (the previous plan, shifted, on the first). A failed QP is
  /// never applied: the plan stays the previous iterate and the status says qp_failed.
  [[nodiscard]] const Result& solve() {
    result_.status = MpcStatus::solved;
    result_.sqp_iterations = 0;
    result_.qp_iterations = 0;
    result_.message = "";
    prepare_tick();
    shift_warm_start();
    const int most = s_.sqp_iterations + s_.sqp_corrections;
    for (int it = 0; it < most; ++it) {
      if (it >= s_.sqp_iterations && result_.constraint_violation <= s_.sqp_tolerance) break;
      assemble();
      QpStatus st = qp_.init(H_, g_, A_, lb_, ub_, l_, u_);
      if (st != QpStatus::invalid_input) st = qp_.solve().status;
      const auto& qr = qp_.result();
      result_.qp_status = st;
      result_.qp_iterations += qr.iterations;
      result_.primal_residual = qr.primal_residual;
      ++result_.sqp_iterations;
      if (st != QpStatus::solved) {
        // A failed correction keeps the solved plan of the iteration before; only a failure
        // within the first sqp_iterations fails the tick.
        if (it < s_.sqp_iterations) {
          result_.status = MpcStatus::qp_failed;
          result_.message = qr.message;
        }
        qp_.reset_warm_start();
        break;
      }
      plan_.U = qr.x;
      result_.constraint_violation = violation(plan_.U);
    }
    // Solved is a promise: the plan meets its nonlinear constraints within sqp_tolerance.
    if (result_.status == MpcStatus::solved &&
        !(result_.constraint_violation <= s_.sqp_tolerance)) {
      result_.status = MpcStatus::not_converged;
      result_.message = "the plan violates its nonlinear constraints beyond sqp_tolerance";
    }
    return result_;
  }

  /// Moves the state one preview period t forward along the plan: CoM by the LIPM with the
  /// first jerk, the swing foot along its polynomials; at the end of a step the swing foot lands
  /// on the first planned footstep, which becomes the support foot, and the plan shifts.
  void advance() {
    state_.com_x = step_.advance(state_.com_x, plan_.jerk_x(0));
    state_.com_y = step_.advance(state_.com_y, plan_.jerk_y(0));
    const StepTiming<Scalar> timing = step_timing();
    const Scalar tau0 = Scalar(state_.phase) * s_.t;
    const FootPose<Scalar> target = plan_.footstep(1);
    state_.swing = swing_foot_sample(timing, state_.swing, tau0, target, tau0 + s_.t).motion;
    state_.time += s_.t;
    shift_jerks();
    ++shifted_samples_;
    if (++state_.phase < S_) return;
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

  // --- Outputs -----------------------------------------------------------------------------------
  const State& state() const { return state_; }
  const Plan& plan() const { return plan_; }
  const Result& result() const { return result_; }
  const Settings& settings() const { return s_; }
  const LipmPreview<Scalar, N>& preview() const { return lipm_; }
  StepTiming<Scalar> step_timing() const { return {s_.t_ds, s_.t_step, s_.step_height}; }
  /// Step of horizon sample j (0 = current support, i = i-th planned footstep); valid after
  /// solve() for the state it planned from.
  int step_of_sample(Index j) const { return step_of_[j]; }
  /// Which foot stands in step i (0 = current support).
  Foot foot_of_step(Index i) const {
    return (i % 2 == 0) ? state_.support_foot : other(state_.support_foot);
  }

  /// The QP of the last SQP iteration (H, g, A, lb ≤ A U ≤ ub, l ≤ U ≤ u): for tests and
  /// diagnostics (e.g. Jacobians against finite differences).
  const MatrixX& qp_H() const { return H_; }
  const VectorX& qp_g() const { return g_; }
  const RowMatrixX& qp_A() const { return A_; }
  const VectorX& qp_lb() const { return lb_; }
  const VectorX& qp_ub() const { return ub_; }
  const VectorX& qp_l() const { return l_; }
  const VectorX& qp_u() const { return u_; }

  /// The nonlinear constraint functions c(U) of eq. 2.65–2.82 for the current state, written as
  /// lb_c ≤ c(U) ≤ ub_c with the same rows as the QP: the QP's rows are their Gauss–Newton
  /// linearisation at the iterate, A = ∂c/∂U. For tests; allocation-free.
  void constraint_values(const VectorX& U, VectorX& c, VectorX& lower, VectorX& upper) const {
    linearise(U, nullptr, &c, lower, upper);
  }
  /// The Jacobian ∂c/∂U at U (the QP's constraint matrix when U is the iterate); lower/upper
  /// receive the QP's row bounds for that linearisation.
  void constraint_jacobian(const VectorX& U, RowMatrixX& J, VectorX& lower, VectorX& upper) const {
    linearise(U, &J, nullptr, lower, upper);
  }

  /// Builds the initial state of a settings set: CoM from com_x/com_y, support foot at
  /// (foot_x, foot_y, foot_q), the other foot foot_distance beside it, standing.
  static State initial_state(const Settings& s) {
    State st;
    st.com_x = s.com_x;
    st.com_y = s.com_y;
    st.support_foot = s.support_foot;
    st.support = {s.foot_x, s.foot_y, s.foot_q};
    st.swing_origin = beside(st.support, s.support_foot, s.foot_distance);
    st.swing = FootMotion<Scalar>::at_rest(st.swing_origin);
    return st;
  }

 private:
  /// The pose `distance` beside foot pose p (of foot `foot`), on the other foot's side.
  static FootPose<Scalar> beside(const FootPose<Scalar>& p, Foot foot, Scalar distance) {
    using std::cos;
    using std::sin;
    const Scalar side = foot == Foot::left ? Scalar(-1) : Scalar(1);
    return {p.x - side * distance * sin(p.q), p.y + side * distance * cos(p.q), p.q};
  }

  static constexpr Scalar kInf = std::numeric_limits<Scalar>::infinity();
  static int index(Foot f) { return f == Foot::left ? 0 : 1; }

  static const Settings& checked(const Settings& s) {
    validate(s);
    check_argument(N == Eigen::Dynamic || s.n == N, "WalkingMpc: settings.n",
                   "the template horizon N = " + std::to_string(N), s.n,
                   "use WalkingMpc<Scalar, Eigen::Dynamic> for a horizon known at run time");
    const Index foot = s.zmp_polygon.rows() > 0 ? s.zmp_polygon.rows() : 4;
    check_argument(FootEdges == Eigen::Dynamic || foot == FootEdges,
                   "WalkingMpc: ZMP polygon edges", "FootEdges = " + std::to_string(FootEdges),
                   foot, "the default sole is a rectangle: 4 edges, or set zmp_polygon");
    check_argument(s.left_foot_convex_hull.rows() == s.right_foot_convex_hull.rows(),
                   "WalkingMpc: right_foot_convex_hull",
                   "as many vertices as left_foot_convex_hull", s.right_foot_convex_hull.rows());
    for (const auto* hull : {&s.left_foot_convex_hull, &s.right_foot_convex_hull}) {
      check_argument(HullEdges == Eigen::Dynamic || hull->rows() == HullEdges,
                     "WalkingMpc: feasibility hull edges",
                     "HullEdges = " + std::to_string(HullEdges), hull->rows());
    }
    return s;
  }

  /// Weight of the yaw-rate tracking per footstep: α per horizon sample, as eq. 2.44 sums the
  /// rate error over the S samples of a step, divided by t_step² to turn yaw steps into rates.
  Scalar yaw_weight() const { return s_.alpha * Scalar(S_) / (s_.t_step * s_.t_step); }
  Scalar step_weight() const {
    return s_.step_velocity_weight * Scalar(S_) / (s_.t_step * s_.t_step);
  }

  /// Reference velocity at horizon sample j + 1: the command rotated along the reference
  /// heading, R(h + ω t (j + 1)) v (eq. 2.43; the thesis keeps the heading constant over the
  /// horizon, which makes curved walks lag).
  void reference(Index j, Scalar heading, Scalar& rx, Scalar& ry) const {
    using std::cos;
    using std::sin;
    const Scalar q = heading + command_[2] * s_.t * Scalar(j + 1);
    rx = command_[0] * cos(q) - command_[1] * sin(q);
    ry = command_[0] * sin(q) + command_[1] * cos(q);
  }

  Index foot_edges() const { return foot_edges_; }
  Index hull_edges() const { return hull_edges_; }

  void set_polygons() {
    Eigen::Matrix<Scalar, Eigen::Dynamic, 2> sole = s_.zmp_polygon;
    if (sole.rows() == 0) {
      const Scalar hx = s_.foot_length / Scalar(2) - s_.security_margin[0];
      const Scalar hy = s_.foot_width / Scalar(2) - s_.security_margin[1];
      sole.resize(4, 2);
      sole << hx, hy, -hx, hy, -hx, -hy, hx, -hy;
    }
    Eigen::Matrix<Scalar, Eigen::Dynamic, 2> mirrored = sole;
    mirrored.col(1) *= Scalar(-1);
    for (int f = 0; f < 2; ++f) {
      foot_A_[f].resize(sole.rows(), 2);
      foot_b_[f].resize(sole.rows());
      polygon_halfplanes(f == 0 ? sole : mirrored, foot_A_[f], foot_b_[f]);
      const auto& hull = f == 0 ? s_.left_foot_convex_hull : s_.right_foot_convex_hull;
      hull_A_[f].resize(hull.rows(), 2);
      hull_b_[f].resize(hull.rows());
      polygon_halfplanes(hull, hull_A_[f], hull_b_[f]);
    }
  }

  /// What makes a finite state implausible (see set_state()), or nullptr.
  const char* implausible(const State& st) const {
    const auto far = [&](Scalar x, Scalar y) {
      return std::hypot(x - st.support.x, y - st.support.y) > s_.max_state_distance;
    };
    if (far(st.com_x[0], st.com_y[0])) return "the CoM farther than max_state_distance";
    if (far(st.swing.x.position, st.swing.y.position) ||
        far(st.swing_origin.x, st.swing_origin.y)) {
      return "the swing foot farther than max_state_distance";
    }
    if (std::abs(st.com_x[1]) > s_.max_com_speed || std::abs(st.com_y[1]) > s_.max_com_speed) {
      return "a CoM speed above max_com_speed";
    }
    if (std::abs(st.com_x[2]) > s_.max_com_acceleration ||
        std::abs(st.com_y[2]) > s_.max_com_acceleration) {
      return "a CoM acceleration above max_com_acceleration";
    }
    return nullptr;
  }

  static bool finite_state(const State& st) {
    using std::isfinite;
    auto pose_ok = [](const FootPose<Scalar>& p) {
      return isfinite(p.x) && isfinite(p.y) && isfinite(p.q);
    };
    auto s3_ok = [](const Sample3<Scalar>& s) {
      return isfinite(s.position) && isfinite(s.velocity) && isfinite(s.acceleration);
    };
    return st.com_x.allFinite() && st.com_y.allFinite() && pose_ok(st.support) &&
           pose_ok(st.swing_origin) && s3_ok(st.swing.x) && s3_ok(st.swing.y) &&
           s3_ok(st.swing.q) && isfinite(st.time);
  }

  // Variable offsets.
  Index ix_u() const { return 0; }
  Index ix_f() const { return N_; }
  Index iy_u() const { return N_ + nf_; }
  Index iy_f() const { return 2 * N_ + nf_; }
  Index iq_f() const { return 2 * (N_ + nf_); }

  /// A plan standing in place: zero jerks, footsteps alternating on the two current feet.
  void initial_plan() {
    plan_.N = int(N_);
    plan_.nf = int(nf_);
    plan_.U.setZero(num_vars());
    for (Index i = 1; i <= nf_; ++i) {
      const FootPose<Scalar>& p = (i % 2 == 1) ? state_.swing_origin : state_.support;
      plan_.U[ix_f() + i - 1] = p.x;
      plan_.U[iy_f() + i - 1] = p.y;
      plan_.U[iq_f() + i - 1] = p.q;
    }
  }

  void shift_jerks() {
    for (Index base : {ix_u(), iy_u()}) {
      for (Index j = 0; j + 1 < N_; ++j) plan_.U[base + j] = plan_.U[base + j + 1];
      plan_.U[base + N_ - 1] = Scalar(0);
    }
  }

  /// After a landing: footstep i+1 becomes i. The new last footstep is guessed where the step
  /// velocity target puts it (the Gauss–Newton rows are linearised there: a guess far from the
  /// solution makes the rotated rows' linearisation error large).
  void shift_footsteps() {
    for (Index base : {ix_f(), iy_f(), iq_f()}) {
      for (Index i = 1; i < nf_; ++i) plan_.U[base + i - 1] = plan_.U[base + i];
    }
    const FootPose<Scalar> last = nf_ >= 2 ? plan_.footstep(int(nf_ - 1)) : state_.support;
    Scalar dx, dy;
    step_displacement(nf_, dx, dy);
    plan_.U[ix_f() + nf_ - 1] = last.x + dx;
    plan_.U[iy_f() + nf_ - 1] = last.y + dy;
    plan_.U[iq_f() + nf_ - 1] = last.q + command_[2] * s_.t_step;
  }

  /// Step velocity target (see step_weight()) of planned step i relative to step i − 1:
  /// F_i − F_{i−1} = R(h_i) (t_step v + lateral), h_i the reference heading between the two
  /// feet of step i. The feet stand foot_distance apart measured in the frame of the foot a
  /// step is planned from, as the feasibility polygons measure it: foot_distance / cos(Δ/2)
  /// between centres when consecutive feet turn by Δ = ω t_step.
  void step_displacement(Index i, Scalar& dx_world, Scalar& dy_world) const {
    using std::cos;
    using std::sin;
    const Scalar turn = command_[2] * s_.t_step;
    const Scalar h = state_.support.q + turn * (Scalar(i) - Scalar(0.5));
    const Scalar side = foot_of_step(i) == Foot::left ? Scalar(1) : Scalar(-1);
    // Sideways, the leading foot steps 2 t_step v_y out and the trailing one closes up.
    const Scalar lateral =
        side * command_[1] > Scalar(0) ? Scalar(2) * s_.t_step * command_[1] : Scalar(0);
    const Scalar dx = s_.t_step * command_[0];
    const Scalar dy = lateral + side * s_.foot_distance / cos(turn / Scalar(2));
    dx_world = cos(h) * dx - sin(h) * dy;
    dy_world = sin(h) * dx + cos(h) * dy;
  }

  /// Moves the QP's warm-start active set along with the plan: advance() shifted the horizon by
  /// shifted_samples_ samples and shifted_steps_ landings, so the constraint that was active on
  /// sample j (footstep i) is now the one on sample j − samples (footstep i − steps).
  void shift_warm_start() {
    const Index ds = shifted_samples_, di = shifted_steps_;
    shifted_samples_ = shifted_steps_ = 0;
    if (ds == 0) return;
    const Index fe = foot_edges(), he = hull_edges(), m = num_rows();
    const Index hull0 = N_ * fe, yaw0 = hull0 + nf_ * he, obstacle0 = yaw0 + 2 * nf_,
                terminal0 = obstacle0 + nf_ * cap_obstacles_;
    // Index i (0-based) of a block of `count` entries per step or sample, moved by `by`.
    auto moved = [](Index i, Index by, Index count) { return i >= by && i - by < count; };
    qp_.rename_warm_start([&](int c) -> int {
      Index r = c;
      if (r < hull0) {  // ZMP: sample j = r / fe
        return moved(r / fe, ds, N_) ? int(r - ds * fe) : -1;
      }
      if (r < yaw0) {  // feasibility: step i − 1 = (r − hull0) / he
        return moved((r - hull0) / he, di, nf_) ? int(r - di * he) : -1;
      }
      if (r < obstacle0) {  // relative yaw and rate: step i − 1 = (r − yaw0) mod nf
        return moved((r - yaw0) % nf_, di, nf_) ? int(r - di) : -1;
      }
      if (r < terminal0) {  // obstacles: step i − 1 = (r − obstacle0) mod nf
        return moved((r - obstacle0) % nf_, di, nf_) ? int(r - di) : -1;
      }
      if (r < m) return c;  // terminal capture point
      // Bounds: jerks move by samples, footsteps by steps.
      const Index v = r - m;
      for (Index base : {ix_u(), iy_u()}) {
        if (v >= base && v < base + N_) return moved(v - base, ds, N_) ? int(r - ds) : -1;
      }
      for (Index base : {ix_f(), iy_f(), iq_f()}) {
        if (v >= base && v < base + nf_) return moved(v - base, di, nf_) ? int(r - di) : -1;
      }
      return -1;
    });
  }

  /// Per-tick data that do not depend on the iterate: step membership, velocity references,
  /// frozen landing footstep.
  void prepare_tick() {
    for (Index j = 0; j < N_; ++j) step_of_[j] = int((state_.phase + j) / S_);
    using std::cos;
    using std::sin;
    const Scalar heading = state_.heading();
    for (Index j = 0; j < N_; ++j) reference(j, heading, ref_x_[j], ref_y_[j]);
    // In the last interval before landing the footstep is fixed: the foot is about to touch.
    const bool frozen = state_.phase == S_ - 1;
    for (Index base : {ix_f(), iy_f(), iq_f()}) {
      l_[base] = frozen ? plan_.U[base] : -kInf;
      u_[base] = frozen ? plan_.U[base] : kInf;
    }
    // Yaw tracking target: consecutive footsteps ω·t_step apart (eq. 2.44, see thesis-map).
    yaw_target_.setConstant(command_[2] * s_.t_step);
    yaw_target_[0] += state_.support.q;
    for (Index i = 1; i <= nf_; ++i) {
      step_displacement(i, step_target_x_[i - 1], step_target_y_[i - 1]);
    }
    step_target_x_[0] += state_.support.x;
    step_target_y_[0] += state_.support.y;
  }

  /// Cost (eq. 2.51–2.60, gradient corrected per docs/design.md §5) and linearised constraints
  /// (eq. 2.84–2.88) at the iterate plan_.U.
  void assemble() {
    U_prev_ = plan_.U;
    const Scalar a = s_.alpha, b = s_.beta, eps = s_.footstep_regularization;
    // Hessian: x and y blocks share  [HUU, −β P_zuᵀV; −β VᵀP_zu, β VᵀV + ε].
    H_.setZero();
    for (Index axis = 0; axis < 2; ++axis) {
      const Index u0 = axis == 0 ? ix_u() : iy_u(), f0 = axis == 0 ? ix_f() : iy_f();
      H_.block(u0, u0, N_, N_) = HUU_;
      for (Index j = 0; j < N_; ++j) {
        const int s = step_of_[j];
        if (s == 0) continue;
        for (Index c = 0; c <= j; ++c) {
          const Scalar v = -b * lipm_.P_zu(j, c);
          H_(u0 + c, f0 + s - 1) += v;
          H_(f0 + s - 1, u0 + c) += v;
        }
        H_(f0 + s - 1, f0 + s - 1) += b;
      }
      for (Index i = 0; i < nf_; ++i) H_(f0 + i, f0 + i) += eps;
      H_.block(f0, f0, nf_, nf_) += step_weight() * DtD_;
    }
    H_.block(iq_f(), iq_f(), nf_, nf_) = Hqq_;
    // Gradient.
    for (Index axis = 0; axis < 2; ++axis) {
      const Index u0 = axis == 0 ? ix_u() : iy_u(), f0 = axis == 0 ? ix_f() : iy_f();
      const auto& c = axis == 0 ? state_.com_x : state_.com_y;
      const VectorX& ref = axis == 0 ? ref_x_ : ref_y_;
      const Scalar f = axis == 0 ? state_.support.x : state_.support.y;
      VectorX& z = axis == 0 ? Zx_ : Zy_;  // scratch: P_zs c − v f, then velocity error
      z.noalias() = lipm_.P_zs * c;
      for (Index j = 0; j < N_; ++j) {
        if (step_of_[j] == 0) z[j] -= f;
      }
      auto gu = g_.segment(u0, N_);
      gu.noalias() = b * lipm_.P_zu.transpose() * z;
      for (Index i = 0; i < nf_; ++i) g_[f0 + i] = -eps * U_prev_[f0 + i];
      g_.segment(f0, nf_).noalias() -=
          step_weight() * D_.transpose() * (axis == 0 ? step_target_x_ : step_target_y_);
      for (Index j = 0; j < N_; ++j) {
        const int s = step_of_[j];
        if (s > 0) g_[f0 + s - 1] -= b * z[j];
      }
      z.noalias() = lipm_.P_vs * c;  // velocity error at U = 0
      z -= ref;
      gu.noalias() += a * lipm_.P_vu.transpose() * z;
    }
    {
      const Scalar w = yaw_weight();
      auto gq = g_.segment(iq_f(), nf_);
      gq.noalias() = -w * D_.transpose() * yaw_target_;
      gq -= eps * U_prev_.segment(iq_f(), nf_);
    }
    linearise(U_prev_, &A_, nullptr, lb_, ub_);
  }

  /// Largest violation max(lb − c(U), c(U) − ub, 0) of the nonlinear constraints at U.
  Scalar violation(const VectorX& U) {
    linearise(U, nullptr, &c_, c_lower_, c_upper_);
    Scalar worst = Scalar(0);
    for (Index r = 0; r < c_.size(); ++r) {
      worst = std::max({worst, c_lower_[r] - c_[r], c_[r] - c_upper_[r]});
    }
    return worst;
  }

  /// One polygon edge a in a frame rotated by θ applied to w: value aᵀR(θ)ᵀw, the row ρ = aᵀR(θ)ᵀ
  /// (∂/∂w) and dq = ∂value/∂θ (the rotation's derivative, different in every row).
  struct Edge {
    Scalar rx, ry, dq, value;
  };
  static Edge rotated_edge(Scalar ax, Scalar ay, Scalar cq, Scalar sq, Scalar wx, Scalar wy) {
    const Scalar rx = ax * cq - ay * sq, ry = ax * sq + ay * cq;
    const Scalar dq = (-ax * sq - ay * cq) * wx + (ax * cq - ay * sq) * wy;
    return {rx, ry, dq, rx * wx + ry * wy};
  }
  /// Writes the columns of footstep i (w = … − F_i, rotated by θ_i) into a row: −ρ for x and y,
  /// dq for θ_i. Returns their part of J U.
  template <typename Row>
  Scalar footstep_columns(const Edge& ed, Index i, const VectorX& U, Row& row) const {
    row[ix_f() + i - 1] = -ed.rx;
    row[iy_f() + i - 1] = -ed.ry;
    row[iq_f() + i - 1] = ed.dq;
    return -ed.rx * U[ix_f() + i - 1] - ed.ry * U[iy_f() + i - 1] + ed.dq * U[iq_f() + i - 1];
  }

  /// The rows a_eᵀ R(θ)ᵀ w ≤ b_e of one polygon, from row r on (advanced past them). `columns`
  /// writes the Jacobian columns of w (and θ) into a row and returns their part of J U.
  template <typename PolyA, typename PolyB, typename Columns>
  void polygon_rows(const PolyA& A, const PolyB& bb, Scalar q, Scalar wx, Scalar wy, RowMatrixX* J,
                    VectorX* c, VectorX& lower, VectorX& upper, Index& r, Columns&& columns) const {
    using std::cos;
    using std::sin;
    const Scalar cq = cos(q), sq = sin(q);
    for (Index e = 0; e < A.rows(); ++e, ++r) {
      const Edge ed = rotated_edge(A(e, 0), A(e, 1), cq, sq, wx, wy);
      lower[r] = -kInf;
      upper[r] = bb[e];
      if (c != nullptr) (*c)[r] = ed.value;
      if (J == nullptr) continue;
      auto row = J->row(r);
      upper[r] -= ed.value - columns(ed, row);  // J U' ≤ b − (c(U) − J U)
    }
  }

  /// Constraint rows at U. With J != nullptr: the Gauss–Newton rows J ΔU around U folded into
  /// lb ≤ J U' ≤ ub (bounds shifted by c(U) − J U). With c != nullptr: the values c(U) and
  /// their bounds. Rows: ZMP (N·FootEdges), feasibility (nf·HullEdges), relative yaw (nf),
  /// relative yaw rate (nf), obstacles (nf·capacity).
  void linearise(const VectorX& U, RowMatrixX* J, VectorX* c, VectorX& lower,
                 VectorX& upper) const {
    using std::cos;
    using std::sin;
    if (J != nullptr) J->setZero();
    Index r = 0;
    auto theta = [&](Index i) { return i == 0 ? state_.support.q : U[iq_f() + i - 1]; };
    auto fx = [&](Index i) { return i == 0 ? state_.support.x : U[ix_f() + i - 1]; };
    auto fy = [&](Index i) { return i == 0 ? state_.support.y : U[iy_f() + i - 1]; };
    // ZMP rows (eq. 2.65–2.69): a_eᵀ R(θ_s)ᵀ (z_j − F_s) ≤ b_e.
    for (Index j = 0; j < N_; ++j) {
      const Index s = (state_.phase + j) / S_;
      const Foot foot = foot_of_step(s);
      const auto& A = foot_A_[index(foot)];
      const auto& bb = foot_b_[index(foot)];
      const Scalar zx =
          lipm_.P_zs.row(j).dot(state_.com_x) + lipm_.P_zu.row(j).dot(U.segment(ix_u(), N_));
      const Scalar zy =
          lipm_.P_zs.row(j).dot(state_.com_y) + lipm_.P_zu.row(j).dot(U.segment(iy_u(), N_));
      const Scalar wx = zx - fx(s), wy = zy - fy(s);
      polygon_rows(A, bb, theta(s), wx, wy, J, c, lower, upper, r, [&](const Edge& ed, auto& row) {
        row.segment(ix_u(), j + 1) = ed.rx * lipm_.P_zu.row(j).head(j + 1);
        row.segment(iy_u(), j + 1) = ed.ry * lipm_.P_zu.row(j).head(j + 1);
        Scalar lin = ed.rx * lipm_.P_zu.row(j).head(j + 1).dot(U.segment(ix_u(), j + 1)) +
                     ed.ry * lipm_.P_zu.row(j).head(j + 1).dot(U.segment(iy_u(), j + 1));
        if (s > 0) lin += footstep_columns(ed, s, U, row);
        return lin;
      });
    }
    // Feasibility rows (eq. 2.70–2.72): a_eᵀ R(θ_{i−1})ᵀ (F_i − F_{i−1}) ≤ b_e, with the
    // polygon of the landing foot (never the other one: docs/design.md §4).
    for (Index i = 1; i <= nf_; ++i) {
      const Foot landing = foot_of_step(i);
      const auto& A = hull_A_[index(landing)];
      const auto& bb = hull_b_[index(landing)];
      const Scalar wx = fx(i) - fx(i - 1), wy = fy(i) - fy(i - 1);
      polygon_rows(A, bb, theta(i - 1), wx, wy, J, c, lower, upper, r,
                   [&](const Edge& ed, auto& row) {
                     row[ix_f() + i - 1] = ed.rx;
                     row[iy_f() + i - 1] = ed.ry;
                     Scalar lin = ed.rx * U[ix_f() + i - 1] + ed.ry * U[iy_f() + i - 1];
                     if (i > 1) lin += footstep_columns(ed, i - 1, U, row);
                     return lin;
                   });
    }
    // Relative yaw (eq. 2.73): |θ_i − θ_{i−1}| ≤ θ_max; relative yaw rate (eq. 2.74) on the
    // swing foot's quintic: 15/8 |θ_i − θ_origin| / t_ss ≤ θ̇_max. Linear in U.
    const Scalar t_ss = s_.t_step - s_.t_ds;
    const Scalar max_turn = Scalar(8) / Scalar(15) * s_.max_relative_yaw_rate * t_ss;
    for (int kind = 0; kind < 2; ++kind) {
      const Scalar limit = kind == 0 ? s_.max_relative_yaw : max_turn;
      for (Index i = 1; i <= nf_; ++i, ++r) {
        // Origin: the previous step (relative yaw), or where this foot lifts off (rate).
        Index o = kind == 0 ? i - 1 : i - 2;
        Scalar origin_value = Scalar(0);
        bool origin_is_var = false;
        if (o >= 1) {
          origin_value = U[iq_f() + o - 1];
          origin_is_var = true;
        } else {
          origin_value = o == 0 ? state_.support.q : state_.swing_origin.q;
        }
        const Scalar value = U[iq_f() + i - 1] - origin_value;
        lower[r] = -limit;
        upper[r] = limit;
        if (c != nullptr) (*c)[r] = value;
        if (J == nullptr) continue;
        (*J)(r, iq_f() + i - 1) = Scalar(1);
        if (origin_is_var) {
          (*J)(r, iq_f() + o - 1) = Scalar(-1);
        } else {
          lower[r] += origin_value;
          upper[r] += origin_value;
        }
      }
    }
    // Obstacles (eq. 2.79–2.82): ‖F_i − o‖ ≥ R + m. Linearising the distance (not its square,
    // as the thesis does) gives the tangent half-plane d̂ᵀ(F_i − o) ≥ R + m in the direction d̂
    // of the iterate from the centre: an inner approximation of the outside of the circle that
    // stays feasible when the iterate (e.g. a new step's guess) lies inside the circle, where
    // the squared form asks for a half-plane beyond reach.
    for (Index k = 0; k < cap_obstacles_; ++k) {
      for (Index i = 1; i <= nf_; ++i, ++r) {
        if (k >= Index(obstacles_.size())) {
          lower[r] = -kInf;
          upper[r] = kInf;
          if (c != nullptr) (*c)[r] = Scalar(0);
          continue;
        }
        const Obstacle& ob = obstacles_[std::size_t(k)];
        Scalar dx = fx(i) - ob.x, dy = fy(i) - ob.y;
        const Scalar value = std::sqrt(dx * dx + dy * dy);
        lower[r] = ob.radius + ob.margin;
        upper[r] = kInf;
        if (c != nullptr) (*c)[r] = value;
        if (J == nullptr) continue;
        if (value > Scalar(1e-9)) {
          dx /= value;
          dy /= value;
        } else {  // at the centre: leave it sideways of the support foot's heading
          dx = -sin(state_.support.q);
          dy = cos(state_.support.q);
        }
        (*J)(r, ix_f() + i - 1) = dx;
        (*J)(r, iy_f() + i - 1) = dy;
        lower[r] -= value - (dx * fx(i) + dy * fy(i));
      }
    }
    // Terminal capture point (capturability): ξ_N in the ZMP polygon of the last planned
    // footstep, a_eᵀ R(θ_nf)ᵀ (ξ_N − F_nf) ≤ b_e. Without it the plan may leave the pendulum
    // diverging beyond the horizon while every QP solves.
    {
      const Foot foot = foot_of_step(nf_);
      const Scalar xx = xi_s_.dot(state_.com_x) + xi_u_.dot(U.segment(ix_u(), N_));
      const Scalar xy = xi_s_.dot(state_.com_y) + xi_u_.dot(U.segment(iy_u(), N_));
      polygon_rows(foot_A_[index(foot)], foot_b_[index(foot)], theta(nf_), xx - fx(nf_),
                   xy - fy(nf_), J, c, lower, upper, r, [&](const Edge& ed, auto& row) {
                     row.segment(ix_u(), N_) = ed.rx * xi_u_;
                     row.segment(iy_u(), N_) = ed.ry * xi_u_;
                     return ed.rx * xi_u_.dot(U.segment(ix_u(), N_)) +
                            ed.ry * xi_u_.dot(U.segment(iy_u(), N_)) +
                            footstep_columns(ed, nf_, U, row);
                   });
    }
    (void)r;
  }

  Settings s_;
  Index S_, N_, nf_, cap_obstacles_, foot_edges_, hull_edges_;
  LipmPreview<Scalar, N> lipm_;
  LipmStep<Scalar> step_;
  DenseQp<Scalar> qp_;
  std::array<FootPolygon, 2> foot_A_;
  std::array<FootRhs, 2> foot_b_;
  std::array<HullPolygon, 2> hull_A_;
  std::array<HullRhs, 2> hull_b_;
  Eigen::Matrix<Scalar, N, N> HUU_;
  MatrixX D_, DtD_, Hqq_;
  VectorX yaw_target_, step_target_x_, step_target_y_;
  Eigen::Matrix<Scalar, 1, 3> xi_s_;
  Eigen::Matrix<Scalar, 1, N> xi_u_;
  MatrixX H_;
  VectorX g_;
  RowMatrixX A_;
  VectorX lb_, ub_, l_, u_;
  VectorX Zx_, Zy_, ref_x_, ref_y_, U_prev_, c_, c_lower_, c_upper_;
  std::vector<int> step_of_;
  std::vector<Obstacle> obstacles_;
  State state_;
  Plan plan_;
  Result result_;
  Vector3 command_ = Vector3::Zero();
  Index shifted_samples_ = 0, shifted_steps_ = 0;  // advance()s since the last solve()
};

}  // namespace walkgen
