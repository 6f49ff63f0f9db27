// Proves that forward kinematics, the centre of mass and both Jacobians never touch the heap
// after the tree and its workspace are made (docs/design.md convention 6), including with an
// expression for q and a Jacobian that is a block of a larger matrix; and so do the IK
// residual, its Jacobian and its errors (kinematics/ik_residual.hpp), and the state estimator's
// update (estimation/base_estimator.hpp), which runs every command period.

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "support/count_allocations.hpp"
#include "support/kinematics.hpp"
#include "walkgen/estimation/base_estimator.hpp"
#include "walkgen/kinematics/ik_residual.hpp"

namespace {

using walkgen_test::count_allocations;

TEST(KinematicTreeNoAlloc, ForwardKinematicsComAndJacobians) {
  std::mt19937 rng(11);
  const walkgen_test::Tree tree(walkgen_test::random_tree(rng, 25));
  auto ws = tree.make_workspace();
  const auto base = walkgen_test::random_base_pose(rng);
  const Eigen::VectorXd q = walkgen_test::random_configuration(tree, rng);
  Eigen::Matrix<double, 6, Eigen::Dynamic> J(6, tree.num_velocities());
  Eigen::Matrix<double, 3, Eigen::Dynamic> Jc(3, tree.num_velocities());
  Eigen::MatrixXd stacked(12, tree.num_velocities());
  Eigen::Vector3d com = Eigen::Vector3d::Zero();
  const int last = tree.num_links() - 1;
  const long news = count_allocations([&] {
    for (int k = 0; k < 10; ++k) {
      tree.forward_kinematics(base.position, base.rotation, q * 0.5, ws);
      com += tree.center_of_mass(ws);
      tree.center_of_mass_jacobian(ws, Jc);
      tree.frame_jacobian(ws, last, J, Eigen::Vector3d(0.1, 0.0, 0.0));
      tree.frame_jacobian(ws, last, stacked.topRows<6>());
    }
  });
  EXPECT_EQ(news, 0);
  EXPECT_TRUE(com.allFinite());
  tree.frame_jacobian(ws, last, J);
  EXPECT_EQ(Eigen::MatrixXd(stacked.topRows<6>()), Eigen::MatrixXd(J));
}

TEST(KinematicTreeNoAlloc, IkResidualJacobianAndErrors) {
  std::mt19937 rng(12);
  const walkgen_test::Tree tree(walkgen_test::random_tree(rng, 25));
  walkgen::IkResidualSettings s;  // any three links of the random tree
  s.left_foot_link = "link7";
  s.right_foot_link = "link12";
  s.torso_link = "link3";
  s.lf_body_point = Eigen::Vector3d(0.05, 0.0, 0.0);
  const walkgen::IkResidual<> residual(tree, s);
  auto ws = residual.make_workspace();
  const auto base = walkgen_test::random_base_pose(rng);
  Eigen::VectorXd x(residual.num_parameters());
  x << base.position, 0.1, -0.2, 0.3, walkgen_test::random_configuration(tree, rng);
  walkgen::IkTarget target;
  target.left_foot.yaw = 0.4;
  walkgen::IkResidual<>::Residual r;
  walkgen::IkResidual<>::Jacobian J(21, x.size());
  double error = 0.0;
  const long news = count_allocations([&] {
    for (int k = 0; k < 10; ++k) {
      residual.evaluate(target, base.rotation, x, r, J, ws);
      error += residual.errors(target, base.rotation, x.data(), ws).com_error;
    }
  });
  EXPECT_EQ(news, 0);
  EXPECT_TRUE(r.allFinite() && J.allFinite() && std::isfinite(error));
}

TEST(KinematicTreeNoAlloc, BaseEstimatorUpdate) {
  std::mt19937 rng(5);
  const walkgen_test::Tree tree(walkgen_test::random_tree(rng, 25));
  walkgen::BaseEstimatorSettings settings;
  settings.sole_links = {{"link7", "link11"}};
  const std::vector<std::string>& joints = tree.joint_names();
  walkgen::BaseEstimator estimator(tree, joints, settings);
  walkgen::RobotOutput m;
  m.q = walkgen_test::random_configuration(tree, rng);
  m.dq = 0.1 * walkgen_test::random_configuration(tree, rng);
  m.imu.available = true;
  m.imu.orientation_W_I = Eigen::Quaterniond(Eigen::AngleAxisd(0.1, Eigen::Vector3d::UnitX()));
  m.imu.angular_velocity_I = Eigen::Vector3d(0.1, -0.2, 0.05);
  m.imu.acceleration_I = Eigen::Vector3d(0.3, 0.0, 9.9);
  m.ft[0].force_S.z() = m.ft[1].force_S.z() = 100.0;  // both feet in contact
  ASSERT_EQ(estimator.reset(Eigen::Vector3d(0.0, 0.0, 1.0), m), walkgen::EstimateStatus::ok);
  walkgen::EstimateStatus status = walkgen::EstimateStatus::ok;
  const long news = count_allocations([&] {
    for (int k = 0; k < 10; ++k) {
      m.ft[1].force_S.z() = k % 2 == 0 ? 100.0 : -5.0;  // the right foot lifts and lands
      if (estimator.update(m, 0.01) != walkgen::EstimateStatus::ok)
        status = walkgen::EstimateStatus::sensor_fault;
    }
  });
  EXPECT_EQ(news, 0);
  EXPECT_EQ(status, walkgen::EstimateStatus::ok);
  EXPECT_TRUE(estimator.estimate().com_W.allFinite());
  EXPECT_TRUE(estimator.estimate().com_velocity_W.allFinite());
}

}  // namespace
