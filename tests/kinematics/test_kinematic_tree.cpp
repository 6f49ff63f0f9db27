// KinematicTree on hand-written descriptions: forward kinematics and centre of mass against
// closed forms, the URDF rpy convention, frame and centre-of-mass Jacobians against central
// finite differences and against automatic differentiation (Eigen's AutoDiffScalar, standing in
// for ceres::Jet) on random trees, and every kind of bad description or call.

#include "walkgen/kinematics/kinematic_tree.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <unsupported/Eigen/AutoDiff>
#include <vector>

#include "support/expect_error.hpp"
#include "support/kinematics.hpp"

namespace {

using walkgen::JointDescription;
using walkgen::JointType;
using walkgen::KinematicDescription;
using walkgen::LinkDescription;
using walkgen_test::make_joint;
using walkgen_test::make_link;
using walkgen_test::random_tree;
using walkgen_test::Tree;

// A planar two-link arm on a base: joints about z, link lengths 1 and 0.5, a fixed tip frame.
KinematicDescription two_link_arm() {
  KinematicDescription d;
  d.name = "arm";
  d.links = {make_link("base", 3.0), make_link("upper", 1.0, {0.5, 0.0, 0.0}),
             make_link("fore", 2.0, {0.25, 0.0, 0.0}), make_link("tip")};
  d.joints = {make_joint("shoulder", JointType::revolute, "base", "upper", {0.0, 0.0, 0.1}),
              make_joint("elbow", JointType::revolute, "upper", "fore", {1.0, 0.0, 0.0}),
              make_joint("tip_fixed", JointType::fixed, "fore", "tip", {0.5, 0.0, 0.0})};
  return d;
}

TEST(KinematicTree, TwoLinkArmMatchesClosedForm) {
  const Tree tree(two_link_arm());
  EXPECT_EQ(tree.num_links(), 4);
  EXPECT_EQ(tree.num_joints(), 2);
  EXPECT_EQ(tree.num_velocities(), 8);
  EXPECT_DOUBLE_EQ(tree.mass(), 6.0);
  auto ws = tree.make_workspace();
  const double a = 0.7, b = -1.2;
  // A base pose: turned by 0.3 rad about z and moved; the closed form is in the base frame.
  const Eigen::Matrix3d R = Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  const Eigen::Vector3d p(0.2, -0.4, 1.0);
  tree.forward_kinematics(p, R, Eigen::Vector2d(a, b), ws);

  const Eigen::Vector3d tip_B(std::cos(a) + 0.5 * std::cos(a + b),
                              std::sin(a) + 0.5 * std::sin(a + b), 0.1);
  const int tip = tree.link_index("tip");
  EXPECT_LT((ws.position_W(tip) - (p + R * tip_B)).norm(), 1e-15);
  const Eigen::Matrix3d R_tip = R * Eigen::AngleAxisd(a + b, Eigen::Vector3d::UnitZ());
  EXPECT_LT((ws.rotation_W(tip) - R_tip).norm(), 1e-15);

  const Eigen::Vector3d upper_com(0.5 * std::cos(a), 0.5 * std::sin(a), 0.1);
  const Eigen::Vector3d fore_com(std::cos(a) + 0.25 * std::cos(a + b),
                                 std::sin(a) + 0.25 * std::sin(a + b), 0.1);
  const Eigen::Vector3d com_B = (1.0 * upper_com + 2.0 * fore_com) / 6.0;  // base CoM at 0
  EXPECT_LT((tree.center_of_mass(ws) - (p + R * com_B)).norm(), 1e-15);
}

TEST(KinematicTree, OriginRpyIsUrdfConvention) {
  KinematicDescription d;
  d.links = {make_link("a", 1.0), make_link("b")};
  d.joints = {make_joint("j", JointType::fixed, "a", "b", {1.0, 2.0, 3.0})};
  d.joints[0].rpy << 0.3, -0.5, 1.1;
  const Tree tree(d);
  auto ws = tree.make_workspace();
  tree.forward_kinematics(Eigen::Vector3d::Zero(), Eigen::Matrix3d::Identity(), Eigen::VectorXd(0),
                          ws);
  auto rot = [](double angle, int axis) {
    return Eigen::AngleAxisd(angle, Eigen::Vector3d::Unit(axis)).toRotationMatrix();
  };
  const Eigen::Matrix3d expected = rot(1.1, 2) * rot(-0.5, 1) * rot(0.3, 0);  // Rz Ry Rx
  EXPECT_LT((ws.rotation_W(tree.link_index("b")) - expected).norm(), 1e-15);
}

// An origin given as a rotation matrix (an MJCF quaternion) replaces rpy, also at the gimbal
// lock; a matrix that is not a rotation is refused.
TEST(KinematicTree, OriginRotationReplacesRpy) {
  KinematicDescription d;
  d.links = {make_link("a", 1.0), make_link("b")};
  d.joints = {make_joint("j", JointType::revolute, "a", "b", {1.0, 2.0, 3.0})};
  d.joints[0].rpy << 0.3, -0.5, 1.1;  // ignored
  const Eigen::Matrix3d R =
      Eigen::AngleAxisd(walkgen::kPi / 2.0, Eigen::Vector3d::UnitY()).toRotationMatrix() *
      Eigen::AngleAxisd(0.4, Eigen::Vector3d::UnitX()).toRotationMatrix();
  d.joints[0].rotation = R;
  const Tree tree(d);
  auto ws = tree.make_workspace();
  Eigen::VectorXd q(1);
  q << 0.7;
  tree.forward_kinematics(Eigen::Vector3d::Zero(), Eigen::Matrix3d::Identity(), q, ws);
  const Eigen::Matrix3d expected = R * Eigen::AngleAxisd(0.7, Eigen::Vector3d::UnitZ());
  EXPECT_LT((ws.rotation_W(tree.link_index("b")) - expected).norm(), 1e-15);
  d.joints[0].rotation = 2.0 * R;
  walkgen_test::expect_invalid_argument([&] { Tree bad(d); },
                                        {"joint 'j'", "orthonormal with determinant +1"});
  d.joints[0].rotation = -R;  // a reflection
  walkgen_test::expect_invalid_argument([&] { Tree bad(d); }, {"determinant +1"});
}

TEST(KinematicTree, LinksParentsFirstAndQInDescriptionOrder) {
  std::mt19937 rng(7);
  const KinematicDescription d = random_tree(rng, 20);
  const Tree tree(d);
  for (int i = 1; i < tree.num_links(); ++i) {
    EXPECT_GE(tree.link(i).parent, 0);
    EXPECT_LT(tree.link(i).parent, i);
  }
  EXPECT_EQ(tree.link(0).parent, -1);
  int k = 0;
  for (const auto& j : d.joints) {
    if (j.type != JointType::revolute) continue;
    EXPECT_EQ(tree.joint_names()[std::size_t(k)], j.name);
    EXPECT_EQ(tree.joint_index(j.name), k);
    ++k;
  }
  EXPECT_EQ(k, tree.num_joints());
}

TEST(KinematicTree, JacobiansMatchCentralDifferencesOnRandomTrees) {
  std::mt19937 rng(42);
  walkgen_test::TreeJacobianChecks checks;
  for (int trial = 0; trial < 20; ++trial) {
    checks.add_random_configuration(Tree(random_tree(rng, 12)), rng, 0.2, {1e-8});
  }
  EXPECT_TRUE(checks.frame.passed()) << checks.frame.message();
  EXPECT_TRUE(checks.com.passed()) << checks.com.message();
  RecordProperty("max_frame_jacobian_fd_error", walkgen_test::scientific(checks.frame.max_error));
  RecordProperty("max_com_jacobian_fd_error", walkgen_test::scientific(checks.com.max_error));
}

// Forward-mode automatic differentiation through the same templated FK (as ceres::Jet will):
// d(point)/dq of every link and d(CoM)/dq equal the analytic Jacobians' joint columns to
// rounding.
TEST(KinematicTree, JacobiansMatchAutomaticDifferentiation) {
  using Ad = Eigen::AutoDiffScalar<Eigen::VectorXd>;
  using AdTree = walkgen::KinematicTree<Ad>;
  std::mt19937 rng(3);
  const Tree tree(random_tree(rng, 10));
  const AdTree ad_tree = tree.cast<Ad>();
  const int n = tree.num_joints(), links = tree.num_links();
  const auto base = walkgen_test::random_base_pose(rng);
  const Eigen::VectorXd q = walkgen_test::random_configuration(tree, rng);

  Eigen::Matrix<Ad, Eigen::Dynamic, 1> q_ad(n);
  for (int i = 0; i < n; ++i) q_ad[i] = Ad(q[i], n, i);
  AdTree::Vector3 p_ad = base.position.cast<Ad>();
  AdTree::Matrix3 R_ad = base.rotation.cast<Ad>();
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) R_ad(i, j).derivatives() = Eigen::VectorXd::Zero(n);
    p_ad[i].derivatives() = Eigen::VectorXd::Zero(n);
  }
  auto ad_ws = ad_tree.make_workspace();
  ad_tree.forward_kinematics(p_ad, R_ad, q_ad, ad_ws);
  // Rows: every link's origin, then the CoM; columns: the joints.
  Eigen::MatrixXd J_ad(3 * links + 3, n);
  for (int link = 0; link <= links; ++link) {
    const AdTree::Vector3 x = link < links ? ad_ws.position_W(link) : ad_tree.center_of_mass(ad_ws);
    for (int r = 0; r < 3; ++r) {
      const bool constant = x[r].derivatives().size() != n;  // the root's origin
      J_ad.row(3 * link + r) = constant ? Eigen::VectorXd::Zero(n) : x[r].derivatives();
    }
  }

  auto ws = tree.make_workspace();
  tree.forward_kinematics(base.position, base.rotation, q, ws);
  Eigen::MatrixXd J(3 * links + 3, n);
  Eigen::Matrix<double, 6, Eigen::Dynamic> J_frame(6, tree.num_velocities());
  walkgen_test::Blocks rows;
  for (int link = 0; link < links; ++link) {
    tree.frame_jacobian(ws, link, J_frame);
    J.middleRows(3 * link, 3) = J_frame.topRows(3).rightCols(n);
    rows.push_back({"origin of link '" + tree.link(link).name + "'", 3});
    for (int r = 0; r < 3; ++r) {
      EXPECT_NEAR(ad_ws.position_W(link)[r].value(), ws.position_W(link)[r], 1e-15);
    }
  }
  Eigen::Matrix<double, 3, Eigen::Dynamic> Jc(3, tree.num_velocities());
  tree.center_of_mass_jacobian(ws, Jc);
  J.bottomRows(3) = Jc.rightCols(n);
  rows.push_back({"CoM", 3});
  walkgen_test::Blocks joints;
  for (const auto& name : tree.joint_names()) joints.push_back({"joint " + name, 1});
  const auto check = walkgen_test::compare_jacobians("joint columns of the frame and CoM Jacobians",
                                                     J, J_ad, {1e-12}, rows, joints,
                                                     "Eigen::AutoDiffScalar through the FK");
  EXPECT_TRUE(check.passed()) << check.message();
  RecordProperty("max_autodiff_error", walkgen_test::scientific(check.max_error));
}

// --- Bad descriptions ----------------------------------------------------------------------------

std::string construction_error(const KinematicDescription& d) {
  try {
    Tree tree(d);
  } catch (const walkgen::invalid_argument& e) {
    return e.what();
  }
  return "no exception";
}

void expect_error(const KinematicDescription& d, const std::vector<std::string>& parts) {
  const std::string message = construction_error(d);
  for (const auto& part : parts) {
    EXPECT_NE(message.find(part), std::string::npos) << "'" << part << "' not in: " << message;
  }
}

TEST(KinematicTree, BadDescriptionsThrowNamingTheElement) {
  KinematicDescription d = two_link_arm();
  expect_error(KinematicDescription{}, {"at least one link"});

  d = two_link_arm();
  d.links[2].name = "upper";
  expect_error(d, {"link 'upper'", "unique name"});

  d = two_link_arm();
  d.joints[1].name = "shoulder";
  expect_error(d, {"joint 'shoulder'", "unique name"});

  d = two_link_arm();
  d.joints[1].parent = "nosuch";
  expect_error(d, {"joint 'elbow'", "parent link", "'nosuch'"});

  d = two_link_arm();
  d.joints[2].child = "nosuch";
  expect_error(d, {"joint 'tip_fixed'", "child link", "'nosuch'"});

  d = two_link_arm();
  d.joints[2].child = "fore";  // fore gets two parent joints
  expect_error(d, {"joint 'tip_fixed'", "only joint whose child is 'fore'", "'elbow'"});

  d = two_link_arm();
  d.joints.pop_back();  // tip is a second root
  expect_error(d, {"exactly one root", "'base', 'tip'"});

  d = two_link_arm();
  d.joints.push_back(make_joint("loop", JointType::fixed, "fore", "base", {0, 0, 0}));
  expect_error(d, {"exactly one root", "none", "cycle"});

  d = two_link_arm();  // a cycle beside the tree: tip -> extra -> tip
  d.links.push_back(make_link("extra"));
  d.joints[2].parent = "extra";
  d.joints.push_back(make_joint("back", JointType::fixed, "tip", "extra", {0, 0, 0}));
  expect_error(d, {"below the root 'base'", "cycle", "'tip', 'extra'"});

  d = two_link_arm();
  d.joints[0].axis.setZero();
  expect_error(d, {"joint 'shoulder'", "axis of length in [1e-6, 1e6]"});

  // Issue 21: (1e200, 0, 0) used to normalise to (0, 0, 0) and load.
  d = two_link_arm();
  d.joints[0].axis = Eigen::Vector3d(1e200, 0, 0);
  expect_error(d, {"joint 'shoulder'", "axis of length in [1e-6, 1e6]"});

  d = two_link_arm();
  d.joints[1].lower = 1.0;
  d.joints[1].upper = -1.0;
  expect_error(d, {"joint 'elbow'", "lower <= upper"});

  d = two_link_arm();
  d.joints[1].xyz.x() = std::nan("");
  expect_error(d, {"joint 'elbow'", "finite origin"});

  d = two_link_arm();
  d.links[1].mass = -1.0;
  expect_error(d, {"link 'upper'", "mass in [0, 1e6] kg"});

  // Issue 21: two links of 1e308 kg used to load with a total mass of inf.
  d = two_link_arm();
  d.links[1].mass = d.links[2].mass = 1e308;
  expect_error(d, {"link 'upper'", "mass in [0, 1e6] kg"});

  d = two_link_arm();
  d.links[1].inertia(0, 1) = 0.5;
  expect_error(d, {"link 'upper'", "symmetric inertia"});
}

TEST(KinematicTree, BadCallsThrow) {
  const Tree tree(two_link_arm());
  auto ws = tree.make_workspace();
  const Eigen::Vector3d p = Eigen::Vector3d::Zero();
  const Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
  try {
    tree.link_index("hand");
    FAIL();
  } catch (const walkgen::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("'base', 'upper', 'fore', 'tip'"), std::string::npos)
        << e.what();
    EXPECT_NE(std::string(e.what()).find("got 'hand'"), std::string::npos) << e.what();
  }
  EXPECT_THROW(tree.joint_index("tip_fixed"), walkgen::invalid_argument);  // not revolute
  Eigen::Matrix<double, 6, Eigen::Dynamic> J(6, tree.num_velocities());
  Eigen::Matrix<double, 3, Eigen::Dynamic> Jc(3, tree.num_velocities());
  EXPECT_THROW(tree.center_of_mass(ws), walkgen::invalid_argument);  // no FK yet
  EXPECT_THROW(tree.frame_jacobian(ws, 1, J), walkgen::invalid_argument);
  try {
    tree.forward_kinematics(p, R, Eigen::Vector3d::Zero(), ws);
    FAIL();
  } catch (const walkgen::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("size of q: expected 2, got 3"), std::string::npos)
        << e.what();
  }
  tree.forward_kinematics(p, R, Eigen::Vector2d::Zero(), ws);
  Eigen::Matrix<double, 6, Eigen::Dynamic> J_small(6, 7);
  try {
    tree.frame_jacobian(ws, 1, J_small);
    FAIL();
  } catch (const walkgen::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("columns of J: expected 8, got 7"), std::string::npos)
        << e.what();
  }
  Eigen::Matrix<double, 3, Eigen::Dynamic> Jc_small(3, 9);
  EXPECT_THROW(tree.center_of_mass_jacobian(ws, Jc_small), walkgen::invalid_argument);
  EXPECT_THROW(tree.frame_jacobian(ws, 4, J), walkgen::invalid_argument);
  EXPECT_THROW(tree.frame_jacobian(ws, -1, J), walkgen::invalid_argument);
  EXPECT_THROW(ws.position_W(4), walkgen::invalid_argument);
  EXPECT_NO_THROW(tree.frame_jacobian(ws, 3, J));
  EXPECT_NO_THROW(tree.center_of_mass_jacobian(ws, Jc));

  KinematicDescription other = two_link_arm();
  other.links.push_back(make_link("extra"));
  other.joints.push_back(make_joint("extra_fixed", JointType::fixed, "tip", "extra", {0, 0, 0}));
  const Tree other_tree(other);
  auto other_ws = other_tree.make_workspace();
  EXPECT_THROW(tree.forward_kinematics(p, R, Eigen::Vector2d::Zero(), other_ws),
               walkgen::invalid_argument);

  KinematicDescription massless = two_link_arm();
  for (auto& l : massless.links) l.mass = 0.0;
  const Tree massless_tree(massless);
  auto massless_ws = massless_tree.make_workspace();
  massless_tree.forward_kinematics(p, R, Eigen::Vector2d::Zero(), massless_ws);
  EXPECT_THROW(massless_tree.center_of_mass(massless_ws), walkgen::invalid_argument);
}

}  // namespace
