#pragma once
/// @file
/// walkgen's humanoid (models/: 15 joints, Heicub-like; walkgen_humanoid_description()) for
/// inverse kinematics: its kinematic tree from the URDF, the base placement of its standing
/// posture (stand_configuration() in walkgen/robot/robot_description.hpp), and HumanoidIk, the
/// Ceres whole-body IK sized for it, started from that posture. Used by the closed loop
/// (walkgen/simulation/), the IK tests, bench_kinematics and examples/walking_joints.
///
/// Target walkgen::humanoid: needs the Ceres (walkgen::ceres) and URDF (walkgen::urdf) adapters;
/// the model is found through walkgen::data_dir() (docs/design.md convention 21).

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <string>

#include "walkgen/ceres/inverse_kinematics.hpp"
#include "walkgen/control/pattern_targets.hpp"
#include "walkgen/core/data_dir.hpp"
#include "walkgen/interpolation/trajectory.hpp"
#include "walkgen/robot/robot_description.hpp"
#include "walkgen/urdf/urdf_loader.hpp"

namespace walkgen {

/// Revolute joints of walkgen's humanoid.
constexpr int kHumanoidJoints = 15;
/// The Ceres whole-body IK of walkgen's humanoid.
using HumanoidIk = CeresInverseKinematics<kHumanoidJoints>;

/// The kinematic tree of `robot` (default walkgen's humanoid), read from its URDF.
/// @throws walkgen::invalid_argument when the URDF cannot be read or is malformed.
inline KinematicTree<double> humanoid_tree(
    const RobotDescription& robot = walkgen_humanoid_description()) {
  return kinematic_tree_from_urdf_file(robot.urdf_path);
}

/// The root position [m] that puts the standing robot's left sole at `left_sole_W` (upright
/// base).
inline Eigen::Vector3d stand_base_position(
    const KinematicTree<double>& tree, const Eigen::Vector3d& left_sole_W,
    const RobotDescription& robot = walkgen_humanoid_description()) {
  auto ws = tree.make_workspace();
  tree.forward_kinematics(Eigen::Vector3d::Zero(), Eigen::Matrix3d::Identity(),
                          stand_configuration(tree, robot), ws);
  return left_sole_W - ws.position_W(tree.link_index(robot.sole_frames[0]));
}

/// Sets `robot`'s standing posture as the initial guess of `ik` (HumanoidIk or any IK with
/// tree() and set_initial_guess()), base upright turned by `yaw` [rad], left sole at
/// `left_sole_W` [m].
template <typename Ik>
void start_standing(Ik& ik, const Eigen::Vector3d& left_sole_W, double yaw = 0.0,
                    const RobotDescription& robot = walkgen_humanoid_description()) {
  const Eigen::Matrix3d R = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  const Eigen::Vector3d offset = stand_base_position(ik.tree(), Eigen::Vector3d::Zero(), robot);
  ik.set_initial_guess(left_sole_W + R * offset, R, stand_configuration(ik.tree(), robot));
}

/// Sets `robot`'s standing posture under the first sample of a walk as the initial guess of
/// `ik`.
template <typename Ik>
void start_walk(Ik& ik, const TrajectorySample<double>& first,
                const RobotDescription& robot = walkgen_humanoid_description()) {
  const IkTarget t = ik_target(first);
  start_standing(ik, t.left_foot.position_W, first.com_q[0], robot);
}

}  // namespace walkgen
