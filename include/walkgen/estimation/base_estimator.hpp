#pragma once
/// @file
/// State estimation for a walking robot (issue 24): where its floating base and its centre of
/// mass are and how fast they move, from what the robot measures — the IMU's orientation, rate
/// and acceleration, the joint angles and speeds, and the feet's forces — not from the plan.
///
/// A linear Kalman filter over x = (p, v, s_l, s_r): the base position and velocity and the two
/// sole positions, all in the world frame W. The IMU's orientation is taken as the base's (a
/// robot's IMU reports a filtered orientation; MuJoCo's framequat is exact), which makes the
/// model linear (the formulation of Bloesch et al., "State estimation for legged robots",
/// RSS 2012, with the orientation known, as in Bledt et al., "MIT Cheetah 3", IROS 2018):
///
///   predict   p += v dt + a dt²/2,  v += a dt,  s_f unchanged     a = R_WI f_I + g (accelerometer)
///             process noise: accelerometer on (p, v); a sole in contact may slip a little
///             (sole_slip_noise), a swinging sole moves freely (swing_noise)
///   correct   s_f − p = R_WB fk_f(q)            for both soles (leg kinematics)
///             v = −(ω_W × r_f + J_f(q) q̇)        for each sole in contact (it does not move)
///
/// Contacts come from the feet's normal forces with hysteresis. The CoM is the kinematic tree's
/// at the estimated base pose, its velocity the CoM Jacobian times (v, ω, q̇). No heap memory
/// after construction; update() is O(1) in the horizon and O(links) in the tree.

#include <Eigen/Core>
#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "walkgen/core/exceptions.hpp"
#include "walkgen/kinematics/kinematic_tree.hpp"
#include "walkgen/robot/robot.hpp"
#include "walkgen/robot/robot_description.hpp"

namespace walkgen {

/// Tuning of BaseEstimator. Standard deviations of white noises; the defaults fit walkgen's
/// humanoid and the G1 in MuJoCo (docs/estimation.md has the measured errors).
struct BaseEstimatorSettings {
  /// Sole frames (left, right) in the kinematic tree: the points that stand still in contact.
  std::array<std::string, 2> sole_links;
  /// The IMU's axes in the base link's frame (R_BI). The IMU is taken to sit at the base
  /// link's origin (walkgen's humanoid's and the G1's do): its lever arm is not modelled.
  Eigen::Matrix3d imu_rotation_B = Eigen::Matrix3d::Identity();
  /// A foot is in contact from a normal force (the force reading turned into W by the sole's
  /// orientation from leg kinematics: the sensor's axes are taken as the sole's) above
  /// contact_on_ratio × the robot's weight and
  /// leaves contact below contact_off_ratio × weight (hysteresis: contact_off_ratio <
  /// contact_on_ratio).
  double contact_on_ratio = 0.15;
  double contact_off_ratio = 0.05;
  double acceleration_noise = 1.0;       ///< [m/s² /√Hz] the accelerometer
  double sole_slip_noise = 0.002;        ///< [m /√s] random walk of a sole in contact
  double swing_noise = 10.0;             ///< [m /√s] random walk of a sole in the air
  double kinematics_noise = 0.003;       ///< [m] a sole's position relative to the base from FK
  double contact_velocity_noise = 0.03;  ///< [m/s] the base velocity from a stance leg
  double gravity = 9.81;                 ///< [m/s²]
};

/// Checks the settings that do not need the tree (BaseEstimator's constructor calls this).
/// @throws walkgen::invalid_argument naming the first bad field.
inline void validate(const BaseEstimatorSettings& s) {
  check_argument(!s.sole_links[0].empty() && !s.sole_links[1].empty(),
                 "BaseEstimatorSettings.sole_links", "two link names (left, right)",
                 "'" + s.sole_links[0] + "', '" + s.sole_links[1] + "'");
  check_argument(
      s.imu_rotation_B.allFinite() &&
          (s.imu_rotation_B.transpose() * s.imu_rotation_B - Eigen::Matrix3d::Identity()).norm() <
              1e-9 &&
          s.imu_rotation_B.determinant() > 0.0,
      "BaseEstimatorSettings.imu_rotation_B", "a rotation matrix",
      "a matrix that is not orthonormal with determinant 1");
  check_argument(s.contact_off_ratio > 0.0 && s.contact_off_ratio < s.contact_on_ratio &&
                     s.contact_on_ratio < 1.0,
                 "BaseEstimatorSettings.contact_on_ratio, contact_off_ratio",
                 "0 < contact_off_ratio < contact_on_ratio < 1",
                 std::to_string(s.contact_on_ratio) + ", " + std::to_string(s.contact_off_ratio));
  for (const auto& [name, value] :
       {std::pair<const char*, double>{"acceleration_noise", s.acceleration_noise},
        {"sole_slip_noise", s.sole_slip_noise},
        {"swing_noise", s.swing_noise},
        {"kinematics_noise", s.kinematics_noise},
        {"contact_velocity_noise", s.contact_velocity_noise},
        {"gravity", s.gravity}}) {
    check_positive((std::string("BaseEstimatorSettings.") + name).c_str(), value);
  }
}

/// The estimator settings of `robot`: its sole frames; the rest at their defaults.
inline BaseEstimatorSettings base_estimator_settings(const RobotDescription& robot) {
  BaseEstimatorSettings s;
  s.sole_links = robot.sole_frames;
  return s;
}

/// What BaseEstimator::update() made of a measurement.
enum class EstimateStatus : std::uint8_t {
  ok,            ///< the estimate moved on with the measurement
  not_started,   ///< reset() has not been called
  no_imu,        ///< the robot reports no IMU: nothing to estimate with
  sensor_fault,  ///< a non-finite or malformed reading: the estimate kept as it was
};

/// "ok", "not_started", "no_imu" or "sensor_fault"; "unknown" for a value out of range.
constexpr const char* to_string(EstimateStatus status) noexcept {
  switch (status) {
    case EstimateStatus::ok:
      return "ok";
    case EstimateStatus::not_started:
      return "not_started";
    case EstimateStatus::no_imu:
      return "no_imu";
    case EstimateStatus::sensor_fault:
      return "sensor_fault";
  }
  return "unknown";
}

/// The estimated state, in the world frame W.
struct BaseEstimate {
  Eigen::Vector3d base_position_W = Eigen::Vector3d::Zero();  ///< [m] the base link's origin
  Eigen::Matrix3d base_rotation_W = Eigen::Matrix3d::Identity();
  Eigen::Vector3d base_velocity_W = Eigen::Vector3d::Zero();     ///< [m/s]
  Eigen::Vector3d angular_velocity_W = Eigen::Vector3d::Zero();  ///< [rad/s] the base's
  Eigen::Vector3d com_W = Eigen::Vector3d::Zero();               ///< [m] whole-body CoM
  Eigen::Vector3d com_velocity_W = Eigen::Vector3d::Zero();      ///< [m/s]
  std::array<Eigen::Vector3d, 2> sole_W{{Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()}};
  std::array<bool, 2> contact{{false, false}};  ///< indexed by Foot (left, right)
  /// [m] standard deviation of the base position along its least certain direction.
  double position_std = 0.0;
};

/// The Kalman filter of this file's header, for one robot and its kinematic tree.
class BaseEstimator {
 public:
  using Tree = KinematicTree<double>;

  /// @param tree the robot's kinematic tree (kept by reference: it must outlive the estimator)
  /// @param joint_names the robot's joints in measurement order (RobotOutput::q); each a
  ///   revolute joint of the tree; the tree's other joints are taken at 0
  /// @throws walkgen::invalid_argument for bad settings, unknown links or joints, or a tree
  ///   without mass.
  BaseEstimator(const Tree& tree, const std::vector<std::string>& joint_names,
                BaseEstimatorSettings settings)
      : tree_(tree), settings_(std::move(settings)), ws_(tree.make_workspace()) {
    validate(settings_);
    check_positive("BaseEstimator: the tree's mass", tree_.mass(), "a tree with mass");
    for (int f = 0; f < 2; ++f) sole_[f] = tree_.link_index(settings_.sole_links[f]);
    to_tree_.reserve(joint_names.size());
    for (const std::string& name : joint_names) to_tree_.push_back(tree_.joint_index(name));
    q_.setZero(tree_.num_joints());
    dq_.setZero(tree_.num_joints());
    nu_.setZero(tree_.num_velocities());
    J_.setZero(6, tree_.num_velocities());
    Jc_.setZero(3, tree_.num_velocities());
    weight_ = tree_.mass() * settings_.gravity;
  }

  /// Starts the estimate: the base at `base_position_W`, at rest, turned as the IMU says, the
  /// soles where the measured joints put them, the contacts from the measured forces.
  /// @return ok, or no_imu / sensor_fault (then not started).
  EstimateStatus reset(const Eigen::Vector3d& base_position_W, const RobotOutput& m) {
    started_ = false;
    const EstimateStatus status = read(m);
    if (status != EstimateStatus::ok) return status;
    if (!base_position_W.allFinite()) return EstimateStatus::sensor_fault;
    x_.setZero();
    x_.segment<3>(0) = base_position_W;
    kinematics(base_position_W);
    for (int f = 0; f < 2; ++f) {
      x_.segment<3>(6 + 3 * f) = ws_.position_W(sole_[f]);
      contact_[std::size_t(f)] = (ws_.rotation_W(sole_[f]) * m.ft[std::size_t(f)].force_S).z() >
                                 settings_.contact_on_ratio * weight_;
    }
    P_.setZero();
    P_.diagonal().setConstant(square(settings_.kinematics_noise));
    P_.block<3, 3>(3, 3).diagonal().setConstant(square(settings_.contact_velocity_noise));
    started_ = true;
    publish();
    return EstimateStatus::ok;
  }

  /// One filter step of `dt` seconds with the measurement taken at its end.
  /// @return ok; not_started before reset(); no_imu / sensor_fault (the estimate unchanged).
  /// @throws walkgen::invalid_argument for dt not finite and > 0 (a programming error); q, dq
  ///   of the wrong size are a malformed reading (sensor_fault).
  EstimateStatus update(const RobotOutput& m, double dt) {
    check_positive("BaseEstimator::update: dt", dt, "a duration > 0 [s]");
    if (!started_) return EstimateStatus::not_started;
    const EstimateStatus status = read(m);
    if (status != EstimateStatus::ok) return status;
    // Leg kinematics of the measured joints with the IMU's orientation: the soles relative to
    // the base (R_WB fk_f(q)) and their axes, whatever the base position.
    kinematics(x_.segment<3>(0));
    std::array<Eigen::Vector3d, 2> r;
    for (int f = 0; f < 2; ++f) {  // contacts, with hysteresis
      r[std::size_t(f)] = ws_.position_W(sole_[f]) - ws_.position_W(0);
      const double fz = (ws_.rotation_W(sole_[f]) * m.ft[std::size_t(f)].force_S).z();
      bool& c = contact_[std::size_t(f)];
      c = c ? fz > settings_.contact_off_ratio * weight_
            : fz > settings_.contact_on_ratio * weight_;
    }
    predict(dt);
    for (int f = 0; f < 2; ++f) correct_sole(f, r[std::size_t(f)]);
    for (int f = 0; f < 2; ++f) {
      if (!contact_[std::size_t(f)]) continue;
      // The sole's velocity J_f (v, ω, q̇) is zero: v = −(J_f[ω] ω + J_f[q̇] q̇).
      tree_.frame_jacobian(ws_, sole_[f], J_);
      const Eigen::Vector3d v_measured =
          -(J_.block(0, 3, 3, 3) * omega_W_ + J_.block(0, 6, 3, J_.cols() - 6) * dq_);
      correct_velocity(v_measured);
    }
    publish();
    return EstimateStatus::ok;
  }

  const BaseEstimate& estimate() const { return estimate_; }
  const BaseEstimatorSettings& settings() const { return settings_; }
  bool started() const { return started_; }

 private:
  using Vector12 = Eigen::Matrix<double, 12, 1>;
  using Matrix12 = Eigen::Matrix<double, 12, 12>;

  static double square(double x) { return x * x; }

  /// The measurement into q_, dq_, R_WB_, omega_W_, acc_W_; no_imu / sensor_fault when unusable.
  EstimateStatus read(const RobotOutput& m) {
    const auto n = Eigen::Index(to_tree_.size());
    if (m.q.size() != n || m.dq.size() != n) return EstimateStatus::sensor_fault;
    const ImuReading& imu = m.imu;
    if (!imu.available) return EstimateStatus::no_imu;
    if (!m.q.allFinite() || !m.dq.allFinite() || !imu.orientation_W_I.coeffs().allFinite() ||
        !imu.angular_velocity_I.allFinite() || !imu.acceleration_I.allFinite() ||
        !(std::abs(imu.orientation_W_I.norm() - 1.0) < 1e-3)) {
      return EstimateStatus::sensor_fault;
    }
    for (int f = 0; f < 2; ++f) {
      const ForceTorqueReading& r = m.ft[std::size_t(f)];
      if (!r.force_S.allFinite()) return EstimateStatus::sensor_fault;
    }
    for (std::size_t j = 0; j < to_tree_.size(); ++j) {
      q_[to_tree_[j]] = m.q[Eigen::Index(j)];
      dq_[to_tree_[j]] = m.dq[Eigen::Index(j)];
    }
    const Eigen::Matrix3d R_WI = imu.orientation_W_I.normalized().toRotationMatrix();
    R_WB_ = R_WI * settings_.imu_rotation_B.transpose();
    omega_W_ = R_WI * imu.angular_velocity_I;
    acc_W_ = R_WI * imu.acceleration_I - Eigen::Vector3d(0.0, 0.0, settings_.gravity);
    return EstimateStatus::ok;
  }

  /// Forward kinematics of the measured joints with the base at p and the IMU's orientation.
  void kinematics(const Eigen::Vector3d& p) { tree_.forward_kinematics(p, R_WB_, q_, ws_); }

  void predict(double dt) {
    x_.segment<3>(0) += x_.segment<3>(3) * dt + 0.5 * dt * dt * acc_W_;
    x_.segment<3>(3) += acc_W_ * dt;
    // P = F P Fᵀ + Q with F = I + dt (p ← v): F P adds dt × the velocity rows to the position
    // rows, (F P) Fᵀ dt × the velocity columns to the position columns.
    P_.topRows<3>() += dt * P_.middleRows<3>(3);
    P_.leftCols<3>() += dt * P_.middleCols<3>(3);
    const double qa = square(settings_.acceleration_noise);
    for (int i = 0; i < 3; ++i) {
      P_(i, i) += qa * dt * dt * dt / 3.0;
      P_(i, 3 + i) += qa * dt * dt / 2.0;
      P_(3 + i, i) += qa * dt * dt / 2.0;
      P_(3 + i, 3 + i) += qa * dt;
    }
    for (int f = 0; f < 2; ++f) {
      const double qs =
          square(contact_[std::size_t(f)] ? settings_.sole_slip_noise : settings_.swing_noise);
      P_.block<3, 3>(6 + 3 * f, 6 + 3 * f).diagonal().array() += qs * dt;
    }
  }

  /// s_f − p = r (leg kinematics), noise kinematics_noise.
  void correct_sole(int f, const Eigen::Vector3d& r) {
    Eigen::Matrix<double, 3, 12> H = Eigen::Matrix<double, 3, 12>::Zero();
    H.block<3, 3>(0, 0) = -Eigen::Matrix3d::Identity();
    H.block<3, 3>(0, 6 + 3 * f) = Eigen::Matrix3d::Identity();
    correct(H, r, square(settings_.kinematics_noise));
  }

  /// v = v_measured, noise contact_velocity_noise.
  void correct_velocity(const Eigen::Vector3d& v_measured) {
    Eigen::Matrix<double, 3, 12> H = Eigen::Matrix<double, 3, 12>::Zero();
    H.block<3, 3>(0, 3) = Eigen::Matrix3d::Identity();
    correct(H, v_measured, square(settings_.contact_velocity_noise));
  }

  /// The Kalman correction by z = H x + e, e ~ N(0, variance I): P ← P − K H P (with the optimal
  /// gain, the Joseph form's value), symmetrised. Written with P Hᵀ (12×3) rather than 12×12
  /// products: each fixed-size product costs every including file compile time.
  void correct(const Eigen::Matrix<double, 3, 12>& H, const Eigen::Vector3d& z, double variance) {
    const Eigen::Matrix<double, 12, 3> PHt = P_ * H.transpose();
    const Eigen::Matrix3d S = H * PHt + variance * Eigen::Matrix3d::Identity();
    const Eigen::Matrix<double, 12, 3> K = PHt * S.inverse();
    x_ += K * (z - H * x_);
    P_ -= K * PHt.transpose();
    P_ = 0.5 * (P_ + P_.transpose()).eval();
  }

  /// The estimate from the state: FK at the estimated base for the CoM and its Jacobian.
  void publish() {
    BaseEstimate& e = estimate_;
    e.base_position_W = x_.segment<3>(0);
    e.base_velocity_W = x_.segment<3>(3);
    e.base_rotation_W = R_WB_;
    e.angular_velocity_W = omega_W_;
    kinematics(e.base_position_W);
    e.com_W = tree_.center_of_mass(ws_);
    tree_.center_of_mass_jacobian(ws_, Jc_);
    nu_.head<3>() = e.base_velocity_W;
    nu_.segment<3>(3) = omega_W_;
    nu_.tail(nu_.size() - 6) = dq_;
    e.com_velocity_W = Jc_ * nu_;
    for (int f = 0; f < 2; ++f) {
      e.sole_W[std::size_t(f)] = x_.segment<3>(6 + 3 * f);
      e.contact[std::size_t(f)] = contact_[std::size_t(f)];
    }
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(P_.block<3, 3>(0, 0),
                                                             Eigen::EigenvaluesOnly);
    e.position_std = std::sqrt(std::max(0.0, eig.eigenvalues().maxCoeff()));
  }

  const Tree& tree_;
  BaseEstimatorSettings settings_;
  Tree::Workspace ws_;
  std::array<int, 2> sole_{{-1, -1}};
  std::vector<int> to_tree_;
  Eigen::VectorXd q_, dq_, nu_;
  Eigen::Matrix<double, 6, Eigen::Dynamic> J_;
  Eigen::Matrix<double, 3, Eigen::Dynamic> Jc_;
  double weight_ = 0.0;
  bool started_ = false;
  std::array<bool, 2> contact_{{false, false}};
  Eigen::Matrix3d R_WB_ = Eigen::Matrix3d::Identity();
  Eigen::Vector3d omega_W_ = Eigen::Vector3d::Zero();
  Eigen::Vector3d acc_W_ = Eigen::Vector3d::Zero();
  Vector12 x_ = Vector12::Zero();
  Matrix12 P_ = Matrix12::Identity();
  BaseEstimate estimate_;
};

}  // namespace walkgen
