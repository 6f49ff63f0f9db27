// Proves that forward kinematics, the centre of mass and both Jacobians never touch the heap
// after the tree and its workspace are made (docs/design.md convention 6), including with an
// expression for q and a Jacobian that is a block of a larger matrix.

#include <gtest/gtest.h>

#include <random>

#include "support/count_allocations.hpp"
#include "support/kinematics.hpp"

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

}  // namespace
