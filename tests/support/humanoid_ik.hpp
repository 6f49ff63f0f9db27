#pragma once
// walkgen's humanoid (models/) for the inverse-kinematics tests, benchmark and example: the tree
// from the URDF, the standing posture, and a Heicub walk of the NMPC interpolated at the command
// period.

#include <Eigen/Core>
#include <stdexcept>
#include <string>
#include <vector>

#include "walkgen/ceres/inverse_kinematics.hpp"
#include "walkgen/core/data_dir.hpp"
#include "walkgen/interpolation/trajectory.hpp"
#include "walkgen/mpc/walking_mpc.hpp"
#include "walkgen/robot_io/urdf.hpp"

namespace walkgen_test {

/// Revolute joints of walkgen's humanoid.
constexpr int kHumanoidJoints = 15;
using HumanoidIk = walkgen::CeresInverseKinematics<kHumanoidJoints>;

inline walkgen::KinematicTree<double> humanoid_tree() {
  return walkgen::kinematic_tree_from_urdf_file(walkgen::humanoid_urdf_path());
}

/// The MJCF keyframe "stand": hip pitch −0.5, knee 1.0, ankle pitch −0.5 rad (soles flat).
inline Eigen::VectorXd stand_configuration(const walkgen::KinematicTree<double>& tree) {
  Eigen::VectorXd q = Eigen::VectorXd::Zero(tree.num_joints());
  for (const char* side : {"l_", "r_"}) {
    const std::string s(side);
    q[tree.joint_index(s + "hip_pitch")] = -0.5;
    q[tree.joint_index(s + "knee")] = 1.0;
    q[tree.joint_index(s + "ankle_pitch")] = -0.5;
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

/// A Heicub walk (thesis Table 6.1: walkgen::heicub_settings() unchanged, com_z = 0.45 m, which
/// the humanoid's standing CoM matches, plus `obstacles`) of `ticks` NMPC ticks, the command at
/// tick k being command(k), interpolated at the command period.
/// @throws std::runtime_error when a command is rejected or a QP fails (the walk would not be the
///   one asked for).
template <typename Command>
std::vector<walkgen::TrajectorySample<double>> heicub_walk(
    const Command& command, int ticks,
    const std::vector<walkgen::CircleObstacle<double>>& obstacles = {}) {
  walkgen::WalkingSettings<double> s = walkgen::heicub_settings();
  s.obstacles = obstacles;
  walkgen::WalkingMpc<double, 16> mpc(s);
  walkgen::WalkingInterpolator<double> interp(s);
  std::vector<walkgen::TrajectorySample<double>> samples(
      std::size_t(ticks * interp.samples_per_tick()));
  for (int k = 0; k < ticks; ++k) {
    const walkgen::CommandStatus accepted = mpc.set_command(command(k));
    const walkgen::MpcStatus solved = mpc.solve().status;
    if (accepted != walkgen::CommandStatus::accepted || solved != walkgen::MpcStatus::solved) {
      throw std::runtime_error("heicub_walk: tick " + std::to_string(k) + ": command " +
                               walkgen::to_string(accepted) + ", NMPC " +
                               walkgen::to_string(solved));
    }
    interp.interpolate(mpc, samples.data() + std::size_t(k * interp.samples_per_tick()));
    mpc.advance();
  }
  return samples;
}

/// A Heicub walk at a constant command.
inline std::vector<walkgen::TrajectorySample<double>> heicub_walk(const Eigen::Vector3d& command,
                                                                  int ticks) {
  return heicub_walk([&command](int) { return command; }, ticks);
}

/// The pattern generator's scenarios (tests/support/walking_scenarios.hpp) at Heicub's speeds,
/// within heicub_settings().max_command = (0.034 m/s, 0.0045 m/s, 0.075 rad/s): the command
/// (v_x, v_y, ω_z) of scenario `name` at tick k. "sequence" changes it every `phase` ticks:
/// forward, curve left, sideways, curve right, stop. "obstacle" walks straight at the obstacle of
/// heicub_obstacle().
inline Eigen::Vector3d heicub_scenario_command(const std::string& name, int k, int phase) {
  if (name == "straight" || name == "obstacle") return {0.034, 0.0, 0.0};
  if (name == "sideways") return {0.0, 0.0045, 0.0};
  if (name == "curved") return {0.03, 0.0, 0.06};
  if (name == "turn") return {0.0, 0.0, 0.075};
  switch (k / phase) {  // "sequence"
    case 0:
      return {0.034, 0.0, 0.0};
    case 1:
      return {0.03, 0.0, 0.075};
    case 2:
      return {0.0, 0.0045, 0.0};
    case 3:
      return {0.03, 0.0, -0.075};
    default:
      return {0.0, 0.0, 0.0};
  }
}

/// The obstacle scenario at Heicub's scale: a circle across the left foot's straight path 0.45 m
/// ahead (radius 0.1 m, margin 0.05 m); the walk steps around it and past it within 64 ticks.
inline std::vector<walkgen::CircleObstacle<double>> heicub_obstacle(const std::string& name) {
  if (name != "obstacle") return {};
  return {{0.45, 0.2, 0.1, 0.05}};
}

/// Sets the standing posture under the first sample of a walk as the initial guess of `ik`.
template <typename Ik>
void start_walk(Ik& ik, const walkgen::TrajectorySample<double>& first) {
  const walkgen::IkTarget t = walkgen::ik_target(first);
  start_standing(ik, t.left_foot.position_W, first.com_q[0]);
}

}  // namespace walkgen_test
