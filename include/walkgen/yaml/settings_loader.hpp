#pragma once
/// @file
/// YAML adapter for the walking settings (docs/design.md conventions 10-12): reads the thesis's
/// configuration files (Table 6.1) into a WalkingSettings, mapping each flat key onto its part
/// (RobotGeometry, GeneratorSettings or InitialState; the table yaml_fields() below). Target
/// walkgen::yaml (yaml-cpp); the core never includes this header.
///
/// Accepted keys, at the top level or one level down under any section map
/// (`optimization: {n: 16, t: 0.1}`):
///   Table 6.1: t_step, security_margin [x, y], left_foot_convex_hull / right_foot_convex_hull
///   (flat [x0, y0, x1, y1, ...]), foot_width, foot_length, foot_distance, command_period,
///   n_still, t_ds, step_height, com_x / com_y / com_q [3], com_z, support_foot (left | right),
///   foot_x, foot_y, foot_q, gravity, obstacle (bool) with x_pos, y_pos, radius and an optional
///   margin, n, t, t_feedback, alpha, beta, gamma, cpu_time, nwsr;
///   walkgen's own: max_relative_yaw, max_relative_yaw_rate, sqp_iterations, sqp_corrections,
///   sqp_tolerance, step_velocity_weight, heading_weight, min_foot_separation, max_command [3],
///   footstep_regularization,
///   max_state_distance, max_com_speed, max_com_acceleration, the soft-constraint weights
///   soft_zmp_polygon, soft_footstep_feasibility, soft_relative_yaw, soft_foot_separation,
///   soft_obstacles, soft_capture_point, and obstacles: [{x, y, radius, margin}, ...].
/// Numbers must be finite (`.inf` and `.nan` are rejected); the integer keys (n, n_still, nwsr,
/// sqp_iterations, sqp_corrections) are decimal digits in [0, 2147483647] (`010` is 10, `0x10`
/// is an error). A missing key keeps its value from `defaults`. Obstacles: if the file has
/// `obstacle` or `obstacles`, it describes the whole set (the `obstacles` list, plus the thesis's
/// single obstacle when `obstacle: true`); otherwise the defaults' obstacles are kept. x_pos,
/// y_pos, radius and margin are checked but unused unless `obstacle: true`, as in the thesis.
///
/// Full reference with an example: docs/yaml.md.

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <climits>
#include <cmath>
#include <cstddef>
#include <string>
#include <utility>
#include <vector>

#include "walkgen/core/decimal.hpp"
#include "walkgen/core/exceptions.hpp"
#include "walkgen/core/foot.hpp"
#include "walkgen/mpc/settings.hpp"

namespace walkgen {

namespace detail {

/// One key of the document: its YAML value and where it was found, for messages.
struct YamlEntry {
  std::string key;   ///< the settings key, e.g. "nwsr"
  std::string path;  ///< where it sits, e.g. "optimization.nwsr"
  YAML::Node value;
};

/// "<source>:<line>: key '<path>'" (line 1-based, left out when yaml-cpp does not know it).
inline std::string yaml_where(const std::string& source, const YAML::Node& node,
                              const std::string& path) {
  const int line = node.Mark().line;
  return source + (line >= 0 ? ":" + std::to_string(line + 1) : std::string()) + ": key '" + path +
         "'";
}

/// What a node is, for the "got ..." part of a message.
inline std::string yaml_describe(const YAML::Node& node) {
  switch (node.Type()) {
    case YAML::NodeType::Scalar:
      return "'" + node.Scalar() + "'";
    case YAML::NodeType::Sequence:
      return "a list of " + std::to_string(node.size()) + " entries";
    case YAML::NodeType::Map:
      return "a map of " + std::to_string(node.size()) + " keys";
    default:
      return "an empty value";
  }
}

/// A value of the document and its key path, read into the settings on demand.
struct YamlValue {
  const std::string& source;  ///< the document's name: a path or "YAML text"
  std::string path;           ///< the key, e.g. "optimization.nwsr" or "com_x[1]"
  YAML::Node node;

  /// "<source>:<line>: key '<path>'", the start of every message about this value.
  std::string where() const { return yaml_where(source, node, path); }
  /// An entry of this value: `suffix` is "[i]" or ".name".
  YamlValue child(const YAML::Node& entry, const std::string& suffix) const {
    return {source, path + suffix, entry};
  }
  /// Throws "<where>: expected <what>, got <node>" unless `condition` holds.
  void check(bool condition, const std::string& what) const {
    check_argument(condition, where().c_str(), what, yaml_describe(node));
  }
  /// node.as<T>() for a scalar node, else the message above.
  template <typename T>
  T as(const char* what) const {
    try {
      if (node.IsScalar()) return node.as<T>();
    } catch (const YAML::Exception&) {
    }
    check(false, what);
    return T();  // not reached
  }

  /// A finite number: "a number" if it does not read as one, "a finite number" for .inf/.nan.
  template <typename Scalar>
  Scalar number() const {
    const Scalar value = as<Scalar>("a number");
    check(std::isfinite(value), "a finite number");
    return value;
  }

  template <typename Scalar>
  void read(Scalar& out) const {
    out = number<Scalar>();
  }
  /// A count: decimal digits (an optional '+') whose value fits an int. yaml-cpp's own
  /// conversion would read 010 as octal and 0x10 as hex, and a negative or too large value
  /// would fail with its exception or wrap.
  void read(int& out) const {
    const std::string expected = "an integer in [0, " + std::to_string(INT_MAX) + "]";
    const std::string text = as<std::string>(expected.c_str());
    unsigned long long value = 0;
    check(parse_decimal(text, INT_MAX, &value, /*allow_plus=*/true), expected);
    out = static_cast<int>(value);
  }
  void read(bool& out) const { out = as<bool>("true or false"); }
  void read(Foot& out) const {
    const std::string name = as<std::string>("left or right");
    check(name == "left" || name == "right", "left or right");
    out = name == "left" ? Foot::left : Foot::right;
  }
  /// [a, b, ...] with exactly Rows numbers.
  template <typename Scalar, int Rows>
  void read(Eigen::Matrix<Scalar, Rows, 1>& out) const {
    check(node.IsSequence() && node.size() == static_cast<std::size_t>(Rows),
          "a list of " + std::to_string(Rows) + " numbers");
    read_numbers(out.data());
  }
  /// A polygon as the thesis writes it: flat [x0, y0, x1, y1, ...], one row per vertex.
  template <typename Scalar>
  void read(Eigen::Matrix<Scalar, Eigen::Dynamic, 2>& out) const {
    check(node.IsSequence() && node.size() >= 6 && node.size() % 2 == 0,
          "a flat list of at least 3 vertices [x0, y0, x1, y1, ...] (an even count)");
    Eigen::Matrix<Scalar, 2, Eigen::Dynamic> xy(2, static_cast<Eigen::Index>(node.size() / 2));
    read_numbers(xy.data());  // column-major: x0, y0, x1, y1, ...
    out = xy.transpose();
  }
  template <typename Scalar>
  void read_numbers(Scalar* out) const {
    for (std::size_t i = 0; i < node.size(); ++i) {
      out[i] = child(node[i], "[" + std::to_string(i) + "]").template number<Scalar>();
    }
  }
};

/// The settings being read plus the thesis's single-obstacle keys, combined at the end.
template <typename Scalar>
struct YamlTarget {
  WalkingSettings<Scalar> s;
  bool has_obstacle = false, obstacle = false, has_obstacles = false;
  std::vector<std::pair<std::string, Scalar>> obstacle_keys;  // x_pos, y_pos, radius, margin
  std::vector<CircleObstacle<Scalar>> obstacles;
  std::string obstacle_where;

  void read_obstacle_key(const YamlValue& v, const char* key) {
    obstacle_keys.emplace_back(key, v.template number<Scalar>());
  }
  /// `obstacles: [{x, y, radius, margin}, ...]`, margin optional.
  void read_obstacles(const YamlValue& v) {
    const std::string form = "{x: .., y: .., radius: .., margin: ..}";
    v.check(v.node.IsSequence(), "a list of maps " + form);
    has_obstacles = true;
    for (std::size_t i = 0; i < v.node.size(); ++i) {
      const YamlValue item = v.child(v.node[i], "[" + std::to_string(i) + "]");
      item.check(item.node.IsMap(), "a map " + form);
      CircleObstacle<Scalar> o;
      bool has_x = false, has_y = false, has_radius = false;
      for (const auto& kv : item.node) {
        const std::string name = kv.first.Scalar();
        const YamlValue field = item.child(kv.second, "." + name);
        const std::string field_where = field.where();
        check_argument(name == "x" || name == "y" || name == "radius" || name == "margin",
                       field_where.c_str(), "x, y, radius or margin", "an unknown key",
                       "an obstacle is {x: .., y: .., radius: .., margin: ..}, margin optional");
        const Scalar value = field.template number<Scalar>();
        if (name == "x") {
          o.x = value, has_x = true;
        } else if (name == "y") {
          o.y = value, has_y = true;
        } else if (name == "radius") {
          o.radius = value, has_radius = true;
        } else {
          o.margin = value;
        }
      }
      item.check(has_x && has_y && has_radius, "the keys x, y and radius");
      obstacles.push_back(o);
    }
  }

  /// Sets s.obstacles from the obstacle keys, if the file had any (see the file comment).
  void finish_obstacles() {
    if (!has_obstacle && !has_obstacles) return;
    if (has_obstacle && obstacle) {
      CircleObstacle<Scalar> o;
      const char* required[] = {"x_pos", "y_pos", "radius"};
      Scalar* fields[] = {&o.x, &o.y, &o.radius};
      for (int i = 0; i < 3; ++i) {
        const auto it = std::find_if(obstacle_keys.begin(), obstacle_keys.end(),
                                     [&](const auto& kv) { return kv.first == required[i]; });
        check_argument(it != obstacle_keys.end(), obstacle_where.c_str(),
                       "x_pos, y_pos and radius with obstacle: true",
                       std::string("no ") + required[i]);
        *fields[i] = it->second;
      }
      for (const auto& kv : obstacle_keys) {
        if (kv.first == "margin") o.margin = kv.second;
      }
      obstacles.push_back(o);
    }
    s.obstacles = obstacles;
  }
};

/// Every key the loader accepts and where it goes; one table for the lookup and the reading.
template <typename Scalar>
struct YamlField {
  const char* key;
  void (*read)(const YamlValue&, YamlTarget<Scalar>&);
};

template <typename Scalar>
const std::vector<YamlField<Scalar>>& yaml_fields() {
  using V = const YamlValue&;
  using T = YamlTarget<Scalar>&;
  static const std::vector<YamlField<Scalar>> fields = {
      // Specifications.
      {"t_step", [](V v, T t) { v.read(t.s.generator().t_step); }},
      {"security_margin", [](V v, T t) { v.read(t.s.geometry().security_margin); }},
      {"left_foot_convex_hull", [](V v, T t) { v.read(t.s.geometry().left_foot_convex_hull); }},
      {"right_foot_convex_hull", [](V v, T t) { v.read(t.s.geometry().right_foot_convex_hull); }},
      {"foot_width", [](V v, T t) { v.read(t.s.geometry().foot_width); }},
      {"foot_length", [](V v, T t) { v.read(t.s.geometry().foot_length); }},
      {"foot_distance", [](V v, T t) { v.read(t.s.geometry().foot_distance); }},
      // Interpolation.
      {"command_period", [](V v, T t) { v.read(t.s.generator().command_period); }},
      {"n_still", [](V v, T t) { v.read(t.s.generator().n_still); }},
      {"t_ds", [](V v, T t) { v.read(t.s.generator().t_ds); }},
      {"step_height", [](V v, T t) { v.read(t.s.geometry().step_height); }},
      // Initial values.
      {"com_x", [](V v, T t) { v.read(t.s.initial_state().com_x); }},
      {"com_y", [](V v, T t) { v.read(t.s.initial_state().com_y); }},
      {"com_z", [](V v, T t) { v.read(t.s.geometry().com_z); }},
      {"com_q", [](V v, T t) { v.read(t.s.initial_state().com_q); }},
      {"support_foot", [](V v, T t) { v.read(t.s.initial_state().support_foot); }},
      {"foot_x", [](V v, T t) { v.read(t.s.initial_state().foot_x); }},
      {"foot_y", [](V v, T t) { v.read(t.s.initial_state().foot_y); }},
      {"foot_q", [](V v, T t) { v.read(t.s.initial_state().foot_q); }},
      // Environment.
      {"gravity", [](V v, T t) { v.read(t.s.geometry().gravity); }},
      // Obstacle (Table 6.1) and walkgen's obstacle list.
      {"obstacle",
       [](V v, T t) {
         v.read(t.obstacle);
         t.has_obstacle = true;
         t.obstacle_where = v.where();
       }},
      {"x_pos", [](V v, T t) { t.read_obstacle_key(v, "x_pos"); }},
      {"y_pos", [](V v, T t) { t.read_obstacle_key(v, "y_pos"); }},
      {"radius", [](V v, T t) { t.read_obstacle_key(v, "radius"); }},
      {"margin", [](V v, T t) { t.read_obstacle_key(v, "margin"); }},
      {"obstacles", [](V v, T t) { t.read_obstacles(v); }},
      // Optimization.
      {"n", [](V v, T t) { v.read(t.s.generator().n); }},
      {"t", [](V v, T t) { v.read(t.s.generator().t); }},
      {"t_feedback", [](V v, T t) { v.read(t.s.generator().t_feedback); }},
      {"alpha", [](V v, T t) { v.read(t.s.generator().alpha); }},
      {"beta", [](V v, T t) { v.read(t.s.generator().beta); }},
      {"gamma", [](V v, T t) { v.read(t.s.generator().gamma); }},
      {"cpu_time", [](V v, T t) { v.read(t.s.generator().cpu_time); }},
      {"nwsr", [](V v, T t) { v.read(t.s.generator().nwsr); }},
      // walkgen's own.
      {"max_relative_yaw", [](V v, T t) { v.read(t.s.geometry().max_relative_yaw); }},
      {"max_relative_yaw_rate", [](V v, T t) { v.read(t.s.geometry().max_relative_yaw_rate); }},
      {"sqp_iterations", [](V v, T t) { v.read(t.s.generator().sqp_iterations); }},
      {"sqp_corrections", [](V v, T t) { v.read(t.s.generator().sqp_corrections); }},
      {"sqp_tolerance", [](V v, T t) { v.read(t.s.generator().sqp_tolerance); }},
      {"step_velocity_weight", [](V v, T t) { v.read(t.s.generator().step_velocity_weight); }},
      {"heading_weight", [](V v, T t) { v.read(t.s.generator().heading_weight); }},
      {"min_foot_separation", [](V v, T t) { v.read(t.s.geometry().min_foot_separation); }},
      {"max_command", [](V v, T t) { v.read(t.s.generator().max_command); }},
      {"footstep_regularization",
       [](V v, T t) { v.read(t.s.generator().footstep_regularization); }},
      {"max_state_distance", [](V v, T t) { v.read(t.s.generator().max_state_distance); }},
      {"max_com_speed", [](V v, T t) { v.read(t.s.generator().max_com_speed); }},
      {"max_com_acceleration", [](V v, T t) { v.read(t.s.generator().max_com_acceleration); }},
      // Soft constraints (GeneratorSettings::soft): flat, as `obstacles` is taken.
      {"soft_zmp_polygon", [](V v, T t) { v.read(t.s.generator().soft.zmp_polygon); }},
      {"soft_footstep_feasibility",
       [](V v, T t) { v.read(t.s.generator().soft.footstep_feasibility); }},
      {"soft_relative_yaw", [](V v, T t) { v.read(t.s.generator().soft.relative_yaw); }},
      {"soft_foot_separation", [](V v, T t) { v.read(t.s.generator().soft.foot_separation); }},
      {"soft_obstacles", [](V v, T t) { v.read(t.s.generator().soft.obstacles); }},
      {"soft_capture_point", [](V v, T t) { v.read(t.s.generator().soft.capture_point); }},
  };
  return fields;
}

template <typename Scalar>
const YamlField<Scalar>* find_yaml_field(const std::string& key) {
  for (const auto& f : yaml_fields<Scalar>()) {
    if (key == f.key) return &f;
  }
  return nullptr;
}

/// Levenshtein distance, for "did you mean ...?" on a misspelt key.
inline std::size_t edit_distance(const std::string& a, const std::string& b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] != b[j - 1] ? 1 : 0)});
      diagonal = up;
    }
  }
  return row[b.size()];
}

template <typename Scalar>
[[noreturn]] void throw_unknown_yaml_key(const std::string& where, const std::string& key) {
  std::string closest, known;
  std::size_t best = key.size() / 3 + 2;  // suggest only close spellings
  for (const auto& f : yaml_fields<Scalar>()) {
    known += (known.empty() ? "" : ", ") + std::string(f.key);
    const std::size_t d = edit_distance(key, f.key);
    if (d < best) best = d, closest = f.key;
  }
  const std::string hint = (closest.empty() ? "" : "did you mean '" + closest + "'? ") +
                           std::string("known keys: ") + known +
                           "; a top-level map is read as a section of these keys";
  throw invalid_argument(
      expected_got(where.c_str(), "a walking-settings key", "an unknown key", hint.c_str()));
}

/// The keys of the document: top-level keys, and the keys of top-level maps (sections) whose
/// own name is not a key. Throws on unknown and repeated keys.
template <typename Scalar>
std::vector<YamlEntry> yaml_entries(const YAML::Node& root, const std::string& source) {
  std::vector<YamlEntry> entries;
  if (root.IsNull()) return entries;  // empty document: all defaults
  check_argument(root.IsMap(), source.c_str(), "a map of settings keys at the top level",
                 yaml_describe(root));
  const auto name_of = [&](const YAML::Node& key, const std::string& prefix) {
    return YamlValue{source, prefix + yaml_describe(key), key}.as<std::string>("a key name");
  };
  const auto add = [&](const std::string& key, const std::string& path, const YAML::Node& value) {
    for (const auto& e : entries) {
      if (e.key == key) {
        const std::string where = yaml_where(source, value, path);
        throw invalid_argument(expected_got(where.c_str(), "each key once",
                                            "it again after '" + e.path + "'",
                                            "remove one of the two"));
      }
    }
    entries.push_back({key, path, value});
  };
  for (const auto& kv : root) {
    const std::string key = name_of(kv.first, "");
    if (find_yaml_field<Scalar>(key) != nullptr) {
      add(key, key, kv.second);
    } else if (kv.second.IsMap()) {  // a section: its keys are settings keys
      for (const auto& inner : kv.second) {
        const std::string inner_key = name_of(inner.first, key + ".");
        const std::string path = key + "." + inner_key;
        if (find_yaml_field<Scalar>(inner_key) == nullptr) {
          throw_unknown_yaml_key<Scalar>(yaml_where(source, inner.first, path), inner_key);
        }
        add(inner_key, path, inner.second);
      }
    } else {
      throw_unknown_yaml_key<Scalar>(yaml_where(source, kv.first, key), key);
    }
  }
  return entries;
}

/// Reads `root` over `defaults` and validates; `source` names the document in messages.
template <typename Scalar>
WalkingSettings<Scalar> walking_settings_from_node(const YAML::Node& root,
                                                   const std::string& source,
                                                   const WalkingSettings<Scalar>& defaults) {
  YamlTarget<Scalar> target;
  target.s = defaults;
  std::vector<YamlEntry> entries;
  try {
    entries = yaml_entries<Scalar>(root, source);
  } catch (const YAML::Exception& e) {  // a yaml-cpp error the checks above did not foresee
    throw invalid_argument(expected_got(source.c_str(), "a map of settings keys", e.what()));
  }
  for (const YamlEntry& e : entries) {
    try {
      find_yaml_field<Scalar>(e.key)->read(YamlValue{source, e.path, e.value}, target);
    } catch (const YAML::Exception& error) {  // as above: the key and yaml-cpp's words
      const std::string where = yaml_where(source, e.value, e.path);
      throw invalid_argument(expected_got(where.c_str(), "a readable value", error.what()));
    }
  }
  target.finish_obstacles();
  try {
    validate(target.s);
  } catch (const invalid_argument& e) {
    throw invalid_argument(source + ": " + e.what());
  }
  return target.s;
}

/// Runs a yaml-cpp load, turning its exceptions into invalid_argument naming `source`.
template <typename Load>
YAML::Node load_yaml(const std::string& source, Load&& load) {
  try {
    return load();
  } catch (const YAML::BadFile& e) {
    throw invalid_argument(expected_got(source.c_str(), "a readable YAML file", e.what(),
                                        "check the path; a relative one is relative to the "
                                        "working directory"));
  } catch (const YAML::Exception& e) {
    throw invalid_argument(expected_got(source.c_str(), "well-formed YAML", e.what()));
  }
}

}  // namespace detail

/// Walking settings from YAML text with the thesis's key names (Table 6.1; see the file comment
/// and docs/yaml.md). Keys the text does not set keep their value from `defaults`.
/// @throws walkgen::invalid_argument for malformed YAML, an unknown or repeated key, a value of
/// the wrong type or size (naming the key, with expected and got), or settings that fail
/// validate().
template <typename Scalar = double>
[[nodiscard]] WalkingSettings<Scalar> walking_settings_from_yaml(
    const std::string& text, const WalkingSettings<Scalar>& defaults = hrp2_settings<Scalar>()) {
  const std::string source = "YAML text";
  return detail::walking_settings_from_node(
      detail::load_yaml(source, [&] { return YAML::Load(text); }), source, defaults);
}

/// Walking settings from a YAML file; as walking_settings_from_yaml(), with `path` in messages.
/// @throws walkgen::invalid_argument also when the file cannot be read.
template <typename Scalar = double>
[[nodiscard]] WalkingSettings<Scalar> load_walking_settings(
    const std::string& path, const WalkingSettings<Scalar>& defaults = hrp2_settings<Scalar>()) {
  return detail::walking_settings_from_node(
      detail::load_yaml(path, [&] { return YAML::LoadFile(path); }), path, defaults);
}

}  // namespace walkgen
