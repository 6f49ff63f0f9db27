// Tests of the reinforcement-learning environments (thesis §11.2), which need the core only:
// the step status' names, the benchmarking environment of §11.2.1 (rewards and ends), the pool
// that steps environments at once, and the NMPC goal environment of §11.2.2 (state in the robot
// frame, a walk to a goal, obstacles kept out of by the footsteps). PPO itself is tested in
// tests/torch/test_ppo.cpp.
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
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

TEST(NmpcGoalEnv, TheMotionInTheStateIsTheRobotsVelocityCommandFootAndPhase) {
  walkgen::NmpcGoalSettings s;
  s.obstacles = 1;
  s.observe_motion = true;
  walkgen::NmpcGoalEnv<16> env(s, 9);
  ASSERT_EQ(env.observation_size(), 2 + 3 + 7);
  walkgen::NmpcGoalTask task;
  task.goal = Eigen::Vector2d(2.0, 1.0);
  task.obstacles.push_back({1.0, -0.6, 0.15, 0.15});
  env.reset(task);
  float obs[12];
  env.observe(obs);
  // the support foot in the robot frame, R_z(θ)ᵀ (F − c)
  const auto expect_foot = [&env](const float* o) {
    const auto& st = env.mpc().state();
    const double q = env.heading(), c = std::cos(q), sn = std::sin(q);
    const Eigen::Vector2d f(st.support.x - env.position().x(), st.support.y - env.position().y());
    EXPECT_NEAR(o[9], c * f.x() + sn * f.y(), 1e-6);
    EXPECT_NEAR(o[10], -sn * f.x() + c * f.y(), 1e-6);
  };
  // standing: no velocity, no command, the step not begun
  EXPECT_NEAR(obs[5], 0.0f, 1e-9);
  EXPECT_NEAR(obs[6], 0.0f, 1e-9);
  EXPECT_EQ(obs[7], 0.0f);
  EXPECT_EQ(obs[8], 0.0f);
  EXPECT_EQ(obs[11], 0.0f);
  expect_foot(obs);
  const float act[2] = {0.8f, 2.5f};  // the turn rate clipped to 1
  for (int k = 0; k < 12; ++k) ASSERT_EQ(env.step(act).end, walkgen::EpisodeEnd::none);
  env.observe(obs);
  const auto& st = env.mpc().state();
  const double q = env.heading(), c = std::cos(q), sn = std::sin(q);
  // the CoM velocity rotated into the robot frame: forward and positive when walking on
  EXPECT_NEAR(obs[5], c * st.com_x[1] + sn * st.com_y[1], 1e-6);
  EXPECT_NEAR(obs[6], -sn * st.com_x[1] + c * st.com_y[1], 1e-6);
  EXPECT_GT(obs[5], 0.05);
  EXPECT_FLOAT_EQ(obs[7], 0.8f);
  EXPECT_FLOAT_EQ(obs[8], 1.0f);
  expect_foot(obs);
  EXPECT_GT(std::hypot(obs[9], obs[10]), 0.02);  // walking: the CoM swings off the foot
  EXPECT_NEAR(obs[11], double(st.phase) / s.walking.samples_per_step(), 1e-7);
  EXPECT_GE(obs[11], 0.0f);
  EXPECT_LT(obs[11], 1.0f);
  // a non-finite action is no command
  const float nan_act[2] = {std::numeric_limits<float>::quiet_NaN(), 0.0f};
  ASSERT_EQ(env.step(nan_act).end, walkgen::EpisodeEnd::none);
  env.observe(obs);
  EXPECT_EQ(obs[7], 0.0f);
  // without observe_motion the state is the thesis's (goal) plus the obstacles
  s.observe_motion = false;
  EXPECT_EQ(walkgen::NmpcGoalEnv<16>(s, 9).observation_size(), 5);
}

TEST(NmpcGoalEnv, ObstacleShapingIsThePotentialDifferenceAndSumsToTheEndsPotential) {
  walkgen::NmpcGoalSettings plain;
  plain.obstacles = 1;
  walkgen::NmpcGoalSettings shaped = plain;
  shaped.obstacle_weight = 2e3;
  shaped.obstacle_shaping_distance = 0.3;
  walkgen::NmpcGoalEnv<16> a(plain, 3), b(shaped, 3);
  walkgen::NmpcGoalTask task;
  task.goal = Eigen::Vector2d(2.0, 0.0);
  task.obstacles.push_back({1.0, 0.0, 0.15, 0.15});  // straight ahead: R + m = 0.3
  a.reset(task);
  b.reset(task);
  const auto phi = [&](const walkgen::NmpcGoalEnv<16>& e) {
    const double c = (e.position() - Eigen::Vector2d(1.0, 0.0)).norm() - 0.3;
    return -2e3 * std::max(0.0, 1.0 - c / 0.3);
  };
  EXPECT_EQ(phi(b), 0.0);  // starts 0.7 m from the circle: outside the shaping distance
  const float forward[2] = {1.0f, 0.0f};
  double sum = 0.0;
  for (int k = 0; k < 60; ++k) {
    const walkgen::EnvStep ra = a.step(forward), rb = b.step(forward);
    ASSERT_EQ(ra.end, rb.end);
    sum += rb.reward - ra.reward;
    if (rb.done()) break;
  }
  // the footsteps stop at the circle; the CoM walked into the shaping zone, so the shaped
  // returns are lower by exactly −Φ at the end (the shaping telescopes)
  EXPECT_LT(phi(b), -500.0);
  EXPECT_NEAR(sum, phi(b), 1e-6 * 2e3);
  shaped.obstacle_shaping_distance = 0.0;
  EXPECT_THROW(walkgen::NmpcGoalEnv<16>(shaped, 3), walkgen::invalid_argument);
}

}  // namespace
