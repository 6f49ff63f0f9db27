#pragma once
/// @file
/// Proximal policy optimisation, actor–critic style (thesis §4.2, algorithm 1), in libtorch:
/// a Gaussian policy N(μ_θ(s), σ²) with a tanh-bounded mean and a learned, state-independent
/// standard deviation, a separate critic V_θ(s), generalised advantage estimation (eq. 4.15),
/// the clipped surrogate (eq. 4.16) with value loss and entropy bonus (eq. 4.17, entropy by
/// eq. 11.2), Adam over shuffled minibatches for several epochs per update. Policies are saved
/// as TorchScript modules that torch.jit.load() reads in Python and torch::jit::load() in C++.
///
/// Use (the trainer of walkgen/torch/training.hpp runs the environments):
/// @code
///   walkgen::PpoSettings s;                      // seeds, sizes, γ, λ, ε, c1, c2, Adam
///   walkgen::TorchPpo ppo(obs_size, act_size, s);
///   ppo.act(obs, batch, /*deterministic=*/false, action, log_prob, value);   // rollouts
///   walkgen::PpoUpdateResult u = ppo.update(rollout);                         // algorithm 1
///   ppo.save("policy.pt");                                       // TorchScript
///   walkgen::TorchPpo again = walkgen::TorchPpo::load("policy.pt");
/// @endcode
/// Type names carry the backend (docs/design.md convention 12); no nested namespace torch.

#include <torch/script.h>
#include <torch/torch.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "walkgen/core/atomic_file.hpp"
#include "walkgen/core/exceptions.hpp"
#include "walkgen/core/math.hpp"
#include "walkgen/learning/ppo_settings.hpp"

namespace walkgen {

/// One update's outcome and statistics (means over its minibatches).
struct PpoUpdateResult {
  PpoUpdateStatus status = PpoUpdateStatus::updated;
  const char* message = "";    ///< why it stopped early; empty when updated
  int steps = 0;               ///< gradient steps taken (minibatches over all epochs)
  double policy_loss = 0.0;    ///< −L^CLIP
  double value_loss = 0.0;     ///< (V_θ(s) − V^target)²
  double entropy = 0.0;        ///< S[π_θ] (eq. 11.2, summed over action dimensions)
  double approx_kl = 0.0;      ///< KL(π_old ‖ π_θ) estimate, mean of (ρ − 1) − log ρ
  double clip_fraction = 0.0;  ///< share of samples with |ρ − 1| > ε
  double std = 0.0;            ///< mean σ after the update
};

/// A rollout of `steps` vectorised steps of `envs` environments (time-major: index t·envs + e).
/// values has (steps + 1)·envs entries: the last row is V(s_T), the bootstrap. done marks the
/// last step of an episode (a truncated episode's bootstrap is added to its reward by the trainer).
struct PpoRollout {
  int steps = 0, envs = 0, observation_size = 0, action_size = 0;
  std::vector<float> observations, actions, log_probs, values, rewards, dones;

  void resize(int steps_, int envs_, int obs, int act) {
    steps = steps_;
    envs = envs_;
    observation_size = obs;
    action_size = act;
    const std::size_t n = static_cast<std::size_t>(steps) * static_cast<std::size_t>(envs);
    observations.assign(n * static_cast<std::size_t>(obs), 0.0f);
    actions.assign(n * static_cast<std::size_t>(act), 0.0f);
    log_probs.assign(n, 0.0f);
    values.assign(n + static_cast<std::size_t>(envs), 0.0f);
    rewards.assign(n, 0.0f);
    dones.assign(n, 0.0f);
  }
};

/// Generalised advantage estimation (eq. 4.15) with δ_t = r_t + γ V(s_{t+1})(1 − done_t) − V(s_t):
/// Â_t = δ_t + γλ(1 − done_t) Â_{t+1}; returns R_t = Â_t + V(s_t) are the critic's targets.
/// rewards, dones: steps·envs; values: (steps + 1)·envs; outputs steps·envs each.
inline void generalized_advantages(const std::vector<float>& rewards,
                                   const std::vector<float>& values,
                                   const std::vector<float>& dones, int steps, int envs,
                                   double gamma, double lambda, std::vector<float>& advantages,
                                   std::vector<float>& returns) {
  const std::size_t n = static_cast<std::size_t>(steps) * static_cast<std::size_t>(envs);
  check_argument(rewards.size() == n && dones.size() == n &&
                     values.size() == n + static_cast<std::size_t>(envs),
                 "generalized_advantages",
                 "rewards, dones of steps*envs and values of "
                 "(steps+1)*envs entries",
                 "other sizes");
  advantages.assign(n, 0.0f);
  returns.assign(n, 0.0f);
  for (int e = 0; e < envs; ++e) {
    double next_advantage = 0.0;
    for (int t = steps - 1; t >= 0; --t) {
      const std::size_t i = static_cast<std::size_t>(t) * envs + e;
      const double not_done = 1.0 - dones[i];
      const double delta = rewards[i] + gamma * values[i + envs] * not_done - values[i];
      next_advantage = delta + gamma * lambda * not_done * next_advantage;
      advantages[i] = static_cast<float>(next_advantage);
      returns[i] = static_cast<float>(next_advantage + values[i]);
    }
  }
}

/// Actor and critic: μ_θ(s) = tanh(MLP(s)), σ = exp(log_std), V_θ(s) = MLP(s).
class TorchActorCriticImpl : public torch::nn::Module {
 public:
  TorchActorCriticImpl(std::int64_t observation_size, std::int64_t action_size,
                       const PpoSettings& s)
      : activation_(s.activation) {
    std::int64_t in = observation_size;
    for (std::size_t i = 0; i < s.actor_hidden.size(); ++i) {
      actor_.push_back(
          register_module("actor" + std::to_string(i), torch::nn::Linear(in, s.actor_hidden[i])));
      in = s.actor_hidden[i];
    }
    actor_.push_back(register_module("actor" + std::to_string(s.actor_hidden.size()),
                                     torch::nn::Linear(in, action_size)));
    in = observation_size;
    for (std::size_t i = 0; i < s.critic_hidden.size(); ++i) {
      critic_.push_back(
          register_module("critic" + std::to_string(i), torch::nn::Linear(in, s.critic_hidden[i])));
      in = s.critic_hidden[i];
    }
    critic_.push_back(register_module("critic" + std::to_string(s.critic_hidden.size()),
                                      torch::nn::Linear(in, 1)));
    {  // a small last actor layer: the policy starts near μ = 0 for every state
      torch::NoGradGuard no_grad;
      actor_.back()->weight.mul_(0.01);
      actor_.back()->bias.zero_();
    }
    log_std_ = register_parameter(
        "log_std", torch::full({action_size}, std::log(s.initial_std), torch::kFloat32));
  }

  /// Policy mean μ_θ(s) ∈ (−1, 1)^A, obs [B, O] → [B, A].
  torch::Tensor mean(const torch::Tensor& obs) { return torch::tanh(mlp(actor_, obs)); }
  /// Critic V_θ(s), obs [B, O] → [B].
  torch::Tensor value(const torch::Tensor& obs) { return mlp(critic_, obs).squeeze(-1); }
  const torch::Tensor& log_std() const { return log_std_; }
  /// log π_θ(a | s) of the Gaussian, summed over action dimensions → [B].
  torch::Tensor log_prob(const torch::Tensor& mean, const torch::Tensor& action) const {
    const torch::Tensor var = torch::exp(2.0 * log_std_);
    return (-(action - mean).pow(2) / (2.0 * var) - log_std_ - 0.5 * std::log(2.0 * kPi)).sum(-1);
  }
  /// S[π_θ] = Σ_dims 0.5 + 0.5 log(2π) + log σ (eq. 11.2).
  torch::Tensor entropy() const { return (0.5 + 0.5 * std::log(2.0 * kPi) + log_std_).sum(); }
  TorchActivation activation() const { return activation_; }

 private:
  torch::Tensor mlp(std::vector<torch::nn::Linear>& layers, torch::Tensor x) {
    for (std::size_t i = 0; i < layers.size(); ++i) {
      x = layers[i]->forward(x);
      if (i + 1 < layers.size())
        x = activation_ == TorchActivation::relu ? torch::relu(x) : torch::tanh(x);
    }
    return x;
  }
  TorchActivation activation_;
  std::vector<torch::nn::Linear> actor_, critic_;
  torch::Tensor log_std_;
};
TORCH_MODULE(TorchActorCritic);

/// What data-parallel PPO needs from the processes of a run: sums over all processes and a
/// broadcast from process 0. walkgen::TorchGlooCommunicator (walkgen/torch/distributed.hpp)
/// implements it on PyTorch's c10d with Gloo; a test may implement it in memory.
class PpoCommunicator {
 public:
  virtual ~PpoCommunicator() = default;
  [[nodiscard]] virtual int rank() const = 0;        ///< this process, 0 … world_size() − 1
  [[nodiscard]] virtual int world_size() const = 0;  ///< the number of processes
  /// Replaces `tensor` (contiguous, CPU) with its sum over all processes.
  virtual void allreduce_sum(torch::Tensor& tensor) = 0;
  /// Replaces `tensor` (contiguous, CPU) with process 0's.
  virtual void broadcast(torch::Tensor& tensor) = 0;
};

/// FNV-1a hash of a text (e.g. a run's settings), the same on every machine.
constexpr std::uint64_t text_hash(const char* text, std::size_t size) noexcept {
  std::uint64_t h = 0xCBF29CE484222325ull;
  for (std::size_t i = 0; i < size; ++i)
    h = (h ^ static_cast<unsigned char>(text[i])) * 0x100000001B3ull;
  return h;
}

/// Checks that every process holds the same `value` (e.g. a hash of its settings, its epoch):
/// process 0's is broadcast, each compares, and the mismatches are summed, so that all
/// processes throw together rather than wait for each other in a later collective.
/// @throws walkgen::invalid_argument on every process when any differs, naming `what`.
inline void check_same_on_all_processes(PpoCommunicator& communicator, std::uint64_t value,
                                        const std::string& what) {
  torch::Tensor mine = torch::tensor({static_cast<std::int64_t>(value)}, torch::kInt64);
  torch::Tensor first = mine.clone();
  communicator.broadcast(first);
  torch::Tensor differs = torch::tensor(
      {first.item<std::int64_t>() != mine.item<std::int64_t>() ? 1.0 : 0.0}, torch::kFloat64);
  communicator.allreduce_sum(differs);
  const int count = static_cast<int>(differs.item<double>());
  check_argument(
      count == 0, "check_same_on_all_processes",
      "the same " + what + " on all " + std::to_string(communicator.world_size()) + " processes",
      std::to_string(count) + " process(es) with another than process 0's",
      "start every process with the same settings (and from the same checkpoint)");
}

/// A 64-bit mix of a seed and two counters (splitmix64's finaliser over their sum): the seed of
/// environment `index` in epoch `epoch`, of its exploration noise, of an update's minibatch
/// order. Equal inputs give equal seeds on every machine, so a run's randomness depends on the
/// seed and the counters only, not on how the environments are spread over processes.
constexpr std::uint64_t mix_seed(std::uint64_t seed, std::uint64_t a, std::uint64_t b) noexcept {
  std::uint64_t z = seed + 0x9E3779B97F4A7C15ull * (a + 1) + 0xD1B54A32D192ED03ull * (b + 1);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

/// PPO: acting, updating (algorithm 1), saving and loading the policy.
class TorchPpo {
 public:
  /// Seeds torch's global generator with settings.seed, then builds the networks and Adam.
  /// @throws walkgen::invalid_argument on non-positive sizes or hyper-parameters out of range.
  TorchPpo(int observation_size, int action_size, const PpoSettings& settings = {})
      : s_(checked(settings, observation_size, action_size)),
        obs_(observation_size),
        act_(action_size),
        model_((torch::manual_seed(settings.seed),
                TorchActorCritic(observation_size, action_size, settings))),
        optimizer_(model_->parameters(), torch::optim::AdamOptions(settings.learning_rate)) {}

  int observation_size() const { return obs_; }
  int action_size() const { return act_; }
  const PpoSettings& settings() const { return s_; }
  TorchActorCritic& model() { return model_; }
  /// Mean σ of the policy.
  double std() const { return torch::exp(model_->log_std()).mean().item<double>(); }

  /// Actions for a batch of observations (obs: batch × O, row-major): sampled from π_θ, or
  /// the mean μ_θ(s) when deterministic (test mode). log_prob and value may be null. `noise`
  /// (batch × A standard normal draws, e.g. from each environment's own generator, as
  /// walkgen::PpoTrainer does) gives the sample μ + σ·noise; when null, torch's global generator
  /// draws it.
  void act(const float* obs, int batch, bool deterministic, float* action,
           float* log_prob = nullptr, float* value = nullptr, const float* noise = nullptr) {
    torch::NoGradGuard no_grad;
    const torch::Tensor o =
        torch::from_blob(const_cast<float*>(obs), {batch, obs_}, torch::kFloat32);
    const torch::Tensor mu = model_->mean(o);
    torch::Tensor a = mu;
    if (!deterministic) {
      const torch::Tensor z = noise != nullptr ? torch::from_blob(const_cast<float*>(noise),
                                                                  {batch, act_}, torch::kFloat32)
                                               : torch::randn_like(mu);
      a = mu + torch::exp(model_->log_std()) * z;
    }
    a = a.contiguous();
    std::memcpy(action, a.data_ptr<float>(),
                sizeof(float) * static_cast<std::size_t>(batch * act_));
    if (log_prob != nullptr) {
      const torch::Tensor lp = model_->log_prob(mu, a).contiguous();
      std::memcpy(log_prob, lp.data_ptr<float>(), sizeof(float) * static_cast<std::size_t>(batch));
    }
    if (value != nullptr) values(obs, batch, value);
  }
  /// Critic values V_θ(s) for a batch of observations.
  void values(const float* obs, int batch, float* value) {
    torch::NoGradGuard no_grad;
    const torch::Tensor o =
        torch::from_blob(const_cast<float*>(obs), {batch, obs_}, torch::kFloat32);
    const torch::Tensor v = model_->value(o).contiguous();
    std::memcpy(value, v.data_ptr<float>(), sizeof(float) * static_cast<std::size_t>(batch));
  }

  /// Makes this policy one process of a data-parallel run (null: alone again): process 0's
  /// weights are broadcast at once, and every update then sums the gradients and the
  /// statistics over the processes, so all of them keep the same weights. Each process passes
  /// update() the rollout of its own environments, all of the same size.
  void set_communicator(PpoCommunicator* communicator) {
    communicator_ = communicator;
    if (communicator_ == nullptr) return;
    torch::NoGradGuard no_grad;
    for (auto& p : model_->parameters()) {
      torch::Tensor t = p.detach().contiguous();
      communicator_->broadcast(t);
      p.copy_(t);
    }
  }
  [[nodiscard]] PpoCommunicator* communicator() const { return communicator_; }
  /// Updates done so far (the counter that seeds each update's minibatch order).
  [[nodiscard]] std::int64_t updates() const { return updates_; }
  /// The run's number of updates K, for PpoSettings::anneal_learning_rate (0: not known, the
  /// step size stays learning_rate).
  /// @throws walkgen::invalid_argument for K < 0.
  void set_total_updates(std::int64_t total) {
    check_argument(total >= 0, "TorchPpo::set_total_updates", "a count >= 0", total);
    total_updates_ = total;
  }
  /// Adam's step size for the next update (PpoSettings::anneal_learning_rate).
  [[nodiscard]] double learning_rate() const {
    if (!s_.anneal_learning_rate || total_updates_ <= 0) return s_.learning_rate;
    const double left = 1.0 - static_cast<double>(updates_) / static_cast<double>(total_updates_);
    return s_.learning_rate * std::max(0.0, left);
  }

  /// One PPO update on a rollout (algorithm 1): GAE, then `epochs` passes over shuffled
  /// minibatches of L = −L^CLIP + c1 L^VF − c2 S (eq. 4.16–4.17) with Adam.
  ///
  /// The minibatches are drawn from the samples of all processes in an order from
  /// mix_seed(seed, updates()); each process computes the loss terms of its own samples
  /// divided by the minibatch's size, and the gradients are summed over the processes; the
  /// advantages are normalised with the statistics of all processes and the KL early stop is
  /// decided on the whole minibatch's mean: K processes with E environments each update as one
  /// process with K·E environments would (to float rounding).
  /// @throws walkgen::invalid_argument if the rollout's sizes do not match the policy.
  PpoUpdateResult update(const PpoRollout& r) {
    check_argument(r.observation_size == obs_ && r.action_size == act_ && r.steps > 0 && r.envs > 0,
                   "TorchPpo::update", "a rollout of this policy's observation/action sizes",
                   "other sizes or an empty rollout");
    const double step_size = learning_rate();
    for (auto& group : optimizer_.param_groups())
      static_cast<torch::optim::AdamOptions&>(group.options()).lr(step_size);
    std::vector<float> rewards(r.rewards);
    for (auto& x : rewards) x = static_cast<float>(x * s_.reward_scale);
    std::vector<float> adv, ret;
    generalized_advantages(rewards, r.values, r.dones, r.steps, r.envs, s_.gamma, s_.lambda, adv,
                           ret);
    const std::int64_t n = static_cast<std::int64_t>(adv.size());
    auto tensor = [](const std::vector<float>& v, std::vector<std::int64_t> shape) {
      return torch::from_blob(const_cast<float*>(v.data()), shape, torch::kFloat32).clone();
    };
    const torch::Tensor obs = tensor(r.observations, {n, obs_});
    const torch::Tensor act = tensor(r.actions, {n, act_});
    const torch::Tensor old_log_prob = tensor(r.log_probs, {n});
    torch::Tensor advantage = tensor(adv, {n});
    const torch::Tensor target = tensor(ret, {n});
    const int world = communicator_ != nullptr ? communicator_->world_size() : 1;
    if (s_.normalize_advantages) {
      // mean and unbiased std over the samples of all processes, summed in double
      double sums[3] = {0.0, 0.0, static_cast<double>(n)};
      for (const float a : adv) {
        sums[0] += a;
        sums[1] += static_cast<double>(a) * a;
      }
      sum_over_processes(sums, 3);
      if (sums[2] > 1.0) {
        const double mean = sums[0] / sums[2];
        const double var = std::max(0.0, (sums[1] - sums[2] * mean * mean) / (sums[2] - 1.0));
        advantage = (advantage - mean) / (std::sqrt(var) + 1e-8);
      }
    }
    // Minibatches are drawn over the samples of all processes: global sample g = t·E·W + k
    // (k = rank·E + e) in an order from mix_seed(seed, updates()); each process takes those of
    // its environments. Losses are sums over a process's share divided by the minibatch's
    // size, so the sum of the processes' gradients is the gradient of the whole minibatch.
    const std::int64_t E = r.envs, T = r.steps, EW = E * world, N = T * EW;
    const std::int64_t M = std::min<std::int64_t>(s_.minibatch, N);
    const std::int64_t rank = communicator_ != nullptr ? communicator_->rank() : 0;

    PpoUpdateResult out;
    int batches = 0;
    bool stop = false;
    std::mt19937_64 order_rng(mix_seed(s_.seed, 0x5EEDull, static_cast<std::uint64_t>(updates_)));
    std::vector<std::int64_t> order(static_cast<std::size_t>(N));
    std::vector<std::int64_t> index;
    index.reserve(static_cast<std::size_t>(M));
    for (int epoch = 0; epoch < s_.epochs && !stop; ++epoch) {
      for (std::int64_t g = 0; g < N; ++g) order[static_cast<std::size_t>(g)] = g;
      for (std::int64_t i = N - 1; i > 0; --i)  // Fisher–Yates with the run's own generator
        std::swap(order[static_cast<std::size_t>(i)],
                  order[static_cast<std::size_t>(order_rng() % static_cast<std::uint64_t>(i + 1))]);
      for (std::int64_t start = 0; start < N; start += M) {
        const std::int64_t count = std::min(start + M, N) - start;
        index.clear();
        for (std::int64_t k = start; k < start + count; ++k) {
          const std::int64_t g = order[static_cast<std::size_t>(k)], t = g / EW, c = g % EW;
          if (c / E == rank) index.push_back(t * E + c % E);
        }
        const double inv = 1.0 / static_cast<double>(count);
        const torch::Tensor idx =
            torch::from_blob(index.data(), {static_cast<std::int64_t>(index.size())}, torch::kLong);
        const torch::Tensor o = obs.index_select(0, idx);
        const torch::Tensor a = act.index_select(0, idx);
        const torch::Tensor A = advantage.index_select(0, idx);
        const torch::Tensor lp = model_->log_prob(model_->mean(o), a);
        const torch::Tensor log_ratio = lp - old_log_prob.index_select(0, idx);
        const torch::Tensor ratio = torch::exp(log_ratio);
        const torch::Tensor surrogate =
            torch::min(ratio * A, torch::clamp(ratio, 1.0 - s_.clip, 1.0 + s_.clip) * A);
        const torch::Tensor policy_loss = -surrogate.sum() * inv;
        const torch::Tensor value_loss =
            (model_->value(o) - target.index_select(0, idx)).pow(2).sum() * inv;
        const torch::Tensor entropy = model_->entropy();  // state-independent σ
        // the minibatch's means: each process's share, summed over the processes
        double stats[4] = {
            ((ratio - 1.0) - log_ratio).sum().item<double>() * inv, policy_loss.item<double>(),
            value_loss.item<double>(),
            ((ratio - 1.0).abs() > s_.clip).to(torch::kFloat64).sum().item<double>() * inv};
        sum_over_processes(stats, 4);
        if (s_.target_kl > 0.0 && stats[0] > s_.target_kl) {
          stop = true;  // this minibatch's step is not taken
          out.status = PpoUpdateStatus::kl_stopped;
          out.message = "the mean KL estimate exceeded target_kl: the update stopped early";
          break;
        }
        const double share = static_cast<double>(index.size()) * inv;
        const torch::Tensor loss =
            policy_loss + s_.value_coef * value_loss - s_.entropy_coef * share * entropy;
        optimizer_.zero_grad();
        loss.backward();
        if (communicator_ != nullptr) sum_gradients();
        if (s_.max_grad_norm > 0.0)
          torch::nn::utils::clip_grad_norm_(model_->parameters(), s_.max_grad_norm);
        optimizer_.step();
        out.approx_kl += stats[0];
        out.policy_loss += stats[1];
        out.value_loss += stats[2];
        out.entropy += entropy.item<double>();
        out.clip_fraction += stats[3];
        ++batches;
      }
    }
    ++updates_;
    out.steps = batches;
    if (batches > 0) {
      out.policy_loss /= batches;
      out.value_loss /= batches;
      out.entropy /= batches;
      out.approx_kl /= batches;
      out.clip_fraction /= batches;
    }
    out.std = std();
    return out;
  }

  /// Writes a checkpoint that resume_checkpoint() continues from: the weights, Adam's state
  /// (moments and step counts), the update counter, torch's global generator and the caller's
  /// `counters` (e.g. the trainer's epoch, the best score so far). Replaced atomically
  /// (walkgen::write_atomically), so a run stopped during a save keeps the previous checkpoint.
  /// Not a policy file: save() writes those.
  /// @throws walkgen::invalid_argument if the file cannot be written.
  void save_checkpoint(const std::string& path,
                       const std::vector<std::pair<std::string, double>>& counters = {}) {
    std::ostringstream bytes;
    try {
      torch::serialize::OutputArchive archive;
      for (const auto& p : model_->named_parameters()) archive.write("model." + p.key(), p.value());
      torch::serialize::OutputArchive adam;
      optimizer_.save(adam);
      archive.write("optimizer", adam);
      archive.write("updates", c10::IValue(updates_));
      archive.write("torch_generator", at::detail::getDefaultCPUGenerator().get_state());
      archive.write("observation_size", c10::IValue(std::int64_t(obs_)));
      archive.write("action_size", c10::IValue(std::int64_t(act_)));
      for (const auto& c : counters) archive.write("counter." + c.first, c10::IValue(c.second));
      archive.save_to(bytes);
    } catch (const c10::Error& e) {
      throw invalid_argument(
          detail::expected_got("TorchPpo::save_checkpoint", "a checkpoint torch can serialise",
                               std::string("the error: ") + e.what_without_backtrace()));
    }
    write_bytes(path, bytes.str(), "TorchPpo::save_checkpoint");
  }

  /// Continues from a checkpoint of save_checkpoint() written by a policy of the same sizes
  /// and settings: restores the weights, Adam's state, the update counter and torch's global
  /// generator, and returns the value of each name in `counter_names` (in that order).
  /// @throws walkgen::invalid_argument if the file is missing, not a checkpoint, of other
  ///   sizes, or lacks a named counter.
  std::vector<double> resume_checkpoint(const std::string& path,
                                        const std::vector<std::string>& counter_names = {}) {
    std::vector<double> counters;
    try {
      torch::serialize::InputArchive archive;
      archive.load_from(path);
      c10::IValue v;
      archive.read("observation_size", v);
      const std::int64_t o = v.toInt();
      archive.read("action_size", v);
      const std::int64_t a = v.toInt();
      check_argument(o == obs_ && a == act_, "TorchPpo::resume_checkpoint",
                     "a checkpoint of a policy with " + std::to_string(obs_) + " inputs and " +
                         std::to_string(act_) + " outputs",
                     std::to_string(o) + " and " + std::to_string(a) + " in " + path);
      torch::NoGradGuard no_grad;
      for (auto& p : model_->named_parameters()) {
        torch::Tensor t;
        archive.read("model." + p.key(), t);
        const std::string where = "TorchPpo::resume_checkpoint: " + p.key();
        check_argument(t.sizes() == p.value().sizes(), where.c_str(), p.value().sizes(), t.sizes());
        p.value().copy_(t);
      }
      torch::serialize::InputArchive adam;
      archive.read("optimizer", adam);
      optimizer_.load(adam);
      archive.read("updates", v);
      updates_ = v.toInt();
      torch::Tensor state;
      archive.read("torch_generator", state);
      at::Generator generator = at::detail::getDefaultCPUGenerator();  // shares the state
      generator.set_state(state);
      for (const auto& name : counter_names) {
        check_argument(archive.try_read("counter." + name, v) && v.isDouble(),
                       "TorchPpo::resume_checkpoint", "a counter " + name, "none in " + path);
        counters.push_back(v.toDouble());
      }
    } catch (const c10::Error& e) {
      throw invalid_argument(detail::expected_got("TorchPpo::resume_checkpoint",
                                                  "a checkpoint written by save_checkpoint",
                                                  path + " (" + e.what_without_backtrace() + ")"));
    }
    return counters;
  }

  /// Saves the policy as a TorchScript module: forward(x) = μ_θ(x) (the test-mode action),
  /// value(x) = V_θ(x), log_std() = log σ; attributes observation_size, action_size, activation,
  /// actor_hidden, critic_hidden. Python: torch.jit.load(path)(torch.zeros(1, O)).
  /// The file is replaced atomically (walkgen::write_atomically): the module is serialised in
  /// memory, written to a temporary file in the same folder and renamed over `path`, so that a
  /// save that fails or is interrupted (a crash, a full disk) leaves the previous policy loadable.
  /// (libtorch's own file writer ends the process on a write error; it never sees the file.)
  /// @throws walkgen::invalid_argument if the file cannot be written (the previous file, if any,
  ///   is then unchanged).
  void save(const std::string& path) const {
    torch::jit::Module m("WalkgenPpoPolicy");
    for (const auto& p : model_->named_parameters())
      m.register_parameter(script_name(p.key()), p.value().detach().clone(), false);
    m.register_attribute("observation_size", c10::IntType::get(), c10::IValue(std::int64_t(obs_)));
    m.register_attribute("action_size", c10::IntType::get(), c10::IValue(std::int64_t(act_)));
    m.register_attribute("activation", c10::IntType::get(),
                         c10::IValue(static_cast<std::int64_t>(s_.activation)));
    m.register_attribute("actor_hidden", c10::ListType::ofInts(),
                         c10::IValue(c10::List<std::int64_t>(s_.actor_hidden)));
    m.register_attribute("critic_hidden", c10::ListType::ofInts(),
                         c10::IValue(c10::List<std::int64_t>(s_.critic_hidden)));
    std::ostringstream src;
    src << "def forward(self, x):\n"
        << script_mlp("actor", s_.actor_hidden.size(), true) << "def value(self, x):\n"
        << script_mlp("critic", s_.critic_hidden.size(), false)
        << "def log_std_values(self):\n    return self.log_std\n";
    m.define(src.str());
    std::ostringstream bytes;
    try {
      m.save(bytes);
    } catch (const c10::Error& e) {
      throw invalid_argument(
          detail::expected_got("TorchPpo::save", "a policy TorchScript can save",
                               std::string("the error: ") + e.what_without_backtrace()));
    }
    write_bytes(path, bytes.str(), "TorchPpo::save");
  }

  /// Loads a policy saved by save(): sizes and layers from the file, training hyper-parameters
  /// from `settings` (its sizes and activation are replaced by the file's).
  /// @throws walkgen::invalid_argument if the file is missing or not a walkgen policy.
  [[nodiscard]] static TorchPpo load(const std::string& path, PpoSettings settings = {}) {
    torch::jit::Module m;
    try {
      m = torch::jit::load(path);
    } catch (const c10::Error& e) {
      throw invalid_argument(detail::expected_got("TorchPpo::load", "a TorchScript file", path,
                                                  "saved by TorchPpo::save?"));
    }
    for (const char* a :
         {"observation_size", "action_size", "activation", "actor_hidden", "critic_hidden"}) {
      check_argument(m.hasattr(a), "TorchPpo::load", std::string("an attribute ") + a,
                     "none in " + path, "the file was not saved by TorchPpo::save");
    }
    settings.actor_hidden = m.attr("actor_hidden").toIntVector();
    settings.critic_hidden = m.attr("critic_hidden").toIntVector();
    settings.activation = static_cast<TorchActivation>(m.attr("activation").toInt());
    TorchPpo ppo(static_cast<int>(m.attr("observation_size").toInt()),
                 static_cast<int>(m.attr("action_size").toInt()), settings);
    ppo.copy_parameters(m, path);
    return ppo;
  }

  /// Replaces this policy's weights by those of a file saved by save() from a policy of the
  /// same sizes (e.g. the best epoch's checkpoint). The optimiser's state is kept.
  /// @throws walkgen::invalid_argument if the file is missing or its layers differ.
  void load_parameters(const std::string& path) {
    torch::jit::Module m;
    try {
      m = torch::jit::load(path);
    } catch (const c10::Error& e) {
      throw invalid_argument(detail::expected_got("TorchPpo::load_parameters", "a TorchScript file",
                                                  path, "saved by TorchPpo::save?"));
    }
    copy_parameters(m, path);
  }

 private:
  void copy_parameters(const torch::jit::Module& m, const std::string& path) {
    torch::NoGradGuard no_grad;
    for (auto& p : model_->named_parameters()) {
      const std::string name = script_name(p.key());
      check_argument(m.hasattr(name), "TorchPpo::load", "a parameter " + name, "none in " + path);
      const torch::Tensor t = m.attr(name).toTensor();
      const std::string where = "TorchPpo::load: " + name;
      check_argument(t.sizes() == p.value().sizes(), where.c_str(), p.value().sizes(), t.sizes());
      p.value().copy_(t);
    }
  }
  // `data` to `path`, atomically (walkgen::write_atomically); `where` names the caller.
  static void write_bytes(const std::string& path, const std::string& data, const char* where) {
    write_atomically(path, [&](const std::string& temp) {
      std::ofstream out(temp, std::ios::binary | std::ios::trunc);
      out.write(data.data(), static_cast<std::streamsize>(data.size()));
      out.close();
      check_argument(!out.fail(), where,
                     "'" + path + "' written (" + std::to_string(data.size()) + " bytes)",
                     "a write error", "is the disk full, the folder writable?");
    });
  }
  void sum_over_processes(double* values, int count) {
    if (communicator_ == nullptr) return;
    torch::Tensor t = torch::from_blob(values, {count}, torch::kFloat64).clone();
    communicator_->allreduce_sum(t);
    std::memcpy(values, t.data_ptr<double>(), sizeof(double) * static_cast<std::size_t>(count));
  }
  // one allreduce of all gradients, flattened (a parameter without a gradient counts as zero,
  // so that every process sends the same layout)
  void sum_gradients() {
    std::vector<torch::Tensor> grads;
    for (auto& p : model_->parameters()) {
      if (!p.grad().defined()) p.mutable_grad() = torch::zeros_like(p);
      grads.push_back(p.grad().reshape({-1}));
    }
    torch::Tensor flat = torch::cat(grads);
    communicator_->allreduce_sum(flat);
    std::int64_t offset = 0;
    for (auto& p : model_->parameters()) {
      const std::int64_t k = p.grad().numel();
      p.mutable_grad().copy_(flat.slice(0, offset, offset + k).view_as(p.grad()));
      offset += k;
    }
  }
  static std::string script_name(std::string key) {
    std::replace(key.begin(), key.end(), '.', '_');
    return key;
  }
  std::string script_mlp(const std::string& prefix, std::size_t hidden, bool tanh_out) const {
    std::ostringstream s;
    s << "    h = x\n";
    const char* act = s_.activation == TorchActivation::relu ? "torch.relu" : "torch.tanh";
    for (std::size_t i = 0; i <= hidden; ++i) {
      const std::string l = "self." + prefix + std::to_string(i);
      const std::string lin = "torch.matmul(h, " + l + "_weight.t()) + " + l + "_bias";
      if (i < hidden)
        s << "    h = " << act << "(" << lin << ")\n";
      else
        s << "    h = " << lin << "\n";
    }
    s << (tanh_out ? "    return torch.tanh(h)\n" : "    return h.squeeze(-1)\n");
    return s.str();
  }
  static const PpoSettings& checked(const PpoSettings& s, int obs, int act) {
    check_argument(obs >= 1 && act >= 1, "TorchPpo", "observation and action sizes >= 1",
                   std::to_string(obs) + " and " + std::to_string(act));
    validate(s);
    return s;
  }

  PpoSettings s_;
  int obs_, act_;
  TorchActorCritic model_;
  torch::optim::Adam optimizer_;
  PpoCommunicator* communicator_ = nullptr;
  std::int64_t updates_ = 0;
  std::int64_t total_updates_ = 0;  ///< K of PpoSettings::anneal_learning_rate (0: unknown)
};

}  // namespace walkgen
