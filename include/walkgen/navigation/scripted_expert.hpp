#pragma once
/// @file
/// The scripted expert of behavioural cloning (thesis §7.1.2, §11.1): a navigation policy that
/// knows the scene (walkgen::NavigationScene) but decides from what the left chest camera can
/// see, so that a network trained on its demonstrations (examples/record_demonstrations) can
/// imitate it; examples/bc_evaluate also asks it where a network ends up (DAgger).
///
/// Target walkgen::navigation: needs walkgen::simulation (MuJoCo, Ceres, URDF) and
/// walkgen::opencv.

#include <Eigen/Core>
#include <cmath>

#include "walkgen/control/go_to_target.hpp"
#include "walkgen/core/math.hpp"
#include "walkgen/navigation/navigation_episode.hpp"

namespace walkgen {

/// The planar pose of a camera (position, heading of its optical axis x) in the world.
inline PlanarPose camera_planar_pose(const CameraImage& camera) {
  const Eigen::Matrix3d& r = camera.pose_W_C.linear();
  return {camera.pose_W_C.translation().x(), camera.pose_W_C.translation().y(),
          std::atan2(r(1, 0), r(0, 0))};
}

/// Half the horizontal field of view of a camera [rad].
inline double half_horizontal_fov(const CameraImage& camera) {
  return std::atan(std::tan(camera.fovy / 2.0) * double(camera.width) / double(camera.height));
}

/// The scripted expert that records the demonstrations. It knows the scene, but decides what
/// is in view from the left chest camera's pose, so that a network which sees its images can
/// imitate it (a first expert turned toward targets outside the view and saturated ω at 4° of
/// heading error, and cloning it did not learn):
/// - the target outside the view (±(half the field of view − 0.05 rad)): turn on the spot,
///   toward it the shorter way once it has been in view in this episode, else to the right
///   until it comes into view (the search turn of figure 11.9); except while passing a chair
///   with the target less than 90° off: then it keeps going around;
/// - in view: GoToTarget from the middle of the feet (the camera sways ±0.12 m with
///   the gait, which swung the aim near the chair), with a gentle heading gain (ω saturates at
///   12° of bearing), aiming at most 16° off the target so that it stays in view; the limit
///   opens within 0.25 m of a chair's inflated circle, so that a robot which walked up to the
///   chair (where DAgger asks the expert) is led around it; every chair is passed on its left
///   (side_for); sideways velocity never used (as the thesis's users did,
///   §11.1.1); stop with the middle of the feet 0.15 m from the target's centre;
/// - the person within 1.2 m and 60° of the camera's axis: wait until it has passed.
/// Without images (o.images null) it never searches.
class ScriptedExpert {
 public:
  /// `scene` must outlive the expert (it is kept by reference); `max_command` is the
  /// generator's (heicub_settings().max_command); `stop_distance` [m] from the target's centre.
  /// @throws walkgen::invalid_argument as GoToTarget's constructor.
  ScriptedExpert(const NavigationScene& scene, const Eigen::Vector3d& max_command,
                 double stop_distance = 0.15)
      : scene_(scene),
        limit_(0.95 * max_command),
        steer_(scene.target, max_command, scene.obstacles_at(0.0, kNavigationObstacleMargin), [&] {
          GoToTargetSettings s;
          s.stop_distance = stop_distance;
          s.heading_gain = 0.35;
          s.max_aim_off_target = 16.0 * kPi / 180.0;  // the target stays in view
          s.aim_limit_opens_within = 0.25;            // ... unless the chair is close
          s.pass_side = side_for(scene);              // every chair on its left
          return s;
        }()) {}

  /// The command (v_x, v_y, ω_z) for an observation of run_navigation_episode().
  Eigen::Vector3d operator()(const NavigationObservation& o) {
    const PlanarPose pose = o.images != nullptr ? camera_planar_pose(o.images->left) : o.pose;
    if (scene_.has_person &&
        in_sight(scene_.person.position(o.time), pose, 1.2, 60.0 * kPi / 180.0)) {
      return Eigen::Vector3d::Zero();  // let the person pass
    }
    const GoToTargetCommand steer = steer_(o.pose);
    if (o.images != nullptr) {
      const double bearing = bearing_of(scene_.target, pose);
      if (std::abs(bearing) < half_horizontal_fov(o.images->left) - 0.05) {
        seen_ = true;
      } else if (!seen_ || steer.passing < 0 || std::abs(bearing) > kPi / 2.0) {
        return {0.0, 0.0, seen_ ? std::copysign(limit_.z(), bearing) : -limit_.z()};
      }
    }
    Eigen::Vector3d c = steer.command;
    c.y() = 0.0;
    return c;
  }

 private:
  /// The way around a chair: always on its left, the chair staying on the robot's right (a
  /// convention, like keeping right on a road). The shorter way, away from the chair's centre
  /// as seen from the line to the target, depends on the chair's 0–0.08 m offset from that
  /// line, a few pixels in the first image and nothing once the chair fills the view; a
  /// network cloned from it passed 12 of 12 chairs right of the line, 2 of 8 left of it.
  /// Without chairs (the person of the dynamic room, whom the expert waits for): the side
  /// closer to the heading.
  static PassSide side_for(const NavigationScene& scene) {
    return scene.chairs.empty() ? PassSide::toward_heading : PassSide::left;
  }

  /// The direction of `point` seen from `pose`, from its heading, in (−π, π] (left > 0).
  static double bearing_of(const Eigen::Vector2d& point, const PlanarPose& pose) {
    return std::remainder(std::atan2(point.y() - pose.y, point.x() - pose.x) - pose.yaw, 2.0 * kPi);
  }

  /// Whether `point` is within `range` of `pose` and `half_angle` of its heading.
  static bool in_sight(const Eigen::Vector2d& point, const PlanarPose& pose, double range,
                       double half_angle) {
    return (point - Eigen::Vector2d(pose.x, pose.y)).norm() < range &&
           std::abs(bearing_of(point, pose)) < half_angle;
  }

  const NavigationScene& scene_;
  Eigen::Vector3d limit_;
  GoToTarget steer_;
  bool seen_ = false;  ///< the target has been in view
};

}  // namespace walkgen
