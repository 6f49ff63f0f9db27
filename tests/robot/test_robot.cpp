// The measured zero moment point from two ankle force-torque sensors (thesis eq. 2.11-2.17).
#include "walkgen/robot/robot.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "walkgen/core/math.hpp"

namespace {

using walkgen::ForceTorqueReading;
using walkgen::measured_zmp;

ForceTorqueReading reading(const Eigen::Vector3d& force, const Eigen::Vector3d& torque,
                           const Eigen::Vector3d& position, double yaw) {
  ForceTorqueReading r;
  r.force_S = force;
  r.torque_S = torque;
  r.pose_W_S = Eigen::Translation3d(position) * Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ());
  return r;
}

// Worked by hand, d = 0.03 m:
// left, sensor at (0, 0.07, 0.03), not turned, f = (2, -1, 100) N, tau = (0.5, -1, 0.1) N m:
//   eq. 2.11 p_x = (1 - 2 * 0.03) / 100 = 0.0094, eq. 2.12 p_y = (0.5 + 1 * 0.03) / 100 = 0.0053
//   -> world (0.0094, 0.0753, 0)
// right, sensor at (0.1, -0.07, 0.03), turned 90 deg about z, f = (0, 0, 300), tau = (0, -3, 0):
//   p_S = (0.01, 0, -0.03) -> world (0.1 - 0, -0.07 + 0.01, 0) = (0.1, -0.06, 0)
// eq. 2.16-2.17: x = (0.0094 * 100 + 0.1 * 300) / 400 = 0.07735,
//                y = (0.0753 * 100 - 0.06 * 300) / 400 = -0.026175
TEST(MeasuredZmp, MatchesHandComputedDoubleSupport) {
  const std::array<ForceTorqueReading, 2> ft{
      {reading({2, -1, 100}, {0.5, -1, 0.1}, {0, 0.07, 0.03}, 0.0),
       reading({0, 0, 300}, {0, -3, 0}, {0.1, -0.07, 0.03}, walkgen::kPi / 2)}};
  const walkgen::MeasuredZmp zmp = measured_zmp(ft, 0.03);
  ASSERT_TRUE(zmp.valid);
  EXPECT_TRUE(zmp.in_contact[0] && zmp.in_contact[1]);
  EXPECT_NEAR(zmp.normal_force, 400.0, 1e-12);
  EXPECT_NEAR(zmp.zmp_W.x(), 0.07735, 1e-12);
  EXPECT_NEAR(zmp.zmp_W.y(), -0.026175, 1e-12);
  EXPECT_NEAR(zmp.zmp_W.z(), 0.0, 1e-12);
}

// Property of eq. 2.8: about the single-support ZMP the sensor's wrench has no horizontal moment.
TEST(MeasuredZmp, HorizontalMomentVanishesAboutTheZmpOfOneFoot) {
  const double d = 0.03;
  const Eigen::Vector3d f(3.0, -4.0, 180.0);
  const Eigen::Vector3d tau(1.2, -0.7, 0.3);
  const ForceTorqueReading left = reading(f, tau, {0.2, 0.1, d}, 0.4);
  ForceTorqueReading right = left;
  right.force_S = Eigen::Vector3d(0, 0, -7.8);  // a swinging foot only weighs on its sensor
  right.torque_S.setZero();
  const walkgen::MeasuredZmp zmp = measured_zmp({{left, right}}, d);
  ASSERT_TRUE(zmp.valid);
  EXPECT_TRUE(zmp.in_contact[0]);
  EXPECT_FALSE(zmp.in_contact[1]);
  const Eigen::Vector3d p_S = left.pose_W_S.inverse() * zmp.zmp_W;
  const Eigen::Vector3d moment_S = (Eigen::Vector3d::Zero() - p_S).cross(f) + tau;
  EXPECT_NEAR(moment_S.x(), 0.0, 1e-12);
  EXPECT_NEAR(moment_S.y(), 0.0, 1e-12);
  EXPECT_NEAR(p_S.z(), -d, 1e-12);
}

TEST(MeasuredZmp, NoContactIsInvalidAndBadHeightsThrow) {
  const ForceTorqueReading hanging =
      reading({0, 0, -7.8}, Eigen::Vector3d::Zero(), {0, 0, 0.5}, 0.0);
  const walkgen::MeasuredZmp zmp = measured_zmp({{hanging, hanging}}, 0.03);
  EXPECT_FALSE(zmp.valid);
  EXPECT_EQ(zmp.normal_force, 0.0);
  EXPECT_THROW(measured_zmp({{hanging, hanging}}, -0.01), walkgen::invalid_argument);
  EXPECT_NO_THROW(measured_zmp({{hanging, hanging}}, 0.0));  // readings at the sole
  EXPECT_THROW(measured_zmp({{hanging, hanging}}, std::nan("")), walkgen::invalid_argument);
  EXPECT_THROW(measured_zmp({{hanging, hanging}}, 0.03, -1.0), walkgen::invalid_argument);
}

TEST(MeasuredZmp, ReadingsAtTheSoleGiveTheCentreOfPressureWithoutAnOffset) {
  // A contact wrench reported at the sole (d = 0): 100 N at (0.02, -0.01) of the sole frame
  // has the moment tau = r x f = (-0.01 * 100, -0.02 * 100, 0) about the sole origin.
  const ForceTorqueReading at_sole =
      reading({0, 0, 100.0}, Eigen::Vector3d(-1.0, -2.0, 0.0), {0.3, 0.1, 0.0}, 0.0);
  const walkgen::MeasuredZmp zmp = measured_zmp({{at_sole, at_sole}}, 0.0);
  ASSERT_TRUE(zmp.valid);
  EXPECT_NEAR(zmp.zmp_W.x(), 0.32, 1e-12);
  EXPECT_NEAR(zmp.zmp_W.y(), 0.09, 1e-12);
  EXPECT_NEAR(zmp.zmp_W.z(), 0.0, 1e-12);
}

TEST(RobotStatus, NamesEveryValue) {
  EXPECT_STREQ(walkgen::to_string(walkgen::JointDrive::position), "position");
  EXPECT_STREQ(walkgen::to_string(walkgen::JointDrive::torque), "torque");
  EXPECT_STREQ(walkgen::to_string(walkgen::RobotStatus::ok), "ok");
  EXPECT_STREQ(walkgen::to_string(walkgen::RobotStatus::fallen), "fallen");
  EXPECT_STREQ(walkgen::to_string(walkgen::RobotStatus::diverged), "diverged");
}

// The support polygon of soles 0.2 x 0.1 m below sensors at d = 0.03 m, worked by hand.
TEST(SupportPolygonMargin, IsTheDistanceToTheNearestEdgeOfTheSolesInContact) {
  const double d = 0.03, L = 0.2, W = 0.1;
  std::array<ForceTorqueReading, 2> ft{{reading({0, 0, 100}, {0, 0, 0}, {0, 0.07, d}, 0.0),
                                        reading({0, 0, 100}, {0, 0, 0}, {0, -0.07, d}, 0.0)}};
  walkgen::MeasuredZmp zmp;
  zmp.valid = true;
  zmp.in_contact = {{true, false}};  // left sole only: x in [-0.1, 0.1], y in [0.02, 0.12]
  zmp.zmp_W = Eigen::Vector3d(0.05, 0.07, 0.0);
  EXPECT_NEAR(walkgen::support_polygon_margin(zmp, ft, d, L, W), 0.05, 1e-12);
  zmp.zmp_W = Eigen::Vector3d(0.0, 0.0, 0.0);  // 0.02 below its inner edge
  EXPECT_NEAR(walkgen::support_polygon_margin(zmp, ft, d, L, W), -0.02, 1e-12);
  zmp.in_contact = {{true, true}};  // both: the hull x in [-0.1, 0.1], y in [-0.12, 0.12]
  EXPECT_NEAR(walkgen::support_polygon_margin(zmp, ft, d, L, W), 0.1, 1e-12);
  zmp.zmp_W = Eigen::Vector3d(0.0, 0.115, 0.0);
  EXPECT_NEAR(walkgen::support_polygon_margin(zmp, ft, d, L, W), 0.005, 1e-12);
  // The right foot 0.1 m ahead: the hull's diagonal edge runs from (0.2, -0.02), the right
  // sole's front-left corner, to (0.1, 0.12), the left sole's front-left one.
  ft[1] = reading({0, 0, 100}, {0, 0, 0}, {0.1, -0.07, d}, 0.0);
  const Eigen::Vector2d a(0.2, -0.02), b(0.1, 0.12);
  const Eigen::Vector2d e = (b - a).normalized();
  for (const Eigen::Vector2d& p : {Eigen::Vector2d(0.15, 0.0), Eigen::Vector2d(0.19, 0.02)}) {
    zmp.zmp_W = Eigen::Vector3d(p.x(), p.y(), 0.0);
    const double left_of_edge = e.x() * (p - a).y() - e.y() * (p - a).x();  // > 0 inside
    EXPECT_NEAR(walkgen::support_polygon_margin(zmp, ft, d, L, W), left_of_edge, 1e-12);
  }
  zmp.zmp_W = Eigen::Vector3d(0.15, 0.0, 0.0);
  EXPECT_NEAR(walkgen::support_polygon_margin(zmp, ft, d, L, W), 0.005 / std::sqrt(0.0296), 1e-12);
  zmp.zmp_W = Eigen::Vector3d(0.19, 0.02, 0.0);
  EXPECT_LT(walkgen::support_polygon_margin(zmp, ft, d, L, W), 0.0);
  // A sole turned 90 degrees: 0.1 m long in x, 0.2 m in y.
  ft[0] = reading({0, 0, 100}, {0, 0, 0}, {0, 0, d}, walkgen::kPi / 2);
  zmp.in_contact = {{true, false}};
  zmp.zmp_W = Eigen::Vector3d(0.03, 0.0, 0.0);
  EXPECT_NEAR(walkgen::support_polygon_margin(zmp, ft, d, L, W), 0.02, 1e-12);
}

TEST(SupportPolygonMargin, NoContactIsNanAndBadSizesThrow) {
  const std::array<ForceTorqueReading, 2> ft{};
  walkgen::MeasuredZmp none;  // not valid
  EXPECT_TRUE(std::isnan(walkgen::support_polygon_margin(none, ft, 0.03, 0.2, 0.1)));
  EXPECT_THROW(walkgen::support_polygon_margin(none, ft, -0.01, 0.2, 0.1),
               walkgen::invalid_argument);
  EXPECT_THROW(walkgen::support_polygon_margin(none, ft, 0.03, -0.2, 0.1),
               walkgen::invalid_argument);
  EXPECT_THROW(walkgen::support_polygon_margin(none, ft, 0.03, 0.2, std::nan("")),
               walkgen::invalid_argument);
}

}  // namespace
