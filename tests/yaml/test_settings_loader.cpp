// YAML settings adapter: the shipped configs equal the presets field by field, the thesis's own
// listing (Table 6.1) loads unchanged, sections are accepted, and every kind of bad input throws
// walkgen::invalid_argument naming the key.

#include "walkgen/yaml/settings_loader.hpp"

#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

namespace {

using Settings = walkgen::WalkingSettings<double>;

const std::string kConfigs = std::string(WALKGEN_SOURCE_DIR) + "/configs/";

template <typename Matrix>
void expect_same_matrix(const Matrix& a, const Matrix& b, const char* name) {
  ASSERT_EQ(a.rows(), b.rows()) << name;
  ASSERT_EQ(a.cols(), b.cols()) << name;
  for (Eigen::Index i = 0; i < a.size(); ++i) {
    EXPECT_DOUBLE_EQ(a.data()[i], b.data()[i]) << name << " entry " << i;
  }
}

// A field of WalkingSettings (or of an obstacle) with its name, for field-by-field comparison.
template <typename Owner, typename T>
struct Field {
  const char* name;
  T Owner::*member;
};
using Vector3 = Settings::Vector3;
using Obstacle = walkgen::CircleObstacle<double>;

// Every field of WalkingSettings, one by one.
void expect_same_settings(const Settings& a, const Settings& b) {
  const Field<Settings, double> numbers[] = {
      {"t_step", &Settings::t_step},
      {"foot_width", &Settings::foot_width},
      {"foot_length", &Settings::foot_length},
      {"foot_distance", &Settings::foot_distance},
      {"command_period", &Settings::command_period},
      {"t_ds", &Settings::t_ds},
      {"step_height", &Settings::step_height},
      {"com_z", &Settings::com_z},
      {"foot_x", &Settings::foot_x},
      {"foot_y", &Settings::foot_y},
      {"foot_q", &Settings::foot_q},
      {"gravity", &Settings::gravity},
      {"t", &Settings::t},
      {"t_feedback", &Settings::t_feedback},
      {"alpha", &Settings::alpha},
      {"beta", &Settings::beta},
      {"gamma", &Settings::gamma},
      {"cpu_time", &Settings::cpu_time},
      {"max_relative_yaw", &Settings::max_relative_yaw},
      {"max_relative_yaw_rate", &Settings::max_relative_yaw_rate},
      {"footstep_regularization", &Settings::footstep_regularization},
      {"sqp_tolerance", &Settings::sqp_tolerance},
      {"max_state_distance", &Settings::max_state_distance},
      {"max_com_speed", &Settings::max_com_speed},
      {"max_com_acceleration", &Settings::max_com_acceleration},
      {"step_velocity_weight", &Settings::step_velocity_weight}};
  for (const auto& f : numbers) EXPECT_DOUBLE_EQ(a.*f.member, b.*f.member) << f.name;
  using Soft = walkgen::SoftConstraintWeights<double>;
  const Field<Soft, double> soft[] = {{"soft_zmp_polygon", &Soft::zmp_polygon},
                                      {"soft_footstep_feasibility", &Soft::footstep_feasibility},
                                      {"soft_relative_yaw", &Soft::relative_yaw},
                                      {"soft_foot_separation", &Soft::foot_separation},
                                      {"soft_obstacles", &Soft::obstacles},
                                      {"soft_capture_point", &Soft::capture_point}};
  for (const auto& f : soft) EXPECT_DOUBLE_EQ(a.soft.*f.member, b.soft.*f.member) << f.name;
  const Field<Settings, int> integers[] = {{"n_still", &Settings::n_still},
                                           {"n", &Settings::n},
                                           {"nwsr", &Settings::nwsr},
                                           {"sqp_iterations", &Settings::sqp_iterations},
                                           {"sqp_corrections", &Settings::sqp_corrections}};
  for (const auto& f : integers) EXPECT_EQ(a.*f.member, b.*f.member) << f.name;
  const Field<Settings, Vector3> vectors[] = {{"com_x", &Settings::com_x},
                                              {"com_y", &Settings::com_y},
                                              {"com_q", &Settings::com_q},
                                              {"max_command", &Settings::max_command}};
  for (const auto& f : vectors) expect_same_matrix(a.*f.member, b.*f.member, f.name);
  expect_same_matrix(a.security_margin, b.security_margin, "security_margin");
  expect_same_matrix(a.left_foot_convex_hull, b.left_foot_convex_hull, "left_foot_convex_hull");
  expect_same_matrix(a.right_foot_convex_hull, b.right_foot_convex_hull, "right_foot_convex_hull");
  EXPECT_EQ(a.support_foot, b.support_foot);
  ASSERT_EQ(a.obstacles.size(), b.obstacles.size());
  const Field<Obstacle, double> obstacle_fields[] = {{"x", &Obstacle::x},
                                                     {"y", &Obstacle::y},
                                                     {"radius", &Obstacle::radius},
                                                     {"margin", &Obstacle::margin}};
  for (std::size_t i = 0; i < a.obstacles.size(); ++i) {
    for (const auto& f : obstacle_fields) {
      EXPECT_DOUBLE_EQ(a.obstacles[i].*f.member, b.obstacles[i].*f.member)
          << "obstacles[" << i << "]." << f.name;
    }
  }
}

// The message of the walkgen::invalid_argument that `load` throws ("" if none or another type).
template <typename Load>
std::string error_of(Load&& load) {
  try {
    load();
  } catch (const walkgen::invalid_argument& e) {
    return e.what();
  } catch (...) {
    return "<an exception other than walkgen::invalid_argument>";
  }
  return "";
}

std::string error_of_text(const std::string& text) {
  return error_of([&] { return walkgen::walking_settings_from_yaml(text); });
}

// Writes `text` to a scratch file and returns its path.
std::string write_temp(const std::string& name, const std::string& text) {
  const std::string path = testing::TempDir() + name;
  std::ofstream(path) << text;
  return path;
}

// The Heicub preset as a file with only Table 6.1's keys loads it over the HRP-2 defaults:
// walkgen's own keys keep HRP-2's values.
Settings heicub_table_keys() {
  Settings s = walkgen::heicub_settings();
  s.step_velocity_weight = walkgen::hrp2_settings().step_velocity_weight;
  s.max_command = walkgen::hrp2_settings().max_command;
  return s;
}

TEST(YamlSettings, ConfigFilesEqualThePresets) {
  // Each file is read over the other robot's preset, so it must set every Table 6.1 key itself.
  expect_same_settings(
      walkgen::load_walking_settings(kConfigs + "hrp2.yaml", walkgen::heicub_settings()),
      walkgen::hrp2_settings());
  expect_same_settings(walkgen::load_walking_settings(kConfigs + "heicub.yaml"),
                       walkgen::heicub_settings());
}

TEST(YamlSettings, MissingKeysKeepTheDefaults) {
  expect_same_settings(walkgen::walking_settings_from_yaml(""), walkgen::hrp2_settings());
  expect_same_settings(
      walkgen::walking_settings_from_yaml("# nothing but a comment\n", walkgen::heicub_settings()),
      walkgen::heicub_settings());

  Settings expected = walkgen::hrp2_settings();
  expected.step_height = 0.07;
  expected.support_foot = walkgen::Foot::right;
  expected.max_relative_yaw = 0.2;
  expected.max_relative_yaw_rate = 1.5;
  expected.sqp_iterations = 3;
  expected.max_command << 0.3, 0.1, 0.2;
  expected.footstep_regularization = 1e-8;
  expected.sqp_corrections = 0;
  expected.sqp_tolerance = 2e-3;
  expected.max_state_distance = 1.5;
  expected.max_com_speed = 3;
  expected.max_com_acceleration = 40;
  expected.step_velocity_weight = 5;
  expected.soft = {1, 2, 3, 4, 5, 6};
  expect_same_settings(walkgen::walking_settings_from_yaml(
                           "soft_zmp_polygon: 1\nsoft_footstep_feasibility: 2\n"
                           "soft_relative_yaw: 3\nsoft_foot_separation: 4\nsoft_obstacles: 5\n"
                           "soft_capture_point: 6\n"
                           "step_height: 0.07\nsupport_foot: right\nmax_relative_yaw: 0.2\n"
                           "max_relative_yaw_rate: 1.5\nsqp_iterations: 3\n"
                           "max_command: [0.3, 0.1, 0.2]\nfootstep_regularization: 1e-8\n"
                           "sqp_corrections: 0\nsqp_tolerance: 2e-3\nstep_velocity_weight: 5\n"
                           "max_state_distance: 1.5\nmax_com_speed: 3\nmax_com_acceleration: 40\n"),
                       expected);
}

TEST(YamlSettings, KeysMayBeGroupedInSections) {
  const std::string text = R"(
gravity: 9.81  # top level and sections mix
specifications:
  t_step: 3.2
  security_margin: [0.02, 0.02]
  left_foot_convex_hull: [-0.11, 0.14, -0.10, 0.16, 0.00, 0.17, 0.10, 0.16, 0.11, 0.14]
  right_foot_convex_hull: [-0.11, -0.14, -0.10, -0.16, 0.00, -0.17, 0.10, -0.16, 0.11, -0.14]
  foot_width: 0.1
  foot_length: 0.2
  foot_distance: 0.14
interpolation: {command_period: 0.01, n_still: 0, t_ds: 1.6, step_height: 0.03}
initial_values:
  com_y: [0.05, 0.0, 0.0]
  com_z: 0.45
  foot_y: 0.07
optimization:
  n: 16
  t: 0.4
  t_feedback: 0.4
  beta: 1e2
  gamma: 1e-2
)";
  expect_same_settings(walkgen::walking_settings_from_yaml(text), heicub_table_keys());
}

// Table 6.1 as the thesis's configs.yaml writes it: flat, with comments, tabs in the hull lists
// and qpOASES's cpu_time/nwsr. The table elides the hulls after the first vertex; these are the
// Heicub file's.
TEST(YamlSettings, ThesisHeicubListingLoadsUnchanged) {
  const std::string text =
      "# Specifications.\n"
      "t_step: 3.2\n"
      "security_margin: [0.02, 0.02]\n"
      "left_foot_convex_hull: [-0.11, 0.14,\n"
      "\t\t        -0.10, 0.16, \n"
      "\t\t         0.00, 0.17, \n"
      "\t\t         0.10, 0.16, \n"
      "\t\t         0.11, 0.14]\n"
      "right_foot_convex_hull: [-0.11, -0.14,\n"
      "\t\t         -0.10, -0.16, \n"
      "\t\t          0.00, -0.17, \n"
      "\t\t          0.10, -0.16, \n"
      "\t\t          0.11, -0.14]\n"
      "foot_width: 0.1\n"
      "foot_length: 0.2\n"
      "foot_distance: 0.14\n"
      "\n"
      "# Interpolation.\n"
      "command_period: 0.01\n"
      "n_still: 0\n"
      "t_ds: 1.6\n"
      "step_height: 0.03\n"
      "\n"
      "# Initial values.\n"
      "com_x: [0.0, 0.0, 0.0]\n"
      "com_y: [0.05, 0.0, 0.0]\n"
      "com_z: 0.45\n"
      "com_q: [0.0, 0.0, 0.0]\n"
      "support_foot: left\n"
      "foot_x: 0.0\n"
      "foot_y: 0.07\n"
      "foot_q: 0.0\n"
      "\n"
      "# Environment.\n"
      "gravity: 9.81\n"
      "\n"
      "# Obstacle.\n"
      "obstacle: false\n"
      "x_pos: 10\n"
      "y_pos: 10\n"
      "radius: 0.5\n"
      "\n"
      "# Optimization.\n"
      "n: 16\n"
      "t: 0.4\t\n"
      "t_feedback: 0.4\n"
      "alpha: 1\n"
      "beta: 1e2\n"
      "gamma: 1e-2\n"
      "cpu_time: 0.1\n"
      "nwsr: 1000\n";
  Settings expected = heicub_table_keys();
  expected.cpu_time = 0.1;
  expected.nwsr = 1000;
  const std::string path = write_temp("walkgen_thesis_heicub.yaml", text);
  expect_same_settings(walkgen::load_walking_settings(path), expected);
  std::remove(path.c_str());
}

TEST(YamlSettings, ObstacleKeys) {
  Settings with_obstacle = walkgen::hrp2_settings();
  with_obstacle.obstacles.push_back({5.0, 5.0, 0.3, 0.0});

  // Table 6.1's single obstacle; margin is optional.
  auto s = walkgen::walking_settings_from_yaml(
      "obstacle: true\nx_pos: 1.6\ny_pos: 1.0\nradius: 1.0\nmargin: 0.2\n", with_obstacle);
  ASSERT_EQ(s.obstacles.size(), 1u);
  EXPECT_DOUBLE_EQ(s.obstacles[0].x, 1.6);
  EXPECT_DOUBLE_EQ(s.obstacles[0].y, 1.0);
  EXPECT_DOUBLE_EQ(s.obstacles[0].radius, 1.0);
  EXPECT_DOUBLE_EQ(s.obstacles[0].margin, 0.2);
  s = walkgen::walking_settings_from_yaml("obstacle: true\nx_pos: 1\ny_pos: 2\nradius: 0.5\n");
  ASSERT_EQ(s.obstacles.size(), 1u);
  EXPECT_DOUBLE_EQ(s.obstacles[0].margin, 0.0);

  // obstacle: false says there is none; x_pos, y_pos, radius are then unused.
  s = walkgen::walking_settings_from_yaml("obstacle: false\nx_pos: 10\ny_pos: 10\nradius: 0.5\n",
                                          with_obstacle);
  EXPECT_TRUE(s.obstacles.empty());
  // Without obstacle keys the defaults' obstacles stay.
  s = walkgen::walking_settings_from_yaml("n: 16\n", with_obstacle);
  expect_same_settings(s, with_obstacle);

  // walkgen's list, plus the thesis's obstacle.
  s = walkgen::walking_settings_from_yaml(R"(
obstacles:
  - {x: 1.0, y: 0.5, radius: 0.2, margin: 0.1}
  - {x: 3.0, y: -0.5, radius: 0.4}
obstacle: true
x_pos: 2
y_pos: 0
radius: 0.3
)");
  ASSERT_EQ(s.obstacles.size(), 3u);
  EXPECT_DOUBLE_EQ(s.obstacles[0].margin, 0.1);
  EXPECT_DOUBLE_EQ(s.obstacles[1].x, 3.0);
  EXPECT_DOUBLE_EQ(s.obstacles[1].y, -0.5);
  EXPECT_DOUBLE_EQ(s.obstacles[1].margin, 0.0);
  EXPECT_DOUBLE_EQ(s.obstacles[2].x, 2.0);
  EXPECT_DOUBLE_EQ(s.obstacles[2].radius, 0.3);
}

struct BadCase {
  std::string text;
  std::vector<std::string> in_message;  // the key first, then expected/got fragments
};

TEST(YamlSettings, BadValuesNameTheKeyWithExpectedAndGot) {
  const std::vector<BadCase> cases = {
      {"security_margin: [0.09, 0.05, 0.01]\n",
       {"key 'security_margin'", "a list of 2 numbers", "a list of 3 entries"}},
      {"security_margin: 0.05\n", {"key 'security_margin'", "a list of 2 numbers", "'0.05'"}},
      {"t_step: fast\n", {"key 't_step'", "a number", "'fast'"}},
      {"t_step:\n", {"key 't_step'", "a number", "an empty value"}},
      {"foot_width: [0.1]\n", {"key 'foot_width'", "a number", "a list of 1 entries"}},
      {"left_foot_convex_hull: [-0.28, 0.2, -0.2, 0.3, 0.0, 0.4, 0.2]\n",
       {"key 'left_foot_convex_hull'", "an even count", "a list of 7 entries"}},
      {"right_foot_convex_hull: [0.1, 0.2, 0.3, 0.4]\n",
       {"key 'right_foot_convex_hull'", "at least 3 vertices", "a list of 4 entries"}},
      {"right_foot_convex_hull: [-0.28, -0.2, -0.2, -0.3, 0.0, x]\n",
       {"key 'right_foot_convex_hull[5]'", "a number", "'x'"}},
      {"com_x: [0.0, zero, 0.0]\n", {"key 'com_x[1]'", "a number", "'zero'"}},
      {"com_q: 0\n", {"key 'com_q'", "a list of 3 numbers", "'0'"}},
      {"n: 16.5\n", {"key 'n'", "an integer", "'16.5'"}},
      {"nwsr: [100]\n", {"key 'nwsr'", "an integer", "a list of 1 entries"}},
      {"support_foot: middle\n", {"key 'support_foot'", "left or right", "'middle'"}},
      {"obstacle: maybe\n", {"key 'obstacle'", "true or false", "'maybe'"}},
      {"radius: wide\n", {"key 'radius'", "a number", "'wide'"}},
      {"obstacle: true\nx_pos: 1.0\nradius: 0.5\n", {"key 'obstacle'", "y_pos", "no y_pos"}},
      {"obstacles: {x: 1}\n", {"key 'obstacles'", "a list of maps", "a map of 1 keys"}},
      {"obstacles: [{x: 1, y: 1}]\n", {"key 'obstacles[0]'", "x, y and radius"}},
      {"obstacles: [{x: 1, y: 1, radius: 0.5, raduis: 1}]\n",
       {"key 'obstacles[0].raduis'", "x, y, radius or margin", "an unknown key"}},
      {"obstacles: [{x: 1, y: one, radius: 0.5}]\n", {"key 'obstacles[0].y'", "a number", "'one'"}},
      {"optimization:\n  n: sixteen\n", {"key 'optimization.n'", "an integer", "'sixteen'"}},
      {"t_step: 0.8\nspecifications:\n  t_step: 1.6\n",
       {"key 'specifications.t_step'", "each key once", "'t_step'"}},
      {"gamma: 1e-5\ngamma: 1e-4\n", {"key 'gamma'", "each key once"}},
      {"[1, 2, 3]\n", {"YAML text", "a map of settings keys", "a list of 3 entries"}},
      // Well-typed but invalid values: validate()'s message, with where the settings came from.
      {"t_step: 0.75\n", {"YAML text: WalkingSettings.t_step", "a whole multiple of t"}},
      {"com_z: -0.8\n", {"YAML text: WalkingSettings.com_z", "expected"}},
      {"obstacles: [{x: 1, y: 1, radius: -0.5}]\n", {"WalkingSettings.obstacles[].radius"}},
  };
  for (const auto& c : cases) {
    const std::string what = error_of_text(c.text);
    ASSERT_FALSE(what.empty()) << "no walkgen::invalid_argument for:\n" << c.text;
    for (const auto& fragment : c.in_message) {
      EXPECT_NE(what.find(fragment), std::string::npos)
          << "'" << fragment << "' is not in the message for:\n"
          << c.text << "message: " << what;
    }
    EXPECT_NE(what.find("expected"), std::string::npos) << what;
  }
}

TEST(YamlSettings, MessagesGiveTheLine) {
  EXPECT_NE(error_of_text("n: 16\nt: 0.1\nt_step: slow\n").find("YAML text:3: key 't_step'"),
            std::string::npos);
  const std::string path = write_temp("walkgen_bad_value.yaml", "n: 16\ncom_z: high\n");
  EXPECT_NE(error_of([&] {
              return walkgen::load_walking_settings(path);
            }).find(path + ":2: key 'com_z': expected a number, got 'high'"),
            std::string::npos);
  std::remove(path.c_str());
}

TEST(YamlSettings, UnknownKeysAreRejectedWithAHint) {
  // The thesis's first configs.yaml had a leftover "delta": a typo must never be ignored.
  std::string what = error_of_text("alpha: 1\ndelta: 1e-5\n");
  EXPECT_NE(what.find("YAML text:2: key 'delta'"), std::string::npos) << what;
  EXPECT_NE(what.find("unknown"), std::string::npos) << what;
  EXPECT_NE(what.find("did you mean 'beta'?"), std::string::npos) << what;
  EXPECT_NE(what.find("known keys: t_step, security_margin"), std::string::npos) << what;

  what = error_of_text("optimization:\n  nwrs: 100\n");
  EXPECT_NE(what.find("key 'optimization.nwrs'"), std::string::npos) << what;
  EXPECT_NE(what.find("did you mean 'nwsr'?"), std::string::npos) << what;

  what = error_of_text("security_margins: [0.09, 0.05]\n");
  EXPECT_NE(what.find("key 'security_margins'"), std::string::npos) << what;
  EXPECT_NE(what.find("did you mean 'security_margin'?"), std::string::npos) << what;

  what = error_of_text("urdf_path: robot.urdf\n");  // no close key: no suggestion
  EXPECT_NE(what.find("key 'urdf_path'"), std::string::npos) << what;
  EXPECT_EQ(what.find("did you mean"), std::string::npos) << what;

  // Sections nest one level only.
  what = error_of_text("robot:\n  feet:\n    foot_width: 0.1\n");
  EXPECT_NE(what.find("key 'robot.feet'"), std::string::npos) << what;
}

TEST(YamlSettings, MalformedYamlAndMissingFilesNameThePath) {
  std::string what = error_of_text("t_step: [0.8\n");
  EXPECT_NE(what.find("YAML text: expected well-formed YAML"), std::string::npos) << what;
  EXPECT_NE(what.find("yaml-cpp: error at line"), std::string::npos) << what;

  const std::string path = write_temp("walkgen_malformed.yaml", "n: 16\nt: {0.1\n");
  what = error_of([&] { return walkgen::load_walking_settings(path); });
  EXPECT_NE(what.find(path + ": expected well-formed YAML"), std::string::npos) << what;
  EXPECT_NE(what.find("yaml-cpp: error at line"), std::string::npos) << what;
  std::remove(path.c_str());

  const std::string missing = kConfigs + "no_such_robot.yaml";
  what = error_of([&] { return walkgen::load_walking_settings(missing); });
  EXPECT_NE(what.find(missing + ": expected a readable YAML file"), std::string::npos) << what;
  EXPECT_NE(what.find("bad file"), std::string::npos) << what;
}

// Issue 21: whatever the text, only walkgen::invalid_argument escapes, naming the key; integer
// keys are decimal counts that fit an int; numbers are finite.
TEST(YamlSettings, IntegersAreDecimalCountsThatFitAnInt) {
  const char* keys[] = {"n", "n_still", "nwsr", "sqp_iterations", "sqp_corrections"};
  for (const char* key : keys) {
    for (const char* value : {"-1", "2147483648", "99999999999999999999999", "0x10", "1e3", "''"}) {
      const std::string text = std::string("optimization:\n  ") + key + ": " + value + "\n";
      const std::string what = error_of_text(text);
      EXPECT_NE(what.find(std::string("YAML text:2: key 'optimization.") + key +
                          "': expected an integer in [0, 2147483647], got "),
                std::string::npos)
          << text << what;
    }
  }
  auto s = walkgen::walking_settings_from_yaml("n: 010\nnwsr: +20\n");
  EXPECT_EQ(s.n, 10);  // decimal, not yaml-cpp's octal
  EXPECT_EQ(s.nwsr, 20);
  s = walkgen::walking_settings_from_yaml("nwsr: 1000000\n");
  EXPECT_EQ(s.nwsr, 1000000);
  // In range for an int, out of range for the settings: validate() says so, naming the setting.
  EXPECT_NE(error_of_text("sqp_iterations: 2147483647\n").find("YAML text: WalkingSettings."),
            std::string::npos);
  EXPECT_NE(error_of_text("n: 0\n").find("YAML text: WalkingSettings.n"), std::string::npos);
}

TEST(YamlSettings, NumbersAreFinite) {
  const std::vector<BadCase> cases = {
      {"t_step: .inf\n", {"YAML text:1: key 't_step'", "a finite number", "'.inf'"}},
      {"gamma: .nan\n", {"key 'gamma'", "a finite number", "'.nan'"}},
      {"cpu_time: -.inf\n", {"key 'cpu_time'", "a finite number"}},
      {"com_x: [0, .nan, 0]\n", {"key 'com_x[1]'", "a finite number"}},
      {"t: 1e999\n", {"key 't'", "a number", "'1e999'"}},
      {"obstacles: [{x: .inf, y: 1, radius: 0.5}]\n", {"key 'obstacles[0].x'", "a finite number"}},
      {"obstacle: true\nx_pos: .nan\ny_pos: 0\nradius: 1\n", {"key 'x_pos'", "a finite number"}},
  };
  for (const auto& c : cases) {
    const std::string what = error_of_text(c.text);
    for (const auto& fragment : c.in_message) {
      EXPECT_NE(what.find(fragment), std::string::npos) << c.text << "message: " << what;
    }
  }
}

TEST(YamlSettings, OnlyWalkgenErrorsEscape) {
  // Each once let a yaml-cpp exception through or is a yaml-cpp corner: aliases, tags, deep
  // nesting, non-scalar keys, several documents, binary.
  const std::vector<std::string> texts = {
      "n: &a 16\nnwsr: *a\nt: *a\n",
      "n: !!str 16\n",
      "t_step: !!binary AAAA\n",
      "? [a, b]\n: 1\n",
      "{[1]: 2}\n",
      "optimization:\n  ? {a: 1}\n  : 2\n",
      "obstacles: [{[x]: 1, y: 1, radius: 1}]\n",
      "obstacles: [[1, 2]]\n",
      "n: 16\n---\nn: 17\n",
      "*undefined\n",
      "n: *undefined\n",
      std::string(5000, '[') + std::string(5000, ']'),
      std::string(5000, '{') + std::string(5000, '}'),
      std::string("n: \0\x01\xff", 7),
      "\xef\xbb\xbf\xff\xfe",
      "!<tag:yaml.org,2002:map> {n: 16}\n",
      "com_x: [&x 1, *x, *x]\n",
      "security_margin: !!seq [0.01, 0.01]\n",
  };
  for (const auto& text : texts) {
    try {
      (void)walkgen::walking_settings_from_yaml(text);
    } catch (const walkgen::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("YAML text"), std::string::npos) << e.what();
    } catch (const std::exception& e) {
      ADD_FAILURE() << "foreign exception " << e.what() << " for:\n" << text.substr(0, 80);
    }
  }
}

TEST(YamlSettings, FloatSettings) {
  const auto s = walkgen::load_walking_settings<float>(kConfigs + "heicub.yaml",
                                                       walkgen::heicub_settings<float>());
  EXPECT_FLOAT_EQ(s.t_step, 3.2f);
  EXPECT_FLOAT_EQ(s.left_foot_convex_hull(4, 1), 0.14f);
  EXPECT_EQ(s.samples_per_step(), 8);
}

}  // namespace
