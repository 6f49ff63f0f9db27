#pragma once
/// @file
/// What every reinforcement-learning environment of walkgen returns from a step, and the
/// benchmarking environment of thesis §11.2.1 (figure 11.16): a point agent moves towards a goal.
///
/// Environments are plain blocks (docs/design.md convention 13): reset(), observe(), step(); they
/// depend on Eigen only (core, walkgen::walkgen), never reset themselves and never print. The
/// trainer of the libtorch backend (walkgen/torch/training.hpp, target walkgen::torch) owns the
/// loop and resets an environment whose episode ended.

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>

#include "walkgen/core/exceptions.hpp"

namespace walkgen {

/// How an episode ended at a step.
enum class EpisodeEnd : std::uint8_t {
  none,       ///< the episode goes on
  success,    ///< the goal was reached ("win")
  failure,    ///< lost: left the allowed region, or the NMPC's QP failed
  truncated,  ///< the step budget ran out (not a terminal state: the trainer bootstraps)
};

/// The enumerator's name ("none", ...), e.g. for logs; "unknown" for a value out of range.
constexpr const char* to_string(EpisodeEnd e) noexcept {
  switch (e) {
    case EpisodeEnd::none:
      return "none";
    case EpisodeEnd::success:
      return "success";
    case EpisodeEnd::failure:
      return "failure";
    case EpisodeEnd::truncated:
      return "truncated";
  }
  return "unknown";
}

/// Outcome of one environment step. Its status is `end` (the name predates the library-wide
/// `status`; environments written by users set it).
struct EnvStep {
  double reward = 0.0;
  EpisodeEnd end = EpisodeEnd::none;
  /// Why the episode ended in failure or was truncated; empty while it goes on and on success.
  /// A static string (the trainer steps environments in its loop).
  const char* message = "";
  bool done() const { return end != EpisodeEnd::none; }
};

/// Settings of the benchmarking environment (thesis §11.2.1). Defaults follow the thesis's
/// code (github.com/mhubii/ppo_libtorch, TestEnvironment.h): 0.1 a.u. per unit action and axis,
/// won within 0.4 a.u., lost beyond 10 a.u.
struct PointGoalSettings {
  double step_size = 0.1;     ///< [a.u.] displacement per unit action, per axis
  double win_radius = 0.4;    ///< [a.u.] the goal is reached closer than this
  double lose_radius = 10.0;  ///< [a.u.] lost farther than this from the goal
  double goal_range = 5.0;    ///< goals are drawn in [−range, range]² around the origin
  /// Goals on the integer grid of [−range, range]² (the thesis code) instead of uniformly in
  /// the square. On the 11 × 11 grid the best possible policy wins only 305.5 episodes per
  /// 10 000 steps on average (docs/learning.md), less than the 311 ± 3 the thesis reports, so
  /// the default is the continuous square ("spawned at a random location", §11.2.1).
  bool integer_goals = false;
  /// Step budget per episode, ending it as truncated; 0: none (the thesis). Training uses one
  /// so that an agent that hovers far from its goal is restarted instead of idling forever.
  int max_steps = 0;
  double win_reward = 10.0;    ///< added on reaching the goal
  double lose_reward = -10.0;  ///< added on leaving lose_radius
};

/// Checks the benchmarking environment's settings (PointGoalEnv's constructor calls this).
/// @throws walkgen::invalid_argument naming the first bad field.
inline void validate(const PointGoalSettings& s) {
  check_positive("PointGoalSettings.step_size", s.step_size);
  check_positive("PointGoalSettings.win_radius", s.win_radius);
  check_positive("PointGoalSettings.goal_range", s.goal_range);
  check_argument(std::isfinite(s.lose_radius) && s.lose_radius > s.win_radius,
                 "PointGoalSettings.lose_radius", "a radius larger than win_radius", s.lose_radius);
  check_argument(s.max_steps >= 0, "PointGoalSettings.max_steps", "a step budget >= 0 (0: none)",
                 s.max_steps);
  check_argument(std::isfinite(s.win_reward), "PointGoalSettings.win_reward", "a finite reward",
                 s.win_reward);
  check_argument(std::isfinite(s.lose_reward), "PointGoalSettings.lose_reward", "a finite reward",
                 s.lose_reward);
}

/// The benchmarking environment of thesis §11.2.1: the agent starts at the origin, a goal is
/// drawn at random; the state is (a_x, a_y, g_x, g_y), the action (Δx, Δy) ∈ [−1, 1]²
/// (clipped) times step_size; the reward is the progress ‖a_{t−1} − g‖ − ‖a_t − g‖, plus
/// win_reward on reaching the goal and lose_reward on leaving lose_radius. Either ends the
/// episode; so does the optional step budget max_steps (truncated).
class PointGoalEnv {
 public:
  static constexpr int kObservationSize = 4;
  static constexpr int kActionSize = 2;

  /// @throws walkgen::invalid_argument for invalid settings (validate()).
  explicit PointGoalEnv(const PointGoalSettings& settings = {}, std::uint64_t seed = 0)
      : s_(settings), rng_(seed) {
    validate(s_);
    reset();
  }

  int observation_size() const { return kObservationSize; }
  int action_size() const { return kActionSize; }

  /// Restarts the goal generator from `seed` (the next reset() draws the seed's first goal).
  void seed(std::uint64_t seed) { rng_.seed(seed); }

  /// Agent back to the origin, a new random goal.
  void reset() {
    Eigen::Vector2d g;
    if (s_.integer_goals) {
      const int r = static_cast<int>(std::floor(s_.goal_range));
      std::uniform_int_distribution<int> d(-r, r);
      g << d(rng_), d(rng_);
    } else {
      std::uniform_real_distribution<double> d(-s_.goal_range, s_.goal_range);
      g << d(rng_), d(rng_);
    }
    reset(g);
  }
  /// Agent back to the origin, the given goal.
  void reset(const Eigen::Vector2d& goal) {
    check_argument(goal.allFinite(), "PointGoalEnv::reset", "a finite goal", "NaN or inf");
    agent_.setZero();
    goal_ = goal;
    steps_ = 0;
  }

  /// Writes the state (a_x, a_y, g_x, g_y) to obs[0..4).
  void observe(float* obs) const {
    obs[0] = static_cast<float>(agent_.x());
    obs[1] = static_cast<float>(agent_.y());
    obs[2] = static_cast<float>(goal_.x());
    obs[3] = static_cast<float>(goal_.y());
  }

  /// Moves the agent by action[0..2) (each clipped to [−1, 1]) times step_size.
  [[nodiscard]] EnvStep step(const float* action) {
    const double before = (agent_ - goal_).norm();
    for (int i = 0; i < 2; ++i) {
      const double a = std::isfinite(action[i]) ? std::clamp<double>(action[i], -1.0, 1.0) : 0.0;
      agent_[i] += s_.step_size * a;
    }
    const double after = (agent_ - goal_).norm();
    EnvStep r;
    r.reward = before - after;
    if (after < s_.win_radius) {
      r.reward += s_.win_reward;
      r.end = EpisodeEnd::success;
    } else if (after > s_.lose_radius) {
      r.reward += s_.lose_reward;
      r.end = EpisodeEnd::failure;
      r.message = "the agent left lose_radius";
    } else if (s_.max_steps > 0 && ++steps_ >= s_.max_steps) {
      r.end = EpisodeEnd::truncated;
      r.message = "the step budget max_steps is spent";
    }
    return r;
  }

  const Eigen::Vector2d& agent() const { return agent_; }
  const Eigen::Vector2d& goal() const { return goal_; }
  const PointGoalSettings& settings() const { return s_; }

 private:
  PointGoalSettings s_;
  std::mt19937_64 rng_;
  Eigen::Vector2d agent_ = Eigen::Vector2d::Zero();
  Eigen::Vector2d goal_ = Eigen::Vector2d::Zero();
  int steps_ = 0;
};

}  // namespace walkgen
