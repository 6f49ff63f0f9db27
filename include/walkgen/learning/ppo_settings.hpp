#pragma once
/// @file
/// PPO's hyper-parameters (thesis §4.2, algorithm 1; eq. 4.15–4.17) and the settings of a
/// training run, without libtorch: the YAML reader (walkgen/yaml/ppo_settings_loader.hpp) and
/// programs read and check them with no learning backend; walkgen/torch/ppo.hpp trains with them.

#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "walkgen/core/exceptions.hpp"

namespace walkgen {

/// Activation of the hidden layers (the output of the policy mean is always tanh).
enum class TorchActivation : std::int64_t {
  relu = 0,  ///< thesis §11.2.1 (benchmark environment)
  tanh = 1,  ///< thesis §11.2.2 (NMPC environment)
};

/// "relu" or "tanh", e.g. for logs; "unknown" for a value out of range (a policy file's
/// `activation` attribute is read into this enum).
constexpr const char* to_string(TorchActivation activation) noexcept {
  switch (activation) {
    case TorchActivation::relu:
      return "relu";
    case TorchActivation::tanh:
      return "tanh";
  }
  return "unknown";
}

/// PPO hyper-parameters. Defaults: the common PPO choices; thesis values per environment are
/// in the examples (examples/ppo_train.cpp) and docs/learning.md.
struct PpoSettings {
  std::vector<std::int64_t> actor_hidden{64, 64};   ///< hidden layer sizes of μ_θ
  std::vector<std::int64_t> critic_hidden{64, 64};  ///< hidden layer sizes of V_θ
  TorchActivation activation = TorchActivation::tanh;
  double initial_std = 0.5;     ///< σ at the start (the policy's exploration)
  double learning_rate = 3e-4;  ///< Adam's step size
  double gamma = 0.99;          ///< discount γ (eq. 4.15)
  double lambda = 0.95;         ///< GAE λ (eq. 4.15)
  double clip = 0.2;            ///< ε of the clipped surrogate (eq. 4.16)
  double value_coef = 0.5;      ///< c1 of eq. 4.17
  double entropy_coef = 0.0;    ///< c2 of eq. 4.17
  int epochs = 8;               ///< K: passes over a rollout per update (algorithm 1)
  int minibatch = 512;          ///< M: samples per gradient step
  double max_grad_norm = 0.5;   ///< global gradient norm clip; ≤ 0 disables it
  /// Early stop of an update's epochs once the mean KL estimate between the rollout's policy
  /// and the current one exceeds this (a guard against the collapse of a too large step);
  /// ≤ 0 disables it.
  double target_kl = 0.02;
  double reward_scale = 1.0;         ///< rewards are multiplied by this before GAE (value scale)
  bool normalize_advantages = true;  ///< advantages to zero mean, unit std per update
  /// Adam's step size falls linearly over the run, learning_rate · (1 − k / K) at update k of
  /// K (TorchPpo::set_total_updates; ppo_train sets K from the run's epochs): the late updates,
  /// which pick the final policy, take small steps. false: constant.
  bool anneal_learning_rate = false;
  /// Seeds the initial weights (torch::manual_seed) and each update's minibatch order
  /// (walkgen::mix_seed); PpoTrainer also seeds the environments and their exploration noise
  /// from it.
  std::uint64_t seed = 0;
};

/// How an update ended.
enum class PpoUpdateStatus : std::uint8_t {
  updated,  ///< every epoch ran over every minibatch
  /// the mean KL estimate of a minibatch exceeded PpoSettings::target_kl: that minibatch's
  /// step and the rest of the update were skipped (PpoUpdateResult::steps were taken)
  kl_stopped,
};

/// "updated" or "kl_stopped", e.g. for logs; "unknown" for a value out of range.
constexpr const char* to_string(PpoUpdateStatus status) noexcept {
  switch (status) {
    case PpoUpdateStatus::updated:
      return "updated";
    case PpoUpdateStatus::kl_stopped:
      return "kl_stopped";
  }
  return "unknown";
}

/// Checks PPO's hyper-parameters (TorchPpo's constructor and load() call this).
/// @throws walkgen::invalid_argument naming the first bad field.
inline void validate(const PpoSettings& s) {
  for (auto h : s.actor_hidden) check_argument(h >= 1, "PpoSettings.actor_hidden", ">= 1", h);
  for (auto h : s.critic_hidden) check_argument(h >= 1, "PpoSettings.critic_hidden", ">= 1", h);
  check_argument(s.activation == TorchActivation::relu || s.activation == TorchActivation::tanh,
                 "PpoSettings.activation", "relu (0) or tanh (1)",
                 static_cast<std::int64_t>(s.activation));
  check_positive("PpoSettings.initial_std", s.initial_std);
  check_positive("PpoSettings.learning_rate", s.learning_rate);
  check_argument(s.gamma > 0.0 && s.gamma <= 1.0, "PpoSettings.gamma", "a value in (0, 1]",
                 s.gamma);
  check_argument(s.lambda >= 0.0 && s.lambda <= 1.0, "PpoSettings.lambda", "a value in [0, 1]",
                 s.lambda);
  check_positive("PpoSettings.clip", s.clip);
  check_non_negative("PpoSettings.value_coef", s.value_coef);
  check_argument(std::isfinite(s.entropy_coef), "PpoSettings.entropy_coef", "finite",
                 s.entropy_coef);
  check_argument(s.epochs >= 1, "PpoSettings.epochs", "at least 1", s.epochs);
  check_argument(s.minibatch >= 1, "PpoSettings.minibatch", "at least 1", s.minibatch);
  check_positive("PpoSettings.reward_scale", s.reward_scale);
}

/// The schedule of a PPO training run (walkgen::PpoTrainer, examples/ppo_train): how many
/// environments, how long a rollout, how many steps make an epoch, the seeds, and how often a
/// checkpoint is written. Counts are over all processes of a distributed run (docs/learning.md).
struct PpoRunSettings {
  int epochs = 30;          ///< training epochs
  long steps = 8192;        ///< environment steps per epoch (all environments, all processes);
                            ///< rounded up to whole rollouts
  int envs = 8;             ///< environments (all processes; a multiple of the process count)
  int rollout_steps = 256;  ///< T: vectorised steps per update (T · envs samples per update)
  int threads = 2;          ///< threads that step a process's environments
  std::uint64_t seed = 1;   ///< seeds the weights, the environments, the exploration noise
                            ///< and the minibatch order
  std::uint64_t validation_seed = 555;     ///< goals of the validation run (best-epoch choice)
  std::uint64_t evaluation_seed = 900000;  ///< held-out goals of the final test
  int checkpoint_every = 1;                ///< epochs between checkpoints (0: none)
};

/// Checks a run's settings. @throws walkgen::invalid_argument naming the first bad field.
inline void validate(const PpoRunSettings& s) {
  check_argument(s.epochs >= 1, "PpoRunSettings.epochs", "at least 1", s.epochs);
  check_argument(s.steps >= 1 && s.steps <= 1000000000000L, "PpoRunSettings.steps",
                 "a count in [1, 10^12]", s.steps);
  check_argument(s.envs >= 1, "PpoRunSettings.envs", "at least 1", s.envs);
  check_argument(s.rollout_steps >= 1, "PpoRunSettings.rollout_steps", "at least 1",
                 s.rollout_steps);
  check_argument(s.threads >= 1, "PpoRunSettings.threads", "at least 1", s.threads);
  check_argument(s.checkpoint_every >= 0, "PpoRunSettings.checkpoint_every", "a count >= 0",
                 s.checkpoint_every);
}

}  // namespace walkgen
