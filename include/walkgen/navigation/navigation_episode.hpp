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
#include <memory>
#include <string>
#include <vector>

#include "walkgen/core/assert.hpp"
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

/// One navigation episode, a tick at a time: the robot of run_navigation_episode() in `scene`,
/// observed (observe(): the person moved, both cameras rendered, the stereo disparity computed)
/// and commanded (step(): the command clamped, recorded, walked for one NMPC tick, the end
/// checked). run_navigation_episode() drives it with a policy; the Python environment
/// walkgen.envs.NavigationEnv with actions. Not copyable or movable (the loop borrows the robot
/// and the IK).
class NavigationEpisode {
 public:
  /// Builds the robot in `scene` (its objects and look, NavigationScene::appearance) and
  /// starts the walk; done() when that or the first render failed (result() says why). Heicub's
  /// settings with the scene's chairs and person as NMPC obstacles (kNavigationObstacleMargin;
  /// the person's circle moves every tick).
  /// @throws walkgen::invalid_argument for invalid options (validate()), an invalid appearance
  ///   of the scene (validate()) or when the humanoid's model cannot be loaded.
  explicit NavigationEpisode(const NavigationScene& scene, NavigationOptions options = {})
      : scene_(scene), options_((validate(options), std::move(options))) {
    static const KinematicTree<double> tree = humanoid_tree();
    validate(scene_.appearance);
    const RobotDescription humanoid = walkgen_humanoid_description();
    MujocoRobotSettings robot_settings = mujoco_robot_settings(humanoid);
    robot_settings.objects = scene_.objects();
    robot_settings.appearance = scene_.appearance.world;
    robot_ = std::make_unique<MujocoRobot>(robot_settings);
    ik_ = std::make_unique<HumanoidIk>(tree);
    settings_ = humanoid.walking;
    settings_.obstacles =
        scene_.obstacles_at(0.0, kNavigationObstacleMargin);  // capacity for chairs and the person
    loop_ = std::make_unique<SimLoop>(settings_, *robot_, *ik_);
    forbidden_ = detail::obstacle_geoms(*robot_);

    const LoopTick& started = loop_->start();
    if (started.status != LoopStatus::ok) {
      detail::set_stopped(result_, started);
      done_ = true;
      return;
    }
    t0_ = robot_->output().time;
    limit_ = options_.time_limit > 0.0 ? options_.time_limit : navigation_time_limit(scene_);
    const StereoImages& first = robot_->render_cameras();
    if (first.status != RenderStatus::ok) {
      result_.status = NavigationStatus::render_unavailable;
      result_.message = first.message;
      done_ = true;
      return;
    }
    stereo_ = std::make_unique<StereoDepth>(make_stereo_depth(first));
  }
  NavigationEpisode(const NavigationEpisode&) = delete;
  NavigationEpisode& operator=(const NavigationEpisode&) = delete;

  /// The episode has ended (result().status says how).
  bool done() const { return done_; }
  const NavigationResult& result() const { return result_; }

  /// Whether observe() may be called: the walk started and the cameras rendered (also after
  /// the episode ended, to see where it ended).
  bool can_observe() const { return stereo_ != nullptr; }

  /// What the robot sees now: the person moved to where it is, both cameras rendered, the WLS
  /// disparity of the pair. Valid until the next observe(). Needs can_observe().
  const NavigationObservation& observe() {
    WALKGEN_ASSERT(can_observe());
    const double t = robot_->output().time - t0_;
    move_person(scene_, t, *robot_, loop_->mpc());
    const StereoImages& images = robot_->render_cameras();
    const cv::Mat left(images.left.height, images.left.width, CV_8UC3,
                       const_cast<std::uint8_t*>(images.left.rgb.data()));
    const cv::Mat right(images.right.height, images.right.width, CV_8UC3,
                        const_cast<std::uint8_t*>(images.right.rgb.data()));
    const StereoDepthFrame& frame = stereo_->compute(left, right);
    obs_ = NavigationObservation{};
    obs_.time = t;
    obs_.images = &images;
    obs_.disparity = &frame.disparity;
    obs_.pose = walking_pose(loop_->mpc().state());
    obs_.scene = &scene_;
    observed_ = true;
    return obs_;
  }

  /// Walks one NMPC tick with `command` (clipped to 95 % of the settings' max_command), after
  /// observe() (called here when it was not since the last step). Records the tick when the
  /// options have a recorder, then checks how the episode stands.
  /// @returns done()
  bool step(Eigen::Vector3d command) {
    WALKGEN_ASSERT(!done_);
    if (!observed_) observe();
    observed_ = false;
    command =
        command.cwiseMax(-0.95 * settings_.max_command).cwiseMin(0.95 * settings_.max_command);
    if (options_.recorder != nullptr) {
      const Eigen::Vector3d label = options_.label ? options_.label(obs_) : command;
      options_.recorder->record(obs_.time, obs_.images->left, *obs_.disparity, label);
    }
    result_.commands.push_back(command);
    result_.rejected_commands += loop_->set_command(command) != CommandStatus::accepted;
    const LoopTick& tick = loop_->tick();
    // not solved, not relaxed (a relaxed plan comes from a solved elastic QP:
    // WalkingSettings::soft)
    result_.qp_failures += tick.mpc != MpcStatus::solved && tick.mpc != MpcStatus::relaxed;
    for (const auto& s : loop_->samples()) {
      if (s.zmp.valid) {
        result_.zmp_distance.push_back(
            std::hypot(s.zmp.zmp_W.x() - s.plan.zmp_x, s.zmp.zmp_W.y() - s.plan.zmp_y));
      }
    }
    if (options_.on_tick) options_.on_tick(*robot_, obs_.time);
    result_.time = robot_->output().time - t0_;
    result_.final_distance = (true_com(*robot_) - scene_.target).norm();
    done_ = check_end(tick);
    return done_;
  }

  MujocoRobot& robot() { return *robot_; }
  const SimLoop& loop() const { return *loop_; }
  const NavigationScene& scene() const { return scene_; }
  /// The simulated time the episode may take [s].
  double time_limit() const { return limit_; }
  /// The clip of step()'s commands: 95 % of the walking settings' max_command.
  Eigen::Vector3d max_command() const { return 0.95 * settings_.max_command; }

 private:
  /// A stop (stopping: the step is finished, the CoM moves between the feet) is ticked through;
  /// a walk stopped for QP failures starts again, any other fault or stop ends the episode.
  bool check_end(const LoopTick& tick) {
    const bool replan = tick.mode == LoopMode::stopped && tick.reason == StopReason::qp_failures &&
                        result_.restarts < options_.max_restarts;
    if (tick.status == LoopStatus::fallen || tick.status == LoopStatus::diverged ||
        tick.mode == LoopMode::fault || (tick.mode == LoopMode::stopped && !replan)) {
      detail::set_stopped(result_, tick);
      return true;
    }
    if (replan) {
      ++result_.restarts;
      const LoopTick& restarted = loop_->start();
      if (restarted.status != LoopStatus::ok) {
        detail::set_stopped(result_, restarted);
        return true;
      }
    }
    if (detail::touches_any(robot_->data(), forbidden_)) {
      result_.status = NavigationStatus::collided;
      result_.collided = true;
      result_.message = "touched an obstacle at t = " + std::to_string(result_.time) + " s";
      return true;
    }
    if (result_.final_distance <= options_.reach_distance) {
      result_.status = NavigationStatus::reached;
      result_.reached = true;
      return true;
    }
    if (result_.time >= limit_) {
      result_.status = NavigationStatus::timed_out;
      result_.message = "time limit " + std::to_string(limit_) + " s";
      return true;
    }
    return false;
  }

  NavigationScene scene_;
  NavigationOptions options_;
  WalkingSettings<double> settings_;
  std::unique_ptr<MujocoRobot> robot_;
  std::unique_ptr<HumanoidIk> ik_;
  std::unique_ptr<SimLoop> loop_;
  std::unique_ptr<StereoDepth> stereo_;
  std::vector<int> forbidden_;
  NavigationResult result_;
  NavigationObservation obs_;
  double t0_ = 0.0, limit_ = 0.0;
  bool done_ = false, observed_ = false;
};

/// Runs `policy` in `scene` until the robot reaches the target, collides, falls, or the time
/// limit passes (a NavigationEpisode, observed and stepped once per NMPC tick). Numerical
/// outcomes (QP failures, a fall, a failed render) are in the result, never thrown.
/// @throws walkgen::invalid_argument for invalid options or an invalid appearance of the scene
///   (validate()), or when the humanoid's model cannot be loaded.
inline NavigationResult run_navigation_episode(const NavigationScene& scene,
                                               const NavigationPolicy& policy,
                                               const NavigationOptions& options = {}) {
  NavigationEpisode episode(scene, options);
  while (!episode.done()) (void)episode.step(policy(episode.observe()));
  return episode.result();
}

}  // namespace walkgen
