#pragma once
/// @file
/// The residual of whole-body inverse kinematics and its analytic Jacobian (thesis §2.4.2, eq.
/// 2.113–2.114; §6.2.3): what a Levenberg–Marquardt solver minimises, as a model of its own.
/// Eigen only (docs/design.md convention 7): the residual is scalar-generic so that Ceres Jets
/// flow through it; walkgen::ceres (ceres/inverse_kinematics.hpp) wraps it into a solver.
///
/// Unknowns x (6 + joints): the floating base (root link) position in W [m], a rotation vector δ
/// of the base orientation relative to a start rotation R_start (R_base = R_start · exp([δ]×))
/// [rad], and the joint angles q [rad] in KinematicTree::joint_names() order. The velocity of
/// the tree differs from ẋ in the base rotation only: ω_W = R_start J_l(δ) δ̇.
///
/// Residuals (21 = kResiduals, seven blocks of three, each times its weight):
///   - rows 0–2: centre of mass (plus com_body_point, in the root frame) − target [m];
///   - rows 3–5 / 9–11: left / right sole point − target [m];
///   - rows 6–8 / 12–14: left / right sole orientation error against a flat sole turned by the
///     target yaw (flat: roll and pitch zero) [rad];
///   - rows 15–17: root link (pelvis) orientation error; rows 18–20: torso link orientation
///     error [rad]: the thesis holds the root frame so that the legs cannot drift into hip
///     dislocations on long walks; holding the torso upright as well fixes the torso joints.
/// An orientation error is the vector part of the rotation from target to actual,
/// vee(E − Eᵀ)/2 with E = R_targetᵀ R (sin of the angle times the axis): smooth, free of
/// divisions, and the angle itself for the small errors a solver sees.
///
/// Model / Workspace (convention 3): an IkResidual is immutable after construction; the FK and
/// Jacobian scratch live in a Workspace made once by make_workspace(); evaluate() and errors()
/// never touch the heap.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <string>

#include "walkgen/core/exceptions.hpp"
#include "walkgen/core/math.hpp"
#include "walkgen/kinematics/ik_target.hpp"
#include "walkgen/kinematics/kinematic_tree.hpp"

namespace walkgen {

/// What the IK residual constrains and how much each block weighs.
struct IkResidualSettings {
  /// `com_body_point`: offset of the constrained point from the whole-body CoM, in the root
  /// link's frame [m] (zero: the CoM itself, RBDL's "computed automatically").
  Eigen::Vector3d com_body_point = Eigen::Vector3d::Zero();
  /// `lf_body_point`, `rf_body_point`: the constrained point of each foot in its sole frame [m].
  Eigen::Vector3d lf_body_point = Eigen::Vector3d::Zero();
  Eigen::Vector3d rf_body_point = Eigen::Vector3d::Zero();

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
};

/// Throws walkgen::invalid_argument naming the first bad field of `s` (link names are checked
/// by IkResidual against its tree).
inline void validate(const IkResidualSettings& s) {
  check_argument(s.com_body_point.allFinite(), "IkResidualSettings.com_body_point",
                 "a finite offset [m]", "NaN or inf");
  check_argument(s.lf_body_point.allFinite(), "IkResidualSettings.lf_body_point",
                 "a finite offset [m]", "NaN or inf");
  check_argument(s.rf_body_point.allFinite(), "IkResidualSettings.rf_body_point",
                 "a finite offset [m]", "NaN or inf");
  check_positive("IkResidualSettings.com_weight", s.com_weight, "a finite weight > 0");
  check_positive("IkResidualSettings.foot_position_weight", s.foot_position_weight,
                 "a finite weight > 0");
  check_positive("IkResidualSettings.foot_orientation_weight", s.foot_orientation_weight,
                 "a finite weight > 0");
  check_positive("IkResidualSettings.base_orientation_weight", s.base_orientation_weight,
                 "a finite weight > 0");
  check_positive("IkResidualSettings.torso_orientation_weight", s.torso_orientation_weight,
                 "a finite weight > 0");
}

namespace detail {

/// exp([d]×) for a rotation vector d (3 entries): Rodrigues' formula, first order below
/// |d|² = machine epsilon. Scalar-generic; the same operations in the same order as
/// ceres::AngleAxisToRotationMatrix, so that both give the same bits.
template <typename T>
Eigen::Matrix<T, 3, 3> so3_exp(const T* d) {
  using std::cos;
  using std::sin;
  using std::sqrt;
  const T one(1.0);
  const T theta2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
  Eigen::Matrix<T, 3, 3> R;
  if (theta2 > T(std::numeric_limits<double>::epsilon())) {
    const T theta = sqrt(theta2);
    const T wx = d[0] / theta, wy = d[1] / theta, wz = d[2] / theta;
    const T c = cos(theta), s = sin(theta);
    // clang-format off
    R(0, 0) =     c   + wx*wx*(one - c);
    R(1, 0) =  wz*s   + wx*wy*(one - c);
    R(2, 0) = -wy*s   + wx*wz*(one - c);
    R(0, 1) =  wx*wy*(one - c)   - wz*s;
    R(1, 1) =     c   + wy*wy*(one - c);
    R(2, 1) =  wx*s   + wy*wz*(one - c);
    R(0, 2) =  wy*s   + wx*wz*(one - c);
    R(1, 2) = -wx*s   + wy*wz*(one - c);
    R(2, 2) =     c   + wz*wz*(one - c);
    // clang-format on
  } else {
    R(0, 0) = one;
    R(1, 0) = d[2];
    R(2, 0) = -d[1];
    R(0, 1) = -d[2];
    R(1, 1) = one;
    R(2, 1) = d[0];
    R(0, 2) = d[1];
    R(1, 2) = -d[0];
    R(2, 2) = one;
  }
  return R;
}

/// vee(E − Eᵀ)/2 with E = R_targetᵀ R: sin(angle)·axis of the rotation from target to actual.
template <typename T>
Eigen::Matrix<T, 3, 1> rotation_residual(const Eigen::Matrix3d& target,
                                         const Eigen::Matrix<T, 3, 3>& R) {
  const Eigen::Matrix<T, 3, 3> E = target.transpose().cast<T>() * R;
  return Eigen::Matrix<T, 3, 1>(E(2, 1) - E(1, 2), E(0, 2) - E(2, 0), E(1, 0) - E(0, 1)) * T(0.5);
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

}  // namespace detail

/// The whole-body IK residual r(x) and its Jacobian ∂r/∂x over a KinematicTree (see the file
/// comment). NumJoints: the tree's revolute joints at compile time (15 for walkgen's humanoid),
/// or Eigen::Dynamic.
template <int NumJoints = Eigen::Dynamic>
class IkResidual {
  static_assert(NumJoints == Eigen::Dynamic || NumJoints >= 1,
                "walkgen: NumJoints must be positive or Eigen::Dynamic");

 public:
  /// Unknowns: base position (3), base rotation vector (3), joints.
  static constexpr int kParameters = NumJoints == Eigen::Dynamic ? Eigen::Dynamic : 6 + NumJoints;
  static constexpr int kResiduals = 21;
  /// First row of each block of three (the file comment's order; the sides' orientation rows
  /// follow their position rows).
  static constexpr int kComRow = 0, kLeftSoleRow = 3, kRightSoleRow = 9, kBaseRow = 15,
                       kTorsoRow = 18;
  /// Names of the seven row blocks of three, in row order (for diagnostics).
  static constexpr std::array<const char*, 7> kRowBlocks = {"CoM",
                                                            "left sole position",
                                                            "left sole orientation",
                                                            "right sole position",
                                                            "right sole orientation",
                                                            "base orientation",
                                                            "torso orientation"};

  using Residual = Eigen::Matrix<double, kResiduals, 1>;
  /// Row major, as Ceres stores a Jacobian.
  using Jacobian = Eigen::Matrix<double, kResiduals, kParameters, Eigen::RowMajor>;

  /// FK poses and Jacobian scratch of evaluate() and errors(), made by make_workspace().
  struct Workspace {
    typename KinematicTree<double>::Workspace fk;
    Eigen::Matrix<double, 6, kParameters> frame_J;
    Eigen::Matrix<double, 3, kParameters> com_J;
  };

  /// @throws walkgen::invalid_argument for bad settings (validate()), a link name the tree
  /// lacks, or a tree whose joint count differs from NumJoints.
  explicit IkResidual(const KinematicTree<double>& tree,
                      const IkResidualSettings& settings = IkResidualSettings())
      : tree_(checked(tree, settings)),
        settings_(settings),
        left_(tree_.link_index(settings.left_foot_link)),
        right_(tree_.link_index(settings.right_foot_link)),
        torso_(tree_.link_index(settings.torso_link)) {}

  /// A workspace for this residual (allocates; do it once).
  Workspace make_workspace() const {
    const int n = tree_.num_velocities();
    return Workspace{tree_.make_workspace(), Eigen::Matrix<double, 6, kParameters>(6, n),
                     Eigen::Matrix<double, 3, kParameters>(3, n)};
  }

  /// The weighted residual r (21) of `target` at the unknowns x (6 + joints), the base rotation
  /// relative to `start_rotation`, by FK on `tree` in `ws`. Scalar-generic for automatic
  /// differentiation: `tree` is this residual's tree() cast to T (KinematicTree::cast()). No
  /// checks; for cost functions (evaluate() checks sizes).
  template <typename T>
  void residual(const IkTarget& target, const Eigen::Matrix3d& start_rotation, const T* x, T* r,
                const KinematicTree<T>& tree, typename KinematicTree<T>::Workspace& ws) const {
    using Vector3 = Eigen::Matrix<T, 3, 1>;
    forward(start_rotation, x, tree, ws);
    Eigen::Map<Eigen::Matrix<T, kResiduals, 1>> res(r);
    const int root = 0;
    const IkResidualSettings& s = settings_;
    const Vector3 com = tree.center_of_mass(ws) + ws.rotation_W(root) * s.com_body_point.cast<T>();
    res.template segment<3>(kComRow) = (com - target.com_W.cast<T>()) * T(s.com_weight);
    for (int side = 0; side < 2; ++side) {
      const int row = side == 0 ? kLeftSoleRow : kRightSoleRow;
      const int link = side == 0 ? left_ : right_;
      const SoleTarget& sole = side == 0 ? target.left_foot : target.right_foot;
      const Eigen::Vector3d& point = side == 0 ? s.lf_body_point : s.rf_body_point;
      const Vector3 p = ws.position_W(link) + ws.rotation_W(link) * point.cast<T>();
      res.template segment<3>(row) = (p - sole.position_W.cast<T>()) * T(s.foot_position_weight);
      res.template segment<3>(row + 3) =
          detail::rotation_residual(flat(sole.yaw), ws.rotation_W(link)) *
          T(s.foot_orientation_weight);
    }
    res.template segment<3>(kBaseRow) =
        detail::rotation_residual(target.base_rotation_W, ws.rotation_W(root)) *
        T(s.base_orientation_weight);
    res.template segment<3>(kTorsoRow) =
        detail::rotation_residual(target.torso_rotation_W, ws.rotation_W(torso_)) *
        T(s.torso_orientation_weight);
  }

  /// The residual r (21) and, where J is not null, its Jacobian ∂r/∂x (21 × (6 + joints), row
  /// major) at x (6 + joints), in double. No checks; for cost functions.
  void evaluate(const IkTarget& target, const Eigen::Matrix3d& start_rotation, const double* x,
                double* r, double* J, Workspace& ws) const {
    residual(target, start_rotation, x, r, tree_, ws.fk);
    if (J != nullptr) jacobian(target, start_rotation, x, J, ws);
  }

  /// The residual r and its Jacobian J = ∂r/∂x of `target` at the unknowns x (base position in
  /// W, rotation vector δ of the base relative to `start_rotation`, q). Allocation-free when J
  /// already has 6 + joints columns.
  /// @throws walkgen::invalid_argument for an x of the wrong size, a non-finite target or x, or
  /// a start_rotation that is not a rotation matrix.
  void evaluate(const IkTarget& target, const Eigen::Matrix3d& start_rotation,
                const Eigen::VectorXd& x, Residual& r, Jacobian& J, Workspace& ws) const {
    const char* where = "IkResidual::evaluate";
    check_argument(x.size() == tree_.num_velocities(), where, tree_.num_velocities(), x.size(),
                   "base position, base rotation vector, then the joints");
    check_argument(target.all_finite() && x.allFinite() && start_rotation.allFinite(), where,
                   "a finite target, start rotation and x", "NaN or inf");
    check_argument(start_rotation.isUnitary(1e-6), where, "a rotation matrix as start rotation",
                   "a matrix that is not orthonormal");
    J.resize(kResiduals, x.size());
    evaluate(target, start_rotation, x.data(), r.data(), J.data(), ws);
  }

  /// The base rotation R_start · exp([δ]×) of the unknowns x (δ = x[3..5]).
  template <typename T>
  static Eigen::Matrix<T, 3, 3> base_rotation(const Eigen::Matrix3d& start_rotation, const T* x) {
    return start_rotation.cast<T>() * detail::so3_exp(x + 3);
  }

  /// The unweighted errors of x against `target` in the error fields of an IkResult (com_error
  /// … torso_orientation_error; status, message, iterations, runs and cost keep their
  /// defaults): sole position (of the body points), yaw and tilt as the worse foot, base and
  /// torso as rotation angles. No checks; leaves x's FK in ws.
  IkResult errors(const IkTarget& target, const Eigen::Matrix3d& start_rotation, const double* x,
                  Workspace& ws) const {
    forward(start_rotation, x, tree_, ws.fk);
    const auto& fk = ws.fk;
    const IkResidualSettings& s = settings_;
    IkResult r;
    r.com_error =
        (tree_.center_of_mass(fk) + fk.rotation_W(0) * s.com_body_point - target.com_W).norm();
    r.foot_position_error = r.foot_yaw_error = r.foot_tilt_error = 0.0;
    for (int side = 0; side < 2; ++side) {
      const int link = side == 0 ? left_ : right_;
      const SoleTarget& sole = side == 0 ? target.left_foot : target.right_foot;
      const Eigen::Vector3d& point = side == 0 ? s.lf_body_point : s.rf_body_point;
      const Eigen::Matrix3d& R = fk.rotation_W(link);
      const double position = (fk.position_W(link) + R * point - sole.position_W).norm();
      const double yaw = angle_distance(yaw_of(R), sole.yaw);
      const double tilt = std::atan2(std::hypot(R(0, 2), R(1, 2)), R(2, 2));
      r.foot_position_error = std::max(r.foot_position_error, position);
      r.foot_yaw_error = std::max(r.foot_yaw_error, yaw);
      r.foot_tilt_error = std::max(r.foot_tilt_error, tilt);
    }
    r.base_orientation_error = detail::rotation_angle(target.base_rotation_W, fk.rotation_W(0));
    r.torso_orientation_error =
        detail::rotation_angle(target.torso_rotation_W, fk.rotation_W(torso_));
    return r;
  }

  const KinematicTree<double>& tree() const { return tree_; }
  const IkResidualSettings& settings() const { return settings_; }
  int num_joints() const { return tree_.num_joints(); }
  /// 6 + num_joints(): the size of x and the columns of the Jacobian.
  int num_parameters() const { return tree_.num_velocities(); }

 private:
  static const KinematicTree<double>& checked(const KinematicTree<double>& tree,
                                              const IkResidualSettings& settings) {
    validate(settings);
    check_argument(NumJoints == Eigen::Dynamic || tree.num_joints() == NumJoints,
                   "IkResidual: joints of the tree", NumJoints, tree.num_joints(),
                   "use NumJoints = Eigen::Dynamic or the tree's num_joints()");
    return tree;
  }

  /// FK of the unknowns x into ws.
  template <typename T>
  void forward(const Eigen::Matrix3d& start_rotation, const T* x, const KinematicTree<T>& tree,
               typename KinematicTree<T>::Workspace& ws) const {
    const Eigen::Map<const Eigen::Matrix<T, NumJoints, 1>> q(x + 6, tree.num_joints());
    tree.forward_kinematics(Eigen::Matrix<T, 3, 1>(x[0], x[1], x[2]),
                            base_rotation(start_rotation, x), q, ws);
  }

  static Eigen::Matrix3d flat(double yaw) {
    return Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  }

  /// The Jacobian ∂r/∂x, 21 × (6 + joints) row major, at the x of the residual() just run in
  /// double (ws.fk holds its FK). The tree's Jacobians map the generalised velocity
  /// v = (ṗ_W, ω_W, q̇) to point and angular velocities; x differs from v in the base rotation
  /// only: ω_W = R_start J_l(δ) δ̇ (J_l: left Jacobian of SO(3)). An orientation error
  /// r = vee(E − Eᵀ)/2, E = Tᵀ R, moves with Ṙ = [ω]× R by ṙ = ½ (tr(E) I − E) Tᵀ ω.
  void jacobian(const IkTarget& target, const Eigen::Matrix3d& start_rotation, const double* x,
                double* out, Workspace& ws) const {
    using Matrix3 = Eigen::Matrix3d;
    const int cols = tree_.num_velocities();
    Eigen::Map<Jacobian> J(out, kResiduals, cols);
    const IkResidualSettings& s = settings_;
    const auto& fk = ws.fk;
    auto& frame_J = ws.frame_J;
    auto& com_J = ws.com_J;
    const Matrix3 turn = start_rotation * detail::so3_left_jacobian(Eigen::Vector3d(x + 3));
    // Rows `row`..+2 = weight · A · (J_v with its angular-velocity columns turned into δ).
    auto put = [&](int row, double weight, const Matrix3& A, const auto& J_v) {
      J.template middleRows<3>(row).noalias() = weight * A * J_v;
      J.template block<3, 3>(row, 3) *= turn;
    };
    auto orientation = [&](const Eigen::Matrix3d& target_rotation, int link) {
      const Matrix3 E = target_rotation.transpose() * fk.rotation_W(link);
      return Matrix3((0.5 * (E.trace() * Matrix3::Identity() - E)) * target_rotation.transpose());
    };
    const int root = 0;
    tree_.center_of_mass_jacobian(fk, com_J);
    com_J.template middleCols<3>(3) -= skew(fk.rotation_W(root) * s.com_body_point);
    put(kComRow, s.com_weight, Matrix3::Identity(), com_J);
    for (int side = 0; side < 2; ++side) {
      const int row = side == 0 ? kLeftSoleRow : kRightSoleRow;
      const int link = side == 0 ? left_ : right_;
      const SoleTarget& sole = side == 0 ? target.left_foot : target.right_foot;
      tree_.frame_jacobian(fk, link, frame_J, side == 0 ? s.lf_body_point : s.rf_body_point);
      put(row, s.foot_position_weight, Matrix3::Identity(), frame_J.template topRows<3>());
      put(row + 3, s.foot_orientation_weight, orientation(flat(sole.yaw), link),
          frame_J.template bottomRows<3>());
    }
    frame_J.setZero();  // the root's angular velocity is v's entries 3..5
    frame_J.template block<3, 3>(3, 3).setIdentity();
    put(kBaseRow, s.base_orientation_weight, orientation(target.base_rotation_W, root),
        frame_J.template bottomRows<3>());
    tree_.frame_jacobian(fk, torso_, frame_J);
    put(kTorsoRow, s.torso_orientation_weight, orientation(target.torso_rotation_W, torso_),
        frame_J.template bottomRows<3>());
  }

  KinematicTree<double> tree_;
  IkResidualSettings settings_;
  int left_, right_, torso_;
};

}  // namespace walkgen
