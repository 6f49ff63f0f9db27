#pragma once
/// @file
/// One navigation episode in a walkgen::NavigationScene (thesis §11.1): the humanoid in MuJoCo,
/// closed loop (figure 6.1, SimLoop), a policy choosing the velocity command once per NMPC tick
/// from what the robot sees (left RGB + WLS disparity of its chest stereo pair) or, for the
/// scripted expert (walkgen/navigation/scripted_expert.hpp), from what it knows of the scene.
/// Optionally records the episode as a demonstration (figure 7.2). Run by
/// examples/record_demonstrations, examples/bc_evaluate and the tests.
///
/// Target walkgen::navigation: needs walkgen::simulation (MuJoCo, Ceres, URDF) and
/// walkgen::opencv.

#include <mujoco/mujoco.h>

#include <Eigen/Core>
#include <cmath>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "walkgen/mujoco/navigation_scene.hpp"
#include "walkgen/opencv/demonstration_recorder.hpp"
#include "walkgen/opencv/stereo_depth.hpp"
#include "walkgen/simulation/humanoid_loop.hpp"

namespace walkgen {

/// What a policy sees at a tick.
struct NavigationObservation {
  double time = 0.0;                       ///< [s] since the episode started
  const StereoImages* images = nullptr;    ///< both chest cameras (RGB, exact depth)
  const cv::Mat* disparity = nullptr;      ///< WLS disparity of the pair [px] (CV_32F)
  PlanarPose pose;                         ///< the generator's estimate (middle of the feet)
  const NavigationScene* scene = nullptr;  ///< for scripted experts only
};

/// A policy: the command (v_x, v_y, ω_z) for an observation; clipped to 95 % of
/// heicub_settings().max_command before it is applied.
using NavigationPolicy = std::function<Eigen::Vector3d(const NavigationObservation&)>;

/// How run_navigation_episode() runs and what it records.
struct NavigationOptions {
  double time_limit = 0.0;      ///< [s] simulated; 0: from the scene (distance and turning)
  double reach_distance = 0.3;  ///< success: the true CoM this close to the target's centre
  DemonstrationRecorder* recorder = nullptr;  ///< records every tick when set
  /// The command the recorder records, when set (DAgger: the expert labels the states that
  /// the learner visits while the learner drives); else the executed command.
  NavigationPolicy label;
  std::function<void(MujocoRobot&, double)> on_tick;  ///< e.g. to render a video
  /// When the loop stopped the robot because the NMPC found no plan (StopReason::qp_failures,
  /// e.g. the person stepped in the way), the walk starts again from where the robot stands,
  /// at most this often per episode; then the episode ends with NavigationStatus::fault.
  int max_restarts = 10;
};

/// Checks how an episode runs (run_navigation_episode() calls this).
/// @throws walkgen::invalid_argument naming the first bad field.
inline void validate(const NavigationOptions& o) {
  check_non_negative("NavigationOptions.time_limit", o.time_limit,
                     "a finite time limit >= 0 s (0: from the scene)");
  check_positive("NavigationOptions.reach_distance", o.reach_distance, "a finite distance > 0 m");
  check_argument(o.max_restarts >= 0, "NavigationOptions.max_restarts", "a count >= 0",
                 o.max_restarts);
}

/// How a navigation episode ended.
enum class NavigationStatus : std::uint8_t {
  reached,             ///< the true CoM came within reach_distance, no collision, no fall
  collided,            ///< the robot touched a wall, chair, crate or the person
  fallen,              ///< the robot fell (also while moving its CoM over a foot at the start)
  diverged,            ///< the simulation diverged
  timed_out,           ///< the time limit passed first
  render_unavailable,  ///< the cameras cannot render (no GL context): nothing was run
  /// the loop stopped the walk for a fault (LoopStatus::fault: an IK failure streak, a sensor
  /// fault, ...; the message says which)
  fault,
};

/// The enumerator's name ("reached", ...), e.g. for logs; "unknown" for a value out of range.
constexpr const char* to_string(NavigationStatus status) noexcept {
  switch (status) {
    case NavigationStatus::reached:
      return "reached";
    case NavigationStatus::collided:
      return "collided";
    case NavigationStatus::fallen:
      return "fallen";
    case NavigationStatus::diverged:
      return "diverged";
    case NavigationStatus::timed_out:
      return "timed_out";
    case NavigationStatus::fault:
      return "fault";
    case NavigationStatus::render_unavailable:
      return "render_unavailable";
  }
  return "unknown";
}

/// What an episode did.
struct NavigationResult {
  NavigationStatus status = NavigationStatus::timed_out;
  bool reached = false;         ///< status reached
  bool collided = false;        ///< status collided
  bool fell = false;            ///< status fallen or diverged (also before the walk started)
  std::string message;          ///< why the episode ended, unless it reached the target
  double time = 0.0;            ///< simulated [s], the start's CoM transfer excluded
  double final_distance = 0.0;  ///< true CoM to the target's centre [m]
  std::vector<Eigen::Vector3d> commands;  ///< one per tick
  std::vector<double> zmp_distance;       ///< NMPC vs measured ZMP per valid sample [m]
  long qp_failures = 0;                   ///< ticks whose NMPC did not solve
  int restarts = 0;  ///< walks started again after a stop for QP failures (max_restarts)
  /// policy commands the loop did not walk as given (non-finite: rejected, the last stays)
  long rejected_commands = 0;
};

/// Time to walk and turn to the scene's target at Heicub's speeds, with a margin.
inline double navigation_time_limit(const NavigationScene& s) {
  const double turn = std::abs(std::atan2(s.target.y(), s.target.x()));
  return 30.0 + 1.6 * (s.target.norm() / 0.032 + turn / 0.071) + (s.has_person ? 60.0 : 0.0);
}

namespace detail {

/// Geom ids of everything the robot must not touch (walls, chairs, crates, person).
inline std::vector<int> obstacle_geoms(const MujocoRobot& robot) {
  std::vector<int> ids;
  for (const auto& o : robot.settings().objects) {
    if (!o.collides || o.name == "target" || o.name == "distractor") continue;
    const int id = mj_name2id(robot.model(), mjOBJ_GEOM, o.name.c_str());
    if (id >= 0) ids.push_back(id);
  }
  return ids;
}

/// An episode that the robot ended (fallen or diverged, LoopTick::status) or the loop stopped
/// for a fault, with its message.
inline void set_stopped(NavigationResult& result, const LoopTick& tick) {
  result.status = tick.status == LoopStatus::diverged ? NavigationStatus::diverged
                  : tick.status == LoopStatus::fault  ? NavigationStatus::fault
                                                      : NavigationStatus::fallen;
  result.fell = tick.status == LoopStatus::fallen || tick.status == LoopStatus::diverged;
  result.message = tick.message;
}

/// Whether a contact of `d` involves one of `geoms`.
inline bool touches_any(const mjData* d, const std::vector<int>& geoms) {
  for (int i = 0; i < d->ncon; ++i) {
    for (int g : geoms) {
      if (d->contact[i].geom1 == g || d->contact[i].geom2 == g) return true;
    }
  }
  return false;
}

}  // namespace detail

/// The stereo pipeline of §3.1 with the thesis's parameters (RGB input) on the ideal simulated
/// pair that `images` (a successful MujocoRobot::render_cameras) came from.
inline StereoDepth make_stereo_depth(const StereoImages& images) {
  const PinholeIntrinsics k =
      pinhole_from_fovy(images.left.width, images.left.height, images.left.fovy);
  const double baseline =
      (images.left.pose_W_C.translation() - images.right.pose_W_C.translation()).norm();
  StereoDepthSettings settings;
  settings.rgb_input = true;
  return StereoDepth(settings, ideal_disparity_to_depth(k, baseline));
}

/// Runs `policy` in `scene` until the robot reaches the target, collides, falls, or the time
/// limit passes. Heicub's settings with the scene's chairs and person as NMPC obstacles
/// (margin 0.12 m; the person's circle moves every tick). Numerical outcomes (QP failures, a
/// fall, a failed render) are in the result, never thrown.
/// @throws walkgen::invalid_argument for invalid options (validate()) or when the humanoid's
///   model cannot be loaded.
inline NavigationResult run_navigation_episode(const NavigationScene& scene,
                                               const NavigationPolicy& policy,
                                               const NavigationOptions& options = {}) {
  validate(options);
  NavigationResult result;
  static const KinematicTree<double> tree = humanoid_tree();
  const RobotDescription humanoid = walkgen_humanoid_description();
  MujocoRobotSettings robot_settings = mujoco_robot_settings(humanoid);
  robot_settings.objects = scene.objects();
  MujocoRobot robot(robot_settings);
  HumanoidIk ik(tree);
  WalkingSettings<double> settings = humanoid.walking;
  settings.obstacles = scene.obstacles_at(0.0, 0.12);  // capacity for chairs and the person
  SimLoop loop(settings, robot, ik);
  const std::vector<int> forbidden = detail::obstacle_geoms(robot);

  const LoopTick& started = loop.start();
  if (started.status != LoopStatus::ok) {
    detail::set_stopped(result, started);
    return result;
  }
  const double t0 = robot.output().time;
  const double limit = options.time_limit > 0.0 ? options.time_limit : navigation_time_limit(scene);

  const StereoImages& first = robot.render_cameras();
  if (first.status != RenderStatus::ok) {
    result.status = NavigationStatus::render_unavailable;
    result.message = first.message;
    return result;
  }
  StereoDepth stereo = make_stereo_depth(first);

  while (true) {
    const double t = robot.output().time - t0;
    if (scene.has_person) {
      const Eigen::Vector2d p = scene.person.position(t);
      robot.set_object_position("person", {p.x(), p.y(), 0.0});
      loop.mpc().set_obstacles(scene.obstacles_at(t, 0.12));
    }
    const StereoImages& images = robot.render_cameras();
    const cv::Mat left(images.left.height, images.left.width, CV_8UC3,
                       const_cast<std::uint8_t*>(images.left.rgb.data()));
    const cv::Mat right(images.right.height, images.right.width, CV_8UC3,
                        const_cast<std::uint8_t*>(images.right.rgb.data()));
    const StereoDepthFrame& frame = stereo.compute(left, right);
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
    result.rejected_commands += loop.set_command(command) != CommandStatus::accepted;
    const LoopTick& tick = loop.tick();
    result.qp_failures += tick.mpc != MpcStatus::solved;
    for (const auto& s : loop.samples()) {
      if (s.zmp.valid) {
        result.zmp_distance.push_back(
            std::hypot(s.zmp.zmp_W.x() - s.plan.zmp_x, s.zmp.zmp_W.y() - s.plan.zmp_y));
      }
    }
    if (options.on_tick) options.on_tick(robot, t);
    result.time = robot.output().time - t0;
    result.final_distance = (true_com(robot) - scene.target).norm();
    // A stop (stopping: the step is finished, the CoM moves between the feet) is ticked through;
    // a walk stopped for QP failures starts again, any other fault or stop ends the episode.
    const bool replan = tick.mode == LoopMode::stopped && tick.reason == StopReason::qp_failures &&
                        result.restarts < options.max_restarts;
    if (tick.status == LoopStatus::fallen || tick.status == LoopStatus::diverged ||
        tick.mode == LoopMode::fault || (tick.mode == LoopMode::stopped && !replan)) {
      detail::set_stopped(result, tick);
      break;
    }
    if (replan) {
      ++result.restarts;
      const LoopTick& restarted = loop.start();
      if (restarted.status != LoopStatus::ok) {
        detail::set_stopped(result, restarted);
        break;
      }
    }
    if (detail::touches_any(robot.data(), forbidden)) {
      result.status = NavigationStatus::collided;
      result.collided = true;
      result.message = "touched an obstacle at t = " + std::to_string(result.time) + " s";
      break;
    }
    if (result.final_distance <= options.reach_distance) {
      result.status = NavigationStatus::reached;
      result.reached = true;
      break;
    }
    if (result.time >= limit) {
      result.status = NavigationStatus::timed_out;
      result.message = "time limit " + std::to_string(limit) + " s";
      break;
    }
  }
  return result;
}

}  // namespace walkgen
