#pragma once
/// @file
/// Whole-body inverse kinematics by Levenberg–Marquardt through Ceres (thesis §2.4.2, eq.
/// 2.113–2.114; §6.2.3; settings of Table 6.2). Ceres adapter: target walkgen::ceres (Debian:
/// libceres-dev); the core never includes this header.
///
/// The residual is evaluated by the same KinematicTree forward kinematics as the rest of walkgen.
/// Its Jacobian is analytic by default (the tree's frame and CoM Jacobians after one FK in
/// double, CeresIkSettings::derivatives); IkDerivatives::automatic lets Ceres differentiate the
/// FK instantiated on ceres::Jet instead, the reference the analytic one is tested against.
/// Unknowns: the floating base (root link) position in W, a rotation vector δ of the
/// base orientation relative to the warm start (R_base = R_start · exp([δ]×)), and the joint
/// angles q, bounded by the joint limits. Residuals (21, each block times its weight):
///   - centre of mass − target (3) [m];
///   - per foot: sole point − target (3) [m], and the sole orientation error against a flat sole
///     turned by the target yaw (3) [rad]: flat = roll and pitch zero;
///   - root link (pelvis) orientation error (3) and torso link orientation error (3) [rad]: the
///     thesis holds the root frame so that the legs cannot drift into hip dislocations on long
///     walks; holding the torso upright as well fixes the torso joints.
/// With 6 + 15 unknowns and 21 residuals the humanoid's problem is square: the CoM target fixes
/// the pelvis position, the orientation targets the pelvis and torso rotations, and each leg
/// reaches its sole. An orientation error is the vector part of the rotation from target to
/// actual, vee(E − Eᵀ)/2 with E = R_targetᵀ R (sin of the angle times the axis): smooth, free of
/// divisions, and the angle itself for the small errors the solver sees.
///
/// Ceres runs LM with DENSE_NORMAL_CHOLESKY on the 21 × 21 system, without its projected line
/// search, and a warm solve starts with the trust region the previous one ended with.
///
/// Allocation: ceres::Solve allocates on every call (its preprocessor, evaluator and summary);
/// the solver is not allocation-free (docs/design.md convention 6 is waived for this adapter).
///
/// Errors (convention 10): bad settings, unknown link names and wrong sizes throw
/// walkgen::invalid_argument; a non-finite target returns IkStatus::invalid_input and an
/// unconverged solve IkStatus::not_converged, both keeping the previous solution.

#include <ceres/ceres.h>
#include <ceres/rotation.h>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <memory>
#include <string>
#include <type_traits>

#include "walkgen/core/exceptions.hpp"
#include "walkgen/core/math.hpp"
#include "walkgen/kinematics/ik_target.hpp"
#include "walkgen/kinematics/kinematic_tree.hpp"

namespace walkgen {

/// How Ceres gets the 21 × (6 + joints) Jacobian of the IK residual.
enum class IkDerivatives {
  /// From the tree's frame and centre-of-mass Jacobians (KinematicTree::frame_jacobian(),
  /// center_of_mass_jacobian()) after one FK in double, chained through the orientation error
  /// and the base rotation vector: a few µs per evaluation.
  analytic,
  /// Ceres' automatic differentiation over the same FK in ceres::Jet (AutoDiffCostFunction):
  /// the reference the analytic Jacobian is tested against, about 60 µs per evaluation.
  automatic,
};

/// Settings of CeresInverseKinematics: the keys of thesis Table 6.2, their mapping onto Ceres,
/// the links it constrains, weights and the convergence test.
struct CeresIkSettings {
  /// `n_init`: Ceres runs a cold solve may take (the first solve, or the first after
  /// set_initial_guess()). Run 1 starts from the initial guess; run k > 1 restarts from the
  /// initial guess with the joints moved a deterministic pseudo-random part of the way towards
  /// a point inside their limits, so a start in a poor basin is left behind. A warm-started solve
  /// (a previous solve converged) runs once. Effect: more robustness to bad initial guesses for
  /// up to n_init times the cost.
  int n_init = 10;
  /// `step_tol`: Ceres' parameter_tolerance, a run stops when the step is smaller than
  /// step_tol·(|x| + step_tol). Ceres' gradient_tolerance is step_tol·1e2, its function_tolerance
  /// 1e-14 (a run usually ends on the gradient once the residual is round-off).
  double step_tol = 1e-12;
  /// `lambda`: LM damping λ of eq. 2.114. Ceres' LM solves (JᵀJ + D/μ) Δq = −Jᵀr with a trust
  /// radius μ; initial_trust_region_radius = 1/lambda for a cold solve, then Ceres adapts μ each
  /// step; a warm solve starts from the μ the previous solve ended with (at least 1/lambda), so
  /// it takes Gauss–Newton steps at once. Smaller lambda: bolder first steps.
  double lambda = 1e-2;
  /// `num_steps`: Ceres' max_num_iterations per run.
  int num_steps = 1000;
  /// `com_body_point`: offset of the constrained point from the whole-body CoM, in the root
  /// link's frame [m] (zero: the CoM itself, RBDL's "computed automatically").
  Eigen::Vector3d com_body_point = Eigen::Vector3d::Zero();
  /// `lf_body_point`, `rf_body_point`: the constrained point of each foot in its sole frame [m].
  Eigen::Vector3d lf_body_point = Eigen::Vector3d::Zero();
  Eigen::Vector3d rf_body_point = Eigen::Vector3d::Zero();

  /// Jacobian of the residual: analytic (default) or Ceres' automatic differentiation. Both
  /// give the same LM iterates up to round-off; analytic is about 20 times faster per solve.
  IkDerivatives derivatives = IkDerivatives::analytic;

  std::string left_foot_link = "l_sole";   ///< sole frame of the left foot (z up when flat)
  std::string right_foot_link = "r_sole";  ///< sole frame of the right foot
  std::string torso_link = "chest";        ///< link whose orientation is held

  /// Weights of the residual blocks (dimensionless; a metre of CoM error costs as much as a
  /// radian of orientation error at weight 1). They matter only where targets conflict
  /// (unreachable): the heavier block is met more closely.
  double com_weight = 1.0;
  double foot_position_weight = 1.0;
  double foot_orientation_weight = 1.0;
  double base_orientation_weight = 1.0;
  double torso_orientation_weight = 1.0;

  /// A solve converges when every error of IkResult is at most these.
  double position_tolerance = 1e-6;     ///< [m]
  double orientation_tolerance = 1e-6;  ///< [rad]
};

/// Throws walkgen::invalid_argument naming the first bad field of `s` (link names are checked
/// by the solver against its tree).
inline void validate(const CeresIkSettings& s) {
  check_argument(s.n_init >= 1, "CeresIkSettings.n_init", "at least 1 run", s.n_init);
  check_positive("CeresIkSettings.step_tol", s.step_tol);
  check_positive("CeresIkSettings.lambda", s.lambda);
  check_argument(s.num_steps >= 1, "CeresIkSettings.num_steps", "at least 1 step", s.num_steps);
  check_argument(
      s.com_body_point.allFinite() && s.lf_body_point.allFinite() && s.rf_body_point.allFinite(),
      "CeresIkSettings body points", "finite offsets [m]", "NaN or inf");
  for (double w : {s.com_weight, s.foot_position_weight, s.foot_orientation_weight,
                   s.base_orientation_weight, s.torso_orientation_weight}) {
    check_positive("CeresIkSettings weights", w, "finite weights > 0");
  }
  check_positive("CeresIkSettings.position_tolerance", s.position_tolerance);
  check_positive("CeresIkSettings.orientation_tolerance", s.orientation_tolerance);
}

namespace detail {

/// vee(E − Eᵀ)/2 with E = R_targetᵀ R: sin(angle)·axis of the rotation from target to actual.
template <typename T>
Eigen::Matrix<T, 3, 1> rotation_residual(const Eigen::Matrix3d& target,
                                         const Eigen::Matrix<T, 3, 3>& R) {
  const Eigen::Matrix<T, 3, 3> E = target.transpose().cast<T>() * R;
  return Eigen::Matrix<T, 3, 1>(E(2, 1) - E(1, 2), E(0, 2) - E(2, 0), E(1, 0) - E(0, 1)) * T(0.5);
}

/// [v]×, the matrix of the cross product v × ·.
inline Eigen::Matrix3d skew(const Eigen::Vector3d& v) {
  Eigen::Matrix3d S;
  S << 0.0, -v.z(), v.y(),  //
      v.z(), 0.0, -v.x(),   //
      -v.y(), v.x(), 0.0;
  return S;
}

/// Left Jacobian of SO(3) at the rotation vector d: exp([d + ε]×) = exp([J_l ε]×) exp([d]×) to
/// first order in ε. J_l = I + (1 − cos θ)/θ² [d]× + (θ − sin θ)/θ³ [d]×², θ = |d|; Taylor
/// series for small θ.
inline Eigen::Matrix3d so3_left_jacobian(const Eigen::Vector3d& d) {
  const double t2 = d.squaredNorm();
  double a = 0.5 - t2 / 24.0, b = 1.0 / 6.0 - t2 / 120.0;  // error below θ⁴/720 < 2e-15
  if (t2 > 1e-6) {
    const double t = std::sqrt(t2);
    a = (1.0 - std::cos(t)) / t2;
    b = (t - std::sin(t)) / (t2 * t);
  }
  const Eigen::Matrix3d S = skew(d);
  return Eigen::Matrix3d::Identity() + a * S + b * S * S;
}

/// Angle of the rotation from a to b [rad], accurate for small angles.
inline double rotation_angle(const Eigen::Matrix3d& a, const Eigen::Matrix3d& b) {
  return Eigen::AngleAxisd(Eigen::Quaterniond(a.transpose() * b).normalized()).angle();
}

/// |x − y| wrapped to [0, π] [rad].
inline double angle_difference(double x, double y) {
  return std::abs(std::remainder(x - y, 2.0 * kPi));
}

}  // namespace detail

/// Whole-body Levenberg–Marquardt IK over a KinematicTree (see the file comment).
/// NumJoints: the tree's revolute joints at compile time (15 for walkgen's humanoid), or
/// Eigen::Dynamic (with automatic derivatives: Ceres' DynamicAutoDiffCostFunction, slower). Holds
/// the current solution (the warm start of the next solve). Not copyable or movable: Ceres keeps
/// pointers into it.
template <int NumJoints = Eigen::Dynamic>
class CeresInverseKinematics {
  static_assert(NumJoints == Eigen::Dynamic || NumJoints >= 1,
                "walkgen: NumJoints must be positive or Eigen::Dynamic");

 public:
  /// Unknowns: base position (3), base rotation vector (3), joints.
  static constexpr int kParameters = NumJoints == Eigen::Dynamic ? Eigen::Dynamic : 6 + NumJoints;
  static constexpr int kResiduals = 21;
  /// Derivatives per Jet pass of the dynamic cost function.
  static constexpr int kDynamicStride = 8;
  using Jet = ceres::Jet<double, NumJoints == Eigen::Dynamic ? kDynamicStride : 6 + NumJoints>;

  /// Builds the solver on `tree` (a copy, plus one on ceres::Jet) and sets the initial guess to
  /// the base at the origin, upright, and q = 0 clamped into the joint limits; callers set a
  /// standing posture with set_initial_guess().
  /// @throws walkgen::invalid_argument for bad settings (validate()), a link name the tree
  /// lacks, or a tree whose joint count differs from NumJoints.
  explicit CeresInverseKinematics(const KinematicTree<double>& tree,
                                  const CeresIkSettings& settings = CeresIkSettings())
      : settings_(settings) {
    validate(settings);
    const int n = tree.num_joints();
    check_argument(NumJoints == Eigen::Dynamic || n == NumJoints,
                   "CeresInverseKinematics: joints of the tree", NumJoints, n,
                   "use CeresInverseKinematics<Eigen::Dynamic> or the tree's num_joints()");
    residual_ = std::make_unique<Residual>(tree, settings);  // throws for unknown link names
    lower_ = tree.lower_limits();
    upper_ = tree.upper_limits();
    x_.setZero(6 + n);
    ceres::CostFunction* cost = nullptr;
    if (settings.derivatives == IkDerivatives::analytic) {
      cost = new AnalyticCost(*residual_);
    } else if constexpr (NumJoints == Eigen::Dynamic) {
      auto* dynamic = new ceres::DynamicAutoDiffCostFunction<Residual, kDynamicStride>(
          residual_.get(), ceres::DO_NOT_TAKE_OWNERSHIP);
      dynamic->AddParameterBlock(6 + n);
      dynamic->SetNumResiduals(kResiduals);
      cost = dynamic;
    } else {
      cost = new ceres::AutoDiffCostFunction<Residual, kResiduals, kParameters>(
          residual_.get(), ceres::DO_NOT_TAKE_OWNERSHIP);
    }
    cost_ = cost;
    problem_.AddResidualBlock(cost, nullptr, x_.data());
    for (int i = 0; i < n; ++i) {
      if (std::isfinite(lower_[i])) problem_.SetParameterLowerBound(x_.data(), 6 + i, lower_[i]);
      if (std::isfinite(upper_[i])) problem_.SetParameterUpperBound(x_.data(), 6 + i, upper_[i]);
    }
    options_.minimizer_type = ceres::TRUST_REGION;
    options_.trust_region_strategy_type = ceres::LEVENBERG_MARQUARDT;
    options_.linear_solver_type = ceres::DENSE_NORMAL_CHOLESKY;
    options_.max_num_iterations = settings.num_steps;
    options_.parameter_tolerance = settings.step_tol;
    options_.gradient_tolerance = settings.step_tol * 1e2;
    options_.function_tolerance = 1e-14;
    options_.initial_trust_region_radius = 1.0 / settings.lambda;
    options_.num_threads = 1;
    // Non-monotonic steps let LM cross the narrow valleys near the joint bounds (round-trip
    // success 99.2 % -> 100 % on the humanoid) and halve the iterations.
    options_.use_nonmonotonic_steps = true;
    // Steps that cross a joint bound are projected onto the bounds, without Ceres' projected line
    // search (which evaluates the Jacobian a second time per iteration).
    options_.max_num_line_search_step_size_iterations = 0;
    options_.logging_type = ceres::SILENT;
    options_.minimizer_progress_to_stdout = false;
    set_initial_guess(Eigen::Vector3d::Zero(), Eigen::Matrix3d::Identity(),
                      Eigen::VectorXd::Zero(n));
  }

  CeresInverseKinematics(const CeresInverseKinematics&) = delete;
  CeresInverseKinematics& operator=(const CeresInverseKinematics&) = delete;

  /// Sets the solution and the start of the next (cold) solve, as the thesis's SetQInit: the
  /// base pose in W and joint angles q [rad] (clamped into the joint limits).
  /// @throws walkgen::invalid_argument for a q of the wrong size or non-finite values.
  void set_initial_guess(const Eigen::Vector3d& base_position_W,
                         const Eigen::Matrix3d& base_rotation_W, const Eigen::VectorXd& q) {
    const char* where = "CeresInverseKinematics::set_initial_guess";
    check_argument(q.size() == num_joints(), where, num_joints(), q.size(),
                   "one angle per revolute joint, see KinematicTree::joint_names()");
    check_argument(base_position_W.allFinite() && base_rotation_W.allFinite() && q.allFinite(),
                   where, "a finite base pose and q", "NaN or inf");
    check_argument(base_rotation_W.isUnitary(1e-6), where, "a rotation matrix for the base",
                   "a matrix that is not orthonormal");
    base_position_ = base_position_W;
    base_rotation_ = Eigen::Quaterniond(base_rotation_W).normalized().toRotationMatrix();
    q_ = q.cwiseMax(lower_).cwiseMin(upper_);
    guess_position_ = base_position_;
    guess_rotation_ = base_rotation_;
    guess_q_ = q_;
    warm_ = false;
  }

  /// Solves for `target`, warm-started from the current solution. On convergence the solution
  /// is updated; otherwise it is kept and the status says why.
  [[nodiscard]] IkResult solve(const IkTarget& target) {
    IkResult result;
    if (!target.all_finite()) return result;  // invalid_input
    residual_->target_ = target;
    const int runs = warm_ ? 1 : settings_.n_init;
    IkResult best;
    for (int run = 0; run < runs; ++run) {
      start_run(run);
      // A warm solve starts with the trust region the previous solve ended with: near the last
      // solution LM takes Gauss–Newton steps at once (3.4 instead of 7.8 iterations a sample).
      options_.initial_trust_region_radius =
          run == 0 && warm_ ? warm_radius_ : 1.0 / settings_.lambda;
      ceres::Solver::Summary summary;
      ceres::Solve(options_, &problem_, &summary);
      result.iterations += summary.num_successful_steps + summary.num_unsuccessful_steps;
      result.runs = run + 1;
      IkResult current = measure(target);
      current.cost = summary.final_cost;
      if (!(current.cost >= best.cost)) {  // also replaces an infinite best
        best = current;
        if (converged(best)) {
          commit();
          best.status = IkStatus::converged;
          best.applied = true;
          warm_ = true;
          warm_radius_ = std::max(
              1.0 / settings_.lambda,
              summary.iterations.empty() ? 0.0 : summary.iterations.back().trust_region_radius);
          break;
        }
      }
    }
    if (best.status != IkStatus::converged) {
      best.status = IkStatus::not_converged;
      warm_radius_ = 1.0 / settings_.lambda;
    }
    best.iterations = result.iterations;
    best.runs = result.runs;
    return best;
  }

  /// The current solution: joint angles [rad] in KinematicTree::joint_names() order, and the
  /// base pose in W.
  const Eigen::VectorXd& q() const { return q_; }
  const Eigen::Vector3d& base_position_W() const { return base_position_; }
  const Eigen::Matrix3d& base_rotation_W() const { return base_rotation_; }

  /// The weighted residual (21) and its Jacobian d r / d x (21 × (6 + joints)) for `target` at
  /// the unknowns x = (base position in W, rotation vector δ of the base relative to
  /// base_rotation_W(), q), computed as Ceres sees them with settings().derivatives. For tests
  /// and diagnostics; the solution is not changed.
  /// @throws walkgen::invalid_argument for an x of the wrong size or a non-finite target or x.
  void residual_and_jacobian(const IkTarget& target, const Eigen::VectorXd& x,
                             Eigen::VectorXd& residual, Eigen::MatrixXd& jacobian) {
    const char* where = "CeresInverseKinematics::residual_and_jacobian";
    check_argument(x.size() == 6 + num_joints(), where, 6 + num_joints(), x.size(),
                   "base position, base rotation vector, then the joints");
    check_argument(target.all_finite() && x.allFinite(), where, "a finite target and x",
                   "NaN or inf");
    residual_->target_ = target;
    residual_->start_rotation_ = base_rotation_;
    residual.resize(kResiduals);
    Eigen::Matrix<double, kResiduals, Eigen::Dynamic, Eigen::RowMajor> J(kResiduals, x.size());
    const double* parameters[] = {x.data()};
    double* jacobians[] = {J.data()};
    cost_->Evaluate(parameters, residual.data(), jacobians);
    jacobian = J;
  }

  int num_joints() const { return residual_->tree_.num_joints(); }
  const KinematicTree<double>& tree() const { return residual_->tree_; }
  const CeresIkSettings& settings() const { return settings_; }

 private:
  /// The cost functor of Ceres' automatic differentiation over the tree's FK.
  struct Residual {
    Residual(const KinematicTree<double>& tree, const CeresIkSettings& s)
        : tree_(tree),
          jet_tree_(tree.template cast<Jet>()),
          ws_(tree_.make_workspace()),
          jet_ws_(jet_tree_.make_workspace()),
          left_(tree_.link_index(s.left_foot_link)),
          right_(tree_.link_index(s.right_foot_link)),
          torso_(tree_.link_index(s.torso_link)),
          s_(s),
          frame_J_(6, tree_.num_velocities()),
          com_J_(3, tree_.num_velocities()) {}

    /// AutoDiffCostFunction's signature (one parameter block).
    template <typename T>
    bool operator()(const T* x, T* r) const {
      return evaluate(x, r, tree_of<T>(), workspace_of<T>());
    }
    /// DynamicAutoDiffCostFunction's signature.
    template <typename T>
    bool operator()(T const* const* x, T* r) const {
      return evaluate(x[0], r, tree_of<T>(), workspace_of<T>());
    }

    template <typename T>
    const KinematicTree<T>& tree_of() const {
      if constexpr (std::is_same<T, double>::value) {
        return tree_;
      } else {
        return jet_tree_;
      }
    }
    template <typename T>
    typename KinematicTree<T>::Workspace& workspace_of() const {
      if constexpr (std::is_same<T, double>::value) {
        return ws_;
      } else {
        return jet_ws_;
      }
    }

    /// FK of the unknowns x (see the class comment) into ws.
    template <typename T>
    void forward(const T* x, const KinematicTree<T>& tree,
                 typename KinematicTree<T>::Workspace& ws) const {
      using Matrix3 = Eigen::Matrix<T, 3, 3>;
      Matrix3 turn;
      ceres::AngleAxisToRotationMatrix(x + 3, turn.data());  // column major, as Eigen's default
      const Matrix3 R = start_rotation_.cast<T>() * turn;
      const Eigen::Map<const Eigen::Matrix<T, NumJoints, 1>> q(x + 6, tree.num_joints());
      tree.forward_kinematics(Eigen::Matrix<T, 3, 1>(x[0], x[1], x[2]), R, q, ws);
    }

    template <typename T>
    bool evaluate(const T* x, T* r, const KinematicTree<T>& tree,
                  typename KinematicTree<T>::Workspace& ws) const {
      using Vector3 = Eigen::Matrix<T, 3, 1>;
      forward(x, tree, ws);
      Eigen::Map<Eigen::Matrix<T, kResiduals, 1>> res(r);
      const int root = 0;
      const Vector3 com =
          tree.center_of_mass(ws) + ws.rotation_W(root) * s_.com_body_point.cast<T>();
      res.template segment<3>(0) = (com - target_.com_W.cast<T>()) * T(s_.com_weight);
      int row = 3;
      for (int side = 0; side < 2; ++side, row += 6) {
        const int link = side == 0 ? left_ : right_;
        const SoleTarget& sole = side == 0 ? target_.left_foot : target_.right_foot;
        const Eigen::Vector3d& point = side == 0 ? s_.lf_body_point : s_.rf_body_point;
        const Vector3 p = ws.position_W(link) + ws.rotation_W(link) * point.cast<T>();
        res.template segment<3>(row) = (p - sole.position_W.cast<T>()) * T(s_.foot_position_weight);
        res.template segment<3>(row + 3) =
            detail::rotation_residual(flat(sole.yaw), ws.rotation_W(link)) *
            T(s_.foot_orientation_weight);
      }
      res.template segment<3>(15) =
          detail::rotation_residual(target_.base_rotation_W, ws.rotation_W(root)) *
          T(s_.base_orientation_weight);
      res.template segment<3>(18) =
          detail::rotation_residual(target_.torso_rotation_W, ws.rotation_W(torso_)) *
          T(s_.torso_orientation_weight);
      return true;
    }

    static Eigen::Matrix3d flat(double yaw) {
      return Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    }

    /// The residual Jacobian d r / d x, 21 × (6 + joints) row major as Ceres stores it, at the
    /// x of the last evaluate() in double (ws_ holds its FK). The tree's Jacobians map the
    /// generalised velocity v = (ṗ_W, ω_W, q̇) to point and angular velocities; x differs from v
    /// in the base rotation only: ω_W = R_start J_l(δ) δ̇ (J_l: left Jacobian of SO(3)). An
    /// orientation error r = vee(E − Eᵀ)/2, E = Tᵀ R, moves with Ṙ = [ω]× R by
    /// ṙ = ½ (tr(E) I − E) Tᵀ ω.
    void jacobian(const double* x, double* out) const {
      using Matrix3 = Eigen::Matrix3d;
      const int cols = tree_.num_velocities();
      Eigen::Map<Eigen::Matrix<double, kResiduals, kParameters, Eigen::RowMajor>> J(out, kResiduals,
                                                                                    cols);
      const Matrix3 turn = start_rotation_ * detail::so3_left_jacobian(Eigen::Vector3d(x + 3));
      // Rows `row`..+2 = weight · A · (J_v with its angular-velocity columns turned into δ).
      auto put = [&](int row, double weight, const Matrix3& A, const auto& J_v) {
        J.template middleRows<3>(row).noalias() = weight * A * J_v;
        J.template block<3, 3>(row, 3) *= turn;
      };
      auto orientation = [&](const Eigen::Matrix3d& target, int link) {
        const Matrix3 E = target.transpose() * ws_.rotation_W(link);
        return Matrix3((0.5 * (E.trace() * Matrix3::Identity() - E)) * target.transpose());
      };
      const int root = 0;
      tree_.center_of_mass_jacobian(ws_, com_J_);
      com_J_.template middleCols<3>(3) -= detail::skew(ws_.rotation_W(root) * s_.com_body_point);
      put(0, s_.com_weight, Matrix3::Identity(), com_J_);
      int row = 3;
      for (int side = 0; side < 2; ++side, row += 6) {
        const int link = side == 0 ? left_ : right_;
        const SoleTarget& sole = side == 0 ? target_.left_foot : target_.right_foot;
        tree_.frame_jacobian(ws_, link, frame_J_, side == 0 ? s_.lf_body_point : s_.rf_body_point);
        put(row, s_.foot_position_weight, Matrix3::Identity(), frame_J_.template topRows<3>());
        put(row + 3, s_.foot_orientation_weight, orientation(flat(sole.yaw), link),
            frame_J_.template bottomRows<3>());
      }
      frame_J_.setZero();  // the root's angular velocity is v's entries 3..5
      frame_J_.template block<3, 3>(3, 3).setIdentity();
      put(15, s_.base_orientation_weight, orientation(target_.base_rotation_W, root),
          frame_J_.template bottomRows<3>());
      tree_.frame_jacobian(ws_, torso_, frame_J_);
      put(18, s_.torso_orientation_weight, orientation(target_.torso_rotation_W, torso_),
          frame_J_.template bottomRows<3>());
    }

    KinematicTree<double> tree_;
    KinematicTree<Jet> jet_tree_;
    mutable typename KinematicTree<double>::Workspace ws_;
    mutable typename KinematicTree<Jet>::Workspace jet_ws_;
    int left_, right_, torso_;
    CeresIkSettings s_;
    mutable Eigen::Matrix<double, 6, kParameters> frame_J_;  ///< scratch of jacobian()
    mutable Eigen::Matrix<double, 3, kParameters> com_J_;
    IkTarget target_;
    Eigen::Matrix3d start_rotation_ = Eigen::Matrix3d::Identity();  ///< R_start of the run
  };

  /// Ceres cost function of the analytic Jacobian: the residual in double plus
  /// Residual::jacobian(), one parameter block of 6 + joints.
  class AnalyticCost final : public ceres::CostFunction {
   public:
    explicit AnalyticCost(const Residual& f) : f_(f) {
      set_num_residuals(kResiduals);
      mutable_parameter_block_sizes()->push_back(f.tree_.num_velocities());
    }
    bool Evaluate(double const* const* x, double* r, double** jacobians) const override {
      f_.evaluate(x[0], r, f_.tree_, f_.ws_);
      if (jacobians != nullptr && jacobians[0] != nullptr) f_.jacobian(x[0], jacobians[0]);
      return true;
    }

   private:
    const Residual& f_;
  };

  /// Sets x_ to the start of run `run`. Run 0 starts from the current solution. Restarts move
  /// the joints towards a pseudo-random point inside their limits: odd runs 20 % of the way from
  /// where the previous run ended (to leave a point stuck at a bound), even runs from the initial
  /// guess, farther each time (to leave a poor basin).
  void start_run(int run) {
    Eigen::VectorXd q = q_;
    Eigen::Vector3d p = base_position_;
    Eigen::Matrix3d R = base_rotation_;
    double fraction = 0.0;
    if (run % 2 == 1) {
      p = x_.template head<3>();
      R = iterate_rotation();
      q = x_.tail(q.size());
      fraction = 0.2;
    } else if (run > 0) {
      p = guess_position_;
      R = guess_rotation_;
      q = guess_q_;
      fraction = std::min(1.0, 0.2 * run);
    }
    unsigned state = 2654435761u * unsigned(run);
    for (Eigen::Index i = 0; i < q.size() && run > 0; ++i) {
      state = state * 1664525u + 1013904223u;
      const double u = double(state >> 8) / double(1u << 24);  // [0, 1)
      const double lo = std::isfinite(lower_[i]) ? lower_[i] : q[i] - kPi;
      const double hi = std::isfinite(upper_[i]) ? upper_[i] : q[i] + kPi;
      q[i] += fraction * (lo + (0.1 + 0.8 * u) * (hi - lo) - q[i]);
    }
    residual_->start_rotation_ = R;
    x_.template head<3>() = p;
    x_.template segment<3>(3).setZero();
    x_.tail(q.size()) = q.cwiseMax(lower_).cwiseMin(upper_);
  }

  /// The base rotation of the iterate x_.
  Eigen::Matrix3d iterate_rotation() const {
    Eigen::Matrix3d turn;
    ceres::AngleAxisToRotationMatrix(x_.data() + 3, turn.data());
    return residual_->start_rotation_ * turn;
  }

  /// Unweighted errors of the iterate x_.
  IkResult measure(const IkTarget& target) const {
    const Residual& f = *residual_;
    f.forward(x_.data(), f.tree_, f.ws_);
    const auto& ws = f.ws_;
    IkResult r;
    r.com_error =
        (f.tree_.center_of_mass(ws) + ws.rotation_W(0) * settings_.com_body_point - target.com_W)
            .norm();
    r.foot_position_error = r.foot_yaw_error = r.foot_tilt_error = 0.0;
    for (int side = 0; side < 2; ++side) {
      const int link = side == 0 ? f.left_ : f.right_;
      const SoleTarget& sole = side == 0 ? target.left_foot : target.right_foot;
      const Eigen::Vector3d& point = side == 0 ? settings_.lf_body_point : settings_.rf_body_point;
      const Eigen::Matrix3d& R = ws.rotation_W(link);
      const double position = (ws.position_W(link) + R * point - sole.position_W).norm();
      const double yaw = detail::angle_difference(std::atan2(R(1, 0), R(0, 0)), sole.yaw);
      const double tilt = std::atan2(std::hypot(R(0, 2), R(1, 2)), R(2, 2));
      r.foot_position_error = std::max(r.foot_position_error, position);
      r.foot_yaw_error = std::max(r.foot_yaw_error, yaw);
      r.foot_tilt_error = std::max(r.foot_tilt_error, tilt);
    }
    r.base_orientation_error = detail::rotation_angle(target.base_rotation_W, ws.rotation_W(0));
    r.torso_orientation_error =
        detail::rotation_angle(target.torso_rotation_W, ws.rotation_W(f.torso_));
    return r;
  }

  bool converged(const IkResult& r) const {
    const double p = settings_.position_tolerance, o = settings_.orientation_tolerance;
    return x_.allFinite() && r.com_error <= p && r.foot_position_error <= p &&
           r.foot_yaw_error <= o && r.foot_tilt_error <= o && r.base_orientation_error <= o &&
           r.torso_orientation_error <= o;
  }

  /// Takes x_ as the solution.
  void commit() {
    base_position_ = x_.template head<3>();
    base_rotation_ = iterate_rotation();
    q_ = x_.tail(num_joints());
  }

  std::unique_ptr<Residual> residual_;  // before problem_: its cost function points into it
  CeresIkSettings settings_;
  ceres::Problem problem_;
  ceres::CostFunction* cost_ = nullptr;  // owned by problem_
  ceres::Solver::Options options_;
  Eigen::VectorXd x_, lower_, upper_, q_, guess_q_;
  Eigen::Vector3d base_position_, guess_position_;
  Eigen::Matrix3d base_rotation_, guess_rotation_;
  bool warm_ = false;
  double warm_radius_ = 1.0;  ///< initial trust region radius of the next warm solve
};

}  // namespace walkgen
