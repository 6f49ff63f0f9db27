// The interpolator on its own (thesis §2.3, §6.2.2): a TickPlan value in, command-period samples
// out. This file includes nothing of the generator: the data path runs one way (issue 22).

#include "walkgen/interpolation/trajectory.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "support/expect_error.hpp"

namespace {

using walkgen::Foot;
using walkgen::InterpolationSettings;
using walkgen::TickPlan;
using walkgen::TrajectorySample;
using walkgen::WalkingInterpolator;

constexpr double kComZ = 0.814, kGravity = 9.81;

InterpolationSettings<double> settings() { return {0.1, 0.005, kComZ, kGravity}; }

// A tick in the middle of a step: the CoM moving with a jerk, the right foot supporting, the left
// swinging from (0.1, 0.1) towards (0.3, 0.12) with yaw 0.2.
TickPlan<double> mid_step_plan(double step_time) {
  TickPlan<double> p;
  p.time = 2.0;
  p.step_time = step_time;
  p.com_x << 0.2, 0.15, -0.3;
  p.com_y << -0.01, 0.05, 0.4;
  p.jerk_x = 1.5;
  p.jerk_y = -2.0;
  p.support_foot = Foot::right;
  p.support = {0.2, -0.1, 0.05};
  p.swing = walkgen::FootMotion<double>::at_rest({0.1, 0.1, 0.0});
  p.landing = {0.3, 0.12, 0.2};
  p.timing = {0.1, 0.8, 0.05};
  return p;
}

std::vector<TrajectorySample<double>> sample(const TickPlan<double>& plan) {
  const WalkingInterpolator<double> interp(settings());
  std::vector<TrajectorySample<double>> out(std::size_t(interp.samples_per_tick()));
  interp.interpolate(plan, out.data());
  return out;
}

TEST(WalkingInterpolator, CoMFollowsTheJerkAndTheZmpIsThePendulumsFromTheTickState) {
  const TickPlan<double> plan = mid_step_plan(0.3);
  const auto out = sample(plan);
  ASSERT_EQ(out.size(), 20u);
  for (std::size_t i = 0; i < out.size(); ++i) {
    const double t = 0.005 * double(i);
    const auto& s = out[i];
    EXPECT_NEAR(s.time, plan.time + t, 1e-15);
    // Constant jerk j from (c, ċ, c̈): c + ċt + c̈t²/2 + jt³/6 (thesis eq. 2.25).
    for (int axis = 0; axis < 2; ++axis) {
      const auto& c0 = axis == 0 ? plan.com_x : plan.com_y;
      const double j = axis == 0 ? plan.jerk_x : plan.jerk_y;
      const auto& c = axis == 0 ? s.com_x : s.com_y;
      EXPECT_NEAR(c[0], c0[0] + c0[1] * t + c0[2] * t * t / 2 + j * t * t * t / 6, 1e-14);
      EXPECT_NEAR(c[1], c0[1] + c0[2] * t + j * t * t / 2, 1e-14);
      EXPECT_NEAR(c[2], c0[2] + j * t, 1e-14);
      // z = c − c_z/g c̈ (eq. 2.6–2.7).
      EXPECT_NEAR(axis == 0 ? s.zmp_x : s.zmp_y, c[0] - kComZ / kGravity * c[2], 1e-14);
    }
    EXPECT_EQ(s.com_z, kComZ);
    EXPECT_EQ(s.zmp_z, 0.0);
    // The support foot stands; the CoM yaw is the feet's mean.
    EXPECT_EQ(s.support_foot, Foot::right);
    EXPECT_EQ(s.right.motion.x.position, plan.support.x);
    EXPECT_EQ(s.right.motion.q.position, plan.support.q);
    EXPECT_EQ(s.right.z.position, 0.0);
    EXPECT_NEAR(s.com_q[0], (s.left.motion.q.position + s.right.motion.q.position) / 2, 1e-15);
    EXPECT_FALSE(s.double_support);
  }
  // The swing foot is in the air mid single support and moves towards the landing footstep.
  EXPECT_GT(out.back().left.z.position, 0.0);
  EXPECT_GT(out.back().left.motion.x.position, out.front().left.motion.x.position);
}

TEST(WalkingInterpolator, SwingFootStandsInDoubleSupportAndLandsOnTheFootstep) {
  for (const auto& s : sample(mid_step_plan(0.0))) {  // [0, 0.1): t_ds = 0.1
    EXPECT_TRUE(s.double_support);
    EXPECT_EQ(s.left.motion.x.position, 0.1);
    EXPECT_EQ(s.left.z.position, 0.0);
  }
  // The last tick of the step, from the foot where the quintic has taken it by 0.7 s: the
  // samples close in on the footstep, slowing down and descending.
  TickPlan<double> last = mid_step_plan(0.7);
  last.swing = walkgen::swing_foot_sample(last.timing, last.swing, 0.0, last.landing, 0.7).motion;
  const auto out = sample(last);
  const auto& end = out.back().left;  // at 0.795 s of a 0.8 s step
  EXPECT_NEAR(end.motion.x.position, 0.3, 1e-5);
  EXPECT_NEAR(end.motion.y.position, 0.12, 1e-5);
  EXPECT_NEAR(end.motion.q.position, 0.2, 1e-5);
  EXPECT_LT(std::abs(end.motion.x.velocity), std::abs(out.front().left.motion.x.velocity));
  EXPECT_LT(end.z.position, out.front().left.z.position);
  EXPECT_NEAR(end.z.position, 0.0, 1e-4);
}

TEST(WalkingInterpolator, InvalidSettingsNameTheKey) {
  auto s = settings();
  s.command_period = 0.2;  // longer than a tick
  walkgen_test::expect_invalid_argument([&] { WalkingInterpolator<double> i(s); },
                                        {"command_period"});
  s = settings();
  s.com_z = std::nan("");
  walkgen_test::expect_invalid_argument([&] { WalkingInterpolator<double> i(s); },
                                        {"InterpolationSettings.com_z"});
  s = settings();
  s.gravity = -9.81;
  walkgen_test::expect_invalid_argument([&] { WalkingInterpolator<double> i(s); },
                                        {"InterpolationSettings.gravity"});
}

}  // namespace
