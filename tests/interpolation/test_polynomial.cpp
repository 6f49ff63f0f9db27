// Foot trajectory polynomials (thesis §2.3.1): boundary conditions, derivatives against finite
// differences, and the closed-form coefficients against a numerical solve of eq. 2.99 / 2.109.

#include "walkgen/interpolation/polynomial.hpp"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <random>
#include <string>

#include "support/derivatives.hpp"

namespace {

using walkgen::Sample3;

class PolynomialTest : public ::testing::Test {
 protected:
  std::mt19937 rng_{42};
  double uniform(double lo, double hi) {
    return std::uniform_real_distribution<double>(lo, hi)(rng_);
  }
  Sample3<double> random_state() { return {uniform(-1, 1), uniform(-2, 2), uniform(-5, 5)}; }
};

// Derivatives reported by evaluate() against central differences of the lower derivative.
template <int Degree>
void expect_consistent_derivatives(const walkgen::Polynomial<double, Degree>& p) {
  const double h = 1e-6;
  auto position = [&](const Eigen::VectorXd& t) {
    return Eigen::VectorXd::Constant(1, p.evaluate(t[0]).position);
  };
  auto velocity = [&](const Eigen::VectorXd& t) {
    return Eigen::VectorXd::Constant(1, p.evaluate(t[0]).velocity);
  };
  walkgen_test::JacobianCheck v, a;
  for (int k = 1; k < 20; ++k) {
    const Eigen::VectorXd t = Eigen::VectorXd::Constant(1, p.duration * k / 20.0);
    const auto s = p.evaluate(t[0]);
    const std::string at = " at t = " + std::to_string(t[0]) + " s";
    v.merge(walkgen_test::compare_jacobians(
        "velocity" + at, Eigen::MatrixXd::Constant(1, 1, s.velocity),
        walkgen_test::central_differences(position, t, h), {1e-6, 1e-6}));
    a.merge(walkgen_test::compare_jacobians(
        "acceleration" + at, Eigen::MatrixXd::Constant(1, 1, s.acceleration),
        walkgen_test::central_differences(velocity, t, h), {1e-5, 1e-5}));
  }
  EXPECT_TRUE(v.passed()) << v.message();
  EXPECT_TRUE(a.passed()) << a.message();
}

TEST_F(PolynomialTest, QuinticMeetsAllSixBoundaryConditions) {
  for (int trial = 0; trial < 200; ++trial) {
    const double T = uniform(0.05, 2.0);
    const auto s0 = random_state(), s1 = random_state();
    const auto p = walkgen::quintic(T, s0, s1);
    const auto a = p.evaluate(0.0), b = p.evaluate(T);
    const double tol = 1e-9 * (1 + 1 / (T * T * T));
    EXPECT_NEAR(a.position, s0.position, tol);
    EXPECT_NEAR(a.velocity, s0.velocity, tol);
    EXPECT_NEAR(a.acceleration, s0.acceleration, tol);
    EXPECT_NEAR(b.position, s1.position, tol);
    EXPECT_NEAR(b.velocity, s1.velocity, tol);
    EXPECT_NEAR(b.acceleration, s1.acceleration, tol);
  }
}

TEST_F(PolynomialTest, QuinticCoefficientsSolveEquation2_109) {
  const double T = 0.7;
  const auto s0 = random_state(), s1 = random_state();
  Eigen::Matrix<double, 6, 6> M;
  M << 1, 0, 0, 0, 0, 0,                                               //
      0, 1, 0, 0, 0, 0,                                                //
      0, 0, 2, 0, 0, 0,                                                //
      1, T, T * T, std::pow(T, 3), std::pow(T, 4), std::pow(T, 5),     //
      0, 1, 2 * T, 3 * T * T, 4 * std::pow(T, 3), 5 * std::pow(T, 4),  //
      0, 0, 2, 6 * T, 12 * T * T, 20 * std::pow(T, 3);
  Eigen::Matrix<double, 6, 1> b;
  b << s0.position, s0.velocity, s0.acceleration, s1.position, s1.velocity, s1.acceleration;
  const Eigen::Matrix<double, 6, 1> expected = M.fullPivLu().solve(b);
  EXPECT_LE((walkgen::quintic(T, s0, s1).a - expected).lpNorm<Eigen::Infinity>(),
            1e-9 * (1 + expected.lpNorm<Eigen::Infinity>()));
}

TEST_F(PolynomialTest, QuinticDerivativesMatchFiniteDifferences) {
  expect_consistent_derivatives(walkgen::quintic(0.8, random_state(), random_state()));
}

TEST_F(PolynomialTest, QuarticLiftStartsAndEndsFlatWithApexAtMidStep) {
  const double T = 0.4, h = 0.05;
  const auto z = walkgen::quartic_lift(T, 0.0, 0.0, h, 0.0, 0.0);
  EXPECT_NEAR(z.evaluate(0).position, 0, 1e-12);
  EXPECT_NEAR(z.evaluate(0).velocity, 0, 1e-12);
  EXPECT_NEAR(z.evaluate(T / 2).position, h, 1e-12);
  EXPECT_NEAR(z.evaluate(T / 2).velocity, 0, 1e-9);  // symmetric: the apex is a maximum
  EXPECT_NEAR(z.evaluate(T).position, 0, 1e-12);
  EXPECT_NEAR(z.evaluate(T).velocity, 0, 1e-12);
  for (int k = 0; k <= 100; ++k) {
    const double zk = z.evaluate(T * k / 100).position;
    EXPECT_GE(zk, -1e-12) << "the foot must not go below the ground";
    EXPECT_LE(zk, h + 1e-12) << "nor above the step height";
  }
  expect_consistent_derivatives(z);
}

TEST_F(PolynomialTest, QuarticCoefficientsSolveEquation2_99) {
  const double T = 0.9, z0 = uniform(-0.1, 0.1), v0 = uniform(-1, 1), zm = uniform(0, 0.2),
               z1 = uniform(-0.1, 0.1), v1 = uniform(-1, 1);
  Eigen::Matrix<double, 5, 5> M;
  const double H = T / 2;
  M << 1, 0, 0, 0, 0,                         //
      0, 1, 0, 0, 0,                          //
      1, H, H * H, H * H * H, H * H * H * H,  //
      1, T, T * T, T * T * T, T * T * T * T,  //
      0, 1, 2 * T, 3 * T * T, 4 * T * T * T;
  const Eigen::Matrix<double, 5, 1> b(z0, v0, zm, z1, v1);
  const Eigen::Matrix<double, 5, 1> expected = M.fullPivLu().solve(b);
  EXPECT_LE((walkgen::quartic_lift(T, z0, v0, zm, z1, v1).a - expected).lpNorm<Eigen::Infinity>(),
            1e-9 * (1 + expected.lpNorm<Eigen::Infinity>()));
}

TEST_F(PolynomialTest, EvaluationHoldsTheEndStatesOutsideTheInterval) {
  const auto p = walkgen::quintic(0.5, Sample3<double>{0, 0, 0}, Sample3<double>{1, 0, 0});
  EXPECT_DOUBLE_EQ(p.evaluate(-0.1).position, 0.0);
  EXPECT_DOUBLE_EQ(p.evaluate(0.7).position, p.evaluate(0.5).position);
  EXPECT_NEAR(p.evaluate(0.7).position, 1.0, 1e-12);
}

TEST_F(PolynomialTest, FloatScalarWorks) {
  const auto p = walkgen::quintic(0.8f, Sample3<float>{0, 0, 0}, Sample3<float>{0.2f, 0, 0});
  EXPECT_NEAR(p.evaluate(0.8f).position, 0.2f, 1e-6f);
  EXPECT_NEAR(p.evaluate(0.4f).position, 0.1f, 1e-6f);  // symmetric rest-to-rest profile
}

TEST_F(PolynomialTest, BadDurationThrowsWithExpectedGot) {
  const Sample3<double> s{0, 0, 0};
  for (double T : {0.0, -0.1, std::numeric_limits<double>::quiet_NaN(),
                   std::numeric_limits<double>::infinity()}) {
    EXPECT_THROW(walkgen::quintic(T, s, s), walkgen::invalid_argument) << T;
    EXPECT_THROW(walkgen::quartic_lift(T, 0.0, 0.0, 0.05, 0.0, 0.0), walkgen::invalid_argument);
  }
  try {
    walkgen::quintic(-1.0, s, s);
    FAIL() << "no exception";
  } catch (const walkgen::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("expected a duration > 0 s, got -1"), std::string::npos)
        << e.what();
  }
}

}  // namespace
