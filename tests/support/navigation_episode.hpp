#pragma once
// One navigation episode in a walkgen::NavigationScene (thesis §11.1): the humanoid in MuJoCo,
// closed loop (figure 6.1), a policy choosing the velocity command once per NMPC tick from what
// the robot sees (left RGB + WLS disparity of its chest stereo pair) or, for the scripted expert,
// from what it knows of the scene. Optionally records the episode as a demonstration (figure
// 7.2). Shared by examples/record_demonstrations.cpp, examples/bc_evaluate.cpp and the tests.

#include <mujoco/mujoco.h>

#include <Eigen/Core>
#include <functional>
#include <string>
#include <vector>

#include "support/simulated_tasks.hpp"
#include "walkgen/core/math.hpp"
#include "walkgen/mujoco/navigation_scene.hpp"
#include "walkgen/opencv/demonstration_recorder.hpp"
#include "walkgen/opencv/stereo_depth.hpp"

namespace walkgen_test {

/// What a policy sees at a tick.
struct NavigationObservation {
  double time = 0.0;                              ///< [s] since the episode started
  const walkgen::StereoImages* images = nullptr;  ///< both chest cameras (RGB, exact depth)
  const cv::Mat* disparity = nullptr;             ///< WLS disparity of the pair [px] (CV_32F)
  walkgen::PlanarPose pose;                       ///< the generator's estimate (middle of the feet)
  const walkgen::NavigationScene* scene = nullptr;  ///< for scripted experts only
};

using NavigationPolicy = std::function<Eigen::Vector3d(const NavigationObservation&)>;

struct NavigationOptions {
  double time_limit = 0.0;      ///< [s] simulated; 0: from the scene (distance and turning)
  double reach_distance = 0.3;  ///< success: the true CoM this close to the target's centre
  walkgen::DemonstrationRecorder* recorder = nullptr;  ///< records every tick when set
  /// The command the recorder records, when set (DAgger: the expert labels the states that
  /// the learner visits while the learner drives); else the executed command.
  NavigationPolicy label;
  std::function<void(walkgen::MujocoRobot&, double)> on_tick;  ///< e.g. to render a video
};

struct NavigationResult {
  bool reached = false;   ///< the true CoM came within reach_distance, no collision, no fall
  bool collided = false;  ///< the robot touched a wall, chair, crate or the person
  bool fell = false;
  std::string message;
  double time = 0.0;
  double final_distance = 0.0;            ///< true CoM to the target's centre [m]
  std::vector<Eigen::Vector3d> commands;  ///< one per tick
  std::vector<double> zmp_distance;       ///< NMPC vs measured ZMP per valid sample [m]
  long qp_failures = 0;
  long rejected_commands = 0;  ///< policy commands the loop rejected (non-finite): the last stays
};

/// The planar pose of a camera (position, heading of its optical axis x) in the world.
inline walkgen::PlanarPose camera_planar_pose(const walkgen::CameraImage& camera) {
  const Eigen::Matrix3d& r = camera.pose_W_C.linear();
  return {camera.pose_W_C.translation().x(), camera.pose_W_C.translation().y(),
          std::atan2(r(1, 0), r(0, 0))};
}

/// Half the horizontal field of view of a camera [rad].
inline double half_horizontal_fov(const walkgen::CameraImage& camera) {
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
/// - in view: walkgen::GoToTarget from the middle of the feet (the camera sways ±0.12 m with
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
  ScriptedExpert(const walkgen::NavigationScene& scene, const Eigen::Vector3d& max_command,
                 double stop_distance = 0.15)
      : scene_(scene),
        limit_(0.95 * max_command),
        steer_(scene.target, max_command, scene.obstacles_at(0.0, 0.12), [&] {
          walkgen::GoToTargetSettings s;
          s.stop_distance = stop_distance;
          s.heading_gain = 0.35;
          s.max_aim_off_target = 16.0 * walkgen::kPi / 180.0;  // the target stays in view
          s.aim_limit_opens_within = 0.25;                     // ... unless the chair is close
          s.pass_side = side_for(scene);                       // every chair on its left
          return s;
        }()) {}

  Eigen::Vector3d operator()(const NavigationObservation& o) {
    const walkgen::PlanarPose pose =
        o.images != nullptr ? camera_planar_pose(o.images->left) : o.pose;
    if (scene_.has_person &&
        in_sight(scene_.person.position(o.time), pose, 1.2, 60.0 * walkgen::kPi / 180.0)) {
      return Eigen::Vector3d::Zero();  // let the person pass
    }
    const walkgen::GoToTargetCommand steer = steer_(o.pose);
    if (o.images != nullptr) {
      const double bearing = bearing_of(scene_.target, pose);
      if (std::abs(bearing) < half_horizontal_fov(o.images->left) - 0.05) {
        seen_ = true;
      } else if (!seen_ || steer.passing < 0 || std::abs(bearing) > walkgen::kPi / 2.0) {
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
  static walkgen::PassSide side_for(const walkgen::NavigationScene& scene) {
    return scene.chairs.empty() ? walkgen::PassSide::toward_heading : walkgen::PassSide::left;
  }

  /// The direction of `point` seen from `pose`, from its heading, in (−π, π] (left > 0).
  static double bearing_of(const Eigen::Vector2d& point, const walkgen::PlanarPose& pose) {
    return std::remainder(std::atan2(point.y() - pose.y, point.x() - pose.x) - pose.yaw,
                          2.0 * walkgen::kPi);
  }

  /// Whether `point` is within `range` of `pose` and `half_angle` of its heading.
  static bool in_sight(const Eigen::Vector2d& point, const walkgen::PlanarPose& pose, double range,
                       double half_angle) {
    return (point - Eigen::Vector2d(pose.x, pose.y)).norm() < range &&
           std::abs(bearing_of(point, pose)) < half_angle;
  }

  const walkgen::NavigationScene& scene_;
  Eigen::Vector3d limit_;
  walkgen::GoToTarget steer_;
  bool seen_ = false;  ///< the target has been in view
};

/// Time to walk and turn to the scene's target at Heicub's speeds, with a margin.
inline double navigation_time_limit(const walkgen::NavigationScene& s) {
  const double turn = std::abs(std::atan2(s.target.y(), s.target.x()));
  return 30.0 + 1.6 * (s.target.norm() / 0.032 + turn / 0.071) + (s.has_person ? 60.0 : 0.0);
}

/// Geom ids of everything the robot must not touch (walls, chairs, crates, person).
inline std::vector<int> obstacle_geoms(const walkgen::MujocoRobot& robot) {
  std::vector<int> ids;
  for (const auto& o : robot.settings().objects) {
    if (!o.collides || o.name == "target" || o.name == "distractor") continue;
    const int id = mj_name2id(robot.model(), mjOBJ_GEOM, o.name.c_str());
    if (id >= 0) ids.push_back(id);
  }
  return ids;
}

inline bool touches(const mjData* d, const std::vector<int>& geoms) {
  for (int i = 0; i < d->ncon; ++i) {
    for (int g : geoms) {
      if (d->contact[i].geom1 == g || d->contact[i].geom2 == g) return true;
    }
  }
  return false;
}

/// The stereo pipeline of §3.1 with the thesis's parameters (RGB input) on the ideal simulated
/// pair that `images` (a successful MujocoRobot::render_cameras) came from.
inline walkgen::StereoDepth make_stereo_depth(const walkgen::StereoImages& images) {
  const walkgen::PinholeIntrinsics k =
      walkgen::pinhole_from_fovy(images.left.width, images.left.height, images.left.fovy);
  const double baseline =
      (images.left.pose_W_C.translation() - images.right.pose_W_C.translation()).norm();
  walkgen::StereoDepthSettings settings;
  settings.rgb_input = true;
  return walkgen::StereoDepth(settings, walkgen::ideal_disparity_to_depth(k, baseline));
}

/// Runs `policy` in `scene` until the robot reaches the target, collides, falls, or the time
/// limit passes.
inline NavigationResult run_navigation_episode(const walkgen::NavigationScene& scene,
                                               const NavigationPolicy& policy,
                                               const NavigationOptions& options = {}) {
  NavigationResult result;
  static const walkgen::KinematicTree<double> tree = humanoid_tree();
  walkgen::MujocoRobotSettings robot_settings;
  robot_settings.objects = scene.objects();
  walkgen::MujocoRobot robot(robot_settings);
  HumanoidIk ik(tree);
  walkgen::WalkingSettings<double> settings = walkgen::heicub_settings();
  settings.obstacles = scene.obstacles_at(0.0, 0.12);  // capacity for chairs and the person
  SimLoop loop(settings, robot, ik);
  const std::vector<int> forbidden = obstacle_geoms(robot);

  const walkgen::LoopTick& started = loop.start();
  if (started.status != walkgen::LoopStatus::ok) {
    result.fell = true;
    result.message = started.message;
    return result;
  }
  const double t0 = robot.output().time;
  const double limit = options.time_limit > 0.0 ? options.time_limit : navigation_time_limit(scene);

  const walkgen::StereoImages& first = robot.render_cameras();
  if (first.status != walkgen::RenderStatus::ok) {
    result.message = first.message;
    return result;
  }
  walkgen::StereoDepth stereo = make_stereo_depth(first);

  while (true) {
    const double t = robot.output().time - t0;
    if (scene.has_person) {
      const Eigen::Vector2d p = scene.person.position(t);
      robot.set_object_position("person", {p.x(), p.y(), 0.0});
      loop.mpc().set_obstacles(scene.obstacles_at(t, 0.12));
    }
    const walkgen::StereoImages& images = robot.render_cameras();
    const cv::Mat left(images.left.height, images.left.width, CV_8UC3,
                       const_cast<std::uint8_t*>(images.left.rgb.data()));
    const cv::Mat right(images.right.height, images.right.width, CV_8UC3,
                        const_cast<std::uint8_t*>(images.right.rgb.data()));
    const walkgen::StereoDepthFrame& frame = stereo.compute(left, right);
    NavigationObservation obs;
    obs.time = t;
    obs.images = &images;
    obs.disparity = &frame.disparity;
    obs.pose = walking_pose(loop.mpc().state());
    obs.scene = &scene;
    Eigen::Vector3d command = policy(obs);
    command = command.cwiseMax(-0.95 * settings.max_command).cwiseMin(0.95 * settings.max_command);
    if (options.recorder != nullptr) {
      const Eigen::Vector3d label = options.label ? options.label(obs) : command;
      options.recorder->record(t, images.left, frame.disparity, label);
    }
    result.commands.push_back(command);
    result.rejected_commands += loop.set_command(command) != walkgen::CommandStatus::accepted;
    const walkgen::LoopTick& tick = loop.tick();
    result.qp_failures += tick.mpc != walkgen::MpcStatus::solved;
    for (const auto& s : loop.samples()) {
      if (s.zmp.valid) {
        result.zmp_distance.push_back(
            std::hypot(s.zmp.zmp_W.x() - s.plan.zmp_x, s.zmp.zmp_W.y() - s.plan.zmp_y));
      }
    }
    if (options.on_tick) options.on_tick(robot, t);
    result.time = robot.output().time - t0;
    result.final_distance = (true_com(robot) - scene.target).norm();
    if (tick.status == walkgen::LoopStatus::fallen ||
        tick.status == walkgen::LoopStatus::diverged) {
      result.fell = true;
      result.message = tick.message;
      break;
    }
    if (touches(robot.data(), forbidden)) {
      result.collided = true;
      result.message = "touched an obstacle at t = " + std::to_string(result.time) + " s";
      break;
    }
    if (result.final_distance <= options.reach_distance) {
      result.reached = true;
      break;
    }
    if (result.time >= limit) {
      result.message = "time limit " + std::to_string(limit) + " s";
      break;
    }
  }
  return result;
}

}  // namespace walkgen_test
