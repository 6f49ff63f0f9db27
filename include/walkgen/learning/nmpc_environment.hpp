#pragma once
/// @file
/// The fusion of the NMPC with reinforcement learning (thesis §11.2.2, figure 11.19): a policy
/// steers walkgen::WalkingMpc towards a goal by velocity commands (v_x, ω_z), and, beyond the
/// thesis (its stated limitation), around circular obstacles that the NMPC's obstacle
/// constraints (eq. 2.79–2.82) keep the footsteps out of.
///
/// Depends on the core only (Eigen); the learning itself is in walkgen/torch/ppo.hpp.

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <utility>
#include <vector>

#include "walkgen/core/assert.hpp"
#include "walkgen/core/exceptions.hpp"
#include "walkgen/core/math.hpp"
#include "walkgen/learning/environment.hpp"
#include "walkgen/mpc/settings.hpp"
#include "walkgen/mpc/walking_mpc.hpp"

namespace walkgen {

/// Settings of the NMPC goal environment. Rewards (thesis §11.2.2):
/// r_t = w_frontal r_frontal + w_goal r_goal − w_time r_time, + success_reward on success.
struct NmpcGoalSettings {
  /// The walking generator's settings. HRP-2 (the default, thesis §9.1) walks up to
  /// 0.35 m/s and turns 0.3 rad/s at T = 0.1 s; Heicub's preset (0.034 m/s, T = 0.4 s,
  /// 3.2 s steps) would need 10× the simulated time for the same goals (docs/learning.md).
  WalkingSettings<double> walking = hrp2_settings<double>();
  int ticks_per_step = 2;          ///< NMPC ticks (of walking.t) per environment step
  int max_steps = 150;             ///< step budget per episode (30 s at the defaults)
  double goal_min_distance = 0.5;  ///< [m] goals are drawn at this distance or more …
  double goal_max_distance = 2.0;  ///< [m] … up to this, at any bearing (behind included)
  double success_radius = 0.2;     ///< [m] CoM closer than this to the goal: success
  /// Fraction of walking.max_command that an action of ±1 commands. Below 1 so that the
  /// command is always accepted as given by WalkingMpc::set_command (which clamps |c| > max).
  double command_fraction = 0.999;
  double frontal_weight = 2e3;    ///< w_frontal (thesis: 2·10³)
  double goal_weight = 6e3;       ///< w_goal (thesis: 6·10³)
  double time_weight = 0.1;       ///< w_time (thesis: 10⁻¹), r_time = episode time [s]
  double success_reward = 100.0;  ///< thesis: 100
  /// On a failed QP (walkgen's choice; the thesis has none). Comparable to the progress reward
  /// of a whole episode (w_goal · 2 m): a smaller penalty made walking into an obstacle until
  /// the NMPC gives up pay almost as well as going around it.
  double failure_reward = -1e4;
  // --- Obstacles (beyond the thesis) -----------------------------------------------------------
  int obstacles = 0;  ///< circular obstacles per episode, each in the state
  double obstacle_min_radius = 0.1, obstacle_max_radius = 0.25;  ///< [m] radius R, uniform
  double obstacle_margin = 0.15;  ///< [m] margin m of eq. 2.79: footsteps keep R + m
  /// Where an obstacle is drawn: at a fraction in [0.3, 0.7] of the way to the goal, moved
  /// sideways by up to this [m], so that it is in the way.
  double obstacle_lateral = 0.2;
  double obstacle_clearance = 0.15;  ///< [m] start and goal stay this far beyond R + m
  /// Adds the robot's motion to the state (beyond the thesis, whose state is the goal alone):
  /// the CoM velocity in the robot frame, the command in effect (as the action that gave it),
  /// the support foot in the robot frame and the fraction of the step elapsed, 7 numbers. The
  /// NMPC carries momentum: at 0.35 m/s its CoM needs a step or two to stop or turn, so
  /// whether a footstep can still avoid an obstacle depends on how fast the robot moves and
  /// where its next step lands, which the goal and obstacle positions alone do not tell.
  bool observe_motion = false;
  /// Weight w_obstacle [reward per unit] of a potential-based shaping term (Ng et al. 1999:
  /// r += Φ(s') − Φ(s), which leaves the optimal policy unchanged) with
  /// Φ = −w_obstacle Σ_k max(0, 1 − c_k / obstacle_shaping_distance), c_k the CoM's distance to
  /// obstacle k's circle R + m: walking into an obstacle's neighbourhood costs at once what
  /// the failed QP at its edge would cost only steps later. 0: no shaping (the thesis).
  double obstacle_weight = 0.0;
  double obstacle_shaping_distance = 0.3;  ///< [m] where Φ starts, beyond R + m
};

/// Checks the NMPC goal environment's settings, the walking settings included (NmpcGoalEnv's
/// constructor calls this, and checks walking.n against its horizon).
/// @throws walkgen::invalid_argument naming the first bad field.
inline void validate(const NmpcGoalSettings& s) {
  validate(s.walking);
  check_argument(s.ticks_per_step >= 1, "NmpcGoalSettings.ticks_per_step", "at least 1",
                 s.ticks_per_step);
  check_argument(s.max_steps >= 1, "NmpcGoalSettings.max_steps", "at least 1", s.max_steps);
  check_positive("NmpcGoalSettings.goal_min_distance", s.goal_min_distance);
  check_argument(s.goal_max_distance >= s.goal_min_distance, "NmpcGoalSettings.goal_max_distance",
                 "at least goal_min_distance", s.goal_max_distance);
  check_positive("NmpcGoalSettings.success_radius", s.success_radius);
  check_argument(s.command_fraction > 0.0 && s.command_fraction < 1.0,
                 "NmpcGoalSettings.command_fraction", "a fraction in (0, 1)", s.command_fraction);
  check_argument(s.obstacles >= 0, "NmpcGoalSettings.obstacles", "a count >= 0", s.obstacles);
  check_positive("NmpcGoalSettings.obstacle_min_radius", s.obstacle_min_radius);
  check_argument(s.obstacle_max_radius >= s.obstacle_min_radius,
                 "NmpcGoalSettings.obstacle_max_radius", "at least obstacle_min_radius",
                 s.obstacle_max_radius);
  check_non_negative("NmpcGoalSettings.obstacle_margin", s.obstacle_margin);
  check_non_negative("NmpcGoalSettings.obstacle_lateral", s.obstacle_lateral);
  check_non_negative("NmpcGoalSettings.obstacle_clearance", s.obstacle_clearance);
  check_non_negative("NmpcGoalSettings.obstacle_weight", s.obstacle_weight);
  check_positive("NmpcGoalSettings.obstacle_shaping_distance", s.obstacle_shaping_distance);
  const std::pair<const char*, double> finite[] = {
      {"NmpcGoalSettings.frontal_weight", s.frontal_weight},
      {"NmpcGoalSettings.goal_weight", s.goal_weight},
      {"NmpcGoalSettings.time_weight", s.time_weight},
      {"NmpcGoalSettings.success_reward", s.success_reward},
      {"NmpcGoalSettings.failure_reward", s.failure_reward}};
  for (const auto& [name, value] : finite) {
    check_argument(std::isfinite(value), name, "a finite value", value);
  }
}

/// One goal (and its obstacles) of an episode, world frame; the robot starts at the
/// preset's initial state, facing +x.
struct NmpcGoalTask {
  Eigen::Vector2d goal = Eigen::Vector2d::Zero();
  std::vector<CircleObstacle<double>> obstacles;
};

/// Environment of thesis §11.2.2. State: the goal in the robot frame,
/// g_a = R_z(θ)ᵀ (g_w − a_w) with a_w the CoM and θ the heading, then per obstacle its centre
/// in the robot frame and R + m (3 numbers), then with NmpcGoalSettings::observe_motion the
/// motion (7 numbers: CoM velocity in the robot frame [m/s], the action in effect, the support
/// foot in the robot frame [m], the elapsed fraction of the step). Action: (v_x, ω_z) ∈ [−1, 1]²
/// (clipped) times command_fraction · max_command; one step is ticks_per_step NMPC ticks (solve +
/// advance). The episode ends on success, on the step budget (truncated), on a failed QP or on
/// a footstep inside an obstacle's radius R (failure); a relaxed plan (MpcStatus::relaxed, with
/// soft blocks in walking.soft: a footstep inside the margin m rather than a failed QP) is
/// walked. Rewards: r_goal = d_{t−1} − d_t (distance of CoM to goal), r_frontal = ĝ_{a,t}[0] −
/// ĝ_{a,t−1}[0] with ĝ_a the unit direction to the goal in the robot frame (the x axis turns
/// towards the goal; the thesis's formula for it is garbled), r_time = the episode's time, and
/// with obstacle_weight > 0 the shaping term Φ_t − Φ_{t−1} near obstacles.
/// @tparam N preview samples of the NMPC (walking.n must equal it)
template <int N = 16>
class NmpcGoalEnv {
 public:
  using Mpc = WalkingMpc<double, N>;
  static constexpr int kActionSize = 2;

  /// @throws walkgen::invalid_argument on invalid settings (also those of the NMPC).
  explicit NmpcGoalEnv(const NmpcGoalSettings& settings = {}, std::uint64_t seed = 0)
      : s_(checked(settings)), mpc_(s_.walking, s_.obstacles), rng_(seed) {
    obstacles_.reserve(static_cast<std::size_t>(s_.obstacles));
    reset();
  }

  static constexpr int kMotionSize = 7;  ///< state numbers that observe_motion adds
  int observation_size() const {
    return 2 + 3 * s_.obstacles + (s_.observe_motion ? kMotionSize : 0);
  }
  int action_size() const { return kActionSize; }

  /// Restarts the task generator from `seed` (the next reset() draws the seed's first task).
  void seed(std::uint64_t seed) { rng_.seed(seed); }

  /// Draws a task: a goal at a uniform bearing in [−π, π) and a distance uniform in
  /// [goal_min_distance, goal_max_distance], and the obstacles in its way.
  NmpcGoalTask sample_task() {
    std::uniform_real_distribution<double> bearing(-kPi, kPi);
    std::uniform_real_distribution<double> dist(s_.goal_min_distance, s_.goal_max_distance);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    const Eigen::Vector2d start = start_position();
    NmpcGoalTask task;
    for (;;) {
      const double b = bearing(rng_), d = dist(rng_);
      task.goal = start + d * Eigen::Vector2d(std::cos(b), std::sin(b));
      task.obstacles.clear();
      for (int k = 0; k < s_.obstacles; ++k) {
        CircleObstacle<double> o;
        o.radius =
            s_.obstacle_min_radius + (s_.obstacle_max_radius - s_.obstacle_min_radius) * unit(rng_);
        o.margin = s_.obstacle_margin;
        const double f = 0.3 + 0.4 * unit(rng_);
        const double lateral = s_.obstacle_lateral * (2.0 * unit(rng_) - 1.0);
        const Eigen::Vector2d along = task.goal - start;
        const Eigen::Vector2d normal(-along.y() / along.norm(), along.x() / along.norm());
        const Eigen::Vector2d c = start + f * along + lateral * normal;
        o.x = c.x();
        o.y = c.y();
        task.obstacles.push_back(o);
      }
      if (task_valid(task)) return task;
    }
  }

  /// Restarts with a new random task.
  void reset() { reset(sample_task()); }
  /// Restarts the NMPC at its initial state (standing, facing +x) with the given task.
  /// @throws walkgen::invalid_argument on a wrong number of obstacles or invalid ones.
  void reset(const NmpcGoalTask& task) {
    check_argument(static_cast<int>(task.obstacles.size()) == s_.obstacles,
                   "NmpcGoalEnv::reset: obstacles", std::to_string(s_.obstacles) + " obstacles",
                   task.obstacles.size(), "NmpcGoalSettings::obstacles sets the state's size");
    check_argument(task.goal.allFinite(), "NmpcGoalEnv::reset: goal", "finite", "NaN or inf");
    obstacles_.assign(task.obstacles.begin(), task.obstacles.end());
    goal_ = task.goal;
    mpc_.set_obstacles(obstacles_);
    mpc_.reset(Mpc::initial_state(s_.walking));
    [[maybe_unused]] const CommandStatus standing = mpc_.set_command(Eigen::Vector3d::Zero());
    WALKGEN_ASSERT(standing == CommandStatus::accepted);  // 0 is within any max_command >= 0
    steps_ = 0;
    failed_ = false;
    conflicts_ = 0;
    action_ = {0.0f, 0.0f};
    min_clearance_ = std::numeric_limits<double>::infinity();
    (void)check_footsteps();  // records the clearance (min_obstacle_clearance)
    previous_frontal_ = unit_goal_robot().x();
    previous_distance_ = distance();
    previous_potential_ = obstacle_potential();
  }

  /// Writes the state (see the class comment) to obs[0..observation_size()).
  void observe(float* obs) const {
    const Eigen::Vector2d g = to_robot(goal_);
    obs[0] = static_cast<float>(g.x());
    obs[1] = static_cast<float>(g.y());
    for (std::size_t k = 0; k < obstacles_.size(); ++k) {
      const auto& o = obstacles_[k];
      const Eigen::Vector2d c = to_robot(Eigen::Vector2d(o.x, o.y));
      obs[2 + 3 * k] = static_cast<float>(c.x());
      obs[3 + 3 * k] = static_cast<float>(c.y());
      obs[4 + 3 * k] = static_cast<float>(o.radius + o.margin);
    }
    if (!s_.observe_motion) return;
    float* m = obs + 2 + 3 * obstacles_.size();
    const auto& st = mpc_.state();
    const Eigen::Vector2d v = rotate_to_robot(Eigen::Vector2d(st.com_x[1], st.com_y[1]));
    const Eigen::Vector2d foot = to_robot(Eigen::Vector2d(st.support.x, st.support.y));
    m[0] = static_cast<float>(v.x());
    m[1] = static_cast<float>(v.y());
    m[2] = action_[0];
    m[3] = action_[1];
    m[4] = static_cast<float>(foot.x());
    m[5] = static_cast<float>(foot.y());
    m[6] = static_cast<float>(double(st.phase) / double(s_.walking.samples_per_step()));
  }

  /// The command that an action maps to: (a_0 v_max, 0, a_1 ω_max) · command_fraction, with
  /// each a_i clipped to [−1, 1] (a NaN or infinite one is 0).
  Eigen::Vector3d command_of(const float* action) const {
    const auto& m = s_.walking.max_command;
    return {clipped(action[0]) * m[0] * s_.command_fraction, 0.0,
            clipped(action[1]) * m[2] * s_.command_fraction};
  }

  /// Sends the action's command and runs ticks_per_step NMPC ticks.
  [[nodiscard]] EnvStep step(const float* action) {
    EnvStep r;
    [[maybe_unused]] const CommandStatus sent = mpc_.set_command(command_of(action));
    WALKGEN_ASSERT(sent == CommandStatus::accepted);  // finite, |c| < max_command by command_of
    action_ = {static_cast<float>(clipped(action[0])), static_cast<float>(clipped(action[1]))};
    for (int k = 0; k < s_.ticks_per_step; ++k) {
      const MpcResult<double>& solved = mpc_.solve();
      // relaxed: the QP was infeasible and walking.soft found the least-violating plan
      if (solved.status != MpcStatus::solved && solved.status != MpcStatus::relaxed) {
        failed_ = true;
        r.message = solved.message;  // the NMPC's static string
        conflicts_ = mpc_.conflicting_blocks();
        break;
      }
      mpc_.advance();
      ++ticks_;
      if (check_footsteps()) {
        failed_ = true;
        r.message = "a footstep inside an obstacle";
        break;
      }
    }
    ++steps_;
    const double d = distance();
    const double frontal = unit_goal_robot().x();
    const double time = mpc_.state().time;
    const double potential = obstacle_potential();
    r.reward = s_.goal_weight * (previous_distance_ - d) +
               s_.frontal_weight * (frontal - previous_frontal_) - s_.time_weight * time +
               (potential - previous_potential_);
    previous_distance_ = d;
    previous_frontal_ = frontal;
    previous_potential_ = potential;
    if (failed_) {
      r.reward += s_.failure_reward;
      r.end = EpisodeEnd::failure;
      if (*r.message == '\0') r.message = "the NMPC failed earlier in this episode";
    } else if (d < s_.success_radius) {
      r.reward += s_.success_reward;
      r.end = EpisodeEnd::success;
    } else if (steps_ >= s_.max_steps) {
      r.end = EpisodeEnd::truncated;
      r.message = "the step budget max_steps is spent";
    }
    return r;
  }

  /// Robot position: the CoM (state().com_x[0], com_y[0]), world frame [m].
  Eigen::Vector2d position() const { return {mpc_.state().com_x[0], mpc_.state().com_y[0]}; }
  double heading() const { return mpc_.state().heading(); }
  double distance() const { return (goal_ - position()).norm(); }
  const Eigen::Vector2d& goal() const { return goal_; }
  const std::vector<CircleObstacle<double>>& obstacles() const { return obstacles_; }
  /// Smallest distance of a footstep (support foot, every tick) to an obstacle's circle,
  /// ‖F − o‖ − R, over the episode [m]: negative means a footstep inside an obstacle.
  double min_obstacle_clearance() const { return min_clearance_; }
  /// When the episode's NMPC failed on an infeasible QP: its conflicting_blocks() mask (names
  /// by mpc().block_names()); 0 otherwise.
  std::uint32_t failure_conflicts() const { return conflicts_; }
  int steps() const { return steps_; }
  long ticks() const { return ticks_; }  ///< NMPC ticks since construction
  const Mpc& mpc() const { return mpc_; }
  const NmpcGoalSettings& settings() const { return s_; }

 private:
  static const NmpcGoalSettings& checked(const NmpcGoalSettings& s) {
    validate(s);
    check_argument(s.walking.n == N || N == Eigen::Dynamic, "NmpcGoalSettings.walking.n",
                   "the environment's horizon N = " + std::to_string(N), s.walking.n);
    return s;
  }

  Eigen::Vector2d start_position() const { return {s_.walking.com_x[0], s_.walking.com_y[0]}; }

  bool task_valid(const NmpcGoalTask& task) const {
    const Eigen::Vector2d start = start_position();
    for (const auto& o : task.obstacles) {
      const Eigen::Vector2d c(o.x, o.y);
      const double keep = o.radius + o.margin + s_.obstacle_clearance;
      // the start (both feet around the CoM) and the goal's success disc stay clear
      if ((c - start).norm() < keep + s_.walking.foot_distance) return false;
      if ((c - task.goal).norm() < keep + s_.success_radius) return false;
    }
    return true;
  }

  static double clipped(float a) {
    return std::isfinite(a) ? std::clamp<double>(a, -1.0, 1.0) : 0.0;
  }
  /// A world-frame vector in the robot frame, R_z(θ)ᵀ d.
  Eigen::Vector2d rotate_to_robot(const Eigen::Vector2d& d) const {
    const double q = heading(), c = std::cos(q), s = std::sin(q);
    return {c * d.x() + s * d.y(), -s * d.x() + c * d.y()};
  }
  Eigen::Vector2d to_robot(const Eigen::Vector2d& p_W) const {
    return rotate_to_robot(p_W - position());
  }
  Eigen::Vector2d unit_goal_robot() const {
    const Eigen::Vector2d g = to_robot(goal_);
    const double n = g.norm();
    return n > 1e-9 ? Eigen::Vector2d(g / n) : Eigen::Vector2d(1.0, 0.0);
  }
  /// Φ of NmpcGoalSettings::obstacle_weight (0 without obstacles or weight).
  double obstacle_potential() const {
    double phi = 0.0;
    if (s_.obstacle_weight == 0.0) return phi;
    for (const auto& o : obstacles_) {
      const double c = (position() - Eigen::Vector2d(o.x, o.y)).norm() - (o.radius + o.margin);
      phi -= s_.obstacle_weight * std::max(0.0, 1.0 - c / s_.obstacle_shaping_distance);
    }
    return phi;
  }
  /// Updates min_clearance_; true when a footstep is inside an obstacle (a collision).
  bool check_footsteps() {
    const auto& st = mpc_.state();
    bool inside = false;
    for (const auto& o : obstacles_) {
      for (const auto* f : {&st.support, &st.swing_origin}) {
        const double c = std::hypot(f->x - o.x, f->y - o.y) - o.radius;
        min_clearance_ = std::min(min_clearance_, c);
        inside = inside || c < 0.0;
      }
    }
    return inside;
  }

  NmpcGoalSettings s_;
  Mpc mpc_;
  std::mt19937_64 rng_;
  std::vector<CircleObstacle<double>> obstacles_;
  Eigen::Vector2d goal_ = Eigen::Vector2d::Zero();
  int steps_ = 0;
  long ticks_ = 0;
  bool failed_ = false;
  std::uint32_t conflicts_ = 0;              // failure_conflicts()
  std::array<float, kActionSize> action_{};  ///< the clipped action in effect (observe_motion)
  double previous_distance_ = 0.0, previous_frontal_ = 0.0, previous_potential_ = 0.0;
  double min_clearance_ = std::numeric_limits<double>::infinity();
};

}  // namespace walkgen
