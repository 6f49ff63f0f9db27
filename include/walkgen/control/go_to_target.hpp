#pragma once
/// @file
/// A scripted high-level command: walk to a target in the plane, around circular obstacles.
/// It stands in for the user of thesis §9.2 (who steered Heicub to a fire extinguisher by
/// keyboard) in the demo and tests, and is the "expert that knows the scene" for recording
/// demonstrations. It only ever produces velocity commands (v_x, v_y, ω_z) within the
/// generator's max_command; the NMPC's own obstacle rows (eq. 2.79) keep the footsteps out of
/// the obstacles, this only chooses a way around them.
///
/// Steering: turn toward the aim point (ω proportional to the heading error), walk forward
/// when the heading error is below turn_in_place_angle, slower near the target, stop within
/// stop_distance. The aim point is the target, or, when the straight line to it passes through
/// an obstacle inflated by radius + margin + clearance, the tangent point of that circle on the
/// side chosen by pass_side; inside the inflated circle (pushed there, or started there) it
/// walks along the circle on that side, turned outward the deeper it is, so that the command
/// stays the same on both sides of a swaying pose.

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "walkgen/core/exceptions.hpp"
#include "walkgen/core/math.hpp"
#include "walkgen/core/obstacle.hpp"

namespace walkgen {

/// How GoToTarget chooses the side to pass a blocking obstacle on.
enum class PassSide {
  toward_heading,  ///< the tangent closer to the robot's heading
  /// the shorter way: away from the obstacle's centre as seen from the straight line to the
  /// target, from the pose where the obstacle starts blocking. It ignores the heading, but a
  /// swaying pose (a camera's) can still flip it for an obstacle near that line; a caller that
  /// knows the start can decide once with left / right (the cloning expert does)
  shorter,
  left,   ///< always on the obstacle's left (it stays on the robot's right)
  right,  ///< always on the obstacle's right
};

/// The enumerator's name ("toward_heading", ...), e.g. for logs; "unknown" for a value out of
/// range.
constexpr const char* to_string(PassSide side) noexcept {
  switch (side) {
    case PassSide::toward_heading:
      return "toward_heading";
    case PassSide::shorter:
      return "shorter";
    case PassSide::left:
      return "left";
    case PassSide::right:
      return "right";
  }
  return "unknown";
}

/// Settings of GoToTarget. Lengths [m], angles [rad].
struct GoToTargetSettings {
  double stop_distance = 0.2;        ///< reached when the robot is this close to the target
  double slow_down_distance = 0.3;   ///< v_x falls linearly over this distance ...
  double min_speed_fraction = 0.5;   ///< ... to this fraction of the full speed
  double heading_gain = 1.0;         ///< ω = gain · heading error [1/s], clamped
  double turn_in_place_angle = 0.5;  ///< above this heading error: no forward speed
  double clearance = 0.1;            ///< added to an obstacle's radius + margin when aiming
  double command_fraction = 0.95;    ///< of max_command actually used (stay inside the limits)
  /// The aim direction stays within this angle of the direction to the target, so that a
  /// camera looking ahead keeps the target in view while passing an obstacle (the way around
  /// becomes a curve; the NMPC's obstacle rows still keep the feet out). π: no limit.
  double max_aim_off_target = kPi;
  /// Within this distance [m] of a blocking obstacle's inflated circle the limit above opens,
  /// linearly, to none at the circle, so that a robot which walked up to the obstacle still
  /// turns enough to get around it (at the circle the tangent is 90° off the centre). 0: the
  /// limit holds everywhere.
  double aim_limit_opens_within = 0.0;
  /// The side to pass a blocking obstacle on (decided when it starts blocking, then kept).
  PassSide pass_side = PassSide::toward_heading;
};

/// Checks GoToTarget's settings (its constructor calls this).
/// @throws walkgen::invalid_argument naming the first bad field.
inline void validate(const GoToTargetSettings& s) {
  check_positive("GoToTargetSettings.stop_distance", s.stop_distance);
  check_positive("GoToTargetSettings.slow_down_distance", s.slow_down_distance);
  check_positive("GoToTargetSettings.heading_gain", s.heading_gain);
  check_positive("GoToTargetSettings.turn_in_place_angle", s.turn_in_place_angle);
  check_argument(s.min_speed_fraction >= 0.0 && s.min_speed_fraction <= 1.0,
                 "GoToTargetSettings.min_speed_fraction", "a fraction in [0, 1]",
                 s.min_speed_fraction);
  check_argument(s.clearance >= 0.0, "GoToTargetSettings.clearance", "a length >= 0", s.clearance);
  check_argument(s.max_aim_off_target > 0.0 && s.max_aim_off_target <= kPi,
                 "GoToTargetSettings.max_aim_off_target", "an angle in (0, π]",
                 s.max_aim_off_target);
  check_argument(s.aim_limit_opens_within >= 0.0 && std::isfinite(s.aim_limit_opens_within),
                 "GoToTargetSettings.aim_limit_opens_within", "a length >= 0",
                 s.aim_limit_opens_within);
  check_argument(s.command_fraction > 0.0 && s.command_fraction <= 1.0,
                 "GoToTargetSettings.command_fraction", "a fraction in (0, 1]", s.command_fraction);
}

/// The planar pose of the robot: position [m] and heading [rad] in the world frame.
struct PlanarPose {
  double x = 0.0, y = 0.0, yaw = 0.0;
};

/// What GoToTarget decided.
struct GoToTargetCommand {
  Eigen::Vector3d command = Eigen::Vector3d::Zero();  ///< (v_x, v_y, ω_z), robot frame
  bool reached = false;                               ///< within stop_distance: command is zero
  Eigen::Vector2d aim = Eigen::Vector2d::Zero();      ///< the point steered at, world frame
  double distance = 0.0;                              ///< to the target [m]
  int passing = -1;  ///< the index of the obstacle the aim goes around, −1: none blocks
};

/// Steers a robot to `target` within `max_command` (WalkingSettings::max_command: |v_x|, |v_y|,
/// |ω_z| bounds) around `obstacles`. Stateful only in one respect: once it has chosen the side
/// on which to pass an obstacle it keeps it until the obstacle no longer blocks the way, so
/// that a swaying pose estimate cannot make it dither between the two.
class GoToTarget {
 public:
  /// @throws walkgen::invalid_argument for non-finite inputs or settings out of range.
  GoToTarget(const Eigen::Vector2d& target, const Eigen::Vector3d& max_command,
             std::vector<CircleObstacle<double>> obstacles = {},
             const GoToTargetSettings& settings = GoToTargetSettings())
      : target_(target),
        max_command_(max_command),
        obstacles_(std::move(obstacles)),
        s_(settings),
        side_(obstacles_.size(), 0.0) {
    check_argument(target.allFinite(), "GoToTarget: target", "a finite point", "NaN or inf");
    check_argument(max_command.allFinite() && (max_command.array() >= 0.0).all(),
                   "GoToTarget: max_command", "finite bounds >= 0", "NaN, inf or negative");
    for (const auto& o : obstacles_) {
      check_argument(std::isfinite(o.x) && std::isfinite(o.y) && std::isfinite(o.radius) &&
                         o.radius > 0.0 && std::isfinite(o.margin) && o.margin >= 0.0,
                     "GoToTarget: obstacle", "finite centre, radius > 0, margin >= 0",
                     "NaN, inf or out of range");
    }
    validate(s_);
  }

  /// The command for a robot at `pose` (for a walking robot a steady estimate such as the
  /// middle of its feet, not the swaying CoM).
  /// @throws walkgen::invalid_argument for a non-finite pose.
  GoToTargetCommand operator()(const PlanarPose& pose) {
    check_argument(std::isfinite(pose.x) && std::isfinite(pose.y) && std::isfinite(pose.yaw),
                   "GoToTarget: pose", "finite x, y, yaw", "NaN or inf");
    GoToTargetCommand out;
    const Eigen::Vector2d p(pose.x, pose.y);
    out.distance = (target_ - p).norm();
    out.aim = target_;
    if (out.distance <= s_.stop_distance) {
      out.reached = true;
      return out;
    }
    const Eigen::Vector2d forward(std::cos(pose.yaw), std::sin(pose.yaw));
    const Eigen::Vector2d d = (target_ - p) / out.distance;
    // The nearest obstacle that blocks the straight line to the target decides the aim.
    double nearest = out.distance;
    double aim_limit = s_.max_aim_off_target;
    for (std::size_t i = 0; i < obstacles_.size(); ++i) {
      const auto& o = obstacles_[i];
      const Eigen::Vector2d c(o.x, o.y);
      const double r = o.radius + o.margin + s_.clearance;
      const double along = (c - p).dot(d);
      const double across = d.x() * (c - p).y() - d.y() * (c - p).x();  // > 0: centre on the left
      const double to_centre = (c - p).norm();
      const bool blocks = along > 0.0 && along < out.distance && std::abs(across) < r;
      if (!blocks) {
        side_[i] = 0.0;  // passed or out of the way: choose afresh next time
        continue;
      }
      if (along >= nearest) continue;
      nearest = along;
      out.passing = int(i);
      // Tangent directions of the circle seen from p: ±asin(r / |c − p|) from the centre's;
      // inside it, ±(90° + up to 90° outward, the deeper the more): along the circle.
      const double half =
          to_centre > r ? std::asin(r / to_centre) : kPi / 2.0 * (2.0 - to_centre / r);
      const double base = std::atan2(c.y() - p.y(), c.x() - p.x());
      if (side_[i] == 0.0 && s_.pass_side != PassSide::toward_heading) {
        side_[i] = s_.pass_side == PassSide::left    ? 1.0
                   : s_.pass_side == PassSide::right ? -1.0
                   : across > 0.0                    ? -1.0
                                                     : 1.0;
      }
      if (side_[i] == 0.0) {  // pass on the side of the tangent closer to the heading
        double best = 1e9;
        for (double side : {1.0, -1.0}) {
          const double a = base + side * half;
          const double turn = angle_distance(a, pose.yaw);
          if (turn < best) {
            best = turn;
            side_[i] = side;
          }
        }
      }
      const double a = base + side_[i] * half;
      const double tangent = std::sqrt(std::max(0.0, to_centre * to_centre - r * r));
      out.aim = p + Eigen::Vector2d(std::cos(a), std::sin(a)) * (tangent + s_.clearance);
      if (s_.aim_limit_opens_within > 0.0) {
        const double open = std::clamp(1.0 - (to_centre - r) / s_.aim_limit_opens_within, 0.0, 1.0);
        aim_limit = s_.max_aim_off_target + open * (kPi - s_.max_aim_off_target);
      }
    }
    Eigen::Vector2d to_aim = out.aim - p;
    const double off = std::atan2(d.x() * to_aim.y() - d.y() * to_aim.x(), d.dot(to_aim));
    if (std::abs(off) > aim_limit) {
      const double a = std::atan2(d.y(), d.x()) + std::copysign(aim_limit, off);
      to_aim = Eigen::Vector2d(std::cos(a), std::sin(a)) * to_aim.norm();
      out.aim = p + to_aim;
    }
    const double heading_error =
        std::atan2(forward.x() * to_aim.y() - forward.y() * to_aim.x(), forward.dot(to_aim));
    const Eigen::Vector3d limit = s_.command_fraction * max_command_;
    out.command.z() = std::clamp(s_.heading_gain * heading_error, -limit.z(), limit.z());
    const double align = std::max(0.0, 1.0 - std::abs(heading_error) / s_.turn_in_place_angle);
    const double approach =
        std::clamp((out.distance - s_.stop_distance) / s_.slow_down_distance, 0.0, 1.0);
    out.command.x() = limit.x() * align * std::max(approach, s_.min_speed_fraction);
    return out;
  }

  const Eigen::Vector2d& target() const { return target_; }

 private:
  Eigen::Vector2d target_;
  Eigen::Vector3d max_command_;
  std::vector<CircleObstacle<double>> obstacles_;
  GoToTargetSettings s_;
  std::vector<double> side_;  ///< per obstacle: +1 pass it on its left tangent, −1 right, 0 free
};

}  // namespace walkgen
