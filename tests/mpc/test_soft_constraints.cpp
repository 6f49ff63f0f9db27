// The soft-constraint fallback (GeneratorSettings::soft, WalkingModel::soften) and the
// infeasibility diagnosis (WalkingMpc::conflicting_blocks). HRP-2 walks straight at 0.3 m/s at
// an obstacle on its path, which makes the linearised QP infeasible a few steps before it: with
// the obstacle rows soft the Gauss–Newton iterations get past the poor linearisation and walk
// around it, every footstep outside the margin. An obstacle that appears too close to keep the
// margin gives the plan that enters it least while every hard block holds (relaxed). Feasible
// ticks are untouched; a soft block that cannot resolve the conflict leaves the tick failed.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <vector>

#include "walkgen/core/exceptions.hpp"
#include "walkgen/mpc/walking_mpc.hpp"

namespace {

using Mpc = walkgen::WalkingMpc<double, 16>;
using walkgen::MpcStatus;
using Obstacle = walkgen::CircleObstacle<double>;

constexpr int kObstacles = 4;  // row block 4 of WalkingModel::Constraints
constexpr double kRadius = 0.15, kMargin = 0.15;
const std::vector<Obstacle> kBlocking{{1.2, 0.0, kRadius, kMargin}};  // on the walking line
const std::vector<Obstacle> kAside{{1.2, 0.45, kRadius, kMargin}};    // beside it

// Walks `mpc` straight at 0.3 m/s among `obstacles` until a tick is not solved (or `ticks`
// ticks); returns the number of ticks walked before it.
int walk_until_not_solved(Mpc& mpc, const std::vector<Obstacle>& obstacles, int ticks) {
  mpc.set_obstacles(obstacles);
  EXPECT_EQ(mpc.set_command({0.3, 0.0, 0.0}), walkgen::CommandStatus::accepted);
  for (int k = 0; k < ticks; ++k) {
    if (mpc.solve().status != MpcStatus::solved) return k;
    mpc.advance();
  }
  return ticks;
}

// Largest violation max(lower − c, c − upper, 0) of row block k's nonlinear constraints by the
// current plan.
double block_violation(const Mpc& mpc, int k) {
  Eigen::VectorXd c(mpc.num_rows()), lower(mpc.num_rows()), upper(mpc.num_rows());
  mpc.constraint_values(mpc.plan().U, c, lower, upper);
  const walkgen::LayoutBlock& b = mpc.layout().rows(k);
  double worst = 0.0;
  for (Eigen::Index r = b.offset; r < b.offset + b.count(); ++r)
    worst = std::max({worst, lower[r] - c[r], c[r] - upper[r]});
  return worst;
}

walkgen::WalkingSettings<double> soft_obstacles(double weight) {
  auto s = walkgen::hrp2_settings<double>();
  s.soft.obstacles = weight;
  return s;
}

TEST(SoftConstraints, TheBlockedWalkIsInfeasibleInTheObstacleRows) {
  Mpc hard(walkgen::hrp2_settings<double>(), 1);
  const int walked = walk_until_not_solved(hard, kBlocking, 80);
  ASSERT_LT(walked, 80) << "the blocking obstacle must make a QP infeasible";
  EXPECT_EQ(hard.result().status, MpcStatus::qp_failed);
  ASSERT_EQ(hard.result().qp_status, walkgen::QpStatus::infeasible);
  // The robot is still outside the margin: the linearised rows, not a collision, conflict.
  const auto& st = hard.state();
  EXPECT_GT(std::hypot(st.com_x[0] - 1.2, st.com_y[0]) - kRadius - kMargin, 0.05);
  const std::uint32_t conflicts = hard.conflicting_blocks();
  EXPECT_TRUE(conflicts >> kObstacles & 1u) << hard.block_names(conflicts);
  EXPECT_EQ(hard.layout().rows(kObstacles).name, std::string("obstacles (eq. 2.79-2.82)"));
  EXPECT_NE(hard.block_names(conflicts).find("obstacles"), std::string::npos);
  EXPECT_EQ(hard.block_names(0), "");
  // The diagnosis leaves the generator as it was: a twin that skipped it plans the same.
  Mpc twin(walkgen::hrp2_settings<double>(), 1);
  ASSERT_EQ(walk_until_not_solved(twin, kBlocking, 80), walked);
  for (int k = 0; k < 5; ++k) {
    hard.advance();
    twin.advance();
    EXPECT_EQ(hard.solve().status, twin.solve().status);
    EXPECT_EQ(hard.plan().U, twin.plan().U) << "tick " << k;
  }
  // Not infeasible: nothing to diagnose.
  Mpc fine(walkgen::hrp2_settings<double>(), 1);
  ASSERT_EQ(fine.solve().status, MpcStatus::solved);
  EXPECT_EQ(fine.conflicting_blocks(), 0u);
}

TEST(SoftConstraints, FeasibleTicksAreUnchanged) {
  // Every block soft: the fallback runs only on an infeasible QP, so a walk past an obstacle
  // that never makes one plans exactly as the hard generator does.
  auto all = walkgen::hrp2_settings<double>();
  all.soft = {1e4, 1e4, 1e4, 1e4, 1e4, 1e4};
  Mpc hard(walkgen::hrp2_settings<double>(), 1), soft(all, 1);
  for (auto* mpc : {&hard, &soft}) {
    mpc->set_obstacles(kAside);
    ASSERT_EQ(mpc->set_command({0.3, 0.0, 0.0}), walkgen::CommandStatus::accepted);
  }
  for (int k = 0; k < 60; ++k) {
    ASSERT_EQ(hard.solve().status, MpcStatus::solved) << "tick " << k;
    const auto& r = soft.solve();
    ASSERT_EQ(r.status, MpcStatus::solved) << "tick " << k;
    EXPECT_FALSE(r.soft_fallback) << "tick " << k;
    EXPECT_EQ(r.relaxed_blocks, 0u);
    ASSERT_EQ(hard.plan().U, soft.plan().U) << "tick " << k;
    hard.advance();
    soft.advance();
  }
  EXPECT_GT(soft.state().com_x[0], 1.2);  // walked past it
}

TEST(SoftConstraints, TheFallbackUndoesABadLinearisationAndWalksAround) {
  // The conflict of the blocked walk is the linearisation's: the tangent half-planes at the
  // shifted plan's footsteps. The elastic QP lets the Gauss–Newton iterations move on, and the
  // corrections converge to a plan that keeps every margin: solved, not relaxed.
  Mpc hard(walkgen::hrp2_settings<double>(), 1), soft(soft_obstacles(1e4), 1);
  const int walked = walk_until_not_solved(hard, kBlocking, 80);
  // The same ticks up to the failure (feasible ticks are unchanged).
  const int soft_walked = walk_until_not_solved(soft, kBlocking, walked);
  ASSERT_EQ(soft_walked, walked);
  EXPECT_EQ(soft.state().com_x, hard.state().com_x);
  const auto& r = soft.solve();
  ASSERT_EQ(r.status, MpcStatus::solved) << r.message;
  EXPECT_TRUE(r.soft_fallback);
  EXPECT_EQ(r.relaxed_blocks, 0u);
  EXPECT_LE(r.constraint_violation, soft.settings().sqp_tolerance);
  // ... and on to 2.5 m. The straight command keeps pushing at the obstacle, so later ticks may
  // enter the margin (relaxed), but none fails, and no footstep lands inside the circle.
  double clearance = 1e9;
  int relaxed = 0;
  for (int k = 0; k < 200 && soft.state().com_x[0] < 2.5; ++k) {
    soft.advance();
    const auto& tick = soft.solve();
    ASSERT_TRUE(tick.status == MpcStatus::solved || tick.status == MpcStatus::relaxed)
        << "tick " << k << ": " << tick.message;
    if (tick.status == MpcStatus::relaxed) {
      ++relaxed;
      EXPECT_EQ(tick.relaxed_blocks, 1u << kObstacles);
      EXPECT_LT(tick.constraint_violation, kMargin);
    }
    for (const auto* f : {&soft.state().support, &soft.state().swing_origin})
      clearance = std::min(clearance, std::hypot(f->x - 1.2, f->y) - kRadius);
  }
  EXPECT_GT(soft.state().com_x[0], 2.5);
  EXPECT_GT(clearance, 0.0);
  std::printf("blocked walk: %d relaxed ticks, smallest footstep-circle distance %.3f m\n", relaxed,
              clearance);
}

TEST(SoftConstraints, AnInfeasibleTickWalksTheLeastViolatingPlan) {
  // An obstacle appears 0.25 m ahead of a robot walking at 0.3 m/s: no plan keeps the margin
  // of 0.15 m (the CoM needs a step to stop, the next footstep is on its way).
  auto ahead = [](const Mpc& mpc) {
    return std::vector<Obstacle>{
        {mpc.state().com_x[0] + 0.25 + kRadius, mpc.state().com_y[0], kRadius, kMargin}};
  };
  Mpc hard(walkgen::hrp2_settings<double>(), 1), soft(soft_obstacles(1e4), 1);
  ASSERT_EQ(walk_until_not_solved(hard, {}, 40), 40);
  ASSERT_EQ(walk_until_not_solved(soft, {}, 40), 40);
  hard.set_obstacles(ahead(hard));
  ASSERT_EQ(hard.solve().status, MpcStatus::qp_failed);
  soft.set_obstacles(ahead(soft));
  const auto& r = soft.solve();
  ASSERT_EQ(r.status, MpcStatus::relaxed) << r.message;
  EXPECT_TRUE(r.soft_fallback);
  EXPECT_EQ(r.qp_status, walkgen::QpStatus::solved);
  EXPECT_EQ(r.relaxed_blocks, 1u << kObstacles) << soft.block_names(r.relaxed_blocks);
  // The elastic QP's solution is a KKT point.
  const auto& qr = soft.workspace().elastic->result();
  EXPECT_LE(qr.primal_residual, 1e-8);
  EXPECT_LE(qr.dual_residual, 1e-6);
  EXPECT_LE(qr.complementarity, 1e-6);
  // The hard blocks hold (to the Gauss–Newton tolerance); the margin is entered, not the circle.
  for (int k = 0; k < soft.layout().num_row_blocks(); ++k) {
    if (k != kObstacles) {
      EXPECT_LE(block_violation(soft, k), 1e-3) << soft.layout().rows(k).name;
    }
  }
  const double entered = block_violation(soft, kObstacles);
  EXPECT_GT(entered, 1e-3);
  EXPECT_LT(entered, kMargin);
  EXPECT_NEAR(r.constraint_violation, entered, 1e-12);
  // Least violating: the plan that ignores the obstacle enters it far deeper.
  Mpc blind(walkgen::hrp2_settings<double>(), 1);
  ASSERT_EQ(walk_until_not_solved(blind, {}, 40), 40);
  ASSERT_EQ(blind.solve().status, MpcStatus::solved);
  blind.set_obstacles(ahead(blind));  // measure the blind plan against the obstacle
  EXPECT_GT(block_violation(blind, kObstacles), entered + 0.05);
  // A weight 100 times smaller trades more margin for the cost.
  Mpc cheap(soft_obstacles(1e2), 1);
  ASSERT_EQ(walk_until_not_solved(cheap, {}, 40), 40);
  cheap.set_obstacles(ahead(cheap));
  ASSERT_EQ(cheap.solve().status, MpcStatus::relaxed);
  EXPECT_GE(block_violation(cheap, kObstacles), entered - 1e-9);
}

TEST(SoftConstraints, ASoftBlockThatCannotResolveTheConflictLeavesTheTickFailed) {
  // Softening the terminal capture point does not free the footsteps from the obstacle rows.
  auto s = walkgen::hrp2_settings<double>();
  s.soft.capture_point = 1e4;
  Mpc hard(walkgen::hrp2_settings<double>(), 1), soft(s, 1);
  const int walked = walk_until_not_solved(hard, kBlocking, 80);
  const std::uint32_t conflicts = hard.conflicting_blocks();
  ASSERT_FALSE(conflicts >> 5 & 1u) << "dropping the capture point alone must not suffice";
  ASSERT_EQ(walk_until_not_solved(soft, kBlocking, 80), walked);
  EXPECT_EQ(soft.result().status, MpcStatus::qp_failed);
  EXPECT_EQ(soft.result().relaxed_blocks, 0u);
}

TEST(SoftConstraints, InvalidWeightsAreRejectedByName) {
  for (double bad : {-1.0, std::nan(""), 1e300, 1e-9}) {
    auto s = walkgen::hrp2_settings<double>();
    s.soft.obstacles = bad;
    try {
      Mpc mpc(s);
      ADD_FAILURE() << "accepted soft.obstacles = " << bad;
    } catch (const walkgen::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("WalkingSettings.soft.obstacles"), std::string::npos)
          << e.what();
    }
  }
}

}  // namespace
