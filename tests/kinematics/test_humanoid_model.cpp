// walkgen's humanoid (models/walkgen_humanoid.urdf, modelled on Heicub, thesis §5) as the
// KinematicTree reads it: the numbers the model promises (15 joints, 25 kg, feet 0.14 m apart,
// force-torque frames d = 0.03 m above the soles, cameras 0.068 m apart, CoM about 0.45 m high
// when standing with bent knees), physically valid inertias, and frame and centre-of-mass
// Jacobians against central finite differences over random in-limit configurations.

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <random>
#include <string>
#include <vector>

#include "support/kinematics.hpp"
#include "walkgen/urdf/urdf_loader.hpp"

namespace {

using walkgen_test::Tree;

Tree humanoid() {
  return walkgen::kinematic_tree_from_urdf_file(std::string(WALKGEN_SOURCE_DIR) +
                                                "/models/walkgen_humanoid.urdf");
}

TEST(HumanoidModel, JointsMassAndLimits) {
  const Tree tree = humanoid();
  const std::vector<std::string> joints = {
      "l_hip_pitch",   "l_hip_roll",   "l_hip_yaw",   "l_knee",     "l_ankle_pitch",
      "l_ankle_roll",  "r_hip_pitch",  "r_hip_roll",  "r_hip_yaw",  "r_knee",
      "r_ankle_pitch", "r_ankle_roll", "torso_pitch", "torso_roll", "torso_yaw"};
  EXPECT_EQ(tree.joint_names(), joints);
  EXPECT_EQ(tree.num_velocities(), 21);  // Heicub: 6 floating-base + 15 joint DoF
  EXPECT_EQ(tree.link(0).name, "root_link");
  EXPECT_NEAR(tree.mass(), 25.0, 1e-12);
  const Eigen::VectorXd lower = tree.lower_limits(), upper = tree.upper_limits();
  for (int i = 0; i < tree.num_joints(); ++i) {
    EXPECT_LT(lower[i], upper[i]) << joints[std::size_t(i)];
    EXPECT_LE(lower[i], 0.0) << joints[std::size_t(i)];  // the zero configuration is valid
    EXPECT_GE(upper[i], 0.0) << joints[std::size_t(i)];
  }
  // Mirrored legs: the right leg's roll and yaw limits are the left's negated and swapped.
  for (const char* j : {"hip_roll", "hip_yaw", "ankle_roll"}) {
    const int l = tree.joint_index(std::string("l_") + j),
              r = tree.joint_index(std::string("r_") + j);
    EXPECT_EQ(lower[l], -upper[r]) << j;
    EXPECT_EQ(upper[l], -lower[r]) << j;
  }
}

TEST(HumanoidModel, InertiasArePhysical) {
  const Tree tree = humanoid();
  for (const auto& link : tree.links()) {
    if (link.mass == 0.0) {  // frames: sole, sensors, cameras
      EXPECT_TRUE(link.inertia.isZero()) << link.name;
      continue;
    }
    EXPECT_GT(link.mass, 0.2) << link.name;
    EXPECT_LT(link.mass, 8.0) << link.name;
    const Eigen::Vector3d moments =
        Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(link.inertia).eigenvalues();
    EXPECT_GT(moments.minCoeff(), 0.0) << link.name;              // positive definite
    EXPECT_GE(moments[0] + moments[1], moments[2]) << link.name;  // triangle inequality
  }
}

TEST(HumanoidModel, FramesAtZeroConfiguration) {
  const Tree tree = humanoid();
  auto ws = tree.make_workspace();
  tree.forward_kinematics(Eigen::Vector3d::Zero(), Eigen::Matrix3d::Identity(),
                          Eigen::VectorXd::Zero(tree.num_joints()), ws);
  auto position = [&](const char* link) { return ws.position_W(tree.link_index(link)); };
  for (int i = 0; i < tree.num_links(); ++i) {  // every frame parallel to the root's...
    if (tree.link(i).name.find("camera") == std::string::npos) {
      EXPECT_TRUE(ws.rotation_W(i).isIdentity(1e-15)) << tree.link(i).name;
    }
  }
  // ... but the cameras, which look down by 0.1 rad (a pitch about y).
  const Eigen::Matrix3d camera = ws.rotation_W(tree.link_index("left_camera"));
  EXPECT_TRUE(camera.isApprox(Eigen::AngleAxisd(0.1, Eigen::Vector3d::UnitY()).toRotationMatrix()));

  const Eigen::Vector3d l_sole = position("l_sole"), r_sole = position("r_sole");
  EXPECT_NEAR(l_sole.y() - r_sole.y(), 0.14, 1e-15);
  EXPECT_NEAR(l_sole.z(), r_sole.z(), 1e-15);
  EXPECT_NEAR((position("l_foot_ft_sensor") - l_sole).z(), 0.03, 1e-15);
  EXPECT_NEAR((position("r_foot_ft_sensor") - r_sole).z(), 0.03, 1e-15);
  EXPECT_NEAR((position("left_camera") - position("right_camera")).norm(), 0.068, 1e-15);
  EXPECT_NEAR(-l_sole.z(), 0.56, 1e-12);  // straight legs: root 0.56 m above the soles
}

TEST(HumanoidModel, StandingComHeightWithBentKnees) {
  // The MJCF keyframe "stand": hip pitch −0.5, knee 1.0, ankle pitch −0.5 rad: soles flat.
  const Tree tree = humanoid();
  Eigen::VectorXd q = Eigen::VectorXd::Zero(tree.num_joints());
  for (const char* side : {"l_", "r_"}) {
    q[tree.joint_index(std::string(side) + "hip_pitch")] = -0.5;
    q[tree.joint_index(std::string(side) + "knee")] = 1.0;
    q[tree.joint_index(std::string(side) + "ankle_pitch")] = -0.5;
  }
  auto ws = tree.make_workspace();
  tree.forward_kinematics(Eigen::Vector3d::Zero(), Eigen::Matrix3d::Identity(), q, ws);
  const int l_sole = tree.link_index("l_sole");
  EXPECT_TRUE(ws.rotation_W(l_sole).isIdentity(1e-15));
  const Eigen::Vector3d com_above_sole = tree.center_of_mass(ws) - ws.position_W(l_sole);
  EXPECT_NEAR(com_above_sole.z(), 0.45, 0.01);    // thesis Table 6.1: com_z = 0.45 m
  EXPECT_LT(std::abs(com_above_sole.x()), 0.05);  // over the feet (0.2 m long)
  RecordProperty("standing_com_height_m", walkgen_test::scientific(com_above_sole.z()));
}

TEST(HumanoidModel, JacobiansMatchCentralDifferences) {
  const Tree tree = humanoid();
  std::mt19937 rng(2024);
  walkgen_test::TreeJacobianChecks checks;
  for (int trial = 0; trial < 100; ++trial) checks.add_random_configuration(tree, rng, 0.1, {1e-8});
  EXPECT_TRUE(checks.frame.passed()) << checks.frame.message();
  EXPECT_TRUE(checks.com.passed()) << checks.com.message();
  RecordProperty("max_frame_jacobian_fd_error", walkgen_test::scientific(checks.frame.max_error));
  RecordProperty("max_com_jacobian_fd_error", walkgen_test::scientific(checks.com.max_error));
}

}  // namespace
