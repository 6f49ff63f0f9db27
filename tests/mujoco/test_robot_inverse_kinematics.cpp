// The Ceres whole-body IK on a robot known only by its description file and MJCF: the Unitree
// G1 (23 joints, kinematics read from the MJCF, soles added by the description) reaches CoM and
// foot targets around its stance, and its solution is checked with forward kinematics.
#include <gtest/gtest.h>

#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <string>

#include "walkgen/ceres/inverse_kinematics.hpp"
#include "walkgen/mujoco/robot_model.hpp"
#include "walkgen/yaml/robot_description_loader.hpp"

namespace {

struct Stand {
  Eigen::Vector3d base, left, right, com;
  Eigen::VectorXd q;
};

Stand stand(const walkgen::KinematicTree<double>& tree, const walkgen::RobotDescription& robot) {
  Stand s;
  s.q = walkgen::stand_configuration(tree, robot);
  auto ws = tree.make_workspace();
  tree.forward_kinematics(Eigen::Vector3d::Zero(), Eigen::Matrix3d::Identity(), s.q, ws);
  // Base placed so that the soles are on the floor (z = 0).
  const double lift = -ws.position_W(tree.link_index(robot.sole_frames[0])).z();
  s.base = Eigen::Vector3d(0, 0, lift);
  tree.forward_kinematics(s.base, Eigen::Matrix3d::Identity(), s.q, ws);
  s.left = ws.position_W(tree.link_index(robot.sole_frames[0]));
  s.right = ws.position_W(tree.link_index(robot.sole_frames[1]));
  s.com = tree.center_of_mass(ws);
  return s;
}

TEST(RobotInverseKinematics, UnitreeG1ReachesCentreOfMassAndFootTargets) {
  const walkgen::RobotDescription robot = walkgen::find_robot_description("unitree_g1");
  const walkgen::KinematicTree<double> tree = walkgen::robot_kinematic_tree_from_mjcf(robot);
  ASSERT_EQ(tree.num_joints(), 23);
  const Stand s = stand(tree, robot);
  walkgen::CeresInverseKinematics<> ik(tree, walkgen::ceres_ik_settings(robot));
  ik.set_initial_guess(s.base, Eigen::Matrix3d::Identity(), s.q);

  struct Case {
    const char* what;
    Eigen::Vector3d com, left_step;
  };
  const Case cases[] = {
      {"CoM over the left sole", {0.0, s.left.y(), s.com.z()}, Eigen::Vector3d::Zero()},
      {"CoM 3 cm lower, 2 cm forward", {0.02, 0.0, s.com.z() - 0.03}, Eigen::Vector3d::Zero()},
      {"left foot 10 cm forward, 5 cm up", {0.0, s.right.y(), s.com.z() - 0.02}, {0.10, 0.0, 0.05}},
      {"left foot 5 cm outwards", {0.0, 0.0, s.com.z() - 0.02}, {0.0, 0.05, 0.0}},
  };
  auto ws = tree.make_workspace();
  for (const Case& c : cases) {  // each a cold solve from the stance
    walkgen::IkTarget target;
    target.com_W = c.com;
    target.left_foot = {s.left + c.left_step, 0.0};
    target.right_foot = {s.right, 0.0};
    target.hold_upright(0.0);
    ik.set_initial_guess(s.base, Eigen::Matrix3d::Identity(), s.q);
    const walkgen::IkResult r = ik.solve(target);
    EXPECT_EQ(r.status, walkgen::IkStatus::converged)
        << c.what << ": " << r.message << " com " << r.com_error << " feet "
        << r.foot_position_error << " tilt " << r.foot_tilt_error << " yaw " << r.foot_yaw_error
        << " base " << r.base_orientation_error << " torso " << r.torso_orientation_error << " it "
        << r.iterations;
    tree.forward_kinematics(ik.base_position_W(), ik.base_rotation_W(), ik.q(), ws);
    EXPECT_LE((tree.center_of_mass(ws) - target.com_W).norm(), 1e-4) << c.what;
    const int l = tree.link_index(robot.sole_frames[0]), rr = tree.link_index(robot.sole_frames[1]);
    EXPECT_LE((ws.position_W(l) - target.left_foot.position_W).norm(), 1e-4) << c.what;
    EXPECT_LE((ws.position_W(rr) - target.right_foot.position_W).norm(), 1e-4) << c.what;
    // Soles flat: their z axes vertical.
    EXPECT_GE(ws.rotation_W(l)(2, 2), std::cos(1e-3)) << c.what;
    EXPECT_GE(ws.rotation_W(rr)(2, 2), std::cos(1e-3)) << c.what;
    // Within the joint limits.
    EXPECT_TRUE((ik.q().array() >= tree.lower_limits().array() - 1e-12).all()) << c.what;
    EXPECT_TRUE((ik.q().array() <= tree.upper_limits().array() + 1e-12).all()) << c.what;
    // The arms (a held group) stay exactly at the stand pose.
    for (const std::string& j : walkgen::ceres_ik_settings(robot).held_joints) {
      EXPECT_EQ(ik.q()[tree.joint_index(j)], s.q[tree.joint_index(j)]) << c.what << ": " << j;
    }
  }
}

// Why the arms are held: the G1's 21 residuals have rank 19 (with the waist's single yaw joint
// the torso's roll and pitch targets repeat the pelvis's), and the 10 arm columns add no
// direction to the 19 the base, legs and waist span: with all 23 joints free, J (21 × 29) has
// rank 19, JᵀJ a 10-dimensional null space, and Ceres' Cholesky fails whenever LM's damping is
// small (warm solves). With the arms held the 19 free columns have full rank.
TEST(RobotInverseKinematics, UnitreeG1HeldArmsMakeTheJacobianFullRank) {
  const walkgen::RobotDescription robot = walkgen::find_robot_description("unitree_g1");
  const walkgen::KinematicTree<double> tree = walkgen::robot_kinematic_tree_from_mjcf(robot);
  const Stand s = stand(tree, robot);
  const walkgen::CeresIkSettings settings = walkgen::ceres_ik_settings(robot);
  ASSERT_EQ(settings.held_joints.size(), 10u);
  walkgen::CeresInverseKinematics<> ik(tree, settings);
  walkgen::IkTarget target;
  target.com_W = s.com;
  target.left_foot = {s.left, 0.0};
  target.right_foot = {s.right, 0.0};
  target.hold_upright(0.0);
  Eigen::VectorXd x(6 + tree.num_joints()), r;
  x << s.base, Eigen::Vector3d::Zero(), s.q;
  Eigen::MatrixXd J;
  ik.set_initial_guess(s.base, Eigen::Matrix3d::Identity(), s.q);
  ik.residual_and_jacobian(target, x, r, J);
  Eigen::MatrixXd free(J.rows(), 0);
  for (Eigen::Index c = 0; c < J.cols(); ++c) {
    bool held = false;
    for (const std::string& j : settings.held_joints) held = held || c == 6 + tree.joint_index(j);
    if (held) continue;
    free.conservativeResize(Eigen::NoChange, free.cols() + 1);
    free.col(free.cols() - 1) = J.col(c);
  }
  ASSERT_EQ(free.cols(), 19);
  const auto rank = [](const Eigen::MatrixXd& m) {
    Eigen::JacobiSVD<Eigen::MatrixXd> svd(m);
    svd.setThreshold(1e-9);
    return svd.rank();
  };
  EXPECT_EQ(rank(free), 19);
  EXPECT_EQ(rank(J), 19);  // 29 columns: 10 null directions
}

// Warm-started as in the walking loop: the CoM moves 60 % of the way from the middle towards the
// left sole (the sway of a walk) and the right foot lifts 4 cm, in 5 ms samples of 1 s
// minimum-jerk motions; every sample converges. (With the CoM fully over the left sole the
// lifted right foot cannot stay flat: its ankle roll would pass its ±0.262 rad limit.)
TEST(RobotInverseKinematics, UnitreeG1FollowsAWeightShiftWarmStarted) {
  const walkgen::RobotDescription robot = walkgen::find_robot_description("unitree_g1");
  const walkgen::KinematicTree<double> tree = walkgen::robot_kinematic_tree_from_mjcf(robot);
  const Stand s = stand(tree, robot);
  walkgen::CeresInverseKinematics<> ik(tree, walkgen::ceres_ik_settings(robot));
  ik.set_initial_guess(s.base, Eigen::Matrix3d::Identity(), s.q);
  int failures = 0;
  double worst_com = 0.0;
  const int n = 200;
  for (int k = 0; k <= 2 * n; ++k) {
    const double r = std::min(1.0, double(k) / n), lift = std::max(0.0, double(k - n) / n);
    const auto blend = [](double x) { return x * x * x * (10.0 - 15.0 * x + 6.0 * x * x); };
    walkgen::IkTarget target;
    target.com_W = s.com + blend(r) * Eigen::Vector3d(0.0, 0.6 * (s.left.y() - s.com.y()), -0.02);
    target.left_foot = {s.left, 0.0};
    target.right_foot = {s.right + Eigen::Vector3d(0.0, 0.0, 0.04 * blend(lift)), 0.0};
    target.hold_upright(0.0);
    const walkgen::IkResult result = ik.solve(target);
    if (result.status != walkgen::IkStatus::converged && failures < 5) {
      ADD_FAILURE() << "sample " << k << ": com " << result.com_error << " feet "
                    << result.foot_position_error << " tilt " << result.foot_tilt_error << " torso "
                    << result.torso_orientation_error << " it " << result.iterations;
    }
    failures += result.status != walkgen::IkStatus::converged;
    worst_com = std::max(worst_com, result.com_error);
  }
  EXPECT_EQ(failures, 0);
  EXPECT_LE(worst_com, 1e-6);
  // Through 401 warm solves the held arms never moved.
  for (const std::string& j : walkgen::ceres_ik_settings(robot).held_joints) {
    EXPECT_EQ(ik.q()[tree.joint_index(j)], s.q[tree.joint_index(j)]) << j;
  }
}

}  // namespace
