// validate() of every settings struct of the core library (WalkingSettings has its own test in
// mpc/test_settings.cpp; the adapters' settings are checked in their tests with the same helper):
// the defaults pass, and a bad value throws walkgen::invalid_argument naming the field, its
// expected range and the value.

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "support/expect_error.hpp"
#include "walkgen/control/go_to_target.hpp"
#include "walkgen/control/walking_loop.hpp"
#include "walkgen/interpolation/trajectory.hpp"
#include "walkgen/kinematics/ik_residual.hpp"
#include "walkgen/learning/environment.hpp"
#include "walkgen/learning/nmpc_environment.hpp"

namespace {

using walkgen_test::expect_rejected;

const double kNan = std::numeric_limits<double>::quiet_NaN();
const double kInf = std::numeric_limits<double>::infinity();

TEST(SettingsValidation, InterpolationSettings) {
  using S = walkgen::InterpolationSettings<double>;
  expect_rejected<S>(walkgen::interpolation_settings(walkgen::hrp2_settings()),
                     {{[](S& s) { s.t = -1.0; }, {"InterpolationSettings.t", "> 0", "-1"}},
                      {[](S& s) { s.command_period = 0.03; },
                       {"InterpolationSettings.command_period", "divides t", "0.03"}},
                      {[](S& s) { s.com_z = kNan; }, {"InterpolationSettings.com_z", "nan"}},
                      {[](S& s) { s.gravity = 0.0; }, {"InterpolationSettings.gravity", "0"}}});
}

TEST(SettingsValidation, WalkingLoopSettings) {
  using S = walkgen::WalkingLoopSettings;
  expect_rejected<S>(
      S(),
      {{[](S& s) { s.feedback_gain = 1.5; },
        {"WalkingLoopSettings.feedback_gain", "(0, 1]", "1.5"}},
       {[](S& s) { s.feedback_gain = 0.0; }, {"WalkingLoopSettings.feedback_gain", "0"}},
       {[](S& s) { s.transfer_time = -1.0; }, {"WalkingLoopSettings.transfer_time", ">= 0", "-1"}},
       {[](S& s) { s.transfer_time = kInf; }, {"WalkingLoopSettings.transfer_time", "inf"}},
       {[](S& s) { s.max_qp_failures = 0; }, {"WalkingLoopSettings.max_qp_failures", ">= 1", "0"}},
       {[](S& s) { s.max_ik_failures = -2; },
        {"WalkingLoopSettings.max_ik_failures", ">= 1", "-2"}},
       {[](S& s) { s.max_saturated_periods = 0; },
        {"WalkingLoopSettings.max_saturated_periods", ">= 1", "0"}},
       {[](S& s) { s.joint_limit_margin = kNan; },
        {"WalkingLoopSettings.joint_limit_margin", "nan"}},
       {[](S& s) { s.max_joint_speed = 0.0; }, {"WalkingLoopSettings.max_joint_speed", "> 0"}},
       {[](S& s) { s.max_force_ratio = kInf; }, {"WalkingLoopSettings.max_force_ratio", "inf"}},
       {[](S& s) { s.max_tilt = 2.0; }, {"WalkingLoopSettings.max_tilt", "(0, 1.6]", "2"}},
       {[](S& s) { s.max_tilt = kNan; }, {"WalkingLoopSettings.max_tilt", "nan"}},
       {[](S& s) { s.max_angular_rate = -1.0; }, {"WalkingLoopSettings.max_angular_rate", "> 0"}},
       {[](S& s) { s.max_acceleration = kNan; }, {"WalkingLoopSettings.max_acceleration", "nan"}}});
}

TEST(SettingsValidation, GoToTargetSettings) {
  using S = walkgen::GoToTargetSettings;
  expect_rejected<S>(
      S(), {{[](S& s) { s.stop_distance = 0.0; }, {"GoToTargetSettings.stop_distance", "> 0"}},
            {[](S& s) { s.slow_down_distance = kNan; },
             {"GoToTargetSettings.slow_down_distance", "nan"}},
            {[](S& s) { s.heading_gain = -2.0; }, {"GoToTargetSettings.heading_gain", "-2"}},
            {[](S& s) { s.turn_in_place_angle = 0.0; }, {"GoToTargetSettings.turn_in_place_angle"}},
            {[](S& s) { s.min_speed_fraction = 2.0; },
             {"GoToTargetSettings.min_speed_fraction", "[0, 1]", "2"}},
            {[](S& s) { s.clearance = -0.1; }, {"GoToTargetSettings.clearance", ">= 0", "-0.1"}},
            {[](S& s) { s.max_aim_off_target = 4.0; },
             {"GoToTargetSettings.max_aim_off_target", "(0, π]", "4"}},
            {[](S& s) { s.aim_limit_opens_within = kInf; },
             {"GoToTargetSettings.aim_limit_opens_within", "inf"}},
            {[](S& s) { s.command_fraction = 1.2; },
             {"GoToTargetSettings.command_fraction", "(0, 1]", "1.2"}}});
}

TEST(SettingsValidation, PointGoalSettings) {
  using S = walkgen::PointGoalSettings;
  expect_rejected<S>(
      S(), {{[](S& s) { s.step_size = 0.0; }, {"PointGoalSettings.step_size", "> 0", "0"}},
            {[](S& s) { s.win_radius = kNan; }, {"PointGoalSettings.win_radius", "nan"}},
            {[](S& s) { s.goal_range = -5.0; }, {"PointGoalSettings.goal_range", "-5"}},
            {[](S& s) { s.lose_radius = 0.3; },
             {"PointGoalSettings.lose_radius", "larger than win_radius", "0.3"}},
            {[](S& s) { s.max_steps = -1; }, {"PointGoalSettings.max_steps", ">= 0", "-1"}},
            {[](S& s) { s.win_reward = kInf; }, {"PointGoalSettings.win_reward", "finite", "inf"}},
            {[](S& s) { s.lose_reward = kNan; }, {"PointGoalSettings.lose_reward", "nan"}}});
}

TEST(SettingsValidation, NmpcGoalSettings) {
  using S = walkgen::NmpcGoalSettings;
  expect_rejected<S>(
      S(),
      {{[](S& s) { s.walking.n = 0; }, {"WalkingSettings.n", "0"}},
       {[](S& s) { s.ticks_per_step = 0; }, {"NmpcGoalSettings.ticks_per_step", "at least 1", "0"}},
       {[](S& s) { s.max_steps = -3; }, {"NmpcGoalSettings.max_steps", "-3"}},
       {[](S& s) { s.goal_min_distance = 0.0; }, {"NmpcGoalSettings.goal_min_distance", "> 0"}},
       {[](S& s) { s.goal_max_distance = 0.1; },
        {"NmpcGoalSettings.goal_max_distance", "goal_min_distance", "0.1"}},
       {[](S& s) { s.success_radius = kNan; }, {"NmpcGoalSettings.success_radius", "nan"}},
       {[](S& s) { s.command_fraction = 1.0; },
        {"NmpcGoalSettings.command_fraction", "(0, 1)", "1"}},
       {[](S& s) { s.obstacles = -1; }, {"NmpcGoalSettings.obstacles", ">= 0", "-1"}},
       {[](S& s) { s.obstacle_min_radius = 0.0; }, {"NmpcGoalSettings.obstacle_min_radius"}},
       {[](S& s) { s.obstacle_max_radius = 0.05; },
        {"NmpcGoalSettings.obstacle_max_radius", "obstacle_min_radius", "0.05"}},
       {[](S& s) { s.obstacle_margin = -0.1; },
        {"NmpcGoalSettings.obstacle_margin", ">= 0", "-0.1"}},
       {[](S& s) { s.obstacle_lateral = -0.2; }, {"NmpcGoalSettings.obstacle_lateral", "-0.2"}},
       {[](S& s) { s.obstacle_clearance = kInf; }, {"NmpcGoalSettings.obstacle_clearance"}},
       {[](S& s) { s.goal_weight = kNan; }, {"NmpcGoalSettings.goal_weight", "finite"}},
       {[](S& s) { s.failure_reward = -kInf; }, {"NmpcGoalSettings.failure_reward", "finite"}}});
}

TEST(SettingsValidation, IkResidualSettings) {
  using S = walkgen::IkResidualSettings;
  expect_rejected<S>(
      S(), {{[](S& s) { s.com_body_point.x() = kNan; },
             {"IkResidualSettings.com_body_point", "finite", "NaN"}},
            {[](S& s) { s.lf_body_point.y() = kInf; }, {"IkResidualSettings.lf_body_point"}},
            {[](S& s) { s.rf_body_point.z() = kNan; }, {"IkResidualSettings.rf_body_point"}},
            {[](S& s) { s.com_weight = 0.0; }, {"IkResidualSettings.com_weight", "> 0", "0"}},
            {[](S& s) { s.foot_position_weight = -1.0; },
             {"IkResidualSettings.foot_position_weight", "-1"}},
            {[](S& s) { s.foot_orientation_weight = kNan; },
             {"IkResidualSettings.foot_orientation_weight", "nan"}},
            {[](S& s) { s.base_orientation_weight = kInf; },
             {"IkResidualSettings.base_orientation_weight", "inf"}},
            {[](S& s) { s.torso_orientation_weight = 0.0; },
             {"IkResidualSettings.torso_orientation_weight"}}});
}

}  // namespace
