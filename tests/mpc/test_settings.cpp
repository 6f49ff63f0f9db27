// Walking settings: the presets carry the thesis's numbers and pass validation; every kind of
// bad value is rejected naming its key.

#include "walkgen/mpc/settings.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include <functional>
#include <limits>
#include <string>

namespace {

using Settings = walkgen::WalkingSettings<double>;

TEST(WalkingSettings, Hrp2PresetHasTheThesisValues) {
  const auto s = walkgen::hrp2_settings();
  EXPECT_NO_THROW(walkgen::validate(s));
  EXPECT_NO_THROW(walkgen::validate(Settings{}));  // the in-class defaults are HRP-2's
  EXPECT_DOUBLE_EQ(s.t_step, 0.8);
  EXPECT_EQ(s.n, 16);
  EXPECT_DOUBLE_EQ(s.t, 0.1);
  EXPECT_DOUBLE_EQ(s.com_z, 0.814);
  EXPECT_DOUBLE_EQ(s.foot_length, 0.2172);
  EXPECT_DOUBLE_EQ(s.foot_width, 0.1380);
  EXPECT_DOUBLE_EQ(s.security_margin[0], 0.09);
  EXPECT_DOUBLE_EQ(s.security_margin[1], 0.05);
  EXPECT_DOUBLE_EQ(s.foot_distance, 0.2);
  EXPECT_DOUBLE_EQ(s.t_ds, 0.4);
  EXPECT_DOUBLE_EQ(s.command_period, 0.005);
  EXPECT_DOUBLE_EQ(s.step_height, 0.05);
  EXPECT_DOUBLE_EQ(s.alpha, 1.0);
  EXPECT_DOUBLE_EQ(s.beta, 1e-6);
  EXPECT_DOUBLE_EQ(s.gamma, 1e-5);
  EXPECT_EQ(s.samples_per_step(), 8);
  EXPECT_EQ(s.planned_steps(), 2);
  // The right foot's region mirrors the left one's.
  EXPECT_TRUE(s.right_foot_convex_hull.col(0).isApprox(s.left_foot_convex_hull.col(0)));
  EXPECT_TRUE(s.right_foot_convex_hull.col(1).isApprox(-s.left_foot_convex_hull.col(1)));
}

TEST(WalkingSettings, HeicubPresetHasTable6_1Values) {
  const auto s = walkgen::heicub_settings();
  EXPECT_NO_THROW(walkgen::validate(s));
  EXPECT_DOUBLE_EQ(s.t_step, 3.2);
  EXPECT_DOUBLE_EQ(s.t, 0.4);
  EXPECT_EQ(s.n, 16);
  EXPECT_DOUBLE_EQ(s.t_ds, 1.6);
  EXPECT_DOUBLE_EQ(s.com_z, 0.45);
  EXPECT_DOUBLE_EQ(s.com_y[0], 0.05);
  EXPECT_DOUBLE_EQ(s.foot_y, 0.07);
  EXPECT_DOUBLE_EQ(s.beta, 1e2);
  EXPECT_DOUBLE_EQ(s.gamma, 1e-2);
  EXPECT_DOUBLE_EQ(s.left_foot_convex_hull(0, 0), -0.11);
  EXPECT_DOUBLE_EQ(s.left_foot_convex_hull(0, 1), 0.14);
  EXPECT_EQ(s.samples_per_step(), 8);
  EXPECT_EQ(s.planned_steps(), 2);
}

// Each case breaks one key; validate() must throw and name that key.
TEST(WalkingSettings, BadValuesAreRejectedNamingTheKey) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const std::vector<std::pair<std::string, std::function<void(Settings&)>>> cases = {
      {"WalkingSettings.n", [](Settings& s) { s.n = 0; }},
      {"WalkingSettings.t", [nan](Settings& s) { s.t = nan; }},
      {"WalkingSettings.t_step", [](Settings& s) { s.t_step = 0.75; }},
      {"WalkingSettings.n", [](Settings& s) { s.n = 1; }},  // horizon reaches no next step
      {"WalkingSettings.t_ds", [](Settings& s) { s.t_ds = 0.8; }},
      {"WalkingSettings.command_period", [](Settings& s) { s.command_period = 0.03; }},
      {"WalkingSettings.security_margin[0]", [](Settings& s) { s.security_margin[0] = 0.11; }},
      {"WalkingSettings.security_margin[1]", [](Settings& s) { s.security_margin[1] = -0.01; }},
      {"WalkingSettings.left_foot_convex_hull",
       [](Settings& s) { s.left_foot_convex_hull(2, 1) = 0.25; }},  // dented: not convex
      {"WalkingSettings.right_foot_convex_hull",
       [](Settings& s) { s.right_foot_convex_hull.resize(2, 2); }},
      {"WalkingSettings.com_z", [](Settings& s) { s.com_z = -0.8; }},
      {"WalkingSettings.com_x/com_y/com_q", [nan](Settings& s) { s.com_y[1] = nan; }},
      {"WalkingSettings.gamma", [](Settings& s) { s.gamma = 0; }},
      {"WalkingSettings.nwsr", [](Settings& s) { s.nwsr = 0; }},
      {"WalkingSettings.obstacles[].radius",
       [](Settings& s) {
         s.obstacles.push_back({1.6, 1.0, -1.0, 0.4});
       }},
      {"WalkingSettings.sqp_iterations", [](Settings& s) { s.sqp_iterations = 0; }},
      {"WalkingSettings.sqp_corrections", [](Settings& s) { s.sqp_corrections = -1; }},
      {"WalkingSettings.sqp_tolerance", [](Settings& s) { s.sqp_tolerance = 0; }},
      {"WalkingSettings.sqp_tolerance", [](Settings& s) { s.sqp_tolerance = std::nan(""); }},
      {"WalkingSettings.step_velocity_weight", [](Settings& s) { s.step_velocity_weight = -1; }},
      // Issue 21, defect 4: values that overflowed int arithmetic or lost every digit used to
      // pass (sqp_iterations + sqp_corrections wrapped and the tick said solved after 0
      // iterations; t_step / t narrowed to S = 8; n + S − 2 overflowed).
      {"WalkingSettings.n", [](Settings& s) { s.n = std::numeric_limits<int>::max(); }},
      {"WalkingSettings.sqp_iterations",
       [](Settings& s) { s.sqp_iterations = std::numeric_limits<int>::max(); }},
      {"WalkingSettings.sqp_corrections",
       [](Settings& s) { s.sqp_corrections = std::numeric_limits<int>::max(); }},
      {"WalkingSettings.t_step", [](Settings& s) { s.t_step = 0.1 * (4294967296.0 + 8.0); }},
      {"WalkingSettings.t_step", [](Settings& s) { s.t_step = 0.1 * 1001; }},
      {"WalkingSettings.n_still", [](Settings& s) { s.n_still = std::numeric_limits<int>::max(); }},
      {"WalkingSettings.nwsr", [](Settings& s) { s.nwsr = std::numeric_limits<int>::max(); }},
      {"WalkingSettings.gamma", [](Settings& s) { s.gamma = 1e-300; }},
      {"WalkingSettings.t", [](Settings& s) { s.t = 1e-300; }},  // H overflows: NaN in the QP
      {"WalkingSettings.command_period", [](Settings& s) { s.command_period = 5e-324; }},
      {"WalkingSettings.cpu_time", [](Settings& s) { s.cpu_time = -5; }},
      {"WalkingSettings.sqp_tolerance", [](Settings& s) { s.sqp_tolerance = 1e-300; }},
      {"WalkingSettings.alpha", [](Settings& s) { s.alpha = 1e300; }},
      {"WalkingSettings.com_x[0]", [](Settings& s) { s.com_x[0] = 1e30; }},
      {"WalkingSettings.foot_y", [](Settings& s) { s.foot_y = -1e200; }},
      {"WalkingSettings.com_x/com_y", [](Settings& s) { s.com_y[0] = 5.0; }},  // 4.9 m off
      {"WalkingSettings.left_foot_convex_hull",
       [](Settings& s) { s.left_foot_convex_hull *= 1e200; }},
      {"WalkingSettings.obstacles[].x",
       [](Settings& s) {
         s.obstacles.push_back({1e300, 1.0, 1.0, 0.4});
       }},
  };
  for (const auto& c : cases) {
    Settings s = walkgen::hrp2_settings();
    c.second(s);
    try {
      walkgen::validate(s);
      ADD_FAILURE() << "no exception for " << c.first;
    } catch (const walkgen::invalid_argument& e) {
      const std::string what = e.what();
      EXPECT_EQ(what.rfind(c.first + ":", 0), 0u) << "expected the key " << c.first << ": " << what;
      EXPECT_NE(what.find("expected"), std::string::npos) << what;
    }
  }
}

// The bounds that validate() names are accepted at their edge: a user who needs them can use them.
TEST(WalkingSettings, TheLimitsThemselvesAreAccepted) {
  Settings s = walkgen::hrp2_settings();
  s.sqp_iterations = walkgen::settings_limits::kMaxSqpIterations;
  s.sqp_corrections = walkgen::settings_limits::kMaxSqpIterations;
  s.nwsr = walkgen::settings_limits::kMaxActiveSetChanges;
  s.n = walkgen::settings_limits::kMaxHorizon;
  EXPECT_NO_THROW(walkgen::validate(s));
  EXPECT_EQ(s.planned_steps(), (1000 + 8 - 2) / 8);
}

TEST(Foot, OtherAndNames) {
  EXPECT_EQ(walkgen::other(walkgen::Foot::left), walkgen::Foot::right);
  EXPECT_EQ(walkgen::other(walkgen::Foot::right), walkgen::Foot::left);
  EXPECT_STREQ(walkgen::to_string(walkgen::Foot::left), "left");
}

}  // namespace
