// Tests of the reinforcement-learning environments (thesis §11.2), which need the core only:
// the step status' names, the benchmarking environment of §11.2.1 (rewards and ends), the pool
// that steps environments at once, and the NMPC goal environment of §11.2.2 (state in the robot
// frame, a walk to a goal, obstacles kept out of by the footsteps). PPO itself is tested in
// tests/torch/test_ppo.cpp.
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <array>
#include <cmath>
#include <stdexcept>
#include <vector>

#include "support/enum_strings.hpp"
#include "walkgen/learning/environment.hpp"
#include "walkgen/learning/nmpc_environment.hpp"
#include "walkgen/learning/step_pool.hpp"

namespace {

// The status of an environment step follows the status enums' to_string() convention
// (tests/core/test_status_strings.cpp).
TEST(EpisodeEnd, EveryEnumeratorHasItsOwnNameAndOutOfRangeIsUnknown) {
  using walkgen::EpisodeEnd;
  walkgen_test::expect_enum_strings(std::array<EpisodeEnd, 4>{
      EpisodeEnd::none, EpisodeEnd::success, EpisodeEnd::failure, EpisodeEnd::truncated});
  static_assert(to_string(EpisodeEnd::truncated)[0] == 't');
}

TEST(PointGoalEnv, RewardsAndEnds) {
  walkgen::PointGoalEnv env;
  env.reset(Eigen::Vector2d(1.0, 0.0));
  float obs[4];
  env.observe(obs);
  EXPECT_EQ(obs[2], 1.0f);
  const float right[2] = {1.0f, 0.0f};
  walkgen::EnvStep r = env.step(right);
  EXPECT_NEAR(r.reward, 0.1, 1e-12);  // progress
  EXPECT_EQ(r.end, walkgen::EpisodeEnd::none);
  EXPECT_STREQ(r.message, "");
  for (int k = 0; k < 4; ++k) r = env.step(right);  // at 0.5: 0.5 away
  EXPECT_EQ(r.end, walkgen::EpisodeEnd::none);
  r = env.step(right);  // 0.4 away: not < 0.4
  r = env.step(right);  // 0.3 away: won
  EXPECT_EQ(r.end, walkgen::EpisodeEnd::success);
  EXPECT_STREQ(r.message, "");
  EXPECT_NEAR(r.reward, 0.1 + 10.0, 1e-9);
  env.reset(Eigen::Vector2d(9.95, 0.0));
  const float away[2] = {-5.0f, 0.0f};  // clipped to −1
  r = env.step(away);
  EXPECT_EQ(r.end, walkgen::EpisodeEnd::failure);
  EXPECT_STREQ(r.message, "the agent left lose_radius");
  EXPECT_NEAR(r.reward, -0.1 - 10.0, 1e-9);
  EXPECT_NEAR(env.agent().x(), -0.1, 1e-12);
  walkgen::PointGoalSettings budget;
  budget.max_steps = 2;
  walkgen::PointGoalEnv short_env(budget);
  short_env.reset(Eigen::Vector2d(5.0, 0.0));
  EXPECT_EQ(short_env.step(right).end, walkgen::EpisodeEnd::none);
  r = short_env.step(right);
  EXPECT_EQ(r.end, walkgen::EpisodeEnd::truncated);
  EXPECT_STREQ(r.message, "the step budget max_steps is spent");
}

// seed(s) restarts the task generator: the tasks that follow are those of a new environment
// with seed s (whose constructor drew the first), whatever was drawn before.
TEST(Environments, SeedRestartsTheTaskSequence) {
  walkgen::PointGoalEnv fresh({}, 42), reseeded({}, 7);
  reseeded.reset();
  reseeded.seed(42);
  for (int k = 0; k < 3; ++k) {
    reseeded.reset();
    EXPECT_EQ(fresh.goal(), reseeded.goal());
    fresh.reset();
  }
  walkgen::NmpcGoalSettings s;
  s.obstacles = 1;
  walkgen::NmpcGoalEnv<16> a(s, 3), b(s, 4);
  a.seed(11);
  b.seed(11);
  a.reset();
  b.reset();
  EXPECT_EQ(a.goal(), b.goal());
  EXPECT_EQ(a.obstacles()[0].x, b.obstacles()[0].x);
  b.seed(12);
  b.reset();
  EXPECT_NE(a.goal(), b.goal());
}

TEST(StepPool, RunsEveryIndexOnceAndRethrows) {
  walkgen::StepPool pool(2);
  std::vector<int> hits(101, 0);
  for (int rep = 0; rep < 50; ++rep) pool.run(101, [&](int i) { ++hits[i]; });
  for (int h : hits) EXPECT_EQ(h, 50);
  EXPECT_THROW(pool.run(4,
                        [](int i) {
                          if (i == 3) throw std::runtime_error("x");
                        }),
               std::runtime_error);
  pool.run(3, [&](int i) { hits[i] = -1; });  // usable after an exception
  EXPECT_EQ(hits[2], -1);
  EXPECT_THROW(walkgen::StepPool(0), walkgen::invalid_argument);
}

TEST(NmpcGoalEnv, StateIsTheGoalInTheRobotFrame) {
  walkgen::NmpcGoalEnv<16> env({}, 5);
  walkgen::NmpcGoalTask task;
  task.goal = Eigen::Vector2d(-1.0, 0.5);
  env.reset(task);
  float obs[2];
  env.observe(obs);
  EXPECT_NEAR(obs[0], -1.0 - env.position().x(), 1e-6);
  EXPECT_NEAR(obs[1], 0.5 - env.position().y(), 1e-6);
  // Turning in place (v = 0, ω = max) for 2 s: the goal rotates by −ω t in the robot frame,
  // the commands are accepted (|c| < max_command) and every QP solves.
  const float turn[2] = {0.0f, 1.0f};
  for (int k = 0; k < 10; ++k) {
    const walkgen::EnvStep r = env.step(turn);
    ASSERT_EQ(r.end, walkgen::EpisodeEnd::none);
    EXPECT_EQ(env.mpc().result().last_command, walkgen::CommandStatus::accepted);
  }
  EXPECT_GT(env.heading(), 0.3);
  const Eigen::Vector3d c = env.command_of(turn);
  EXPECT_LT(c[2], env.settings().walking.max_command[2]);
  EXPECT_GT(c[2], 0.99 * env.settings().walking.max_command[2]);
  const double q = env.heading();
  const Eigen::Vector2d d = task.goal - env.position();
  env.observe(obs);
  EXPECT_NEAR(obs[0], std::cos(q) * d.x() + std::sin(q) * d.y(), 1e-5);
  EXPECT_NEAR(obs[1], -std::sin(q) * d.x() + std::cos(q) * d.y(), 1e-5);
}

TEST(NmpcGoalEnv, TheStepBudgetTruncatesWithItsMessage) {
  walkgen::NmpcGoalSettings s;
  s.max_steps = 1;
  walkgen::NmpcGoalEnv<16> env(s, 5);  // goals at 0.5 m or more: not reached in one step
  const float stand[2] = {0.0f, 0.0f};
  const walkgen::EnvStep r = env.step(stand);
  EXPECT_EQ(r.end, walkgen::EpisodeEnd::truncated);
  EXPECT_STREQ(r.message, "the step budget max_steps is spent");
}

TEST(NmpcGoalEnv, WalkingToAGoalSucceedsWithTheBonus) {
  walkgen::NmpcGoalEnv<16> env({}, 5);
  walkgen::NmpcGoalTask task;
  task.goal = Eigen::Vector2d(0.8, 0.0);
  env.reset(task);
  const float forward[2] = {1.0f, 0.0f};
  walkgen::EnvStep r;
  double total = 0.0;
  for (int k = 0; k < env.settings().max_steps && !r.done(); ++k) {
    r = env.step(forward);
    total += r.reward;
  }
  EXPECT_EQ(r.end, walkgen::EpisodeEnd::success);
  EXPECT_LT(env.distance(), env.settings().success_radius);
  // ≈ w_goal · (0.8 − 0.2) + 100 − the time penalty
  EXPECT_GT(total, 6e3 * 0.55 + 100 - 200);
  EXPECT_LT(total, 6e3 * 0.8 + 100);
}

TEST(NmpcGoalEnv, ObstaclesAreInTheStateAndKeptOutOfByTheFootsteps) {
  walkgen::NmpcGoalSettings s;
  s.obstacles = 1;
  walkgen::NmpcGoalEnv<16> env(s, 9);
  EXPECT_EQ(env.observation_size(), 5);
  walkgen::NmpcGoalTask task;
  task.goal = Eigen::Vector2d(2.0, 0.0);
  task.obstacles.push_back({1.0, 0.05, 0.15, 0.15});
  env.reset(task);
  float obs[5];
  env.observe(obs);
  EXPECT_NEAR(obs[4], 0.3f, 1e-6);
  const float forward[2] = {1.0f, 0.0f};
  for (int k = 0; k < 60; ++k)
    if (env.step(forward).done()) break;
  EXPECT_GE(env.min_obstacle_clearance(), 0.15 - 2e-3);  // the margin, up to the SQP tolerance
  task.obstacles.clear();
  EXPECT_THROW(env.reset(task), walkgen::invalid_argument);
}

}  // namespace
