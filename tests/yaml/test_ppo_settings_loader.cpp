// The YAML reader of PPO's settings and a run's schedule (walkgen/yaml/ppo_settings_loader.hpp):
// every key lands in its field, missing keys keep the defaults, and each kind of bad input gives
// an invalid_argument that names the key.
#include "walkgen/yaml/ppo_settings_loader.hpp"

#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <string>

namespace {

using walkgen::ppo_config_from_yaml;
using walkgen::PpoConfig;

// The message of the invalid_argument that reading `text` throws ("" when none is thrown).
std::string error_of(const std::string& text) {
  try {
    (void)ppo_config_from_yaml(text);
  } catch (const walkgen::invalid_argument& e) {
    return e.what();
  }
  return "";
}

TEST(PpoSettingsLoader, ReadsEveryKey) {
  const PpoConfig c = ppo_config_from_yaml(R"(
ppo:
  actor_hidden: [32, 16, 8]
  critic_hidden: [128]
  activation: relu
  initial_std: 0.3
  learning_rate: 0.0005
  gamma: 0.98
  lambda: 0.9
  clip: 0.1
  value_coef: 0.25
  entropy_coef: 0.01
  epochs: 4
  minibatch: 128
  max_grad_norm: 1.5
  target_kl: 0.05
  reward_scale: 0.01
  normalize_advantages: false
  anneal_learning_rate: true
run:
  epochs: 12
  steps: 4096
  envs: 16
  rollout_steps: 128
  threads: 4
  seed: 18446744073709551615
  validation_seed: 7
  evaluation_seed: 8
  checkpoint_every: 3
)");
  EXPECT_EQ(c.ppo.actor_hidden, (std::vector<std::int64_t>{32, 16, 8}));
  EXPECT_EQ(c.ppo.critic_hidden, (std::vector<std::int64_t>{128}));
  EXPECT_EQ(c.ppo.activation, walkgen::TorchActivation::relu);
  EXPECT_DOUBLE_EQ(c.ppo.initial_std, 0.3);
  EXPECT_DOUBLE_EQ(c.ppo.learning_rate, 0.0005);
  EXPECT_DOUBLE_EQ(c.ppo.gamma, 0.98);
  EXPECT_DOUBLE_EQ(c.ppo.lambda, 0.9);
  EXPECT_DOUBLE_EQ(c.ppo.clip, 0.1);
  EXPECT_DOUBLE_EQ(c.ppo.value_coef, 0.25);
  EXPECT_DOUBLE_EQ(c.ppo.entropy_coef, 0.01);
  EXPECT_EQ(c.ppo.epochs, 4);
  EXPECT_EQ(c.ppo.minibatch, 128);
  EXPECT_DOUBLE_EQ(c.ppo.max_grad_norm, 1.5);
  EXPECT_DOUBLE_EQ(c.ppo.target_kl, 0.05);
  EXPECT_DOUBLE_EQ(c.ppo.reward_scale, 0.01);
  EXPECT_FALSE(c.ppo.normalize_advantages);
  EXPECT_TRUE(c.ppo.anneal_learning_rate);
  EXPECT_EQ(c.run.epochs, 12);
  EXPECT_EQ(c.run.steps, 4096);
  EXPECT_EQ(c.run.envs, 16);
  EXPECT_EQ(c.run.rollout_steps, 128);
  EXPECT_EQ(c.run.threads, 4);
  EXPECT_EQ(c.run.seed, 18446744073709551615ull);
  EXPECT_EQ(c.run.validation_seed, 7u);
  EXPECT_EQ(c.run.evaluation_seed, 8u);
  EXPECT_EQ(c.run.checkpoint_every, 3);
}

TEST(PpoSettingsLoader, MissingKeysKeepTheDefaults) {
  PpoConfig defaults;
  defaults.ppo.learning_rate = 0.123;
  defaults.run.epochs = 77;
  const PpoConfig c = walkgen::ppo_config_from_yaml("run: {seed: 5}", defaults);
  EXPECT_DOUBLE_EQ(c.ppo.learning_rate, 0.123);
  EXPECT_EQ(c.run.epochs, 77);
  EXPECT_EQ(c.run.seed, 5u);
  const PpoConfig empty = walkgen::ppo_config_from_yaml("", defaults);
  EXPECT_EQ(empty.run.epochs, 77);
}

TEST(PpoSettingsLoader, BadInputNamesTheKey) {
  // an unknown key lists the known ones
  EXPECT_NE(error_of("ppo: {learning_rat: 0.1}").find("key 'ppo.learning_rat'"), std::string::npos);
  EXPECT_NE(error_of("ppo: {learning_rat: 0.1}").find("learning_rate"), std::string::npos);
  EXPECT_NE(error_of("trainer: {}").find("one of the keys ppo, run"), std::string::npos);
  // wrong types and ranges
  EXPECT_NE(error_of("ppo: {gamma: .nan}").find("'ppo.gamma'"), std::string::npos);
  EXPECT_NE(error_of("ppo: {gamma: 1.5}").find("PpoSettings.gamma"), std::string::npos);
  EXPECT_NE(error_of("ppo: {activation: sigmoid}").find("relu or tanh"), std::string::npos);
  EXPECT_NE(error_of("ppo: {actor_hidden: [64, 0]}").find("'ppo.actor_hidden[1]'"),
            std::string::npos);
  EXPECT_NE(error_of("ppo: {actor_hidden: []}").find("a list of layer sizes"), std::string::npos);
  EXPECT_NE(error_of("run: {epochs: -3}").find("'run.epochs'"), std::string::npos);
  EXPECT_NE(error_of("run: {epochs: 0x10}").find("whole number"), std::string::npos);
  EXPECT_NE(error_of("run: {seed: 18446744073709551616}").find("'run.seed'"), std::string::npos);
  EXPECT_NE(error_of("run: {envs: 2147483648}").find("'run.envs'"), std::string::npos);
  EXPECT_NE(error_of("run: {steps: 1000000000001}").find("'run.steps'"), std::string::npos);
  EXPECT_NE(error_of("run: {epochs: 3, epochs: 4}").find("each key once"), std::string::npos);
  EXPECT_NE(error_of("run: [1, 2]").find("a map of keys"), std::string::npos);
  EXPECT_NE(error_of("- 1\n- 2").find("a map with the keys ppo and run"), std::string::npos);
  EXPECT_NE(error_of("ppo: {gamma: [").find("well-formed YAML"), std::string::npos);
  // the line of the bad key
  EXPECT_NE(error_of("run:\n  seed: 1\n  threads: many\n").find(":3: key 'run.threads'"),
            std::string::npos);
}

TEST(PpoSettingsLoader, ReadsFilesAndNamesThem) {
  const std::string path = ::testing::TempDir() + "walkgen_ppo_config.yaml";
  {
    std::ofstream f(path);
    f << "run:\n  epochs: 9\n";
  }
  EXPECT_EQ(walkgen::load_ppo_config(path).run.epochs, 9);
  {
    std::ofstream f(path);
    f << "run:\n  epochs: nine\n";
  }
  try {
    (void)walkgen::load_ppo_config(path);
    ADD_FAILURE() << "no error for a bad value";
  } catch (const walkgen::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find(path + ":2: key 'run.epochs'"), std::string::npos)
        << e.what();
  }
  std::remove(path.c_str());
  EXPECT_THROW((void)walkgen::load_ppo_config(path), walkgen::invalid_argument);
}

}  // namespace
