#pragma once
/// @file
/// A robot's identity in one value: where its models are, the names of its joints, soles,
/// sensors, cameras and base, its standing posture and its walking settings (whose
/// RobotGeometry holds the foot geometry). The MuJoCo backend, the closed loop and the IK take
/// their names and posture from it, so that no other header spells a robot's name.
///
/// walkgen_humanoid_description() is walkgen's own humanoid, the robot that models/generate.py
/// writes; tests/mujoco/test_robot_description.cpp checks every entry against the two model
/// files that script generates. Eigen only (no MuJoCo, no URDF parser).

#include <Eigen/Core>

#include <array>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "walkgen/core/data_dir.hpp"
#include "walkgen/core/exceptions.hpp"
#include "walkgen/mpc/settings.hpp"

namespace walkgen {

/// One joint angle of a posture.
struct JointAngle {
  std::string joint;   ///< joint name, one of RobotDescription::joint_names
  double angle = 0.0;  ///< [rad]
};

/// A frame the description adds to a body of the model (a sole of a model without sites).
struct FrameDescription {
  std::string name;                               ///< unique among the model's bodies and sites
  std::string body;                               ///< the body it is welded to
  Eigen::Vector3d xyz = Eigen::Vector3d::Zero();  ///< origin in the body frame [m]
  Eigen::Vector3d rpy = Eigen::Vector3d::Zero();  ///< URDF roll, pitch, yaw [rad]
};

/// Joints that share feedback gains (legs, waist, arms): what a torque-controlled robot's joint
/// controller (walkgen/robot/joint_control.hpp) uses. A position-servo robot's gains are its
/// model's; its description needs no groups.
struct JointGroup {
  std::string name;                 ///< e.g. "legs"
  std::vector<std::string> joints;  ///< joints of RobotDescription::joint_names
  double kp = 0.0;                  ///< [N m/rad] stiffness, >= 0
  double kd = 0.0;                  ///< [N m s/rad] damping, >= 0
  /// Held at their stand_pose angles by an IK built with ceres_ik_settings(robot) (its
  /// held_joints; the guess comes from start_standing()): the IK leaves them out, e.g. a
  /// humanoid's arms, so that it does not swing them to place the CoM.
  bool held = false;
};

/// How a torque-driven robot keeps its balance while it walks (docs/robots.md, "Balance"):
/// the joint controller's feed-forward puts the contact forces under the CoM motion the pattern
/// asks for, with feedback on the CoM (MujocoRobot, JointFeedforward::balance), and whether the
/// NMPC is restarted from the measured CoM (WalkingLoopSettings::com_feedback).
struct BalanceDescription {
  bool contact_feedforward = false;  ///< false: the weight feed-forward only
  double com_kp = 20.0;              ///< [1/s^2] CoM position feedback, >= 0
  double com_kd = 8.0;               ///< [1/s] CoM velocity feedback, >= 0
  bool nmpc_feedback = true;         ///< restart the NMPC from the measured CoM (§6.3)
};

/// Everything that names or sizes one robot. Left before right in every pair; an optional pair
/// (force-torque sensors, cameras) is two empty names when the robot has none.
struct RobotDescription {
  std::string name;       ///< e.g. "walkgen_humanoid"
  std::string urdf_path;  ///< kinematics and inertias (KinematicTree)
  std::string mjcf_path;  ///< the simulated robot (MujocoRobot)
  /// Actuated joints in command and measurement order (URDF joints, MuJoCo joints and
  /// actuators of these names).
  std::vector<std::string> joint_names;
  /// Sole frames: URDF links, MJCF sites or added `frames` at the sole centre, z up, where the
  /// IK puts the feet.
  std::array<std::string, 2> sole_frames;
  /// Frames added to bodies of the model (kinematic trees read from the MJCF get them).
  std::vector<FrameDescription> frames;
  /// Ankle force-torque sensor frames: URDF links and MJCF sites (sensors "<site>_force",
  /// "<site>_torque"), `ft_sensor_height` above the sole. Optional.
  std::array<std::string, 2> ft_sensor_frames;
  double ft_sensor_height = 0.0;       ///< [m] d of eq. 2.11-2.12
  std::array<std::string, 2> cameras;  ///< MJCF cameras of the stereo pair. Optional.
  /// The MJCF site of the IMU (sensors "<site>_quat", "<site>_gyro", "<site>_acc"). Optional.
  std::string imu_site;
  std::string base_body;  ///< the floating base (URDF root link, MJCF body)
  /// The upper body whose orientation the IK holds upright (empty: the base's only).
  std::string torso_body;
  std::string stand_keyframe;  ///< MJCF keyframe holding the standing posture
  /// The standing posture: these joints at these angles, every other joint at 0.
  std::vector<JointAngle> stand_pose;
  /// Feedback gains by joint group; each joint in at most one group.
  std::vector<JointGroup> joint_groups;
  /// The corners of each sole's contact region in its sole frame [m] (x forward, y left),
  /// where they are not the walking settings' foot_length × foot_width rectangle: e.g. a foot
  /// touching through contact points. Empty or four corners, symmetric about the sole's x axis
  /// (the same region for both soles). Where the true ZMP is checked (support_polygon_margin()).
  std::vector<Eigen::Vector2d> sole_polygon;
  /// How it balances while walking (torque-driven robots; the defaults: the thesis' loop).
  BalanceDescription balance;
  /// The walking settings the robot walks with: foot size and distance, feasibility regions and
  /// CoM height (geometry()), timing and weights (generator()), the start (initial_state()).
  WalkingSettings<double> walking;
};

/// Checks a description on its own (the names are looked up in the models by their users).
/// @throws walkgen::invalid_argument naming the first bad entry.
inline void validate(const RobotDescription& d) {
  check_argument(!d.name.empty(), "RobotDescription.name", "a name", "an empty string");
  check_argument(!d.joint_names.empty(), "RobotDescription.joint_names", "at least one joint",
                 "none");
  for (std::size_t i = 0; i < d.joint_names.size(); ++i) {
    check_argument(!d.joint_names[i].empty(), "RobotDescription.joint_names", "non-empty names",
                   "an empty name at index " + std::to_string(i));
    for (std::size_t j = 0; j < i; ++j) {
      check_argument(d.joint_names[j] != d.joint_names[i], "RobotDescription.joint_names",
                     "each joint once", "'" + d.joint_names[i] + "' twice");
    }
  }
  const std::array<std::pair<const char*, const std::array<std::string, 2>*>, 3> pairs = {
      {{"RobotDescription.sole_frames", &d.sole_frames},
       {"RobotDescription.ft_sensor_frames", &d.ft_sensor_frames},
       {"RobotDescription.cameras", &d.cameras}}};
  for (const auto& p : pairs) {
    const std::array<std::string, 2>& names = *p.second;
    const bool optional = p.second != &d.sole_frames;
    const bool none = names[0].empty() && names[1].empty();
    check_argument(
        (optional && none) || (!names[0].empty() && !names[1].empty() && names[0] != names[1]),
        p.first,
        optional ? "two different names (left, right) or none"
                 : "two different names (left, right)",
        "'" + names[0] + "', '" + names[1] + "'");
  }
  check_argument(!d.base_body.empty(), "RobotDescription.base_body", "a body name",
                 "an empty string");
  if (!d.ft_sensor_frames[0].empty()) {
    check_positive("RobotDescription.ft_sensor_height", d.ft_sensor_height);
  }
  for (std::size_t i = 0; i < d.frames.size(); ++i) {
    const FrameDescription& f = d.frames[i];
    check_argument(!f.name.empty() && !f.body.empty(), "RobotDescription.frames",
                   "a name and a body", "'" + f.name + "' on '" + f.body + "'");
    check_argument(f.xyz.allFinite() && f.rpy.allFinite(), "RobotDescription.frames",
                   "a finite xyz and rpy", "'" + f.name + "' with NaN or inf");
    for (std::size_t j = 0; j < i; ++j) {
      check_argument(d.frames[j].name != f.name, "RobotDescription.frames", "each name once",
                     "'" + f.name + "' twice");
    }
  }
  for (std::size_t i = 0; i < d.stand_pose.size(); ++i) {
    const JointAngle& a = d.stand_pose[i];
    bool known = false;
    for (const std::string& j : d.joint_names) known = known || j == a.joint;
    check_argument(known, "RobotDescription.stand_pose", "joints of joint_names",
                   "'" + a.joint + "'");
    check_argument(std::isfinite(a.angle), "RobotDescription.stand_pose", "finite angles", a.angle);
    for (std::size_t j = 0; j < i; ++j) {
      check_argument(d.stand_pose[j].joint != a.joint, "RobotDescription.stand_pose",
                     "each joint once", "'" + a.joint + "' twice");
    }
  }
  for (std::size_t g = 0; g < d.joint_groups.size(); ++g) {
    const JointGroup& group = d.joint_groups[g];
    const std::string at = "RobotDescription.joint_groups: '" + group.name + "'";
    check_argument(!group.name.empty() && !group.joints.empty(), at.c_str(),
                   "a name and at least one joint", "an empty name or no joints");
    check_argument(
        std::isfinite(group.kp) && std::isfinite(group.kd) && group.kp >= 0.0 && group.kd >= 0.0,
        at.c_str(), "finite gains kp, kd >= 0",
        std::to_string(group.kp) + ", " + std::to_string(group.kd));
    for (const std::string& joint : group.joints) {
      bool known = false;
      for (const std::string& j : d.joint_names) known = known || j == joint;
      check_argument(known, at.c_str(), "joints of joint_names", "'" + joint + "'");
      int times = 0;
      for (const JointGroup& other : d.joint_groups) {
        for (const std::string& j : other.joints) times += j == joint;
      }
      check_argument(times == 1, at.c_str(), "each joint in one group only",
                     "'" + joint + "' " + std::to_string(times) + " times");
    }
  }
  check_argument(d.sole_polygon.empty() || d.sole_polygon.size() == 4,
                 "RobotDescription.sole_polygon", "none or four corners",
                 std::to_string(d.sole_polygon.size()) + " corners");
  for (const Eigen::Vector2d& c : d.sole_polygon) {
    check_argument(c.allFinite() && c.norm() < 10.0, "RobotDescription.sole_polygon",
                   "finite corners within 10 m of the sole frame", "NaN, inf or farther");
    bool mirrored = false;
    for (const Eigen::Vector2d& o : d.sole_polygon) {
      mirrored = mirrored || (o - Eigen::Vector2d(c.x(), -c.y())).norm() < 1e-9;
    }
    check_argument(mirrored, "RobotDescription.sole_polygon",
                   "corners symmetric about the sole's x axis (the same region for both soles)",
                   "a corner without its mirror image");
  }
  check_argument(std::isfinite(d.balance.com_kp) && std::isfinite(d.balance.com_kd) &&
                     d.balance.com_kp >= 0.0 && d.balance.com_kd >= 0.0,
                 "RobotDescription.balance", "finite gains com_kp, com_kd >= 0",
                 std::to_string(d.balance.com_kp) + ", " + std::to_string(d.balance.com_kd));
  validate(d.walking);
}

/// The corners of the left sole's contact region in its frame: RobotDescription::sole_polygon,
/// or the walking settings' foot_length × foot_width rectangle (both symmetric about x: the
/// right sole's too).
inline std::array<Eigen::Vector2d, 4> sole_corners(const RobotDescription& d) {
  if (d.sole_polygon.size() == 4) {
    return {{d.sole_polygon[0], d.sole_polygon[1], d.sole_polygon[2], d.sole_polygon[3]}};
  }
  const double x = d.walking.foot_length / 2.0, y = d.walking.foot_width / 2.0;
  return {{{x, y}, {x, -y}, {-x, y}, {-x, -y}}};
}

/// Feedback gains per joint, in joint_names order.
struct JointGains {
  Eigen::VectorXd kp;  ///< [N m/rad]; NaN for a joint in no group
  Eigen::VectorXd kd;  ///< [N m s/rad]; NaN for a joint in no group
};

/// The gains of the description's joint groups over joint_names (NaN where a joint is in none).
inline JointGains joint_gains(const RobotDescription& d) {
  const auto n = static_cast<Eigen::Index>(d.joint_names.size());
  JointGains gains{Eigen::VectorXd::Constant(n, std::nan("")),
                   Eigen::VectorXd::Constant(n, std::nan(""))};
  for (const JointGroup& group : d.joint_groups) {
    for (const std::string& joint : group.joints) {
      for (Eigen::Index i = 0; i < n; ++i) {
        if (d.joint_names[static_cast<std::size_t>(i)] != joint) continue;
        gains.kp[i] = group.kp;
        gains.kd[i] = group.kd;
      }
    }
  }
  return gains;
}

/// The standing posture as a vector over `joint_names` (the order of the description, not of a
/// model; see stand_configuration() below for a tree's order).
inline std::vector<double> stand_angles(const RobotDescription& d) {
  std::vector<double> q(d.joint_names.size(), 0.0);
  for (const JointAngle& a : d.stand_pose) {
    for (std::size_t i = 0; i < d.joint_names.size(); ++i) {
      if (d.joint_names[i] == a.joint) q[i] = a.angle;
    }
  }
  return q;
}

/// walkgen's humanoid (models/generate.py: 15 joints, Heicub-like, position servos), walking
/// with Heicub's settings (thesis Table 6.1): its 0.2 × 0.1 m soles 0.14 m apart are Heicub's.
/// The model paths are under data_dir() (empty when walkgen's CMake target did not say where).
inline RobotDescription walkgen_humanoid_description() {
  RobotDescription d;
  d.name = "walkgen_humanoid";
  d.urdf_path = humanoid_urdf_path();
  d.mjcf_path = humanoid_mjcf_path();
  d.joint_names = {"l_hip_pitch",   "l_hip_roll",   "l_hip_yaw",   "l_knee",     "l_ankle_pitch",
                   "l_ankle_roll",  "r_hip_pitch",  "r_hip_roll",  "r_hip_yaw",  "r_knee",
                   "r_ankle_pitch", "r_ankle_roll", "torso_pitch", "torso_roll", "torso_yaw"};
  d.sole_frames = {{"l_sole", "r_sole"}};
  d.ft_sensor_frames = {{"l_foot_ft_sensor", "r_foot_ft_sensor"}};
  d.ft_sensor_height = 0.03;
  d.cameras = {{"left_camera", "right_camera"}};
  d.imu_site = "imu";
  d.base_body = "root_link";
  d.torso_body = "chest";
  d.stand_keyframe = "stand";
  for (const char* side : {"l_", "r_"}) {
    const std::string s(side);
    d.stand_pose.push_back({s + "hip_pitch", -0.5});
    d.stand_pose.push_back({s + "knee", 1.0});
    d.stand_pose.push_back({s + "ankle_pitch", -0.5});
  }
  d.walking = heicub_settings<double>();
  return d;
}

/// `robot`'s standing posture (RobotDescription::stand_pose; walkgen's humanoid: the MJCF
/// keyframe "stand", hip pitch −0.5, knee 1.0, ankle pitch −0.5 rad, soles flat) in the joint
/// order of `tree` (a KinematicTree, or anything with num_joints() and joint_index()), every
/// other joint 0.
/// @throws walkgen::invalid_argument when `tree` lacks one of the posture's joints.
template <typename Tree>
Eigen::VectorXd stand_configuration(
    const Tree& tree, const RobotDescription& robot = walkgen_humanoid_description()) {
  Eigen::VectorXd q = Eigen::VectorXd::Zero(tree.num_joints());
  for (const JointAngle& a : robot.stand_pose) q[tree.joint_index(a.joint)] = a.angle;
  return q;
}

}  // namespace walkgen
