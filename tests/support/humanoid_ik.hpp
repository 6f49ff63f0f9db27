#pragma once
// walkgen's humanoid (models/) for the inverse-kinematics tests, benchmark and example: the tree
// from the URDF, the standing posture, and a Heicub walk of the NMPC interpolated at the command
// period.

#include <Eigen/Core>
#include <string>
#include <vector>

#include "walkgen/ceres/inverse_kinematics.hpp"
#include "walkgen/interpolation/trajectory.hpp"
#include "walkgen/mpc/walking_mpc.hpp"
#include "walkgen/robot_io/urdf.hpp"

namespace walkgen_test {

/// Revolute joints of walkgen's humanoid.
constexpr int kHumanoidJoints = 15;
using HumanoidIk = walkgen::CeresInverseKinematics<kHumanoidJoints>;

inline walkgen::KinematicTree<double> humanoid_tree() {
  return walkgen::kinematic_tree_from_urdf_file(std::string(WALKGEN_SOURCE_DIR) +
                                                "/models/walkgen_humanoid.urdf");
}

/// The MJCF keyframe "stand": hip pitch −0.3, knee 0.6, ankle pitch −0.3 rad (soles flat).
inline Eigen::VectorXd stand_configuration(const walkgen::KinematicTree<double>& tree) {
  Eigen::VectorXd q = Eigen::VectorXd::Zero(tree.num_joints());
  for (const char* side : {"l_", "r_"}) {
    const std::string s(side);
    q[tree.joint_index(s + "hip_pitch")] = -0.3;
    q[tree.joint_index(s + "knee")] = 0.6;
    q[tree.joint_index(s + "ankle_pitch")] = -0.3;
  }
  return q;
}

/// The root position that puts the standing robot's left sole at `left_sole_W` (upright base).
inline Eigen::Vector3d stand_base_position(const walkgen::KinematicTree<double>& tree,
                                           const Eigen::Vector3d& left_sole_W) {
  auto ws = tree.make_workspace();
  tree.forward_kinematics(Eigen::Vector3d::Zero(), Eigen::Matrix3d::Identity(),
                          stand_configuration(tree), ws);
  return left_sole_W - ws.position_W(tree.link_index("l_sole"));
}

/// Sets the standing posture as the initial guess of `ik`, base upright turned by yaw, left
/// sole at `left_sole_W`.
template <typename Ik>
void start_standing(Ik& ik, const Eigen::Vector3d& left_sole_W, double yaw = 0.0) {
  const Eigen::Matrix3d R = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  const Eigen::Vector3d offset = stand_base_position(ik.tree(), Eigen::Vector3d::Zero());
  ik.set_initial_guess(left_sole_W + R * offset, R, stand_configuration(ik.tree()));
}

/// CoM height of the IK walks [m]. At heicub_settings()' 0.45 m the support leg of the humanoid
/// is within 0.1 mm of full stretch when the CoM sways over it: the IK fails at t = 3.73 s (CoM
/// 8e-5 m short), and knees near straight turn fast (1.4 rad/s). 0.43 m keeps them bent.
constexpr double kWalkComHeight = 0.43;

/// A Heicub walk (thesis Table 6.1, walkgen::heicub_settings(), which matches the humanoid) of
/// `ticks` NMPC ticks at a constant command, interpolated at the command period. The CoM walks
/// at com_z = kWalkComHeight instead of the preset's 0.45 m.
inline std::vector<walkgen::TrajectorySample<double>> heicub_walk(const Eigen::Vector3d& command,
                                                                  int ticks) {
  walkgen::WalkingSettings<double> s = walkgen::heicub_settings();
  s.com_z = kWalkComHeight;
  walkgen::WalkingMpc<double, 16> mpc(s);
  walkgen::WalkingInterpolator<double> interp(s);
  std::vector<walkgen::TrajectorySample<double>> samples(
      std::size_t(ticks * interp.samples_per_tick()));
  for (int k = 0; k < ticks; ++k) {
    mpc.set_command(command);
    mpc.solve();
    interp.interpolate(mpc, samples.data() + std::size_t(k * interp.samples_per_tick()));
    mpc.advance();
  }
  return samples;
}

/// Sets the standing posture under the first sample of a walk as the initial guess of `ik`.
template <typename Ik>
void start_walk(Ik& ik, const walkgen::TrajectorySample<double>& first) {
  const walkgen::IkTarget t = walkgen::ik_target(first);
  start_standing(ik, t.left_foot.position_W, first.com_q[0]);
}

}  // namespace walkgen_test
