#pragma once
/// @file
/// YAML adapter for PPO training: reads a file of two maps into walkgen::PpoSettings (`ppo`, the
/// hyper-parameters of thesis §4.2) and walkgen::PpoRunSettings (`run`, the schedule and seeds).
/// A missing key keeps its value from the defaults passed in (examples/ppo_train passes each
/// environment's thesis values); docs/learning.md lists every key with its default.
///
/// @code{.yaml}
///   ppo:
///     actor_hidden: [64, 64]     # layer sizes; critic_hidden likewise
///     activation: tanh           # or relu
///     learning_rate: 0.001
///     entropy_coef: 0.0          # also initial_std, gamma, lambda, clip, value_coef, epochs,
///                                # minibatch, max_grad_norm, target_kl, reward_scale,
///                                # normalize_advantages, anneal_learning_rate
///   run:
///     epochs: 30                 # also steps, envs, rollout_steps, threads, seed,
///     checkpoint_every: 1        # validation_seed, evaluation_seed
/// @endcode
/// Target walkgen::yaml (yaml-cpp); no libtorch needed.

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <climits>
#include <cstdint>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "walkgen/core/decimal.hpp"
#include "walkgen/core/exceptions.hpp"
#include "walkgen/learning/ppo_settings.hpp"
#include "walkgen/yaml/settings_loader.hpp"

namespace walkgen {

/// PPO's hyper-parameters and a run's schedule, as one file holds them.
struct PpoConfig {
  PpoSettings ppo;
  PpoRunSettings run;
};

namespace detail {

/// A whole number of decimal digits in [min, max] (no sign, no octal or hex).
inline unsigned long long yaml_whole(const YamlValue& v, unsigned long long min,
                                     unsigned long long max) {
  const std::string expected =
      "a whole number in [" + std::to_string(min) + ", " + std::to_string(max) + "]";
  const std::string text = v.as<std::string>(expected.c_str());
  unsigned long long value = 0;
  v.check(parse_decimal(text, max, &value, /*allow_plus=*/false) && value >= min, expected);
  return value;
}

/// Reads one map of `keys` (name → reader); an unknown key is an error that lists the known ones.
inline void read_yaml_map(
    const YamlValue& map,
    const std::vector<std::pair<const char*, std::function<void(const YamlValue&)>>>& keys) {
  map.check(map.node.IsMap(), "a map of keys");
  std::vector<std::string> seen;
  for (const auto& entry : map.node) {
    const std::string key = entry.first.as<std::string>();
    const YamlValue value = map.child(entry.second, (map.path.empty() ? "" : ".") + key);
    value.check(std::find(seen.begin(), seen.end(), key) == seen.end(), "each key once");
    seen.push_back(key);
    bool known = false;
    for (const auto& k : keys) {
      if (key != k.first) continue;
      k.second(value);
      known = true;
    }
    if (!known) {
      std::string names;
      for (const auto& k : keys) names += (names.empty() ? "" : ", ") + std::string(k.first);
      value.check(false, "one of the keys " + names);
    }
  }
}

inline PpoConfig ppo_config_from_node(const YAML::Node& root, const std::string& source,
                                      PpoConfig config) {
  const YamlValue doc{source, "", root};
  if (!root.IsNull()) {
    check_argument(root.IsMap(), source.c_str(), "a map with the keys ppo and run",
                   yaml_describe(root));
  }
  PpoSettings& p = config.ppo;
  PpoRunSettings& r = config.run;
  auto number = [](double& out) {
    return [&out](const YamlValue& v) { out = v.number<double>(); };
  };
  auto count = [](int& out, unsigned long long min) {
    return [&out, min](const YamlValue& v) { out = static_cast<int>(yaml_whole(v, min, INT_MAX)); };
  };
  auto seed = [](std::uint64_t& out) {
    return [&out](const YamlValue& v) { out = yaml_whole(v, 0, ULLONG_MAX); };
  };
  auto layers = [](std::vector<std::int64_t>& out) {
    return [&out](const YamlValue& v) {
      v.check(v.node.IsSequence() && v.node.size() >= 1, "a list of layer sizes, e.g. [64, 64]");
      out.clear();
      for (std::size_t i = 0; i < v.node.size(); ++i)
        out.push_back(static_cast<std::int64_t>(
            yaml_whole(v.child(v.node[i], "[" + std::to_string(i) + "]"), 1, 1u << 20)));
    };
  };
  const std::vector<std::pair<const char*, std::function<void(const YamlValue&)>>> ppo_keys = {
      {"actor_hidden", layers(p.actor_hidden)},
      {"critic_hidden", layers(p.critic_hidden)},
      {"activation",
       [&p](const YamlValue& v) {
         const std::string name = v.as<std::string>("relu or tanh");
         v.check(name == "relu" || name == "tanh", "relu or tanh");
         p.activation = name == "relu" ? TorchActivation::relu : TorchActivation::tanh;
       }},
      {"initial_std", number(p.initial_std)},
      {"learning_rate", number(p.learning_rate)},
      {"gamma", number(p.gamma)},
      {"lambda", number(p.lambda)},
      {"clip", number(p.clip)},
      {"value_coef", number(p.value_coef)},
      {"entropy_coef", number(p.entropy_coef)},
      {"epochs", count(p.epochs, 1)},
      {"minibatch", count(p.minibatch, 1)},
      {"max_grad_norm", number(p.max_grad_norm)},
      {"target_kl", number(p.target_kl)},
      {"reward_scale", number(p.reward_scale)},
      {"normalize_advantages",
       [&p](const YamlValue& v) { p.normalize_advantages = v.as<bool>("true or false"); }},
      {"anneal_learning_rate",
       [&p](const YamlValue& v) { p.anneal_learning_rate = v.as<bool>("true or false"); }},
  };
  const std::vector<std::pair<const char*, std::function<void(const YamlValue&)>>> run_keys = {
      {"epochs", count(r.epochs, 1)},
      {"steps",
       [&r](const YamlValue& v) {
         r.steps = static_cast<long>(yaml_whole(v, 1, 1000000000000ull));
       }},
      {"envs", count(r.envs, 1)},
      {"rollout_steps", count(r.rollout_steps, 1)},
      {"threads", count(r.threads, 1)},
      {"seed", seed(r.seed)},
      {"validation_seed", seed(r.validation_seed)},
      {"evaluation_seed", seed(r.evaluation_seed)},
      {"checkpoint_every", count(r.checkpoint_every, 0)},
  };
  if (root.IsMap()) {
    read_yaml_map(doc, {{"ppo", [&](const YamlValue& v) { read_yaml_map(v, ppo_keys); }},
                        {"run", [&](const YamlValue& v) { read_yaml_map(v, run_keys); }}});
  }
  try {
    validate(config.ppo);
    validate(config.run);
  } catch (const invalid_argument& e) {
    throw invalid_argument(source + ": " + e.what());
  }
  return config;
}

}  // namespace detail

/// PPO settings and a run's schedule from YAML text (keys: see the file comment); keys the text
/// does not set keep their value from `defaults`.
/// @throws walkgen::invalid_argument for malformed YAML, an unknown key (the message lists the
///   known ones), a value of the wrong type or out of range (naming the key and its line), or
///   settings that fail validate().
[[nodiscard]] inline PpoConfig ppo_config_from_yaml(const std::string& text,
                                                    const PpoConfig& defaults = {}) {
  const std::string source = "YAML text";
  return detail::ppo_config_from_node(detail::load_yaml(source, [&] { return YAML::Load(text); }),
                                      source, defaults);
}

/// As ppo_config_from_yaml(), from a file; `path` is named in messages.
/// @throws walkgen::invalid_argument also when the file cannot be read.
[[nodiscard]] inline PpoConfig load_ppo_config(const std::string& path,
                                               const PpoConfig& defaults = {}) {
  return detail::ppo_config_from_node(detail::load_yaml(path, [&] { return YAML::LoadFile(path); }),
                                      path, defaults);
}

}  // namespace walkgen
