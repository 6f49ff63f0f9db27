#pragma once
/// @file
/// The closed loop of thesis figure 6.1 with walkgen's humanoid in MuJoCo: SimLoop is
/// walkgen::WalkingLoop (NMPC of horizon 16, interpolation, HumanoidIk, CoM feedback, measured
/// ZMP) around a walkgen::MujocoRobot, plus what a task around it needs: the pose to steer on
/// and the true (simulated) centre of mass. docs/simulation.md shows how to run it.
///
/// Target walkgen::simulation: needs walkgen::humanoid (Ceres, URDF) and walkgen::mujoco.

#include <mujoco/mujoco.h>

#include <Eigen/Core>
#include <cmath>

#include "walkgen/control/go_to_target.hpp"
#include "walkgen/control/walking_loop.hpp"
#include "walkgen/humanoid/humanoid_ik.hpp"
#include "walkgen/mujoco/mujoco_robot.hpp"

namespace walkgen {

/// The closed loop of walkgen's humanoid: horizon 16, the Ceres IK.
using SimLoop = WalkingLoop<16, HumanoidIk>;

/// The robot's pose for steering (GoToTarget): the middle of its feet (support and swing foot
/// now), which does not sway like the CoM, and its heading, in the generator's world frame.
inline PlanarPose walking_pose(const WalkingState<double>& st) {
  return {(st.support.x + st.swing.x.position) / 2.0, (st.support.y + st.swing.y.position) / 2.0,
          st.heading()};
}

/// The robot's pose as someone watching it sees it: the middle of its soles' true poses
/// (RobotOutput::ft of a simulator) and their mean heading. Where a robot's feet land off the
/// plan (a torque-driven robot slips and turns), steering on this pose keeps it on its way.
inline PlanarPose measured_walking_pose(const RobotOutput& out) {
  const Eigen::Isometry3d& l = out.ft[0].pose_W_S;
  const Eigen::Isometry3d& r = out.ft[1].pose_W_S;
  const Eigen::Vector2d middle = (l.translation() + r.translation()).head<2>() / 2.0;
  const Eigen::Vector2d heading = l.linear().col(0).head<2>() + r.linear().col(0).head<2>();
  return {middle.x(), middle.y(), std::atan2(heading.y(), heading.x())};
}

/// The true whole-body CoM of a MuJoCo robot on the ground plane (x, y) [m]: MuJoCo's subtree
/// CoM of the base body, after the last step.
inline Eigen::Vector2d true_com(MujocoRobot& robot) {
  const int root = mj_name2id(robot.model(), mjOBJ_BODY, robot.settings().base_body.c_str());
  const double* c = robot.data()->subtree_com + 3 * root;
  return {c[0], c[1]};
}

}  // namespace walkgen
