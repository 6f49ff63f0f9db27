// walkgen::GoToTarget, the scripted user of the simulated tasks: commands within the limits,
// turning toward the target, stopping, passing obstacles on a kept side, bad input.
#include "walkgen/control/go_to_target.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "walkgen/core/math.hpp"

namespace {

using walkgen::GoToTarget;
using walkgen::GoToTargetCommand;
using walkgen::kPi;
using walkgen::PlanarPose;

const Eigen::Vector3d kMax(0.034, 0.0045, 0.075);  // Heicub's max_command

TEST(GoToTarget, WalksStraightAtATargetAheadAndStopsWithinTheStopDistance) {
  GoToTarget steer({2.0, 0.0}, kMax);
  const auto far = steer(PlanarPose{0.0, 0.0, 0.0});
  EXPECT_FALSE(far.reached);
  EXPECT_NEAR(far.command.x(), 0.95 * kMax.x(), 1e-12);  // full speed (command_fraction 0.95)
  EXPECT_NEAR(far.command.y(), 0.0, 1e-12);
  EXPECT_NEAR(far.command.z(), 0.0, 1e-12);
  EXPECT_NEAR(far.distance, 2.0, 1e-12);
  // Within slow_down_distance (0.3) of the stop distance (0.2): slower, at least half speed.
  const auto near = steer(PlanarPose{2.0 - 0.35, 0.0, 0.0});
  EXPECT_NEAR(near.command.x(), 0.95 * kMax.x() * 0.5, 1e-12);
  const auto there = steer(PlanarPose{1.85, 0.05, 0.3});
  EXPECT_TRUE(there.reached);
  EXPECT_EQ(there.command, Eigen::Vector3d::Zero());
}

TEST(GoToTarget, TurnsInPlaceTowardATargetBehindAndOnTheShorterSide) {
  GoToTarget steer({-1.5, 0.3}, kMax);
  const auto c = steer(PlanarPose{0.0, 0.0, 0.0});
  EXPECT_EQ(c.command.x(), 0.0);  // heading error ~2.9 rad > turn_in_place_angle
  EXPECT_NEAR(c.command.z(), 0.95 * kMax.z(), 1e-12);  // left: the target is at +168 degrees
  GoToTarget right({-1.5, -0.3}, kMax);
  EXPECT_NEAR(right(PlanarPose{0.0, 0.0, 0.0}).command.z(), -0.95 * kMax.z(), 1e-12);
  // A small heading error: walking and turning, ω = gain * error.
  GoToTarget ahead({1.0, 0.1}, kMax);
  const auto a = ahead(PlanarPose{0.0, 0.0, 0.0});
  EXPECT_NEAR(a.command.z(), std::min(std::atan2(0.1, 1.0), 0.95 * kMax.z()), 1e-12);
  EXPECT_GT(a.command.x(), 0.0);
}

TEST(GoToTarget, AimsAtATangentOfABlockingObstacleAndKeepsItsSide) {
  // The chair of the obstacle task: centre (1.0, 0.05), radius 0.15, margin 0.12.
  const walkgen::CircleObstacle<double> chair{1.0, 0.05, 0.15, 0.12};
  GoToTarget steer({2.0, 0.0}, kMax, {chair});
  const auto c = steer(PlanarPose{0.3, 0.0, 0.0});
  const double r = 0.15 + 0.12 + 0.1;  // + clearance
  // The aim lies on the tangent: its direction from p makes asin(r / |c - p|) with the centre's.
  const Eigen::Vector2d p(0.3, 0.0), centre(1.0, 0.05);
  const Eigen::Vector2d to_aim = c.aim - p, to_centre = centre - p;
  const double angle = std::acos(to_aim.normalized().dot(to_centre.normalized()));
  EXPECT_NEAR(angle, std::asin(r / to_centre.norm()), 1e-9);
  EXPECT_LT(c.aim.y(), 0.0);  // the centre is left of the way: pass on its right
  EXPECT_LT(c.command.z(), 0.0);
  // Swaying to the other side of the line does not change the side once chosen.
  const auto sway = steer(PlanarPose{0.3, 0.12, 0.05});
  EXPECT_LT(sway.aim.y(), 0.12);
  EXPECT_LT(sway.command.z(), 0.0);
  // Past the obstacle: straight to the target again.
  const auto past = steer(PlanarPose{1.3, -0.3, 0.0});
  EXPECT_NEAR((past.aim - Eigen::Vector2d(2.0, 0.0)).norm(), 0.0, 1e-12);
}

TEST(GoToTarget, MaxAimOffTargetKeepsTheTargetWithinThatAngleOfTheAim) {
  const walkgen::CircleObstacle<double> chair{1.0, 0.05, 0.15, 0.12};
  walkgen::GoToTargetSettings s;
  s.max_aim_off_target = 0.35;  // 20 degrees
  GoToTarget free({2.0, 0.0}, kMax, {chair});
  GoToTarget limited({2.0, 0.0}, kMax, {chair}, s);
  const PlanarPose p{0.6, 0.0, 0.0};  // near the chair: the tangent is ~70 degrees off
  const auto wide = free(p);
  const auto kept = limited(p);
  const Eigen::Vector2d to_target(2.0 - 0.6, 0.0);
  auto off = [&](const Eigen::Vector2d& aim) {
    const Eigen::Vector2d a = aim - Eigen::Vector2d(0.6, 0.0);
    return std::acos(a.normalized().dot(to_target.normalized()));
  };
  EXPECT_GT(off(wide.aim), 0.35 + 0.3);
  EXPECT_NEAR(off(kept.aim), 0.35, 1e-9);
  EXPECT_LT(kept.aim.y(), 0.0);                            // the same side as without the limit
  EXPECT_NEAR(kept.command.z(), -0.95 * kMax.z(), 1e-12);  // turning right toward the aim
  // Past the chair: the aim is the target itself.
  EXPECT_NEAR((limited(PlanarPose{1.5, 0.1, 0.0}).aim - Eigen::Vector2d(2.0, 0.0)).norm(), 0.0,
              1e-12);
  s.max_aim_off_target = 0.0;
  EXPECT_THROW(GoToTarget({1.0, 0.0}, kMax, {}, s), walkgen::invalid_argument);
}

TEST(GoToTarget, PassSideChoosesTheSideWhateverTheHeading) {
  using walkgen::PassSide;
  auto settings = [](PassSide side) {
    walkgen::GoToTargetSettings s;
    s.pass_side = side;
    return s;
  };
  for (double offset : {-0.05, 0.05}) {  // the chair right or left of the way to the target
    const walkgen::CircleObstacle<double> chair{1.0, offset, 0.15, 0.12};
    for (double yaw : {-0.1, 0.1}) {  // heading toward either side
      const PlanarPose p{0.3, 0.0, yaw};
      GoToTarget left({2.0, 0.0}, kMax, {chair}, settings(PassSide::left));
      GoToTarget right({2.0, 0.0}, kMax, {chair}, settings(PassSide::right));
      GoToTarget shorter({2.0, 0.0}, kMax, {chair}, settings(PassSide::shorter));
      GoToTarget heading({2.0, 0.0}, kMax, {chair});
      EXPECT_GT(left(p).aim.y(), offset + 0.15) << "offset " << offset << ", yaw " << yaw;
      EXPECT_LT(right(p).aim.y(), offset - 0.15) << "offset " << offset << ", yaw " << yaw;
      // The shorter way: away from the centre, whatever the heading ...
      EXPECT_LT(shorter(p).aim.y() * offset, 0.0) << "offset " << offset << ", yaw " << yaw;
      // ... where toward_heading follows the heading.
      EXPECT_GT(heading(p).aim.y() * yaw, 0.0) << "offset " << offset << ", yaw " << yaw;
      // The aim is on the tangent: asin(r / |c − p|) from the centre's direction.
      const Eigen::Vector2d at(0.3, 0.0), centre(1.0, offset);
      const double angle =
          std::acos((shorter(p).aim - at).normalized().dot((centre - at).normalized()));
      EXPECT_NEAR(angle, std::asin((0.15 + 0.12 + 0.1) / (centre - at).norm()), 1e-9);
    }
  }
}

TEST(GoToTarget, InsideTheInflatedCircleItWalksAlongTheCircleOnTheKeptSide) {
  // Pushed inside radius + margin + clearance (0.37 m): the aim goes along the circle on the
  // chosen side, turned outward the deeper it is (90° + 90° · depth / r from the centre's
  // direction), the same side on both sides of the straight line (no flipping with sway).
  const walkgen::CircleObstacle<double> chair{1.0, 0.05, 0.15, 0.12};
  const double r = 0.15 + 0.12 + 0.1;
  walkgen::GoToTargetSettings s;
  s.pass_side = walkgen::PassSide::right;
  GoToTarget steer({2.0, 0.0}, kMax, {chair}, s);
  for (double y : {0.0, 0.1, 0.0, 0.1}) {
    const Eigen::Vector2d p(0.7, y), centre(1.0, 0.05);
    const auto c = steer(PlanarPose{p.x(), p.y(), 0.0});
    EXPECT_EQ(c.passing, 0);
    const Eigen::Vector2d to_aim = c.aim - p, to_centre = centre - p;
    const double angle = std::acos(to_aim.normalized().dot(to_centre.normalized()));
    EXPECT_NEAR(angle, kPi / 2.0 * (2.0 - to_centre.norm() / r), 1e-9) << "y " << y;
    // Right of the centre's direction (clockwise from it): a negative cross product.
    EXPECT_LT(to_centre.x() * to_aim.y() - to_centre.y() * to_aim.x(), 0.0) << "y " << y;
    EXPECT_LT(c.command.z(), 0.0) << "y " << y;  // turning right, away from the chair
    EXPECT_EQ(c.command.x(), 0.0) << "y " << y;  // more than turn_in_place_angle to turn
  }
  EXPECT_EQ(steer(PlanarPose{1.5, -0.4, 0.0}).passing, -1);  // past it: nothing blocks
}

TEST(GoToTarget, TheAimLimitOpensNearTheObstacleAndLeadsAroundIt) {
  const walkgen::CircleObstacle<double> chair{1.0, 0.05, 0.15, 0.12};
  const double r = 0.15 + 0.12 + 0.1, limit = 16.0 * kPi / 180.0;
  walkgen::GoToTargetSettings s;
  s.max_aim_off_target = limit;
  s.aim_limit_opens_within = 0.25;
  s.pass_side = walkgen::PassSide::right;
  const Eigen::Vector2d target(2.0, 0.0), centre(1.0, 0.05);
  auto off = [&](const GoToTargetCommand& c, const Eigen::Vector2d& p) {
    return std::acos((c.aim - p).normalized().dot((target - p).normalized()));
  };
  // Far from the circle the limit holds; nearer it opens linearly; at the circle it is gone.
  for (double gap : {0.4, 0.3, 0.2, 0.1, 0.0}) {
    const Eigen::Vector2d p = centre - Eigen::Vector2d(r + gap, 0.05);
    GoToTarget limited(target, kMax, {chair}, s);
    walkgen::GoToTargetSettings free_settings = s;
    free_settings.max_aim_off_target = kPi;
    GoToTarget free(target, kMax, {chair}, free_settings);
    const auto c = limited(PlanarPose{p.x(), p.y(), 0.0});
    const double open = std::clamp(1.0 - ((centre - p).norm() - r) / 0.25, 0.0, 1.0);
    const double wide = off(free(PlanarPose{p.x(), p.y(), 0.0}), p);
    EXPECT_NEAR(off(c, p), std::min(wide, limit + open * (kPi - limit)), 1e-9) << "gap " << gap;
    EXPECT_LT(c.aim.y(), p.y()) << "gap " << gap;  // on the kept side
  }
  // A unicycle driven by the commands from right in front of the chair (where a cloned
  // network ends up) gets around it without entering radius + margin and reaches the target
  // (in 78 s); with the fixed limit it walks through the chair (0.09 m from its centre), where
  // the NMPC's obstacle rows stop the real robot.
  for (double opens : {0.25, 0.0}) {
    s.aim_limit_opens_within = opens;
    GoToTarget steer(target, kMax, {chair}, s);
    PlanarPose pose{0.66, 0.05, 0.0};
    double closest = 1e9, t = 0.0;
    bool reached = false;
    for (; t < 400.0 && !reached; t += 0.1) {
      const auto c = steer(pose);
      reached = c.reached;
      pose.x += c.command.x() * std::cos(pose.yaw) * 0.1;
      pose.y += c.command.x() * std::sin(pose.yaw) * 0.1;
      pose.yaw += c.command.z() * 0.1;
      closest = std::min(closest, std::hypot(pose.x - centre.x(), pose.y - centre.y()));
    }
    if (opens > 0.0) {
      EXPECT_TRUE(reached);
      EXPECT_LT(t, 150.0);
      EXPECT_GT(closest, 0.15 + 0.12);
    } else {
      EXPECT_LT(closest, 0.15 + 0.12);  // it walks into the NMPC's circle, which stops it
    }
  }
}

TEST(GoToTarget, CommandsStayWithinTheLimits) {
  GoToTarget steer({0.5, 3.0}, kMax, {{0.2, 1.0, 0.2, 0.1}});
  for (double yaw = -3.0; yaw <= 3.0; yaw += 0.25) {
    for (double x = -1.0; x <= 1.0; x += 0.5) {
      const auto c = steer(PlanarPose{x, 0.0, yaw});
      EXPECT_LE(std::abs(c.command.x()), kMax.x());
      EXPECT_GE(c.command.x(), 0.0);
      EXPECT_LE(std::abs(c.command.y()), kMax.y());
      EXPECT_LE(std::abs(c.command.z()), kMax.z());
    }
  }
}

TEST(GoToTarget, BadInputThrows) {
  EXPECT_THROW(GoToTarget({std::nan(""), 0.0}, kMax), walkgen::invalid_argument);
  EXPECT_THROW(GoToTarget({1.0, 0.0}, Eigen::Vector3d(-1.0, 0.0, 0.0)), walkgen::invalid_argument);
  EXPECT_THROW(GoToTarget({1.0, 0.0}, kMax, {{0.5, 0.0, -0.1, 0.0}}), walkgen::invalid_argument);
  walkgen::GoToTargetSettings s;
  s.command_fraction = 0.0;
  EXPECT_THROW(GoToTarget({1.0, 0.0}, kMax, {}, s), walkgen::invalid_argument);
  for (double opens : {-0.1, std::nan("")}) {
    walkgen::GoToTargetSettings bad;
    bad.aim_limit_opens_within = opens;
    EXPECT_THROW(GoToTarget({1.0, 0.0}, kMax, {}, bad), walkgen::invalid_argument);
  }
  GoToTarget ok({1.0, 0.0}, kMax);
  EXPECT_THROW(ok(PlanarPose{0.0, std::nan(""), 0.0}), walkgen::invalid_argument);
}

}  // namespace
