#pragma once
/// @file
/// Vectorised rollouts and evaluation for walkgen::TorchPpo (thesis algorithm 1: N agents run
/// π_θold for T steps, then the surrogate is optimised). The environments are stepped at once
/// on a walkgen::StepPool that the program owns; one batched forward pass of the policy per step.
///
/// An environment type provides observation_size(), action_size(), reset(), observe(float*)
/// and EnvStep step(const float*) (walkgen/learning/environment.hpp, nmpc_environment.hpp).

#include <algorithm>
#include <chrono>
#include <cstring>
#include <functional>
#include <random>
#include <vector>

#include "walkgen/core/exceptions.hpp"
#include "walkgen/learning/environment.hpp"
#include "walkgen/learning/step_pool.hpp"
#include "walkgen/torch/ppo.hpp"

namespace walkgen {

/// PPO for the benchmarking environment (thesis §11.2.1): actor and critic 16-32 ReLU, tanh
/// mean, ε = 0.2, c1 = 0.5, Adam at 10⁻³, minibatch 512, 8 epochs per update.
inline PpoSettings point_goal_ppo_settings() {
  PpoSettings s;
  s.actor_hidden = {16, 32};
  s.critic_hidden = {16, 32};
  s.activation = TorchActivation::relu;
  s.learning_rate = 1e-3;
  s.initial_std = 0.5;
  s.entropy_coef = 0.0;
  s.minibatch = 512;
  s.epochs = 8;
  s.gamma = 0.99;
  return s;
}

/// PPO for the NMPC environment (thesis §11.2.2): 64-64 tanh, Adam at 10⁻³, σ from 0.6,
/// minibatch 256, 5 epochs, rewards × 10⁻³ for the critic (returns of ~10⁴ from the weights
/// 2·10³ and 6·10³ become ~10).
inline PpoSettings nmpc_goal_ppo_settings() {
  PpoSettings s;
  s.actor_hidden = {64, 64};
  s.critic_hidden = {64, 64};
  s.activation = TorchActivation::tanh;
  s.learning_rate = 1e-3;
  s.initial_std = 0.6;
  s.entropy_coef = 0.0;
  s.minibatch = 256;
  s.epochs = 5;
  s.gamma = 0.99;
  s.lambda = 0.95;
  s.reward_scale = 1e-3;
  return s;
}

/// Statistics of one training epoch (a whole number of updates), over all processes.
struct PpoEpoch {
  int epoch = 0;             ///< 1-based
  long steps = 0;            ///< environment steps in this epoch (all environments)
  double mean_reward = 0.0;  ///< reward per step, averaged over the epoch (figure 11.17 a)
  double mean_return = 0.0;  ///< undiscounted return per finished episode
  int episodes = 0, wins = 0, losses = 0, truncations = 0;
  double std = 0.0;        ///< σ of the policy at the epoch's end (figure 11.17 b)
  double seconds = 0.0;    ///< wall time of the epoch
  int updates = 0;         ///< PPO updates in the epoch
  PpoUpdateResult update;  ///< the last update's statistics
  /// Finished episodes that reached their goal (wins / episodes; 0 when none finished).
  [[nodiscard]] double success_rate() const {
    return episodes > 0 ? static_cast<double>(wins) / episodes : 0.0;
  }
};

/// Runs a set of environments with a TorchPpo policy and updates it every rollout_steps
/// vectorised steps. Episodes that end are reset at once; a truncated episode (step budget)
/// is bootstrapped: γ V(s_final) is added to its last reward, as its state is not terminal.
///
/// An epoch is a whole number of updates and starts afresh: environment i (its index over all
/// processes) is seeded with mix_seed(seed, i, epoch) and reset, and its exploration noise comes
/// from its own generator, seeded likewise; episodes still running when the epoch ends are cut
/// there (bootstrapped, as a truncation) and not counted. So the state of a run between epochs
/// is the policy, Adam's state and the counters — what TorchPpo::save_checkpoint() writes — and
/// a run resumed from a checkpoint (set_epoch()) continues exactly as the uninterrupted one. With
/// a communicator on the policy (TorchPpo::set_communicator), each process steps its share of
/// the environments and the epoch's statistics are summed over the processes.
template <class Env>
class PpoTrainer {
 public:
  /// @param envs the environments, stepped in parallel on pool (one thread when null); each
  ///        needs seed(std::uint64_t) besides the environment interface
  /// @param rollout_steps vectorised steps per update: T of algorithm 1, T · envs samples
  /// @throws walkgen::invalid_argument on no environments, sizes that differ from the policy's,
  ///         or rollout_steps < 1.
  PpoTrainer(TorchPpo& ppo, std::vector<Env>& envs, int rollout_steps, StepPool* pool = nullptr)
      : ppo_(ppo), envs_(envs), pool_(pool), T_(rollout_steps) {
    check_argument(!envs_.empty(), "PpoTrainer", "at least one environment", 0);
    check_argument(rollout_steps >= 1, "PpoTrainer", "rollout_steps >= 1", rollout_steps);
    E_ = static_cast<int>(envs_.size());
    O_ = envs_[0].observation_size();
    A_ = envs_[0].action_size();
    check_argument(O_ == ppo.observation_size() && A_ == ppo.action_size(), "PpoTrainer",
                   "environments of the policy's observation and action sizes",
                   std::to_string(O_) + " and " + std::to_string(A_));
    rollout_.resize(T_, E_, O_, A_);
    obs_.assign(static_cast<std::size_t>(E_ * O_), 0.0f);
    final_obs_.assign(static_cast<std::size_t>(E_ * O_), 0.0f);
    action_.assign(static_cast<std::size_t>(E_ * A_), 0.0f);
    noise_.assign(static_cast<std::size_t>(E_ * A_), 0.0f);
    log_prob_.assign(static_cast<std::size_t>(E_), 0.0f);
    value_.assign(static_cast<std::size_t>(E_), 0.0f);
    steps_.resize(static_cast<std::size_t>(E_));
    episode_return_.assign(static_cast<std::size_t>(E_), 0.0);
    noise_rng_.resize(static_cast<std::size_t>(E_));
    normal_.resize(static_cast<std::size_t>(E_));
  }

  /// Epochs run so far (the next run_epoch() is epoch epochs() + 1).
  [[nodiscard]] int epochs() const { return epoch_; }
  /// Continues a run after `epochs` epochs (from a checkpoint): the next epoch is epochs + 1.
  void set_epoch(int epochs) {
    check_argument(epochs >= 0, "PpoTrainer::set_epoch", "a count >= 0", epochs);
    epoch_ = epochs;
  }
  /// Updates per epoch for `steps` environment steps over all processes (at least one).
  [[nodiscard]] long updates_per_epoch(long steps) const {
    const long per_update = static_cast<long>(T_) * E_ * world();
    return std::max(1L, (steps + per_update - 1) / per_update);
  }

  /// Runs one epoch: updates_per_epoch(steps) rollouts and their updates.
  PpoEpoch run_epoch(long steps) {
    const auto t0 = std::chrono::steady_clock::now();
    PpoEpoch ep;
    ep.epoch = ++epoch_;
    begin_epoch();
    double sums[7] = {0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0};  // steps, reward, return, episodes, ...
    const long updates = updates_per_epoch(steps);
    for (long u = 0; u < updates; ++u) {
      for (int t = 0; t < T_; ++t) vector_step(t, sums);
      observe_all(obs_.data());
      ppo_.values(obs_.data(), E_, rollout_.values.data() + static_cast<std::size_t>(T_) * E_);
      ep.update = ppo_.update(rollout_);
      ++ep.updates;
    }
    if (PpoCommunicator* c = ppo_.communicator()) {
      torch::Tensor t = torch::from_blob(sums, {7}, torch::kFloat64).clone();
      c->allreduce_sum(t);
      std::memcpy(sums, t.data_ptr<double>(), sizeof(sums));
    }
    ep.steps = static_cast<long>(sums[0]);
    ep.episodes = static_cast<int>(sums[3]);
    ep.wins = static_cast<int>(sums[4]);
    ep.losses = static_cast<int>(sums[5]);
    ep.truncations = static_cast<int>(sums[6]);
    ep.mean_reward = ep.steps > 0 ? sums[1] / static_cast<double>(ep.steps) : 0.0;
    ep.mean_return = ep.episodes > 0 ? sums[2] / ep.episodes : 0.0;
    ep.std = ppo_.std();
    ep.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return ep;
  }

 private:
  int world() const {
    return ppo_.communicator() != nullptr ? ppo_.communicator()->world_size() : 1;
  }
  void for_each_env(const std::function<void(int)>& job) {
    if (pool_ != nullptr)
      pool_->run(E_, job);
    else
      for (int e = 0; e < E_; ++e) job(e);
  }
  void begin_epoch() {
    const int first = ppo_.communicator() != nullptr ? ppo_.communicator()->rank() * E_ : 0;
    const std::uint64_t seed = ppo_.settings().seed;
    for (int e = 0; e < E_; ++e) {
      const auto global = static_cast<std::uint64_t>(first + e);
      envs_[e].seed(mix_seed(seed, global, static_cast<std::uint64_t>(epoch_)));
      noise_rng_[e].seed(
          mix_seed(seed ^ 0xA5A5A5A5A5A5A5A5ull, global, static_cast<std::uint64_t>(epoch_)));
      normal_[e].reset();
      episode_return_[e] = 0.0;
    }
    for_each_env([this](int e) { envs_[e].reset(); });
  }
  void observe_all(float* obs) {
    for (int e = 0; e < E_; ++e) envs_[e].observe(obs + static_cast<std::size_t>(e) * O_);
  }
  void vector_step(int t, double* sums) {
    observe_all(obs_.data());
    for (int e = 0; e < E_; ++e)
      for (int a = 0; a < A_; ++a)
        noise_[static_cast<std::size_t>(e * A_ + a)] = normal_[e](noise_rng_[e]);
    ppo_.act(obs_.data(), E_, false, action_.data(), log_prob_.data(), value_.data(),
             noise_.data());
    for_each_env([this](int e) {
      EnvStep r = envs_[e].step(action_.data() + static_cast<std::size_t>(e) * A_);
      if (r.end == EpisodeEnd::truncated)
        envs_[e].observe(final_obs_.data() + static_cast<std::size_t>(e) * O_);
      steps_[e] = r;
    });
    const std::size_t base = static_cast<std::size_t>(t) * E_;
    std::copy(obs_.begin(), obs_.end(), rollout_.observations.begin() + base * O_);
    std::copy(action_.begin(), action_.end(), rollout_.actions.begin() + base * A_);
    std::copy(log_prob_.begin(), log_prob_.end(), rollout_.log_probs.begin() + base);
    std::copy(value_.begin(), value_.end(), rollout_.values.begin() + base);
    sums[0] += E_;
    for (int e = 0; e < E_; ++e) {
      const EnvStep& r = steps_[e];
      double reward = r.reward;
      sums[1] += r.reward;
      episode_return_[e] += r.reward;
      if (r.end == EpisodeEnd::truncated) {
        float v = 0.0f;
        ppo_.values(final_obs_.data() + static_cast<std::size_t>(e) * O_, 1, &v);
        reward += ppo_.settings().gamma * v / ppo_.settings().reward_scale;
      }
      rollout_.rewards[base + e] = static_cast<float>(reward);
      rollout_.dones[base + e] = r.done() ? 1.0f : 0.0f;
      if (r.done()) {
        sums[2] += episode_return_[e];
        sums[3] += 1.0;
        sums[4] += r.end == EpisodeEnd::success;
        sums[5] += r.end == EpisodeEnd::failure;
        sums[6] += r.end == EpisodeEnd::truncated;
        episode_return_[e] = 0.0;
      }
    }
    // resets (an NMPC reset re-initialises the generator) in parallel too
    for_each_env([this](int e) {
      if (steps_[e].done()) envs_[e].reset();
    });
  }

  TorchPpo& ppo_;
  std::vector<Env>& envs_;
  StepPool* pool_;
  int T_, E_ = 0, O_ = 0, A_ = 0, epoch_ = 0;
  PpoRollout rollout_;
  std::vector<float> obs_, final_obs_, action_, noise_, log_prob_, value_;
  std::vector<EnvStep> steps_;
  std::vector<double> episode_return_;
  std::vector<std::mt19937_64> noise_rng_;
  std::vector<std::normal_distribution<float>> normal_;
};

/// Wins and losses of the deterministic policy (the mean μ_θ, test mode) over `steps` steps of
/// one environment, resetting it whenever an episode ends (thesis §11.2.1: 10 runs of 10 000).
struct PpoTestResult {
  long steps = 0;
  int wins = 0, losses = 0, truncations = 0;
  double mean_reward = 0.0;
};
template <class Env>
[[nodiscard]] PpoTestResult evaluate_steps(TorchPpo& ppo, Env& env, long steps) {
  PpoTestResult out;
  std::vector<float> obs(static_cast<std::size_t>(env.observation_size()));
  std::vector<float> action(static_cast<std::size_t>(env.action_size()));
  double reward = 0.0;
  env.reset();
  for (out.steps = 0; out.steps < steps; ++out.steps) {
    env.observe(obs.data());
    ppo.act(obs.data(), 1, true, action.data());
    const EnvStep r = env.step(action.data());
    reward += r.reward;
    if (!r.done()) continue;
    out.wins += r.end == EpisodeEnd::success;
    out.losses += r.end == EpisodeEnd::failure;
    out.truncations += r.end == EpisodeEnd::truncated;
    env.reset();
  }
  out.mean_reward = steps > 0 ? reward / static_cast<double>(steps) : 0.0;
  return out;
}

/// One evaluated task (episode) of evaluate_tasks().
struct PpoTaskResult {
  EpisodeEnd end = EpisodeEnd::none;  ///< the status: how the episode ended (EnvStep::end)
  const char* message = "";           ///< EnvStep::message of the episode's last step
  int steps = 0;
  double reward = 0.0;
};

/// Runs the deterministic policy on each task (one episode each, env.reset(task)), using the
/// environments in parallel on pool (one batched forward per step). `on_end(task index, env)`
/// is called when a task's episode ends, before the environment is reused (e.g. to read the
/// environment's min_obstacle_clearance()).
template <class Env, class Task>
[[nodiscard]] std::vector<PpoTaskResult> evaluate_tasks(
    TorchPpo& ppo, std::vector<Env>& envs, const std::vector<Task>& tasks, StepPool* pool,
    const std::function<void(std::size_t, const Env&)>& on_end = nullptr) {
  check_argument(!envs.empty(), "evaluate_tasks", "at least one environment", 0);
  const int O = envs[0].observation_size(), A = envs[0].action_size();
  const int E = static_cast<int>(envs.size());
  std::vector<PpoTaskResult> out(tasks.size());
  std::vector<long> task_of(static_cast<std::size_t>(E), -1);
  std::size_t next = 0;
  auto assign = [&](int e) {
    task_of[e] = next < tasks.size() ? static_cast<long>(next) : -1;
    if (next < tasks.size()) envs[e].reset(tasks[next++]);
  };
  for (int e = 0; e < E; ++e) assign(e);
  std::vector<float> obs(static_cast<std::size_t>(E * O)), action(static_cast<std::size_t>(E * A));
  std::vector<EnvStep> steps(static_cast<std::size_t>(E));
  for (;;) {
    std::vector<int> active;
    for (int e = 0; e < E; ++e)
      if (task_of[e] >= 0) active.push_back(e);
    if (active.empty()) break;
    const int B = static_cast<int>(active.size());
    for (int b = 0; b < B; ++b)
      envs[active[b]].observe(obs.data() + static_cast<std::size_t>(b) * O);
    ppo.act(obs.data(), B, true, action.data());
    const std::function<void(int)> job = [&](int b) {
      steps[b] = envs[active[b]].step(action.data() + static_cast<std::size_t>(b) * A);
    };
    if (pool != nullptr)
      pool->run(B, job);
    else
      for (int b = 0; b < B; ++b) job(b);
    for (int b = 0; b < B; ++b) {
      const int e = active[b];
      PpoTaskResult& res = out[static_cast<std::size_t>(task_of[e])];
      res.reward += steps[b].reward;
      ++res.steps;
      if (!steps[b].done()) continue;
      res.end = steps[b].end;
      res.message = steps[b].message;
      if (on_end) on_end(static_cast<std::size_t>(task_of[e]), envs[e]);
      assign(e);
    }
  }
  return out;
}

}  // namespace walkgen
