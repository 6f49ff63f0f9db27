// Tests of the LIPM preview matrices (thesis eq. 2.25–2.42 with docs/design.md's errata) against
// step-by-step simulation of eq. 2.28, which shares no code with the closed forms.

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <random>

#include "walkgen/core/exceptions.hpp"
#include "walkgen/model/lipm.hpp"

namespace {

using walkgen::LipmPreview;
using walkgen::LipmStep;

TEST(Lipm, StepIntegratesConstantJerkExactly) {
  // With constant jerk j from (p, v, a): p(T) = p + vT + aT²/2 + jT³/6.
  const LipmStep<double> step(0.1);
  const Eigen::Vector3d c(0.3, -0.2, 1.5);
  const Eigen::Vector3d next = step.advance(c, 2.0);
  EXPECT_NEAR(next[0], 0.3 - 0.02 + 1.5 * 0.005 + 2.0 * 0.001 / 6.0, 1e-15);
  EXPECT_NEAR(next[1], -0.2 + 0.15 + 2.0 * 0.005, 1e-15);
  EXPECT_NEAR(next[2], 1.5 + 0.2, 1e-15);
}

template <int N>
void check_against_simulation(int horizon) {
  const double T = 0.1, cz = 0.814, g = 9.81;
  const LipmPreview<double, N> P(T, cz, g, horizon);
  const LipmStep<double> step(T);
  std::mt19937 rng(42);
  std::normal_distribution<double> normal;
  for (int trial = 0; trial < 20; ++trial) {
    Eigen::Vector3d c(normal(rng), normal(rng), normal(rng));
    Eigen::VectorXd jerk(horizon);
    for (int i = 0; i < horizon; ++i) jerk[i] = normal(rng);
    const Eigen::VectorXd pos = P.P_ps * c + P.P_pu * jerk;
    const Eigen::VectorXd vel = P.P_vs * c + P.P_vu * jerk;
    const Eigen::VectorXd acc = P.P_as * c + P.P_au * jerk;
    const Eigen::VectorXd zmp = P.P_zs * c + P.P_zu * jerk;
    Eigen::Vector3d s = c;
    for (int i = 0; i < horizon; ++i) {
      s = step.advance(s, jerk[i]);
      EXPECT_NEAR(pos[i], s[0], 1e-12 * (1 + std::abs(s[0])));
      EXPECT_NEAR(vel[i], s[1], 1e-12 * (1 + std::abs(s[1])));
      EXPECT_NEAR(acc[i], s[2], 1e-12 * (1 + std::abs(s[2])));
      EXPECT_NEAR(zmp[i], s[0] - cz / g * s[2], 1e-12 * (1 + std::abs(s[0])));  // eq. 2.39
    }
  }
}

TEST(Lipm, PreviewMatchesSimulationFixedHorizon) { check_against_simulation<16>(16); }
TEST(Lipm, PreviewMatchesSimulationDynamicHorizon) {
  check_against_simulation<Eigen::Dynamic>(7);
  check_against_simulation<Eigen::Dynamic>(40);
}

TEST(Lipm, ErrataEntries) {
  // docs/design.md §5: P_pu(i, j) = (1 + 3d + 3d²) T³/6, P_vu(i, j) = (1 + 2d) T²/2, d = i − j.
  const double T = 0.2;
  const LipmPreview<double> P(T, 0.8, 9.81, 5);
  EXPECT_NEAR(P.P_pu(4, 1), (1 + 9 + 27) * T * T * T / 6, 1e-15);
  EXPECT_NEAR(P.P_vu(4, 1), (1 + 6) * T * T / 2, 1e-15);
  EXPECT_EQ(P.P_pu(1, 4), 0.0);
  EXPECT_NEAR(P.P_zs(2, 2), 9 * T * T / 2 - 0.8 / 9.81, 1e-15);      // eq. 2.41
  EXPECT_NEAR(P.P_zu(3, 3), T * T * T / 6 - T * 0.8 / 9.81, 1e-15);  // eq. 2.42 diagonal
}

TEST(Lipm, BadArgumentsThrow) {
  EXPECT_THROW((LipmPreview<double>(0.0, 0.8, 9.81, 16)), walkgen::invalid_argument);
  EXPECT_THROW((LipmPreview<double>(0.1, -0.8, 9.81, 16)), walkgen::invalid_argument);
  EXPECT_THROW((LipmPreview<double>(0.1, 0.8, 9.81, 0)), walkgen::invalid_argument);
  EXPECT_THROW((LipmPreview<double, 16>(0.1, 0.8, 9.81, 8)), walkgen::invalid_argument);
  EXPECT_THROW((LipmPreview<double>(0.1, 0.8)), walkgen::invalid_argument);  // N not given
  EXPECT_THROW(LipmStep<double>(std::nan("")), walkgen::invalid_argument);
}

}  // namespace
