#pragma once
/// @file
/// The NMPC as a formulation (thesis §2.2): WalkingModel, immutable after construction — the
/// settings, the row layout, the LIPM preview, the constraint blocks (mpc/constraints/) with
/// their polygons, the cost terms (mpc/costs/) and the constant part of their Hessian — and
/// WalkingWorkspace, what changes every tick — the schedule, the QP's data, scratch. The
/// driver (mpc/walking_mpc.hpp) owns one of each.
///
/// The two ordered lists below are the whole formulation: the constraint blocks in row order
/// (the layout takes each block's shape from them, in that order, so counting, assembly and
/// the warm-start shift cannot disagree) and the cost terms in summation order.

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "walkgen/core/exceptions.hpp"
#include "walkgen/model/lipm.hpp"
#include "walkgen/mpc/constraints/capture_point.hpp"
#include "walkgen/mpc/constraints/foot_separation.hpp"
#include "walkgen/mpc/constraints/footstep_feasibility.hpp"
#include "walkgen/mpc/constraints/obstacles.hpp"
#include "walkgen/mpc/constraints/relative_yaw.hpp"
#include "walkgen/mpc/constraints/zmp_polygon.hpp"
#include "walkgen/mpc/costs/footstep_regularization.hpp"
#include "walkgen/mpc/costs/heading.hpp"
#include "walkgen/mpc/costs/jerk.hpp"
#include "walkgen/mpc/costs/step_velocity.hpp"
#include "walkgen/mpc/costs/velocity_tracking.hpp"
#include "walkgen/mpc/costs/yaw_rate.hpp"
#include "walkgen/mpc/costs/zmp_centring.hpp"
#include "walkgen/mpc/settings.hpp"
#include "walkgen/mpc/walking_layout.hpp"
#include "walkgen/mpc/walking_schedule.hpp"
#include "walkgen/qp/dense_qp.hpp"

namespace walkgen {

/// What a tick computes: the schedule, the QP of the last SQP iteration and scratch. The QP's
/// data (H, g, A, lb ≤ A U ≤ ub, l ≤ U ≤ u) live once, in the solver: the model assembles them
/// in place into `qp.problem()` and the solver factorises them there (no copy per solve). Sized
/// once from the layout; public for tests and diagnostics (WalkingMpc::workspace() gives
/// read-only access).
template <typename Scalar>
struct WalkingWorkspace {
  using VectorX = MpcVector<Scalar>;
  static constexpr Scalar kInf = std::numeric_limits<Scalar>::infinity();

  WalkingSchedule<Scalar> schedule;
  /// The QP solver and its data: problem().H the Hessian (eq. 2.56), .g the gradient (eq. 2.57,
  /// 2.85), .A the constraint rows' Jacobian at `iterate` (eq. 2.86–2.88), .lb/.ub their bounds
  /// shifted by c(iterate) − A iterate, .l/.u the variable bounds (±∞ but the landing footstep
  /// when it is frozen).
  DenseQp<Scalar> qp;
  VectorX iterate;              ///< the U the QP was linearised at
  VectorX scratch;              ///< N entries for the cost terms
  VectorX c, c_lower, c_upper;  ///< c(U) and its bounds at the last plan (the violation)
  /// The elastic QP of the soft-constraint fallback (WalkingModel::soften): U and a slack pair
  /// per soft row; present when some block is soft (GeneratorSettings::soft).
  std::optional<DenseQp<Scalar>> elastic;

  /// @param soft_rows rows of the soft blocks (WalkingModel::soft_rows()); 0: no elastic QP
  explicit WalkingWorkspace(const WalkingLayout& L, Eigen::Index soft_rows = 0)
      : schedule(L.dims()),
        qp(L.num_vars(), L.num_rows()),
        iterate(VectorX::Zero(L.num_vars())),
        scratch(VectorX::Zero(L.dims().N)),
        c(VectorX::Zero(L.num_rows())),
        c_lower(VectorX::Zero(L.num_rows())),
        c_upper(VectorX::Zero(L.num_rows())) {
    if (soft_rows > 0) elastic.emplace(L.num_vars() + 2 * soft_rows, L.num_rows());
  }
};

/// The formulation. Template parameters as WalkingMpc's.
template <typename Scalar, int N, int FootEdges, int HullEdges>
class WalkingModel {
 public:
  using Index = Eigen::Index;
  using Settings = WalkingSettings<Scalar>;
  using VectorX = MpcVector<Scalar>;
  using MatrixX = MpcMatrix<Scalar>;
  using RowMatrixX = MpcRowMatrix<Scalar>;
  using Tick = WalkingTick<Scalar, N>;
  using Workspace = WalkingWorkspace<Scalar>;
  using Obstacle = CircleObstacle<Scalar>;

  /// The constraint blocks, in row order.
  using Constraints =
      std::tuple<ZmpPolygon<Scalar, N, FootEdges>, FootstepFeasibility<Scalar, HullEdges>,
                 RelativeYaw<Scalar>, FootSeparation<Scalar>, Obstacles<Scalar>,
                 CapturePoint<Scalar, N, FootEdges>>;
  /// The cost terms, in summation order.
  using Costs = std::tuple<FootstepRegularization<Scalar>, StepVelocity<Scalar>, YawRate<Scalar>,
                           Heading<Scalar>, VelocityTracking<Scalar, N>, ZmpCentring<Scalar, N>,
                           Jerk<Scalar>>;
  static constexpr int kNumConstraints = int(std::tuple_size<Constraints>::value);

  /// Validates the settings and builds the formulation.
  /// @param obstacle_capacity most obstacles a tick will be given (at least the settings' own)
  /// @throws walkgen::invalid_argument on invalid settings or sizes that contradict N,
  ///         FootEdges or HullEdges.
  explicit WalkingModel(const Settings& settings, Index obstacle_capacity = 0);

  const Settings& settings() const { return s_; }
  const WalkingLayout& layout() const { return layout_; }
  const LipmPreview<Scalar, N>& preview() const { return preview_; }
  const LipmStep<Scalar>& lipm_step() const { return step_; }
  const Constraints& constraints() const { return constraints_; }
  const Costs& costs() const { return costs_; }
  /// The Hessian's part that never changes: every cost term's constant blocks.
  const MatrixX& constant_hessian() const { return H_constant_; }

  /// Soft constraints (GeneratorSettings::soft): row block k's exact-penalty weight, 0 = hard.
  Scalar soft_weight(int k) const { return soft_weights_[std::size_t(k)]; }
  /// Rows of the soft blocks: the slack pairs of the elastic QP.
  Index soft_rows() const { return soft_rows_; }
  /// The elastic QP from the hard one: variables (U, s⁺, s⁻ of each soft row in row order),
  /// rows lb ≤ A U + s⁺ − s⁻ ≤ ub, s ≥ 0, cost ½UᵀHU + gᵀU + Σ w (s⁺ + s⁻ + (s⁺² + s⁻²)/2)
  /// (GeneratorSettings::soft). `elastic` is sized num_vars() + 2 soft_rows() by num_rows().
  template <class Problem>
  void soften(const Problem& hard, Problem& elastic) const;

  /// A plan's violation of the nonlinear constraints, hard and soft blocks apart.
  struct Violation {
    Scalar hard = Scalar(0);  ///< largest violation of a hard block's row
    Scalar soft = Scalar(0);  ///< largest violation of a soft block's row
    Scalar soft_change = std::numeric_limits<Scalar>::infinity();  ///< |soft − previous soft|
    std::uint32_t soft_blocks = 0;  ///< soft blocks violated beyond tol (bit k = row block k)
  };
  /// Splits c(U) against its bounds (violation()'s outputs) by block; `previous` is the split
  /// of the iteration before (for soft_change).
  Violation split_violation(const VectorX& c, const VectorX& lower, const VectorX& upper,
                            const Violation& previous, Scalar tol) const;
  /// max(lower − c, c − upper, 0) over the rows [first, first + count).
  static Scalar rows_violation(const VectorX& c, const VectorX& lower, const VectorX& upper,
                               Index first, Index count) {
    Scalar worst = Scalar(0);
    for (Index r = first; r < first + count; ++r)
      worst = std::max({worst, lower[r] - c[r], c[r] - upper[r]});
    return worst;
  }

  /// The view the blocks read, for a state, the obstacles in force and an iterate U.
  Tick tick(const WalkingState<Scalar>& state, const std::vector<Obstacle>& obstacles,
            const WalkingSchedule<Scalar>& schedule, const VectorX& iterate) const {
    return {s_, layout_, preview_, state, obstacles, schedule, iterate};
  }

  /// Calls f(block, its LayoutBlock) for every constraint block, in row order.
  template <typename F>
  void for_each_constraint(F&& f) const {
    for_each_constraint(f, std::make_integer_sequence<int, kNumConstraints>{});
  }

  /// The per-tick data that do not depend on the iterate: the schedule, and the bounds that
  /// freeze the landing footstep in the last interval before it touches down.
  /// `reference_heading` [rad]: the commanded heading now (WalkingMpc::reference_heading()).
  void prepare(const WalkingState<Scalar>& state, const Eigen::Matrix<Scalar, 3, 1>& command,
               Scalar reference_heading, const VectorX& plan, Workspace& w) const;

  /// H and g of the cost (eq. 2.51–2.60, gradient per docs/design.md §5) at t.iterate: the
  /// constant Hessian plus every cost term's tick part.
  void assemble_cost(const Tick& t, MatrixX& H, VectorX& g, VectorX& scratch) const;

  /// The nonlinear constraint values c(U) of eq. 2.65–2.82, for any scalar T (Jets included).
  template <typename T>
  void constraint_values(const Tick& t, const MpcVector<T>& U, MpcVector<T>& c) const {
    for_each_constraint(
        [&](const auto& b, const LayoutBlock& rows) { b.template values<T>(t, rows, U, c); });
  }
  /// Their bounds lower ≤ c(U) ≤ upper.
  void constraint_bounds(const Tick& t, VectorX& lower, VectorX& upper) const;
  /// The Gauss–Newton rows at U (eq. 2.86–2.88): J = ∂c/∂U, bounds shifted by c(U) − J U.
  void linearise(const Tick& t, const VectorX& U, RowMatrixX& J, VectorX& lower,
                 VectorX& upper) const;
  /// Largest violation max(lower − c(U), c(U) − upper, 0) of the nonlinear constraints at U;
  /// c, lower and upper receive the values and bounds.
  Scalar violation(const Tick& t, const VectorX& U, VectorX& c, VectorX& lower,
                   VectorX& upper) const;

 private:
  template <typename F, int... K>
  void for_each_constraint(F& f, std::integer_sequence<int, K...>) const {
    (f(std::get<K>(constraints_), layout_.rows(K)), ...);
  }

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

  static WalkingDims dims_of(const Settings& s, Index obstacle_capacity) {
    WalkingDims d;
    d.N = s.n;
    d.nf = s.planned_steps();
    d.S = s.samples_per_step();
    d.foot_edges = s.zmp_polygon.rows() > 0 ? s.zmp_polygon.rows() : 4;
    d.hull_edges = s.left_foot_convex_hull.rows();
    d.obstacles = std::max<Index>(obstacle_capacity, Index(s.obstacles.size()));
    return d;
  }

  /// The left sole's ZMP polygon (zmp_polygon, or the foot rectangle shrunk by security_margin,
  /// fig. 6.4), the soles' and the feasibility polygons' half-planes, the blocks.
  static Constraints make_constraints(const Settings& s, const LipmPreview<Scalar, N>& preview) {
    Eigen::Matrix<Scalar, Eigen::Dynamic, 2> sole = s.zmp_polygon;
    if (sole.rows() == 0) {
      const Scalar hx = s.foot_length / Scalar(2) - s.security_margin[0];
      const Scalar hy = s.foot_width / Scalar(2) - s.security_margin[1];
      sole.resize(4, 2);
      sole << hx, hy, -hx, hy, -hx, -hy, hx, -hy;
    }
    Eigen::Matrix<Scalar, Eigen::Dynamic, 2> mirrored = sole;
    mirrored.col(1) *= Scalar(-1);
    const FootPolygons<Scalar, FootEdges> soles(sole, mirrored);
    const FootPolygons<Scalar, HullEdges> hulls(s.left_foot_convex_hull, s.right_foot_convex_hull);
    return Constraints(ZmpPolygon<Scalar, N, FootEdges>(soles),
                       FootstepFeasibility<Scalar, HullEdges>(hulls), RelativeYaw<Scalar>(s),
                       FootSeparation<Scalar>(s), Obstacles<Scalar>(),
                       CapturePoint<Scalar, N, FootEdges>(soles, preview));
  }

  Settings s_;
  WalkingLayout layout_;
  LipmPreview<Scalar, N> preview_;
  LipmStep<Scalar> step_;
  Constraints constraints_;
  Costs costs_;
  MatrixX H_constant_;
  std::array<Scalar, kNumConstraints> soft_weights_{};
  Index soft_rows_ = 0;

  /// Calls f(block k, row, column of its s⁺ (s⁻ is the next), weight) for every soft row.
  template <typename F>
  void for_each_soft_row(F&& f) const {
    Index j = layout_.num_vars();
    for (int k = 0; k < kNumConstraints; ++k) {
      const Scalar w = soft_weights_[std::size_t(k)];
      if (!(w > Scalar(0))) continue;
      const LayoutBlock& b = layout_.rows(k);
      for (Index r = b.offset; r < b.offset + b.count(); ++r, j += 2) f(k, r, j, w);
    }
  }
};

// ------------------------------------------------------------------------------------------------
// Implementation, outside the class so that it is not implicitly inline (see mpc/walking_mpc.hpp).

template <typename Scalar, int N, int FootEdges, int HullEdges>
WalkingModel<Scalar, N, FootEdges, HullEdges>::WalkingModel(const Settings& settings,
                                                            Index obstacle_capacity)
    : s_(checked(settings)),
      layout_(dims_of(s_, obstacle_capacity)),
      preview_(s_.t, s_.com_z, s_.gravity, s_.n),
      step_(s_.t),
      constraints_(make_constraints(s_, preview_)),
      costs_(FootstepRegularization<Scalar>(s_), StepVelocity<Scalar>(s_), YawRate<Scalar>(s_),
             Heading<Scalar>(s_), VelocityTracking<Scalar, N>(s_), ZmpCentring<Scalar, N>(s_),
             Jerk<Scalar>(s_)) {
  std::apply(
      [&](const auto&... block) {
        (layout_.add_rows(block.kName, block.shape(layout_.dims())), ...);
      },
      constraints_);
  H_constant_.setZero(layout_.num_vars(), layout_.num_vars());
  std::apply(
      [&](const auto&... cost) {
        (cost.add_constant_hessian(layout_, preview_, H_constant_), ...);
      },
      costs_);
  static_assert(kNumConstraints == 6,
                "walkgen: SoftConstraintWeights names one weight per constraint block");
  const auto& w = s_.soft;  // in the order of Constraints
  soft_weights_ = {w.zmp_polygon, w.footstep_feasibility, w.relative_yaw, w.foot_separation,
                   w.obstacles,   w.capture_point};
  for (int k = 0; k < kNumConstraints; ++k) {
    if (soft_weights_[std::size_t(k)] > Scalar(0)) soft_rows_ += layout_.rows(k).count();
  }
}

template <typename Scalar, int N, int FootEdges, int HullEdges>
template <class Problem>
void WalkingModel<Scalar, N, FootEdges, HullEdges>::soften(const Problem& hard,
                                                           Problem& elastic) const {
  const Index n = layout_.num_vars();
  elastic.H.setZero();
  elastic.H.topLeftCorner(n, n) = hard.H;
  elastic.g.head(n) = hard.g;
  elastic.A.setZero();
  elastic.A.leftCols(n) = hard.A;
  elastic.lb = hard.lb;
  elastic.ub = hard.ub;
  elastic.l.head(n) = hard.l;
  elastic.u.head(n) = hard.u;
  for_each_soft_row([&](int, Index r, Index j, Scalar w) {
    for (Index k = 0; k < 2; ++k) {
      elastic.A(r, j + k) = k == 0 ? Scalar(1) : Scalar(-1);
      elastic.H(j + k, j + k) = w;
      elastic.g[j + k] = w;
      elastic.l[j + k] = Scalar(0);
      elastic.u[j + k] = Workspace::kInf;
    }
  });
}

template <typename Scalar, int N, int FootEdges, int HullEdges>
auto WalkingModel<Scalar, N, FootEdges, HullEdges>::split_violation(const VectorX& c,
                                                                    const VectorX& lower,
                                                                    const VectorX& upper,
                                                                    const Violation& previous,
                                                                    Scalar tol) const -> Violation {
  Violation v;
  for (int k = 0; k < kNumConstraints; ++k) {
    const LayoutBlock& b = layout_.rows(k);
    const Scalar worst = rows_violation(c, lower, upper, b.offset, b.count());
    if (soft_weights_[std::size_t(k)] > Scalar(0)) {
      v.soft = std::max(v.soft, worst);
      if (worst > tol) v.soft_blocks |= 1u << k;
    } else {
      v.hard = std::max(v.hard, worst);
    }
  }
  v.soft_change = std::abs(v.soft - previous.soft);
  return v;
}

template <typename Scalar, int N, int FootEdges, int HullEdges>
void WalkingModel<Scalar, N, FootEdges, HullEdges>::prepare(
    const WalkingState<Scalar>& state, const Eigen::Matrix<Scalar, 3, 1>& command,
    Scalar reference_heading, const VectorX& plan, Workspace& w) const {
  w.schedule.update(s_, state, command, reference_heading);
  const bool frozen = state.phase == layout_.dims().S - 1;
  for (Index base : {layout_.step_x(), layout_.step_y(), layout_.step_q()}) {
    w.qp.problem().l[base] = frozen ? plan[base] : -Workspace::kInf;
    w.qp.problem().u[base] = frozen ? plan[base] : Workspace::kInf;
  }
}

template <typename Scalar, int N, int FootEdges, int HullEdges>
void WalkingModel<Scalar, N, FootEdges, HullEdges>::assemble_cost(const Tick& t, MatrixX& H,
                                                                  VectorX& g,
                                                                  VectorX& scratch) const {
  H = H_constant_;
  g.setZero();
  std::apply([&](const auto&... cost) { (cost.add(t, H, g, scratch), ...); }, costs_);
}

template <typename Scalar, int N, int FootEdges, int HullEdges>
void WalkingModel<Scalar, N, FootEdges, HullEdges>::constraint_bounds(const Tick& t, VectorX& lower,
                                                                      VectorX& upper) const {
  for_each_constraint(
      [&](const auto& b, const LayoutBlock& rows) { b.bounds(t, rows, lower, upper); });
}

template <typename Scalar, int N, int FootEdges, int HullEdges>
void WalkingModel<Scalar, N, FootEdges, HullEdges>::linearise(const Tick& t, const VectorX& U,
                                                              RowMatrixX& J, VectorX& lower,
                                                              VectorX& upper) const {
  J.setZero();
  for_each_constraint(
      [&](const auto& b, const LayoutBlock& rows) { b.linearise(t, rows, U, J, lower, upper); });
}

template <typename Scalar, int N, int FootEdges, int HullEdges>
Scalar WalkingModel<Scalar, N, FootEdges, HullEdges>::violation(const Tick& t, const VectorX& U,
                                                                VectorX& c, VectorX& lower,
                                                                VectorX& upper) const {
  constraint_values<Scalar>(t, U, c);
  constraint_bounds(t, lower, upper);
  return rows_violation(c, lower, upper, 0, c.size());
}

}  // namespace walkgen
