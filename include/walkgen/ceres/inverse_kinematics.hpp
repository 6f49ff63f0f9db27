#pragma once
/// @file
/// Whole-body inverse kinematics by Levenberg–Marquardt through Ceres (thesis §2.4.2, eq.
/// 2.113–2.114; §6.2.3; settings of Table 6.2). Ceres adapter: target walkgen::ceres (Debian:
/// libceres-dev); the core never includes this header.
///
/// The residual is IkResidual (kinematics/ik_residual.hpp, Eigen only): the unknowns (base
/// position in W, rotation vector δ of the base relative to the warm start, joint angles q,
/// bounded here by the joint limits), the 21 weighted residuals (CoM, soles, sole tilt and yaw,
/// base and torso orientation) and their analytic Jacobian. This header wraps it into a Ceres
/// problem: the cost function (the analytic Jacobian by default, CeresIkSettings::derivatives;
/// IkDerivatives::automatic lets Ceres differentiate IkResidual::residual() on ceres::Jet
/// instead, the reference the analytic one is tested against), multi-start, warm starts and the
/// result. With 6 + 15 unknowns and 21 residuals the humanoid's problem is square: the CoM
/// target fixes the pelvis position, the orientation targets the pelvis and torso rotations,
/// and each leg reaches its sole.
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
#include <ceres/version.h>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <string>
#include <type_traits>
#include <vector>

#include "walkgen/core/exceptions.hpp"
#include "walkgen/core/math.hpp"
#include "walkgen/kinematics/ik_residual.hpp"
#include "walkgen/kinematics/ik_target.hpp"
#include "walkgen/kinematics/kinematic_tree.hpp"
#include "walkgen/robot/robot_description.hpp"

#if CERES_VERSION_MAJOR < 2 || (CERES_VERSION_MAJOR == 2 && CERES_VERSION_MINOR < 1)
#error "walkgen/ceres/inverse_kinematics.hpp needs Ceres >= 2.1 (ceres::SubsetManifold)"
#endif

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

/// "analytic" or "automatic", e.g. for logs; "unknown" for a value out of range.
constexpr const char* to_string(IkDerivatives derivatives) noexcept {
  switch (derivatives) {
    case IkDerivatives::analytic:
      return "analytic";
    case IkDerivatives::automatic:
      return "automatic";
  }
  return "unknown";
}

/// Settings of CeresInverseKinematics: the residual's (IkResidualSettings: body points, links,
/// weights), the keys of thesis Table 6.2 and their mapping onto Ceres, and the convergence test.
struct CeresIkSettings : IkResidualSettings {
  /// `n_init`: Ceres runs a cold solve may take (the first solve, or the first after
  /// set_initial_guess()). Run 1 starts from the initial guess; run k > 1 restarts from the
  /// initial guess with the free joints (all but held_joints) moved a deterministic pseudo-random
  /// part of the way towards a point inside their limits, so a start in a poor basin is left
  /// behind. A warm-started solve (a previous solve converged) runs once. Effect: more robustness
  /// to bad initial guesses for up to n_init times the cost.
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

  /// Jacobian of the residual: analytic (default) or Ceres' automatic differentiation. Both
  /// give the same LM iterates up to round-off; analytic is about 20 times faster per solve.
  IkDerivatives derivatives = IkDerivatives::analytic;

  /// Joints held at their initial-guess angles (set_initial_guess()): Ceres leaves them out of
  /// the unknowns (a ceres::SubsetManifold), so e.g. a humanoid's arms stay where they hang
  /// instead of swinging to place the CoM. Names of KinematicTree::joint_names().
  std::vector<std::string> held_joints;

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
  validate(static_cast<const IkResidualSettings&>(s));
  check_positive("CeresIkSettings.position_tolerance", s.position_tolerance);
  check_positive("CeresIkSettings.orientation_tolerance", s.orientation_tolerance);
}

/// The IK settings of `robot`: its sole frames, its torso body held upright (the base when it
/// names none) and the joints of its `held` joint groups held; the rest at their defaults.
inline CeresIkSettings ceres_ik_settings(const RobotDescription& robot) {
  CeresIkSettings s;
  s.left_foot_link = robot.sole_frames[0];
  s.right_foot_link = robot.sole_frames[1];
  s.torso_link = robot.torso_body.empty() ? robot.base_body : robot.torso_body;
  for (const JointGroup& group : robot.joint_groups) {
    if (group.held) {
      s.held_joints.insert(s.held_joints.end(), group.joints.begin(), group.joints.end());
    }
  }
  return s;
}

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
  static constexpr int kParameters = IkResidual<NumJoints>::kParameters;
  static constexpr int kResiduals = IkResidual<NumJoints>::kResiduals;
  /// Derivatives per Jet pass of the dynamic cost function.
  static constexpr int kDynamicStride = 8;
  using Jet = ceres::Jet<double, NumJoints == Eigen::Dynamic ? kDynamicStride : 6 + NumJoints>;

  /// Builds the solver on `tree` (a copy, plus one on ceres::Jet) and sets the initial guess to
  /// the base at the origin, upright, and q = 0 clamped into the joint limits; callers set a
  /// standing posture with set_initial_guess().
  /// @throws walkgen::invalid_argument for bad settings (validate()), a link or held joint name
  /// the tree lacks, or a tree whose joint count differs from NumJoints.
  explicit CeresInverseKinematics(const KinematicTree<double>& tree,
                                  const CeresIkSettings& settings = CeresIkSettings())
      : settings_(settings),
        residual_(tree, validated(settings)),
        ws_(residual_.make_workspace()),
        jet_tree_(residual_.tree().template cast<Jet>()),
        jet_ws_(jet_tree_.make_workspace()) {
    const int n = tree.num_joints();
    lower_ = tree.lower_limits();
    upper_ = tree.upper_limits();
    x_.setZero(6 + n);
    ceres::CostFunction* cost = nullptr;
    if (settings.derivatives == IkDerivatives::analytic) {
      cost = new AnalyticCost(*this);
    } else if constexpr (NumJoints == Eigen::Dynamic) {
      auto* dynamic =
          new ceres::DynamicAutoDiffCostFunction<JetCost, kDynamicStride>(new JetCost{this});
      dynamic->AddParameterBlock(6 + n);
      dynamic->SetNumResiduals(kResiduals);
      cost = dynamic;
    } else {
      cost = new ceres::AutoDiffCostFunction<JetCost, kResiduals, kParameters>(new JetCost{this});
    }
    cost_ = cost;
    problem_.AddResidualBlock(cost, nullptr, x_.data());
    for (int i = 0; i < n; ++i) {
      if (std::isfinite(lower_[i])) problem_.SetParameterLowerBound(x_.data(), 6 + i, lower_[i]);
      if (std::isfinite(upper_[i])) problem_.SetParameterUpperBound(x_.data(), 6 + i, upper_[i]);
    }
    held_ = Eigen::Array<bool, Eigen::Dynamic, 1>::Constant(n, false);
    std::vector<int> constant;
    const auto& names = tree.joint_names();
    for (const std::string& name : settings.held_joints) {
      const auto it = std::find(names.begin(), names.end(), name);
      check_argument(it != names.end(), "CeresIkSettings.held_joints",
                     "revolute joints of the tree " + detail::quoted_list(names),
                     detail::quote_name(name));
      const int i = static_cast<int>(it - names.begin());
      if (!held_[i]) constant.push_back(6 + i);
      held_[i] = true;
    }
    if (!constant.empty()) {
      problem_.SetManifold(x_.data(), new ceres::SubsetManifold(6 + n, constant));
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
    if (!target.all_finite()) {
      result.message = "a non-finite target: nothing was solved, the previous solution is kept";
      return result;  // invalid_input
    }
    target_ = target;
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
      best.message = "an error above its tolerance after every run: the previous solution is kept";
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
  /// base_rotation_W(), q), computed with settings().derivatives; the columns of held joints
  /// are included (Ceres' manifold drops them). For tests and diagnostics; the solution is not
  /// changed.
  /// @throws walkgen::invalid_argument for an x of the wrong size or a non-finite target or x.
  void residual_and_jacobian(const IkTarget& target, const Eigen::VectorXd& x,
                             Eigen::VectorXd& residual, Eigen::MatrixXd& jacobian) {
    const char* where = "CeresInverseKinematics::residual_and_jacobian";
    check_argument(x.size() == 6 + num_joints(), where, 6 + num_joints(), x.size(),
                   "base position, base rotation vector, then the joints");
    check_argument(target.all_finite() && x.allFinite(), where, "a finite target and x",
                   "NaN or inf");
    target_ = target;
    start_rotation_ = base_rotation_;
    residual.resize(kResiduals);
    Eigen::Matrix<double, kResiduals, Eigen::Dynamic, Eigen::RowMajor> J(kResiduals, x.size());
    const double* parameters[] = {x.data()};
    double* jacobians[] = {J.data()};
    cost_->Evaluate(parameters, residual.data(), jacobians);
    jacobian = J;
  }

  int num_joints() const { return residual_.num_joints(); }
  const KinematicTree<double>& tree() const { return residual_.tree(); }
  const CeresIkSettings& settings() const { return settings_; }
  /// The residual this solver minimises (for evaluating it without Ceres).
  const IkResidual<NumJoints>& residual() const { return residual_; }

 private:
  /// Ceres' automatic differentiation functor: IkResidual::residual() on the tree in T (double
  /// for residual-only evaluations, Jet for the Jacobian). One parameter block.
  struct JetCost {
    CeresInverseKinematics* ik;

    /// AutoDiffCostFunction's signature.
    template <typename T>
    bool operator()(const T* x, T* r) const {
      if constexpr (std::is_same<T, double>::value) {
        ik->residual_.residual(ik->target_, ik->start_rotation_, x, r, ik->residual_.tree(),
                               ik->ws_.fk);
      } else {
        ik->residual_.residual(ik->target_, ik->start_rotation_, x, r, ik->jet_tree_, ik->jet_ws_);
      }
      return true;
    }
    /// DynamicAutoDiffCostFunction's signature.
    template <typename T>
    bool operator()(T const* const* x, T* r) const {
      return (*this)(x[0], r);
    }
  };

  /// Ceres cost function of the analytic Jacobian: IkResidual::evaluate() in double, one
  /// parameter block of 6 + joints.
  class AnalyticCost final : public ceres::CostFunction {
   public:
    explicit AnalyticCost(CeresInverseKinematics& ik) : ik_(ik) {
      set_num_residuals(kResiduals);
      mutable_parameter_block_sizes()->push_back(ik.residual_.num_parameters());
    }
    bool Evaluate(double const* const* x, double* r, double** jacobians) const override {
      double* J = jacobians != nullptr ? jacobians[0] : nullptr;
      ik_.residual_.evaluate(ik_.target_, ik_.start_rotation_, x[0], r, J, ik_.ws_);
      return true;
    }

   private:
    CeresInverseKinematics& ik_;
  };

  /// `s` after validate() (the residual checks the tree: joint count and link names).
  static const CeresIkSettings& validated(const CeresIkSettings& s) {
    validate(s);
    return s;
  }

  /// Sets x_ to the start of run `run`. Run 0 starts from the current solution. Restarts move
  /// the free joints (held ones keep their guess) towards a pseudo-random point inside their
  /// limits: odd runs 20 % of the way from where the previous run ended (to leave a point stuck at
  /// a bound), even runs from the initial guess, farther each time (to leave a poor basin).
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
      if (held_[i]) continue;
      const double u = double(state >> 8) / double(1u << 24);  // [0, 1)
      const double lo = std::isfinite(lower_[i]) ? lower_[i] : q[i] - kPi;
      const double hi = std::isfinite(upper_[i]) ? upper_[i] : q[i] + kPi;
      q[i] += fraction * (lo + (0.1 + 0.8 * u) * (hi - lo) - q[i]);
    }
    start_rotation_ = R;
    x_.template head<3>() = p;
    x_.template segment<3>(3).setZero();
    x_.tail(q.size()) = q.cwiseMax(lower_).cwiseMin(upper_);
  }

  /// The base rotation of the iterate x_.
  Eigen::Matrix3d iterate_rotation() const {
    return IkResidual<NumJoints>::base_rotation(start_rotation_, x_.data());
  }

  /// Unweighted errors of the iterate x_.
  IkResult measure(const IkTarget& target) {
    return residual_.errors(target, start_rotation_, x_.data(), ws_);
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

  CeresIkSettings settings_;
  // The cost functions in problem_ point to these: declared before problem_.
  IkResidual<NumJoints> residual_;
  typename IkResidual<NumJoints>::Workspace ws_;
  KinematicTree<Jet> jet_tree_;
  typename KinematicTree<Jet>::Workspace jet_ws_;
  IkTarget target_;
  Eigen::Matrix3d start_rotation_ = Eigen::Matrix3d::Identity();  ///< R_start of the run
  ceres::Problem problem_;
  ceres::CostFunction* cost_ = nullptr;  // owned by problem_
  ceres::Solver::Options options_;
  Eigen::VectorXd x_, lower_, upper_, q_, guess_q_;
  Eigen::Vector3d base_position_, guess_position_;
  Eigen::Matrix3d base_rotation_, guess_rotation_;
  Eigen::Array<bool, Eigen::Dynamic, 1> held_;  ///< per joint: held at its guess
  bool warm_ = false;
  double warm_radius_ = 1.0;  ///< initial trust region radius of the next warm solve
};

}  // namespace walkgen
