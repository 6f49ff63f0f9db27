// Proves that a generator tick (set_command, solve, interpolate, advance, set_obstacles within the
// capacity, set_state) never touches the heap after construction (docs/design.md convention 6), for
// fixed and dynamic sizes, with obstacles, through correction iterations and a failed QP.

#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include "support/count_allocations.hpp"
#include "walkgen/interpolation/trajectory.hpp"
#include "walkgen/mpc/walking_mpc.hpp"

namespace {

using walkgen_test::count_allocations;

template <typename Mpc>
void expect_ticks_do_not_allocate(const walkgen::WalkingSettings<double>& s) {
  Mpc mpc(s, /*obstacle_capacity=*/2);
  walkgen::WalkingInterpolator<double> interp(walkgen::interpolation_settings(s));
  std::vector<walkgen::TrajectorySample<double>> buffer(std::size_t(interp.samples_per_tick()));
  const std::vector<walkgen::CircleObstacle<double>> none, one{{1.6, 1.0, 1.0, 0.4}},
      blocking{{0.0, 0.0, 2.0, 0.5}};
  int solved = 0, failed = 0, corrected = 0, rejected = 0;
  const long news = count_allocations([&] {
    for (int k = 0; k < 60; ++k) {
      rejected +=
          mpc.set_command({0.1, 0.0, k > 30 ? 0.1 : 0.0}) != walkgen::CommandStatus::accepted;
      if (k == 10) mpc.set_obstacles(one);
      if (k == 40) mpc.set_obstacles(blocking);  // infeasible: the safe plan is kept
      if (k == 41) mpc.set_obstacles(none);
      if (k == 20) {
        auto st = mpc.state();
        st.com_x[0] += 0.005;  // feedback
        mpc.set_state(st);
      }
      const auto& r = mpc.solve();
      (r.status == walkgen::MpcStatus::solved ? solved : failed)++;
      corrected += r.sqp_iterations > s.sqp_iterations;
      interp.interpolate(mpc.tick_plan(), buffer.data());
      mpc.advance();
    }
  });
  EXPECT_EQ(news, 0);
  EXPECT_EQ(rejected, 0);
  EXPECT_GE(solved, 58);
  EXPECT_GE(failed, 1);     // the blocking obstacle was really exercised
  EXPECT_GE(corrected, 1);  // and so were the correction iterations
}

TEST(WalkingMpcNoAlloc, FixedSizes) {
  expect_ticks_do_not_allocate<walkgen::WalkingMpc<double, 16>>(walkgen::hrp2_settings<double>());
}

TEST(WalkingMpcNoAlloc, DynamicSizes) {
  auto s = walkgen::hrp2_settings<double>();
  s.n = 24;
  expect_ticks_do_not_allocate<
      walkgen::WalkingMpc<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::Dynamic>>(s);
}

// The soft-constraint fallback (an infeasible QP solved again as the elastic QP) and the
// diagnosis of a failed one (conflicting_blocks) allocate nothing either.
TEST(WalkingMpcNoAlloc, SoftFallbackAndDiagnosis) {
  auto s = walkgen::hrp2_settings<double>();
  auto soft_settings = s;
  soft_settings.soft.obstacles = 1e4;
  walkgen::WalkingMpc<double, 16> hard(s, 1), soft(soft_settings, 1);
  const std::vector<walkgen::CircleObstacle<double>> none, blocking{{0.0, 0.0, 2.0, 0.5}};
  int relaxed = 0, failed = 0;
  std::uint32_t conflicts = 0;
  const long news = count_allocations([&] {
    for (int k = 0; k < 30; ++k) {
      for (auto* mpc : {&hard, &soft}) {
        (void)mpc->set_command({0.1, 0.0, 0.0});
        if (k == 10) mpc->set_obstacles(blocking);  // the robot inside the margin
        if (k == 12) mpc->set_obstacles(none);
        const auto& r = mpc->solve();
        relaxed += r.status == walkgen::MpcStatus::relaxed;
        if (r.status == walkgen::MpcStatus::qp_failed) {
          ++failed;
          conflicts |= mpc->conflicting_blocks();
        }
        mpc->advance();
      }
    }
  });
  EXPECT_EQ(news, 0);
  EXPECT_EQ(relaxed, 2);  // the soft generator's two blocked ticks
  EXPECT_EQ(failed, 2);   // the hard generator's
  EXPECT_NE(conflicts, 0u);
}

}  // namespace
