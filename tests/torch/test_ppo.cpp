// Tests of walkgen::torch (thesis §4.2, §11.2): GAE (eq. 4.15) against a hand computation, the
// Gaussian policy's log-probability and entropy (eq. 11.2), TorchScript save/load (also from
// Python where /usr/bin/python3 has torch), and a short seeded PPO run on the benchmarking
// environment of §11.2.1 that must learn. The environments themselves (core only) are tested in
// tests/learning/test_environments.cpp.
#include <gtest/gtest.h>
#include <sys/resource.h>
#include <torch/torch.h>

#include <array>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <set>
#include <string>
#include <vector>

#include "support/enum_strings.hpp"
#include "support/expect_error.hpp"
#include "walkgen/core/math.hpp"
#include "walkgen/learning/environment.hpp"
#include "walkgen/torch/ppo.hpp"
#include "walkgen/torch/training.hpp"
#include "walkgen/torch/velocity_network.hpp"

namespace {

std::string temp_path(const std::string& name) {
  return std::string(WALKGEN_TORCH_TEST_DIR) + "/" + name;
}

TEST(Gae, MatchesHandComputation) {
  // Two environments, three steps; env 1 ends its episode at t = 1.
  const std::vector<float> rewards{1.0f, 0.5f, 2.0f, -1.0f, 0.0f, 3.0f};  // [t][e]
  const std::vector<float> values{0.1f, 0.2f, 0.3f, 0.4f, 0.5f, 0.6f, 0.7f, 0.8f};
  const std::vector<float> dones{0, 0, 0, 1, 0, 0};
  const double g = 0.9, l = 0.8;
  std::vector<float> adv, ret;
  walkgen::generalized_advantages(rewards, values, dones, 3, 2, g, l, adv, ret);
  // env 0: δ2 = 0 + .9·.7 − .5, δ1 = 2 + .9·.5 − .3, δ0 = 1 + .9·.3 − .1
  const double d2 = 0.0 + g * 0.7 - 0.5, d1 = 2.0 + g * 0.5 - 0.3, d0 = 1.0 + g * 0.3 - 0.1;
  EXPECT_NEAR(adv[4], d2, 1e-6);
  EXPECT_NEAR(adv[2], d1 + g * l * d2, 1e-6);
  EXPECT_NEAR(adv[0], d0 + g * l * (d1 + g * l * d2), 1e-6);
  // env 1: done at t = 1 cuts the bootstrap and the trace
  const double e2 = 3.0 + g * 0.8 - 0.6, e1 = -1.0 - 0.4, e0 = 0.5 + g * 0.4 - 0.2;
  EXPECT_NEAR(adv[5], e2, 1e-6);
  EXPECT_NEAR(adv[3], e1, 1e-6);
  EXPECT_NEAR(adv[1], e0 + g * l * e1, 1e-6);
  EXPECT_NEAR(ret[1], adv[1] + 0.2, 1e-6);
  EXPECT_THROW(walkgen::generalized_advantages(rewards, values, dones, 2, 2, g, l, adv, ret),
               walkgen::invalid_argument);
}

TEST(TorchActorCritic, GaussianLogProbAndEntropy) {
  walkgen::PpoSettings s;
  s.initial_std = 0.3;
  walkgen::TorchPpo ppo(3, 2, s);
  const torch::Tensor mean = torch::tensor({{0.1f, -0.2f}});
  const torch::Tensor a = torch::tensor({{0.4f, 0.1f}});
  const double sigma = 0.3;
  double expected = 0.0;
  for (double d : {0.3, 0.3})
    expected += -d * d / (2 * sigma * sigma) - std::log(sigma) - 0.5 * std::log(2 * walkgen::kPi);
  EXPECT_NEAR(ppo.model()->log_prob(mean, a).item<double>(), expected, 1e-5);
  // eq. 11.2 per dimension
  EXPECT_NEAR(ppo.model()->entropy().item<double>(),
              2 * (0.5 + 0.5 * std::log(2 * walkgen::kPi) + std::log(sigma)), 1e-5);
  EXPECT_NEAR(ppo.std(), sigma, 1e-6);
}

TEST(TorchPpo, SeededRunsAreReproducible) {
  walkgen::PpoSettings s;
  s.seed = 42;
  float a1[4], a2[4];
  const float obs[4] = {0.1f, 0.2f, 0.3f, 0.4f};
  {
    walkgen::TorchPpo p(4, 2, s);
    p.act(obs, 2, false, a1);
  }
  {
    walkgen::TorchPpo p(4, 2, s);
    p.act(obs, 2, false, a2);
  }
  for (int i = 0; i < 4; ++i) EXPECT_EQ(a1[i], a2[i]);
}

TEST(TorchPpo, SaveLoadTorchScriptRoundTrip) {
  walkgen::PpoSettings s;
  s.actor_hidden = {16, 32};
  s.critic_hidden = {8};
  s.activation = walkgen::TorchActivation::relu;
  s.seed = 3;
  walkgen::TorchPpo ppo(4, 2, s);
  {  // move the weights away from the initialisation
    torch::NoGradGuard no_grad;
    for (auto& p : ppo.model()->parameters()) p.add_(0.05 * torch::randn_like(p));
  }
  const std::string path = temp_path("ppo_roundtrip.pt");
  ppo.save(path);
  walkgen::TorchPpo loaded = walkgen::TorchPpo::load(path);
  EXPECT_EQ(loaded.settings().actor_hidden, s.actor_hidden);
  EXPECT_EQ(loaded.settings().critic_hidden, s.critic_hidden);
  const float obs[8] = {1.0f, -2.0f, 3.0f, 0.5f, -1.0f, 0.0f, 2.0f, -4.0f};
  float a[4], b[4], va[2], vb[2];
  ppo.act(obs, 2, true, a, nullptr, va);
  loaded.act(obs, 2, true, b, nullptr, vb);
  for (int i = 0; i < 4; ++i) EXPECT_FLOAT_EQ(a[i], b[i]);
  for (int i = 0; i < 2; ++i) EXPECT_FLOAT_EQ(va[i], vb[i]);
  EXPECT_NEAR(loaded.std(), ppo.std(), 1e-7);

  // The TorchScript module itself gives the same mean action (C++ torch::jit).
  torch::jit::Module m = torch::jit::load(path);
  const torch::Tensor x = torch::from_blob(const_cast<float*>(obs), {2, 4}, torch::kFloat32);
  const torch::Tensor y = m.forward({x}).toTensor();
  for (int i = 0; i < 4; ++i) EXPECT_NEAR(y.view({-1})[i].item<float>(), a[i], 1e-6);

#ifdef WALKGEN_TORCH_PYTHON
  // ... and Python's torch.jit.load.
  const std::string out = temp_path("ppo_roundtrip_python.txt");
  const std::string cmd = "/usr/bin/python3 -c \"import torch; m = torch.jit.load('" + path +
                          "'); x = torch.tensor([[1.0, -2.0, 3.0, 0.5], [-1.0, 0.0, 2.0, -4.0]]); "
                          "print(' '.join('%.9g' % v for v in m(x).flatten().tolist()), "
                          "' '.join('%.9g' % v for v in m.value(x).tolist()))\" > '" +
                          out + "'";
  ASSERT_EQ(std::system(cmd.c_str()), 0) << cmd;
  std::ifstream in(out);
  for (int i = 0; i < 4; ++i) {
    double v = 0;
    ASSERT_TRUE(in >> v);
    EXPECT_NEAR(v, a[i], 1e-6);
  }
  for (int i = 0; i < 2; ++i) {
    double v = 0;
    ASSERT_TRUE(in >> v);
    EXPECT_NEAR(v, va[i], 1e-5);
  }
#endif

  // A policy of other sizes cannot take these weights; a missing file is a named error.
  walkgen::TorchPpo other(5, 2, s);
  EXPECT_THROW(other.load_parameters(path), walkgen::invalid_argument);
  EXPECT_THROW((void)walkgen::TorchPpo::load(temp_path("no_such_policy.pt")),
               walkgen::invalid_argument);
  EXPECT_THROW(ppo.save("/no/such/folder/p.pt"), walkgen::invalid_argument);
}

// Issue 21, defect 7b: ppo_train saves the best policy over the previous one; a save that stops
// half-way (a crash, a full disk) must leave the previous policy loadable. save() writes a
// temporary file in the same folder and renames it over the target.
TEST(TorchPpo, SaveIsAtomic) {
  namespace fs = std::filesystem;
  const fs::path folder = fs::path(temp_path("ppo_atomic"));
  fs::remove_all(folder);
  fs::create_directories(folder);
  const std::string path = (folder / "policy.pt").string();
  const auto listing = [&] {
    std::set<std::string> names;
    for (const auto& e : fs::directory_iterator(folder)) names.insert(e.path().filename().string());
    return names;
  };
  const auto bytes = [&] {
    std::ifstream in(path, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  };
  walkgen::PpoSettings s;
  s.seed = 5;
  walkgen::TorchPpo first(4, 2, s);
  first.save(path);
  EXPECT_EQ(listing(), (std::set<std::string>{"policy.pt"}));  // no temporary file left
  const std::string saved = bytes();
  ASSERT_GT(saved.size(), 2000u);

  s.seed = 6;
  walkgen::TorchPpo second(4, 2, s);
  {  // A full disk: writes past 1000 bytes fail (RLIMIT_FSIZE; SIGXFSZ ignored meanwhile).
    void (*handler)(int) = std::signal(SIGXFSZ, SIG_IGN);
    rlimit previous{};
    getrlimit(RLIMIT_FSIZE, &previous);
    rlimit lowered = previous;
    lowered.rlim_cur = 1000;
    setrlimit(RLIMIT_FSIZE, &lowered);
    bool threw = false;
    try {
      second.save(path);
    } catch (const walkgen::invalid_argument& e) {
      threw = std::string(e.what()).find(path) != std::string::npos;
    } catch (...) {
    }
    setrlimit(RLIMIT_FSIZE, &previous);
    std::signal(SIGXFSZ, handler);
    EXPECT_TRUE(threw) << "a save that could not write the file did not say so";
  }
  EXPECT_EQ(bytes(), saved) << "the previous policy was overwritten";
  EXPECT_EQ(listing(), (std::set<std::string>{"policy.pt"}));
  walkgen::TorchPpo loaded = walkgen::TorchPpo::load(path);
  const float obs[4] = {1.0f, -2.0f, 3.0f, 0.5f};
  float a[2], b[2];
  first.act(obs, 1, true, a, nullptr, nullptr);
  loaded.act(obs, 1, true, b, nullptr, nullptr);
  for (int i = 0; i < 2; ++i) EXPECT_FLOAT_EQ(a[i], b[i]);

  second.save(path);  // with room on the disk the new policy replaces the old one
  EXPECT_EQ(listing(), (std::set<std::string>{"policy.pt"}));
  walkgen::TorchPpo replaced = walkgen::TorchPpo::load(path);
  second.act(obs, 1, true, a, nullptr, nullptr);
  replaced.act(obs, 1, true, b, nullptr, nullptr);
  for (int i = 0; i < 2; ++i) EXPECT_FLOAT_EQ(a[i], b[i]);
}

TEST(TorchPpo, RejectsBadSettings) {
  walkgen::PpoSettings s;
  s.clip = 0.0;
  EXPECT_THROW(walkgen::TorchPpo(4, 2, s), walkgen::invalid_argument);
  s = {};
  s.gamma = 1.5;
  EXPECT_THROW(walkgen::TorchPpo(4, 2, s), walkgen::invalid_argument);
  EXPECT_THROW(walkgen::TorchPpo(0, 2, {}), walkgen::invalid_argument);
}

TEST(TorchPpo, SettingsAreValidatedNamingTheField) {
  using S = walkgen::PpoSettings;
  walkgen_test::expect_rejected<S>(
      S(), {{[](S& s) {
               s.actor_hidden = {64, 0};
             },
             {"PpoSettings.actor_hidden", ">= 1", "0"}},
            {[](S& s) { s.critic_hidden = {-3}; }, {"PpoSettings.critic_hidden", "-3"}},
            {[](S& s) { s.activation = static_cast<walkgen::TorchActivation>(7); },
             {"PpoSettings.activation", "relu (0) or tanh (1)", "7"}},
            {[](S& s) { s.initial_std = 0.0; }, {"PpoSettings.initial_std", "> 0", "0"}},
            {[](S& s) { s.learning_rate = std::nan(""); }, {"PpoSettings.learning_rate", "nan"}},
            {[](S& s) { s.gamma = 1.5; }, {"PpoSettings.gamma", "(0, 1]", "1.5"}},
            {[](S& s) { s.lambda = -0.5; }, {"PpoSettings.lambda", "[0, 1]", "-0.5"}},
            {[](S& s) { s.clip = 0.0; }, {"PpoSettings.clip", "> 0"}},
            {[](S& s) { s.value_coef = -1.0; }, {"PpoSettings.value_coef", ">= 0", "-1"}},
            {[](S& s) { s.entropy_coef = std::numeric_limits<double>::infinity(); },
             {"PpoSettings.entropy_coef", "inf"}},
            {[](S& s) { s.epochs = 0; }, {"PpoSettings.epochs", "at least 1", "0"}},
            {[](S& s) { s.minibatch = -1; }, {"PpoSettings.minibatch", "-1"}},
            {[](S& s) { s.reward_scale = 0.0; }, {"PpoSettings.reward_scale", "> 0"}}});
  using V = walkgen::VelocityNetworkSettings;
  walkgen_test::expect_rejected<V>(
      V(), {{[](V& v) { v.max_command.x() = std::nan(""); },
             {"VelocityNetworkSettings.max_command", "finite"}},
            {[](V& v) { v.disparity_scale = 0.0; },
             {"VelocityNetworkSettings.disparity_scale", "> 0", "0"}},
            {[](V& v) { v.block = 0; }, {"VelocityNetworkSettings.block", ">= 1", "0"}}});
}

TEST(TorchPpo, EnumStrings) {
  walkgen_test::expect_enum_strings(std::array<walkgen::TorchActivation, 2>{
      walkgen::TorchActivation::relu, walkgen::TorchActivation::tanh});
  walkgen_test::expect_enum_strings(std::array<walkgen::PpoUpdateStatus, 2>{
      walkgen::PpoUpdateStatus::updated, walkgen::PpoUpdateStatus::kl_stopped});
  static_assert(to_string(walkgen::TorchActivation::tanh)[0] == 't');
  static_assert(to_string(walkgen::PpoUpdateStatus::kl_stopped)[0] == 'k');
}

// An update says how it ended: every epoch's minibatches (updated), or stopped at the first
// minibatch whose KL estimate exceeds target_kl (kl_stopped), here at once: the rollout's log
// probabilities are 1 below the policy's, a KL estimate of e − 2 ≈ 0.72.
// 8 steps of 2 environments (4 observations, 2 actions) acted by `ppo`, with log-probabilities
// shifted so that the update's ratios differ from 1.
walkgen::PpoRollout small_rollout(walkgen::TorchPpo& ppo) {
  walkgen::PpoRollout r;
  r.resize(8, 2, 4, 2);
  for (std::size_t i = 0; i < r.observations.size(); ++i) {
    r.observations[i] = 0.1f * static_cast<float>(i % 7);
  }
  ppo.act(r.observations.data(), 16, false, r.actions.data(), r.log_probs.data(), r.values.data());
  for (float& lp : r.log_probs) lp -= 1.0f;
  for (std::size_t i = 0; i < r.rewards.size(); ++i) r.rewards[i] = static_cast<float>(i % 3);
  return r;
}

TEST(TorchPpo, UpdateReportsHowItEnded) {
  walkgen::PpoSettings s;
  s.epochs = 2;
  s.minibatch = 4;
  for (const double target_kl : {0.0, 0.1}) {
    s.target_kl = target_kl;
    walkgen::TorchPpo ppo(4, 2, s);
    const walkgen::PpoUpdateResult u = ppo.update(small_rollout(ppo));
    if (target_kl == 0.0) {
      EXPECT_EQ(u.status, walkgen::PpoUpdateStatus::updated);
      EXPECT_STREQ(u.message, "");
      EXPECT_EQ(u.steps, 8);  // 2 epochs of 16 samples in minibatches of 4
    } else {
      EXPECT_EQ(u.status, walkgen::PpoUpdateStatus::kl_stopped);
      EXPECT_NE(std::string(u.message).find("target_kl"), std::string::npos) << u.message;
      EXPECT_EQ(u.steps, 0);
    }
  }
}

// Thesis §11.2.1, shortened: 30 epochs of 8192 steps, seeded. Learning is asserted as a rise of
// the mean reward per step from the first epoch to the best of the last three by at least 0.1
// (a random policy makes ≈ 0.01 per step, a good one ≈ 0.3), and test-mode wins.
TEST(TorchPpo, LearnsTheBenchmarkEnvironment) {
  torch::set_num_threads(1);
  walkgen::PpoSettings s = walkgen::point_goal_ppo_settings();
  s.seed = 1;
  walkgen::PointGoalSettings es;
  es.max_steps = 200;
  std::vector<walkgen::PointGoalEnv> envs;
  for (int e = 0; e < 8; ++e) envs.emplace_back(es, 1000 + e);
  walkgen::TorchPpo ppo(4, 2, s);
  walkgen::PpoTrainer<walkgen::PointGoalEnv> trainer(ppo, envs, 512);
  std::vector<double> rewards;
  for (int k = 0; k < 30; ++k) rewards.push_back(trainer.run_epoch(8192).mean_reward);
  const double late = std::max({rewards[27], rewards[28], rewards[29]});
  std::printf("mean reward per step: first epoch %.4f, best of the last three %.4f\n", rewards[0],
              late);
  EXPECT_GT(late, rewards[0] + 0.1);
  walkgen::PointGoalEnv test(es, 77);
  const walkgen::PpoTestResult t = walkgen::evaluate_steps(ppo, test, 2000);
  std::printf("test mode, 2000 steps: %d wins, %d losses\n", t.wins, t.losses);
  EXPECT_GT(t.wins, 20);
  EXPECT_EQ(t.losses, 0);
}

// The weights of a policy, flattened (for exact comparisons).
std::vector<float> weights(walkgen::TorchPpo& ppo) {
  std::vector<float> out;
  for (const auto& p : ppo.model()->parameters()) {
    const torch::Tensor t = p.detach().contiguous().reshape({-1});
    out.insert(out.end(), t.data_ptr<float>(), t.data_ptr<float>() + t.numel());
  }
  return out;
}

TEST(PpoTrainer, ResumedFromACheckpointContinuesExactly) {
  torch::set_num_threads(1);
  walkgen::PpoSettings s = walkgen::point_goal_ppo_settings();
  s.seed = 3;
  walkgen::PointGoalSettings es;
  es.max_steps = 200;
  const auto make_envs = [&] {
    std::vector<walkgen::PointGoalEnv> envs;
    for (int e = 0; e < 4; ++e) envs.emplace_back(es, 0);
    return envs;
  };
  const std::string path = temp_path("checkpoint.pt");
  // the uninterrupted run: 3 epochs, a checkpoint after the second
  std::vector<walkgen::PointGoalEnv> envs = make_envs();
  walkgen::TorchPpo ppo(4, 2, s);
  walkgen::PpoTrainer<walkgen::PointGoalEnv> trainer(ppo, envs, 128);
  (void)trainer.run_epoch(1024);
  (void)trainer.run_epoch(1024);
  ppo.save_checkpoint(path, {{"epoch", 2.0}, {"note", 0.5}});
  const std::vector<float> at_checkpoint = weights(ppo);
  const walkgen::PpoEpoch third = trainer.run_epoch(1024);
  const std::vector<float> uninterrupted = weights(ppo);
  EXPECT_EQ(ppo.updates(), 3 * 2);
  // a new process: other initial weights (another seed's), then the checkpoint
  walkgen::PpoSettings other = s;
  other.seed = 99;
  std::vector<walkgen::PointGoalEnv> envs2 = make_envs();
  walkgen::TorchPpo resumed(4, 2, other);
  EXPECT_NE(weights(resumed), at_checkpoint);
  const std::vector<double> counters = resumed.resume_checkpoint(path, {"epoch", "note"});
  ASSERT_EQ(counters.size(), 2u);
  EXPECT_EQ(counters[0], 2.0);
  EXPECT_EQ(counters[1], 0.5);
  EXPECT_EQ(weights(resumed), at_checkpoint);
  EXPECT_EQ(resumed.updates(), 4);
  walkgen::PpoSettings same = s;  // the minibatch order comes from the seed in the settings
  walkgen::TorchPpo again(4, 2, same);
  (void)again.resume_checkpoint(path);
  walkgen::PpoTrainer<walkgen::PointGoalEnv> trainer2(again, envs2, 128);
  trainer2.set_epoch(static_cast<int>(counters[0]));
  const walkgen::PpoEpoch third_again = trainer2.run_epoch(1024);
  EXPECT_EQ(third_again.epoch, 3);
  EXPECT_EQ(third_again.wins, third.wins);
  EXPECT_EQ(third_again.mean_reward, third.mean_reward);
  EXPECT_EQ(weights(again), uninterrupted);  // bit for bit: Adam's moments came back too
}

TEST(TorchPpo, AnnealedLearningRateFallsLinearlyAndIsAdamsStep) {
  walkgen::PpoSettings s;
  s.epochs = 1;
  s.minibatch = 4;
  s.target_kl = 0.0;
  s.learning_rate = 1e-3;
  s.anneal_learning_rate = true;
  walkgen::TorchPpo ppo(4, 2, s);
  EXPECT_DOUBLE_EQ(ppo.learning_rate(), 1e-3);  // the run's length not known: constant
  ppo.set_total_updates(2);
  const walkgen::PpoRollout r = small_rollout(ppo);
  EXPECT_DOUBLE_EQ(ppo.learning_rate(), 1e-3);
  const std::vector<float> w0 = weights(ppo);
  (void)ppo.update(r);
  EXPECT_NE(weights(ppo), w0);
  EXPECT_DOUBLE_EQ(ppo.learning_rate(), 0.5e-3);  // 1 − 1/2
  (void)ppo.update(r);
  EXPECT_DOUBLE_EQ(ppo.learning_rate(), 0.0);
  const std::vector<float> w2 = weights(ppo);
  (void)ppo.update(r);  // past the run's end the step is 0: Adam leaves the weights
  EXPECT_EQ(weights(ppo), w2);
  EXPECT_THROW(ppo.set_total_updates(-1), walkgen::invalid_argument);
  s.anneal_learning_rate = false;
  walkgen::TorchPpo constant(4, 2, s);
  constant.set_total_updates(2);
  (void)constant.update(small_rollout(constant));
  EXPECT_DOUBLE_EQ(constant.learning_rate(), 1e-3);
}

TEST(PpoTrainer, EpochsAreWholeUpdates) {
  walkgen::PpoSettings s = walkgen::point_goal_ppo_settings();
  std::vector<walkgen::PointGoalEnv> envs(2);
  walkgen::TorchPpo ppo(4, 2, s);
  walkgen::PpoTrainer<walkgen::PointGoalEnv> trainer(ppo, envs, 100);
  EXPECT_EQ(trainer.updates_per_epoch(1), 1);
  EXPECT_EQ(trainer.updates_per_epoch(200), 1);
  EXPECT_EQ(trainer.updates_per_epoch(201), 2);
  const walkgen::PpoEpoch ep = trainer.run_epoch(201);
  EXPECT_EQ(ep.updates, 2);
  EXPECT_EQ(ep.steps, 400);
  EXPECT_THROW(trainer.set_epoch(-1), walkgen::invalid_argument);
}

TEST(TorchPpo, CheckpointErrorsNameTheFile) {
  walkgen::PpoSettings s;
  walkgen::TorchPpo ppo(4, 2, s);
  const std::string path = temp_path("checkpoint_errors.pt");
  ppo.save_checkpoint(path, {{"epoch", 1.0}});
  walkgen::TorchPpo other(5, 2, s);
  try {
    (void)other.resume_checkpoint(path);
    ADD_FAILURE() << "a checkpoint of other sizes was accepted";
  } catch (const walkgen::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("4 and 2"), std::string::npos) << e.what();
  }
  EXPECT_THROW((void)ppo.resume_checkpoint(path, {"no_such_counter"}), walkgen::invalid_argument);
  EXPECT_THROW((void)ppo.resume_checkpoint(temp_path("no_such_checkpoint.pt")),
               walkgen::invalid_argument);
  EXPECT_THROW(ppo.save_checkpoint(temp_path("no_such_folder/checkpoint.pt")),
               walkgen::invalid_argument);
  // the policy file is not a checkpoint
  ppo.save(temp_path("policy_not_checkpoint.pt"));
  EXPECT_THROW((void)ppo.resume_checkpoint(temp_path("policy_not_checkpoint.pt")),
               walkgen::invalid_argument);
}

}  // namespace
