#pragma once
/// @file
/// The robot interface (docs/design.md §1, "robot I/O"): joint position commands in; measured
/// joints, ankle force-torque sensors, chest stereo images and time out. Eigen only: a simulator
/// (walkgen/mujoco/mujoco_robot.hpp, target walkgen::mujoco) or a real robot implements it.
///
/// Also the measured zero moment point from the two ankle force-torque sensors (thesis §2.1.2,
/// eq. 2.11-2.17), a pure function of the readings.
///
/// Frames: W world (x forward, y left, z up), S an ankle sensor frame (z up through the sole
/// centre when the foot is flat, the sole d metres below its origin), C a camera frame (x along
/// the optical axis, y left, z up; models/README.md). Units SI.

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "walkgen/core/exceptions.hpp"
#include "walkgen/core/foot.hpp"

namespace walkgen {

/// What a robot reports after a step. Anything but `ok` means the robot stopped: step() does
/// nothing more until reset() (a backend never continues silently).
enum class RobotStatus : std::uint8_t {
  ok,        ///< stepping normally
  fallen,    ///< the base dropped below its fall height (80 % of nominal by default)
  diverged,  ///< the state became non-finite or the simulator gave up (bad accelerations)
};

/// "ok", "fallen" or "diverged", e.g. for logs; "unknown" for a value out of range.
constexpr const char* to_string(RobotStatus status) noexcept {
  switch (status) {
    case RobotStatus::ok:
      return "ok";
    case RobotStatus::fallen:
      return "fallen";
    case RobotStatus::diverged:
      return "diverged";
  }
  return "unknown";
}

/// The outcome of a joint command (convention 10c: numerical problems are a status, not thrown).
enum class JointCommandStatus : std::uint8_t {
  accepted,  ///< the targets are applied from the next step on
  rejected,  ///< a target was not finite: the previous targets are kept
};

/// "accepted" or "rejected", e.g. for logs; "unknown" for a value out of range.
constexpr const char* to_string(JointCommandStatus status) noexcept {
  switch (status) {
    case JointCommandStatus::accepted:
      return "accepted";
    case JointCommandStatus::rejected:
      return "rejected";
  }
  return "unknown";
}

/// One 6-axis ankle force-torque sensor (thesis fig. 2.3).
struct ForceTorqueReading {
  /// Force [N] that the foot below the sensor exerts on the leg above it, in the sensor frame S:
  /// f_z > 0 while the foot carries weight, about -(foot mass) g while it swings.
  Eigen::Vector3d force_S = Eigen::Vector3d::Zero();
  /// Torque [N m] of the same wrench about the sensor origin, in S.
  Eigen::Vector3d torque_S = Eigen::Vector3d::Zero();
  /// The sensor frame in the world: p_W = pose_W_S * p_S.
  Eigen::Isometry3d pose_W_S = Eigen::Isometry3d::Identity();
};

/// One inertial measurement unit on the robot's base or torso (MuJoCo: a site with the sensors
/// "<site>_quat" (framequat), "<site>_gyro" and "<site>_acc").
struct ImuReading {
  bool available = false;  ///< false: the robot has no IMU and the rest is unset
  /// The IMU frame I in the world (its tilt is the angle between I's z axis and W's).
  Eigen::Quaterniond orientation_W_I = Eigen::Quaterniond::Identity();
  Eigen::Vector3d angular_velocity_I = Eigen::Vector3d::Zero();  ///< [rad/s] gyroscope, in I
  /// [m/s^2] accelerometer (specific force: acceleration minus gravity), in I: +g along z at
  /// rest and upright.
  Eigen::Vector3d acceleration_I = Eigen::Vector3d::Zero();

  /// [rad] the angle between the IMU's z axis and the world's vertical.
  double tilt() const {
    const double c = (orientation_W_I * Eigen::Vector3d::UnitZ()).z();
    return std::acos(std::clamp(c, -1.0, 1.0));
  }
};

/// Everything a robot measures, at one instant.
struct RobotOutput {
  double time = 0.0;                     ///< [s] since reset()
  Eigen::VectorXd q;                     ///< measured joint positions [rad], joint_names() order
  Eigen::VectorXd dq;                    ///< measured joint velocities [rad/s], same order
  std::array<ForceTorqueReading, 2> ft;  ///< ankle sensors, indexed by Foot (left, right)
  ImuReading imu;                        ///< the base's or torso's IMU, when the robot has one
  double base_height = 0.0;              ///< [m] height of the floating base (root link) in W
  /// Joint torques [N m] of the last physics step, joint_names order: what the motors of a
  /// torque-controlled robot applied (after clamping), the servos' force for position servos.
  Eigen::VectorXd tau;
  /// Clamped torques since reset(): (joint, physics step) pairs whose commanded torque
  /// exceeded the motor's limit (torque drive only; 0 for position servos).
  long saturations = 0;
  RobotStatus status = RobotStatus::ok;
  std::string message;  ///< why, when status is not ok (e.g. "base height 0.31 m < 0.40 m")

  const ForceTorqueReading& sensor(Foot foot) const { return ft[static_cast<int>(foot)]; }
};

/// One camera image, rows from the top, columns from the left.
struct CameraImage {
  int width = 0;                  ///< [px]
  int height = 0;                 ///< [px]
  std::vector<std::uint8_t> rgb;  ///< width * height * 3 bytes, row-major
  std::vector<float> depth;       ///< [m] along the optical axis, width * height, row-major;
                                  ///< background (nothing hit) reads far_clip
  double near_clip = 0.0;         ///< [m] the depth range that can be measured
  double far_clip = 0.0;          ///< [m]
  double fovy = 0.0;              ///< vertical field of view [rad]
  Eigen::Isometry3d pose_W_C = Eigen::Isometry3d::Identity();  ///< camera frame in the world
};

/// Whether images could be produced (offscreen rendering needs a GL context).
enum class RenderStatus : std::uint8_t { ok, unavailable };

/// "ok" or "unavailable", e.g. for logs; "unknown" for a value out of range.
constexpr const char* to_string(RenderStatus status) noexcept {
  switch (status) {
    case RenderStatus::ok:
      return "ok";
    case RenderStatus::unavailable:
      return "unavailable";
  }
  return "unknown";
}

/// The chest stereo pair.
struct StereoImages {
  CameraImage left;
  CameraImage right;
  RenderStatus status = RenderStatus::unavailable;
  std::string message;  ///< "rendering unavailable: <why>" unless status is ok
};

/// How a robot's joints follow the commanded positions.
enum class JointDrive : std::uint8_t {
  position,  ///< position servos (the robot's own gains)
  torque,    ///< torque motors behind walkgen's joint controller (walkgen/robot/joint_control.hpp)
};

/// "position" or "torque", e.g. for logs; "unknown" for a value out of range.
constexpr const char* to_string(JointDrive drive) noexcept {
  switch (drive) {
    case JointDrive::position:
      return "position";
    case JointDrive::torque:
      return "torque";
  }
  return "unknown";
}

/// What does not change while the robot runs.
struct RobotInfo {
  std::vector<std::string> joint_names;  ///< the order of commands and measurements
  /// d [m]: sensor origin above the sole (eq. 2.11-2.12); 0 when the readings are the contact
  /// forces at the soles (a robot without ankle sensors).
  double ft_sensor_height = 0.0;
  JointDrive drive = JointDrive::position;  ///< how the joints follow the commands
  double nominal_base_height = 0.0;         ///< [m] base height standing (reset state)
  double fall_height = 0.0;                 ///< [m] below this base height the robot has fallen
  double timestep = 0.0;                    ///< [s] of one physics or control step
  int image_width = 0;                      ///< [px]
  int image_height = 0;                     ///< [px]
};

/// What the walking pattern asks of the robot's balance over the next command period, in the
/// frame of the planned support sole (x forward, y left, on the sole's plane): where the centre
/// of mass should be and how it should move, and where the ZMP is planned. A torque-driven
/// robot's controller may turn it into contact forces (MujocoRobot, JointFeedforward::balance);
/// a robot that does not use it ignores it.
struct BalanceReference {
  bool valid = false;
  int support = 0;                                ///< the sole of the frame: 0 left, 1 right
  Eigen::Vector2d com = Eigen::Vector2d::Zero();  ///< [m]
  Eigen::Vector2d com_velocity = Eigen::Vector2d::Zero();      ///< [m/s]
  Eigen::Vector2d com_acceleration = Eigen::Vector2d::Zero();  ///< [m/s^2]
  Eigen::Vector2d zmp = Eigen::Vector2d::Zero();               ///< [m]
  double com_height = 0.0;                                     ///< [m] above the sole
};

/// A robot: joint position targets in, measurements out. Blocks step (convention 13): the
/// application owns the loop, the clock and the threads.
class Robot {
 public:
  virtual ~Robot() = default;

  virtual const RobotInfo& info() const = 0;

  /// Joint position targets [rad] in info().joint_names order, applied from the next step on.
  /// @throws walkgen::invalid_argument when q_target has the wrong size.
  /// @return rejected (and the previous targets kept) when a target is not finite.
  [[nodiscard]] virtual JointCommandStatus set_joint_targets(
      const Eigen::Ref<const Eigen::VectorXd>& q_target) = 0;

  /// Advances by `duration` [s] (rounded to whole timesteps, at least one) and returns the status;
  /// once it is not ok, step() does nothing until reset().
  /// @throws walkgen::invalid_argument when duration is not finite and > 0.
  [[nodiscard]] virtual RobotStatus step(double duration) = 0;

  /// The balance the pattern asks for over the next step() (see BalanceReference); ignored
  /// unless the robot's controller uses it.
  virtual void set_balance_reference(const BalanceReference& reference) { (void)reference; }

  /// The latest measurements.
  virtual const RobotOutput& output() const = 0;

  /// Renders both chest cameras at the current state; status unavailable (with the reason) when
  /// there is no renderer.
  [[nodiscard]] virtual const StereoImages& render_cameras() = 0;

  /// Back to the initial state (time 0, status ok).
  virtual void reset() = 0;

 protected:
  Robot() = default;
  Robot(const Robot&) = default;
  Robot& operator=(const Robot&) = default;
};

/// The measured zero moment point and the weight it rests on.
struct MeasuredZmp {
  Eigen::Vector3d zmp_W = Eigen::Vector3d::Zero();  ///< [m] on the sole plane(s), world frame
  double normal_force = 0.0;  ///< [N] Σ f_z of the feet in contact (eq. 2.16 denominator)
  std::array<bool, 2> in_contact{{false, false}};  ///< per Foot: f_z >= min_normal_force
  bool valid = false;  ///< false when no foot carries min_normal_force (zmp_W is then zero)
};

/// The zero moment point from the two ankle force-torque sensors (thesis eq. 2.11-2.17).
///
/// Per foot in its sensor frame (eq. 2.11-2.12): p_S = ((-τ_y - f_x d) / f_z, (τ_x - f_y d) / f_z,
/// -d), i.e. the point on the sole where the wrench reduces to a force (zero horizontal moment);
/// then to the world with pose_W_S. Both feet (eq. 2.14-2.17): p = Σ p_i f_i,z / Σ f_i,z with f_i,z
/// the world vertical force, over the feet carrying at least min_normal_force (a swinging foot
/// only weighs on its sensor and would pull the average away).
///
/// @param ft  the left and right readings (index Foot), as in RobotOutput::ft
/// @param sensor_height  d [m], sensor origin above the sole, >= 0 (0: readings at the sole, as
///   a robot without ankle sensors reports its contact forces)
/// @param min_normal_force  [N] a foot counts as in contact from this vertical force, > 0
/// @throws walkgen::invalid_argument when sensor_height is not finite and >= 0 or
///   min_normal_force not finite and > 0.
inline MeasuredZmp measured_zmp(const std::array<ForceTorqueReading, 2>& ft, double sensor_height,
                                double min_normal_force = 5.0) {
  check_argument(std::isfinite(sensor_height) && sensor_height >= 0.0,
                 "measured_zmp: sensor_height", "a finite height >= 0 m", sensor_height);
  check_positive("measured_zmp: min_normal_force", min_normal_force, "a finite force > 0 N");
  MeasuredZmp result;
  Eigen::Vector3d weighted = Eigen::Vector3d::Zero();
  for (int i = 0; i < 2; ++i) {
    const ForceTorqueReading& r = ft[i];
    const double fz_S = r.force_S.z();
    const double fz_W = (r.pose_W_S.linear() * r.force_S).z();
    if (!(fz_S >= min_normal_force && fz_W >= min_normal_force)) continue;  // also NaN
    const Eigen::Vector3d p_S((-r.torque_S.y() - r.force_S.x() * sensor_height) / fz_S,
                              (r.torque_S.x() - r.force_S.y() * sensor_height) / fz_S,
                              -sensor_height);
    weighted += (r.pose_W_S * p_S) * fz_W;
    result.normal_force += fz_W;
    result.in_contact[i] = true;
  }
  if (result.normal_force > 0.0) {
    result.zmp_W = weighted / result.normal_force;
    result.valid = result.zmp_W.allFinite();
  }
  return result;
}

/// How far a measured ZMP lies inside the support polygon: the convex hull of the soles in
/// contact (MeasuredZmp::in_contact), each the quadrilateral `sole` (its corners in the sole's
/// plane, x forward, in any order; e.g. the contact points of a foot) around the point
/// sensor_height below its sensor origin along the sensor's z. Horizontal plane of the world
/// frame.
///
/// @return the distance [m] from the ZMP to the nearest edge when inside (≥ 0), the largest
///   violated edge distance, negated, when outside (< 0; for a convex polygon at most the
///   Euclidean distance); NaN when zmp is not valid.
/// @throws walkgen::invalid_argument when sensor_height is not finite and >= 0 or a corner is
///   not finite.
inline double support_polygon_margin(const MeasuredZmp& zmp,
                                     const std::array<ForceTorqueReading, 2>& ft,
                                     double sensor_height,
                                     const std::array<Eigen::Vector2d, 4>& sole) {
  check_argument(std::isfinite(sensor_height) && sensor_height >= 0.0,
                 "support_polygon_margin: sensor_height", "a finite height >= 0 m", sensor_height);
  for (const Eigen::Vector2d& c : sole) {
    check_argument(c.allFinite(), "support_polygon_margin: sole", "finite corners [m]",
                   "NaN or inf");
  }
  if (!zmp.valid) return std::numeric_limits<double>::quiet_NaN();
  std::array<Eigen::Vector2d, 8> corners;
  int n = 0;
  for (int i = 0; i < 2; ++i) {
    if (!zmp.in_contact[std::size_t(i)]) continue;
    const Eigen::Isometry3d& T = ft[std::size_t(i)].pose_W_S;
    for (const Eigen::Vector2d& c : sole) {
      corners[std::size_t(n++)] = (T * Eigen::Vector3d(c.x(), c.y(), -sensor_height)).head<2>();
    }
  }
  // Convex hull (Andrew's monotone chain) of at most 8 corners, counter-clockwise.
  for (int i = 1; i < n; ++i) {  // insertion sort by (x, y): at most 8 corners
    for (int j = i; j > 0; --j) {
      const Eigen::Vector2d& a = corners[std::size_t(j - 1)];
      const Eigen::Vector2d& b = corners[std::size_t(j)];
      if (a.x() < b.x() || (a.x() == b.x() && a.y() <= b.y())) break;
      std::swap(corners[std::size_t(j - 1)], corners[std::size_t(j)]);
    }
  }
  auto cross = [](const Eigen::Vector2d& o, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
    return (a.x() - o.x()) * (b.y() - o.y()) - (a.y() - o.y()) * (b.x() - o.x());
  };
  std::array<Eigen::Vector2d, 16> hull;
  int h = 0;
  for (int i = 0; i < n; ++i) {  // lower hull
    while (h >= 2 && cross(hull[std::size_t(h - 2)], hull[std::size_t(h - 1)],
                           corners[std::size_t(i)]) <= 0.0)
      --h;
    hull[std::size_t(h++)] = corners[std::size_t(i)];
  }
  for (int i = n - 2, lower = h + 1; i >= 0; --i) {  // upper hull
    while (h >= lower && cross(hull[std::size_t(h - 2)], hull[std::size_t(h - 1)],
                               corners[std::size_t(i)]) <= 0.0)
      --h;
    hull[std::size_t(h++)] = corners[std::size_t(i)];
  }
  const Eigen::Vector2d p = zmp.zmp_W.head<2>();
  double margin = std::numeric_limits<double>::infinity();
  for (int e = 0; e + 1 < h; ++e) {  // hull[h-1] == hull[0]
    const Eigen::Vector2d edge = hull[std::size_t(e + 1)] - hull[std::size_t(e)];
    const Eigen::Vector2d inward(-edge.y(), edge.x());  // left of a counter-clockwise edge
    margin = std::min(margin, inward.normalized().dot(p - hull[std::size_t(e)]));
  }
  return margin;
}

/// support_polygon_margin() with foot_length × foot_width rectangles centred under the sensors,
/// x forward.
/// @throws walkgen::invalid_argument as above, or when a foot size is not finite and > 0.
inline double support_polygon_margin(const MeasuredZmp& zmp,
                                     const std::array<ForceTorqueReading, 2>& ft,
                                     double sensor_height, double foot_length, double foot_width) {
  check_positive("support_polygon_margin: foot_length", foot_length, "a finite length > 0 m");
  check_positive("support_polygon_margin: foot_width", foot_width, "a finite width > 0 m");
  const double x = foot_length / 2.0, y = foot_width / 2.0;
  return support_polygon_margin(zmp, ft, sensor_height, {{{x, y}, {x, -y}, {-x, y}, {-x, -y}}});
}

}  // namespace walkgen
