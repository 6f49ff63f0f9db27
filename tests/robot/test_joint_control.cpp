// The joint controller of torque-driven robots (walkgen/robot/joint_control.hpp): the PD law
// with feed-forward, the clamp to the motors' limits and its count, limp on non-finite input.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <initializer_list>
#include <string>

#include "walkgen/robot/joint_control.hpp"

namespace {

using walkgen::JointTorqueController;
using walkgen::JointTorqueResult;

Eigen::VectorXd vec(std::initializer_list<double> v) {
  Eigen::VectorXd x(static_cast<Eigen::Index>(v.size()));
  Eigen::Index i = 0;
  for (double e : v) x[i++] = e;
  return x;
}

TEST(JointTorqueController, PdPlusFeedforwardWorkedByHand) {
  const JointTorqueController c(vec({100, 50}), vec({5, 2}), vec({-80, -10}), vec({80, 10}));
  Eigen::VectorXd tau(2);
  // joint 0: 1 + 100 (0.5 - 0.4) + 5 (0.2 - 0.0) = 12; joint 1: -2 + 50 (0 - 0.1) + 2 (0 - 1) = -9
  const JointTorqueResult r = c.compute(vec({0.5, 0.0}), vec({0.2, 0.0}), vec({1.0, -2.0}),
                                        vec({0.4, 0.1}), vec({0.0, 1.0}), tau);
  EXPECT_TRUE(r.finite);
  EXPECT_EQ(r.saturated, 0);
  EXPECT_NEAR(tau[0], 12.0, 1e-12);
  EXPECT_NEAR(tau[1], -9.0, 1e-12);
}

TEST(JointTorqueController, ClampsToTheLimitsAndCountsEachClampedJoint) {
  const JointTorqueController c(vec({1000, 1000, 1000}), vec({0, 0, 0}), vec({-50, -50, -5}),
                                vec({50, 25, 5}));
  Eigen::VectorXd tau(3);
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(3);
  const JointTorqueResult r = c.compute(vec({1.0, 0.04, -1.0}), zero, zero, zero, zero, tau);
  EXPECT_EQ(r.saturated, 3);  // 1000 -> 50, 40 -> 25, -1000 -> -5
  EXPECT_DOUBLE_EQ(tau[0], 50.0);
  EXPECT_DOUBLE_EQ(tau[1], 25.0);
  EXPECT_DOUBLE_EQ(tau[2], -5.0);
}

TEST(JointTorqueController, NonFiniteInputGivesZeroTorqueAndSaysSo) {
  const JointTorqueController c(vec({100, 100}), vec({1, 1}), vec({-10, -10}), vec({10, 10}));
  Eigen::VectorXd tau = vec({3.0, 3.0});
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(2);
  for (int which = 0; which < 5; ++which) {
    Eigen::VectorXd in[5] = {zero, zero, zero, zero, zero};
    in[which][1] = std::nan("");
    const JointTorqueResult r = c.compute(in[0], in[1], in[2], in[3], in[4], tau);
    EXPECT_FALSE(r.finite) << "input " << which;
    EXPECT_EQ(tau, zero) << "input " << which;
  }
}

std::string thrown(const std::function<void()>& f) {
  try {
    f();
  } catch (const walkgen::invalid_argument& e) {
    return e.what();
  }
  return "";
}

TEST(JointTorqueController, BadGainsSizesAndLimitsThrowNamingTheJoint) {
  const Eigen::VectorXd one = vec({1.0}), two = vec({1.0, 1.0});
  EXPECT_NE(thrown([&] { JointTorqueController(two, one, -two, two); }).find("one size"),
            std::string::npos);
  const std::string negative = thrown([&] { JointTorqueController(two, vec({1, -1}), -two, two); });
  EXPECT_NE(negative.find("joint 1"), std::string::npos) << negative;
  EXPECT_NE(thrown([&] {
              JointTorqueController(vec({1, std::nan("")}), two, -two, two);
            }).find("joint 1"),
            std::string::npos);
  EXPECT_NE(thrown([&] { JointTorqueController(two, two, two, two); }).find("tau_min <= 0"),
            std::string::npos);
  EXPECT_NO_THROW(JointTorqueController(two, two, -two, two));
}

}  // namespace
