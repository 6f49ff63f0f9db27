#pragma once
/// @file
/// Where the walking pattern meets the kinematics: the IK target (kinematics/ik_target.hpp) of a
/// command-period sample of the pattern (interpolation/trajectory.hpp). Eigen only.

#include <Eigen/Core>

#include "walkgen/interpolation/trajectory.hpp"
#include "walkgen/kinematics/ik_target.hpp"

namespace walkgen {

/// The IK target of a sample of the walking pattern: CoM (x, y, com_z), the feet at (x, y,
/// height, yaw), pelvis and torso upright turned by the CoM yaw. The soles are at the ground height
/// 0 of the generator.
inline IkTarget ik_target(const TrajectorySample<double>& s) {
  IkTarget t;
  t.com_W = Eigen::Vector3d(s.com_x[0], s.com_y[0], s.com_z);
  auto sole = [](const SwingSample<double>& f) {
    return SoleTarget{Eigen::Vector3d(f.motion.x.position, f.motion.y.position, f.z.position),
                      f.motion.q.position};
  };
  t.left_foot = sole(s.left);
  t.right_foot = sole(s.right);
  t.hold_upright(s.com_q[0]);
  return t;
}

}  // namespace walkgen
