// The whole-body IK residual and its analytic Jacobian (include/walkgen/kinematics/ik_residual.hpp)
// on walkgen's humanoid, without Ceres: the Jacobian against central differences over random
// targets, configurations and base rotation vectors (both joint counts), the residual and the
// errors at the configuration a target was made from, a broken Jacobian entry caught by the
// checker with its block named, and bad input. tests/ceres/test_inverse_kinematics.cpp checks
// the same Jacobian against Ceres' Jets.

#include "walkgen/kinematics/ik_residual.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>
#include <string>

#include "support/derivatives.hpp"
#include "support/kinematics.hpp"
#include "walkgen/urdf/urdf_loader.hpp"

namespace {

using walkgen::IkTarget;
using walkgen_test::Tree;

const Tree& humanoid() {
  static const Tree t = walkgen::kinematic_tree_from_urdf_file(std::string(WALKGEN_SOURCE_DIR) +
                                                               "/models/walkgen_humanoid.urdf");
  return t;
}

Eigen::Matrix3d random_rotation(std::mt19937& rng, double max_angle) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const Eigen::Vector3d axis = Eigen::Vector3d(u(rng), u(rng), u(rng)).normalized();
  return Eigen::AngleAxisd(max_angle * u(rng), axis).toRotationMatrix();
}

/// A target near the FK of a random configuration: every residual block non-zero.
IkTarget random_target(std::mt19937& rng) {
  const Tree& t = humanoid();
  auto ws = t.make_workspace();
  const auto base = walkgen_test::random_base_pose(rng);
  t.forward_kinematics(base.position, base.rotation, walkgen_test::random_configuration(t, rng),
                       ws);
  std::uniform_real_distribution<double> u(-0.1, 0.1);
  auto near = [&](const Eigen::Vector3d& p) {
    return Eigen::Vector3d(p + Eigen::Vector3d(u(rng), u(rng), u(rng)));
  };
  IkTarget target;
  target.com_W = near(t.center_of_mass(ws));
  target.left_foot = {near(ws.position_W(t.link_index("l_sole"))), 30 * u(rng)};
  target.right_foot = {near(ws.position_W(t.link_index("r_sole"))), 30 * u(rng)};
  target.base_rotation_W = random_rotation(rng, 0.3) * base.rotation;
  target.torso_rotation_W = random_rotation(rng, 0.3) * ws.rotation_W(t.link_index("chest"));
  return target;
}

/// The residual's row blocks (IkResidual::kRowBlocks, three rows each).
walkgen_test::Blocks row_blocks() {
  walkgen_test::Blocks rows;
  for (const char* name : walkgen::IkResidual<>::kRowBlocks) rows.push_back({name, 3});
  return rows;
}

/// The analytic Jacobian against central differences of the residual at random x: base rotation
/// vectors 0 and 1e-5 to 0.8 rad, random start rotations, non-zero body points.
template <int NumJoints>
void check_against_central_differences() {
  const walkgen::IkResidual<NumJoints> residual(
      humanoid(), walkgen_test::offset_ik_settings<walkgen::IkResidualSettings>());
  auto ws = residual.make_workspace();
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  walkgen_test::JacobianCheck worst;
  for (int i = 0; i < 24; ++i) {
    const IkTarget target = random_target(rng);
    const Eigen::Matrix3d start = random_rotation(rng, walkgen::kPi);
    const Eigen::Vector3d axis = Eigen::Vector3d(u(rng), u(rng), u(rng)).normalized();
    const double angle = i % 6 == 5 ? 0.0 : std::pow(10.0, -5.0 + 4.9 * (i % 6) / 4.0);
    Eigen::VectorXd x(residual.num_parameters());
    x << u(rng), u(rng), u(rng), angle * axis, walkgen_test::random_configuration(humanoid(), rng);
    typename walkgen::IkResidual<NumJoints>::Residual r;
    typename walkgen::IkResidual<NumJoints>::Jacobian J;
    residual.evaluate(target, start, x, r, J, ws);
    auto f = [&](const Eigen::VectorXd& xx) {
      typename walkgen::IkResidual<NumJoints>::Residual rr;
      residual.evaluate(target, start, xx.data(), rr.data(), nullptr, ws);
      return Eigen::VectorXd(rr);
    };
    EXPECT_LE((f(x) - r).cwiseAbs().maxCoeff(), 0.0);  // with or without the Jacobian
    worst.merge(
        walkgen_test::compare_jacobians("IK residual Jacobian (sample " + std::to_string(i) +
                                            ", |delta| " + std::to_string(angle) + ")",
                                        J, walkgen_test::central_differences(f, x), {1e-8},
                                        row_blocks(), walkgen_test::velocity_blocks(humanoid())));
  }
  EXPECT_TRUE(worst.passed()) << worst.message();
  std::printf("IK residual Jacobian vs central differences (joints %d): largest difference %.2e\n",
              NumJoints, worst.max_error);
  ::testing::Test::RecordProperty("max_fd_error", walkgen_test::scientific(worst.max_error));
}

TEST(IkResidual, AnalyticJacobianMatchesCentralDifferences) {
  check_against_central_differences<15>();
  check_against_central_differences<Eigen::Dynamic>();
}

// At the configuration a target was made from, the residual and every error vanish: the zero
// configuration (soles flat, every frame parallel to the root's) under a turned, moved base,
// reached from a start rotation 0.3 rad off by the base rotation vector.
TEST(IkResidual, VanishesAtTheConfigurationTheTargetWasMadeFrom) {
  const walkgen::IkResidual<15> residual(humanoid());
  auto ws = residual.make_workspace();
  const Tree& t = humanoid();
  auto fk = t.make_workspace();
  const double yaw = 0.7;
  const Eigen::Matrix3d R = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  const Eigen::Vector3d p(0.3, -0.2, 0.6);
  t.forward_kinematics(p, R, Eigen::VectorXd::Zero(15), fk);
  IkTarget target;
  target.com_W = t.center_of_mass(fk);
  target.left_foot = {fk.position_W(t.link_index("l_sole")), yaw};
  target.right_foot = {fk.position_W(t.link_index("r_sole")), yaw};
  target.hold_upright(yaw);
  const Eigen::Matrix3d start =
      Eigen::AngleAxisd(yaw - 0.3, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  Eigen::VectorXd x = Eigen::VectorXd::Zero(21);
  x << p, 0.0, 0.0, 0.3, Eigen::VectorXd::Zero(15);
  walkgen::IkResidual<15>::Residual r;
  walkgen::IkResidual<15>::Jacobian J;
  residual.evaluate(target, start, x, r, J, ws);
  EXPECT_LE(r.cwiseAbs().maxCoeff(), 1e-15);
  EXPECT_TRUE(walkgen::IkResidual<15>::base_rotation(start, x.data()).isApprox(R, 1e-15));
  const walkgen::IkResult e = residual.errors(target, start, x.data(), ws);
  for (double error : {e.com_error, e.foot_position_error, e.foot_yaw_error, e.foot_tilt_error,
                       e.base_orientation_error, e.torso_orientation_error}) {
    EXPECT_LE(error, 1e-7);  // rotation angles from a quaternion: about sqrt(eps)
  }
  EXPECT_EQ(e.status, walkgen::IkStatus::invalid_input);  // errors only: nothing was solved
}

// The checker catches one wrong entry of the analytic Jacobian and names its place: the right
// sole's height against the right knee.
TEST(IkResidual, ABrokenJacobianEntryFailsTheCheckWithItsBlock) {
  const walkgen::IkResidual<15> residual(humanoid());
  auto ws = residual.make_workspace();
  std::mt19937 rng(5);
  const IkTarget target = random_target(rng);
  Eigen::VectorXd x(21);
  x << 0.1, 0.2, 0.5, 0.01, -0.02, 0.03, walkgen_test::random_configuration(humanoid(), rng);
  walkgen::IkResidual<15>::Residual r;
  walkgen::IkResidual<15>::Jacobian J;
  const Eigen::Matrix3d start = Eigen::Matrix3d::Identity();
  residual.evaluate(target, start, x, r, J, ws);
  auto f = [&](const Eigen::VectorXd& xx) {
    walkgen::IkResidual<15>::Residual rr;
    residual.evaluate(target, start, xx.data(), rr.data(), nullptr, ws);
    return Eigen::VectorXd(rr);
  };
  const Eigen::MatrixXd J_fd = walkgen_test::central_differences(f, x);
  const auto rows = row_blocks(), cols = walkgen_test::velocity_blocks(humanoid());
  EXPECT_TRUE(walkgen_test::compare_jacobians("IK residual Jacobian", J, J_fd, {1e-8}, rows, cols)
                  .passed());
  const int knee = 6 + humanoid().joint_index("r_knee");
  J(walkgen::IkResidual<15>::kRightSoleRow + 2, knee) += 1e-3;
  const auto check =
      walkgen_test::compare_jacobians("IK residual Jacobian", J, J_fd, {1e-8}, rows, cols);
  EXPECT_FALSE(check.passed());
  EXPECT_EQ(check.failures, 1);
  EXPECT_EQ(check.row, 11);
  EXPECT_EQ(check.col, knee);
  const std::string message = check.message();
  for (const char* part :
       {"IK residual Jacobian vs central differences", "1 entry beyond the tolerance 1e-08",
        "row 11 [right sole position (row 2 of 3)]", "column 15 [joint r_knee]"}) {
    EXPECT_NE(message.find(part), std::string::npos) << "'" << part << "' not in: " << message;
  }
  std::printf("the checker on a broken entry: %s\n", message.c_str());
  // A NaN fails too, and blocks that do not cover the matrix are a mistake of the test.
  J(0, 0) = std::nan("");
  EXPECT_EQ(walkgen_test::compare_jacobians("J", J, J_fd, {1e-8}).failures, 2);
  EXPECT_THROW(walkgen_test::compare_jacobians("J", J, J_fd, {1e-8}, {{"CoM", 3}}),
               std::invalid_argument);
}

TEST(IkResidual, BadInputThrows) {
  walkgen::IkResidualSettings s;
  s.torso_link = "no_such_link";
  EXPECT_THROW(walkgen::IkResidual<>(humanoid(), s), walkgen::invalid_argument);
  s = walkgen::IkResidualSettings();
  s.com_weight = 0.0;
  EXPECT_THROW(walkgen::IkResidual<>(humanoid(), s), walkgen::invalid_argument);
  s = walkgen::IkResidualSettings();
  s.lf_body_point.x() = std::nan("");
  EXPECT_THROW(walkgen::IkResidual<>(humanoid(), s), walkgen::invalid_argument);
  EXPECT_THROW(walkgen::IkResidual<3>{humanoid()}, walkgen::invalid_argument);

  const walkgen::IkResidual<> residual(humanoid());
  auto ws = residual.make_workspace();
  walkgen::IkResidual<>::Residual r;
  walkgen::IkResidual<>::Jacobian J;
  const Eigen::Matrix3d I = Eigen::Matrix3d::Identity();
  EXPECT_THROW(residual.evaluate(IkTarget(), I, Eigen::VectorXd::Zero(20), r, J, ws),
               walkgen::invalid_argument);
  EXPECT_THROW(residual.evaluate(IkTarget(), 2.0 * I, Eigen::VectorXd::Zero(21), r, J, ws),
               walkgen::invalid_argument);
  IkTarget bad;
  bad.left_foot.yaw = std::nan("");
  EXPECT_THROW(residual.evaluate(bad, I, Eigen::VectorXd::Zero(21), r, J, ws),
               walkgen::invalid_argument);
  EXPECT_NO_THROW(residual.evaluate(IkTarget(), I, Eigen::VectorXd::Zero(21), r, J, ws));
  EXPECT_TRUE(r.allFinite() && J.allFinite());
}

}  // namespace
