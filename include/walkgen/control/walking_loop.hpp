#pragma once
/// @file
/// The closed walking loop of thesis figure 6.1 (§6.1, §6.3): velocity command → NMPC →
/// interpolation at the command period → whole-body inverse kinematics → joint targets →
/// robot, with the centre of mass fed back from forward kinematics of the measured joints every
/// t_feedback, and the zero moment point measured by the ankle force-torque sensors
/// (eq. 2.11–2.17) logged beside the generator's.
///
/// Core (Eigen only): the robot is any walkgen::Robot (e.g. walkgen::MujocoRobot) and the inverse
/// kinematics any solver with CeresInverseKinematics' interface (walkgen::ceres provides that
/// one):
///
///     walkgen::MujocoRobot robot;
///     walkgen::CeresInverseKinematics<15> ik(tree);
///     walkgen::WalkingLoop<16, walkgen::CeresInverseKinematics<15>> loop(
///         walkgen::heicub_settings(), robot, ik);
///     if (loop.start().status != walkgen::LoopStatus::ok) { /* the robot is not standing */ }
///     if (loop.set_command({0.03, 0.0, 0.0}) != walkgen::CommandStatus::accepted) { /* ... */ }
///     while (loop.tick().status == walkgen::LoopStatus::ok) {
///       for (const auto& s : loop.samples()) { /* s.plan.zmp_x vs s.zmp.zmp_W.x(), ... */ }
///     }
///
/// Safety (docs/safety.md): every tick reports a LoopMode and a StopReason. request_stop()
/// finishes the step and stands the robot on both feet (walking → stopping → stopped); streaks
/// of failed QPs or saturated motors stop it the same way; streaks of failed IK solves,
/// non-finite or out-of-range measurements and a fall end in LoopMode::fault, where the last
/// joint targets are held. Keep calling tick() in every mode: it carries the stop out and then
/// holds the robot. Numerical trouble is a status, never an exception out of tick().
///
/// The world frame is the generator's: at start() the robot is placed so that its support sole
/// (WalkingSettings::support_foot) is at the settings' foot pose, flat on the ground. A real
/// robot measures no base pose, and neither does the loop: the measured CoM is forward
/// kinematics from the current support sole, assumed where the plan put it (as the thesis does).

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "walkgen/control/pattern_targets.hpp"
#include "walkgen/core/exceptions.hpp"
#include "walkgen/core/foot.hpp"
#include "walkgen/core/math.hpp"
#include "walkgen/estimation/base_estimator.hpp"
#include "walkgen/interpolation/polynomial.hpp"
#include "walkgen/interpolation/trajectory.hpp"
#include "walkgen/kinematics/ik_target.hpp"
#include "walkgen/kinematics/kinematic_tree.hpp"
#include "walkgen/mpc/walking_mpc.hpp"
#include "walkgen/robot/robot.hpp"
#include "walkgen/robot/robot_description.hpp"

namespace walkgen {

/// What a tick of the loop ended with. Anything but ok, qp_failed, not_converged or relaxed
/// stops the walk.
enum class LoopStatus : std::uint8_t {
  ok,           ///< the tick's samples were executed
  qp_failed,    ///< the NMPC kept its previous (shifted) plan, which was executed; see MpcStatus
  fallen,       ///< the robot reports a fall (RobotStatus::fallen); the loop stops
  diverged,     ///< the simulation diverged (RobotStatus::diverged); the loop stops
  not_started,  ///< tick() before start(), or after the robot stopped
  /// the NMPC's plan, executed, violates its nonlinear constraints by more than sqp_tolerance
  /// (MpcStatus::not_converged; LoopTick::mpc and the generator's result say by how much)
  not_converged,
  /// a fault ended the walk (LoopTick::reason, LoopTick::message): the loop stops the robot or
  /// holds it (LoopTick::mode)
  fault,
  /// the NMPC's QP was infeasible and its soft constraints (WalkingSettings::soft) gave the
  /// least-violating plan, which was executed (MpcStatus::relaxed; the generator's result names
  /// the violated blocks)
  relaxed,
};

/// The enumerator's name ("ok", ...), e.g. for logs; "unknown" for a value out of range.
constexpr const char* to_string(LoopStatus s) noexcept {
  switch (s) {
    case LoopStatus::ok:
      return "ok";
    case LoopStatus::qp_failed:
      return "qp_failed";
    case LoopStatus::fallen:
      return "fallen";
    case LoopStatus::diverged:
      return "diverged";
    case LoopStatus::not_started:
      return "not_started";
    case LoopStatus::not_converged:
      return "not_converged";
    case LoopStatus::fault:
      return "fault";
    case LoopStatus::relaxed:
      return "relaxed";
  }
  return "unknown";
}

/// Where the loop's safety state machine stands (docs/safety.md).
enum class LoopMode : std::uint8_t {
  idle,     ///< before the first start()
  walking,  ///< the NMPC's plans are executed
  /// the current step is finished along the plan (velocity command zero), then the CoM moves
  /// between the feet in WalkingLoopSettings::transfer_time
  stopping,
  stopped,  ///< on both feet with the CoM between them, the joint targets held; start() walks on
  /// the last joint targets held (damping mode), or the robot stopped itself (a fall): no plan
  /// is executed; start() (after the robot's reset() where it fell) walks again
  fault,
};

/// The enumerator's name ("idle", ...), e.g. for logs; "unknown" for a value out of range.
constexpr const char* to_string(LoopMode m) noexcept {
  switch (m) {
    case LoopMode::idle:
      return "idle";
    case LoopMode::walking:
      return "walking";
    case LoopMode::stopping:
      return "stopping";
    case LoopMode::stopped:
      return "stopped";
    case LoopMode::fault:
      return "fault";
  }
  return "unknown";
}

/// Why the loop left LoopMode::walking (none while it walks).
enum class StopReason : std::uint8_t {
  none,
  requested,  ///< request_stop(): stopping, then stopped
  /// WalkingLoopSettings::max_qp_failures ticks in a row without a new plan: stopping (the
  /// current step finishes), then stopped
  qp_failures,
  /// WalkingLoopSettings::max_ik_failures command periods in a row without an IK solution
  /// (e.g. an unreachable CoM height): fault, the last solution held
  ik_failures,
  /// WalkingLoopSettings::max_saturated_periods command periods in a row with a clamped motor:
  /// stopping, then stopped
  torque_saturation,
  /// a non-finite or out-of-range measurement (joint position or velocity, force sensor): fault,
  /// the last joint targets held
  sensor_fault,
  fallen,    ///< the robot reports a fall (RobotStatus::fallen): fault, the robot stopped
  diverged,  ///< the robot reports divergence (RobotStatus::diverged): fault, the robot stopped
};

/// The enumerator's name ("none", ...), e.g. for logs; "unknown" for a value out of range.
constexpr const char* to_string(StopReason r) noexcept {
  switch (r) {
    case StopReason::none:
      return "none";
    case StopReason::requested:
      return "requested";
    case StopReason::qp_failures:
      return "qp_failures";
    case StopReason::ik_failures:
      return "ik_failures";
    case StopReason::torque_saturation:
      return "torque_saturation";
    case StopReason::sensor_fault:
      return "sensor_fault";
    case StopReason::fallen:
      return "fallen";
    case StopReason::diverged:
      return "diverged";
  }
  return "unknown";
}

/// Where the CoM fed back to the NMPC comes from (WalkingLoopSettings::feedback).
enum class FeedbackSource : std::uint8_t {
  /// Forward kinematics of the measured joints from the support sole where the plan put it
  /// (thesis §6.3): the CoM position only, blind to the robot tipping over a sole edge.
  kinematics,
  /// walkgen::BaseEstimator (IMU, leg kinematics, foot forces): the CoM position and velocity
  /// where the robot really is, so that a push moves the planned footsteps. A robot without an
  /// IMU (or a faulty estimate) is fed back from kinematics.
  estimator,
};

/// The enumerator's name ("kinematics", "estimator"); "unknown" for a value out of range.
constexpr const char* to_string(FeedbackSource f) noexcept {
  switch (f) {
    case FeedbackSource::kinematics:
      return "kinematics";
    case FeedbackSource::estimator:
      return "estimator";
  }
  return "unknown";
}

/// Settings of the loop itself; the generator's are WalkingSettings (t, command_period,
/// t_feedback), the solver's its own.
struct WalkingLoopSettings {
  /// Feed the measured CoM back to the NMPC every WalkingSettings::t_feedback (§6.3).
  bool com_feedback = true;
  /// Where the fed-back CoM comes from (docs/safety.md): kinematics (the thesis') or the
  /// estimator (position and velocity).
  FeedbackSource feedback = FeedbackSource::kinematics;
  /// Kinematics feedback: fraction of the measured − planned CoM position fed back, in (0, 1].
  /// Velocity and acceleration stay the plan's: differentiated joint measurements are too noisy
  /// to help.
  double feedback_gain = 1.0;
  /// Estimator feedback: fractions of the estimated − planned CoM position and velocity fed
  /// back, in [0, 1]. Higher gains make the plan chase the servos' tracking error and the
  /// walk oscillate (walkgen's humanoid: 0.5 / 0.6 already fail; docs/safety.md).
  double estimated_position_gain = 0.3;
  double estimated_velocity_gain = 0.3;
  /// Feedback without jumps (docs/safety.md): after a feedback the executed CoM blends from
  /// where the previous command left it (position, velocity, acceleration) into the restarted
  /// plan over the tick, along a quintic offset that ends at zero; the ZMP of the pattern moves
  /// with the offset's LIPM ZMP. False: the command jumps to the restarted plan (the thesis),
  /// and the servos' step excites the robot (the measured ZMP rings for about 0.3 s).
  bool smooth_feedback = false;
  /// The estimator's settings (its sole links: the loop's own sole links are used).
  BaseEstimatorSettings estimator = base_estimator_settings(walkgen_humanoid_description());
  /// Sole links of the tree (left, right): where the IK puts the feet and the feedback starts.
  /// Defaults: walkgen's humanoid (walkgen_humanoid_description()); loop_settings() takes them
  /// from any description.
  std::string left_sole_link = walkgen_humanoid_description().sole_frames[0];
  std::string right_sole_link = walkgen_humanoid_description().sole_frames[1];
  /// Frames of the ankle force-torque sensors in the tree (left, right): where the robot's
  /// readings are (the soles for a robot that reports contact forces instead).
  std::string left_ft_sensor_link = walkgen_humanoid_description().ft_sensor_frames[0];
  std::string right_ft_sensor_link = walkgen_humanoid_description().ft_sensor_frames[1];
  /// [s] start(): time to move the CoM from where it stands over the support foot; a stop:
  /// time to move it from where the step ended to between the feet.
  double transfer_time = 2.0;
  /// Safety (docs/safety.md). Ticks in a row whose QP failed (MpcStatus::qp_failed: the
  /// previous plan, shifted, is executed) before the loop stops: at most max_qp_failures − 1
  /// ticks walk a stale plan, then the current step finishes and the robot stands.
  int max_qp_failures = 3;
  /// Command periods in a row without an IK solution (the previous joints sent again) before
  /// the loop holds the robot (LoopMode::fault).
  int max_ik_failures = 10;
  /// Command periods in a row in which a motor's torque was clamped (RobotOutput::saturations
  /// grew) before the loop stops.
  int max_saturated_periods = 20;
  /// [rad] how far a measured joint may lie beyond its limits in the IK's tree before it is a
  /// sensor fault.
  double joint_limit_margin = 0.1;
  /// [rad/s] the largest believable joint speed; faster is a sensor fault.
  double max_joint_speed = 50.0;
  /// The largest believable force-sensor reading, in robot weights (KinematicTree::mass() g).
  double max_force_ratio = 20.0;
  /// [rad] a robot with an IMU (RobotOutput::imu) whose IMU tilts further from the vertical is
  /// falling: LoopStatus::fallen, before the robot's own fall check (base height) would tell.
  double max_tilt = 0.5;
  /// [rad/s] the gyroscope's range (2000 °/s); a faster reading is a sensor fault.
  double max_angular_rate = 35.0;
  /// [m/s^2] the accelerometer's range (16 g); a larger reading is a sensor fault.
  double max_acceleration = 160.0;
};

/// Checks the loop's own settings (the sole and sensor links are checked against the IK's tree
/// by WalkingLoop's constructor, which calls this).
/// @throws walkgen::invalid_argument naming the first bad field.
inline void validate(const WalkingLoopSettings& s) {
  check_argument(s.feedback_gain > 0.0 && s.feedback_gain <= 1.0,
                 "WalkingLoopSettings.feedback_gain", "a fraction in (0, 1]", s.feedback_gain);
  check_argument(
      s.feedback == FeedbackSource::kinematics || s.feedback == FeedbackSource::estimator,
      "WalkingLoopSettings.feedback", "kinematics or estimator", int(s.feedback));
  check_argument(s.estimated_position_gain >= 0.0 && s.estimated_position_gain <= 1.0,
                 "WalkingLoopSettings.estimated_position_gain", "a fraction in [0, 1]",
                 s.estimated_position_gain);
  check_argument(s.estimated_velocity_gain >= 0.0 && s.estimated_velocity_gain <= 1.0,
                 "WalkingLoopSettings.estimated_velocity_gain", "a fraction in [0, 1]",
                 s.estimated_velocity_gain);
  check_argument(std::isfinite(s.transfer_time) && s.transfer_time >= 0.0,
                 "WalkingLoopSettings.transfer_time", "a duration >= 0 [s]", s.transfer_time);
  check_argument(s.max_qp_failures >= 1, "WalkingLoopSettings.max_qp_failures", "a count >= 1",
                 s.max_qp_failures);
  check_argument(s.max_ik_failures >= 1, "WalkingLoopSettings.max_ik_failures", "a count >= 1",
                 s.max_ik_failures);
  check_argument(s.max_saturated_periods >= 1, "WalkingLoopSettings.max_saturated_periods",
                 "a count >= 1", s.max_saturated_periods);
  check_argument(std::isfinite(s.joint_limit_margin) && s.joint_limit_margin >= 0.0,
                 "WalkingLoopSettings.joint_limit_margin", "an angle >= 0 [rad]",
                 s.joint_limit_margin);
  check_positive("WalkingLoopSettings.max_joint_speed", s.max_joint_speed, "a speed > 0 [rad/s]");
  check_positive("WalkingLoopSettings.max_force_ratio", s.max_force_ratio,
                 "a multiple of the robot's weight > 0");
  check_argument(s.max_tilt > 0.0 && s.max_tilt <= 1.6, "WalkingLoopSettings.max_tilt",
                 "an angle in (0, 1.6] [rad]", s.max_tilt);
  check_positive("WalkingLoopSettings.max_angular_rate", s.max_angular_rate, "a rate > 0 [rad/s]");
  check_positive("WalkingLoopSettings.max_acceleration", s.max_acceleration,
                 "an acceleration > 0 [m/s^2]");
}

/// The loop settings with `robot`'s sole and sensor frames; the rest at their defaults.
inline WalkingLoopSettings loop_settings(const RobotDescription& robot) {
  WalkingLoopSettings s;
  s.left_sole_link = robot.sole_frames[0];
  s.right_sole_link = robot.sole_frames[1];
  // A robot without ankle sensors reports its contact forces at the soles (MujocoRobot).
  const bool sensors = !robot.ft_sensor_frames[0].empty();
  s.left_ft_sensor_link = sensors ? robot.ft_sensor_frames[0] : robot.sole_frames[0];
  s.right_ft_sensor_link = sensors ? robot.ft_sensor_frames[1] : robot.sole_frames[1];
  s.estimator = base_estimator_settings(robot);
  s.com_feedback = robot.balance.nmpc_feedback;
  return s;
}

/// One command period of the loop: what was planned and what was measured after it.
struct LoopSample {
  /// The pattern executed (CoM, ZMP, feet), world frame: the NMPC's interpolated plan while
  /// walking and finishing a step, the CoM's move between the feet while stopping, the held
  /// standing pose (at rest) when stopped or in a fault.
  TrajectorySample<double> plan;
  /// From the ankle sensors after the sample's physics (eq. 2.11–2.17), with the sensor poses
  /// of forward kinematics from the planned support sole: the frame of `plan`, as a robot
  /// without a base pose measurement sees it. Compare it with plan.zmp_x, plan.zmp_y.
  MeasuredZmp zmp;
  /// The raw sensor readings, with the sensor poses the robot reports (a simulator: the true
  /// world poses, where zmp_W = measured_zmp(ft, d) lies in the true support polygon).
  std::array<ForceTorqueReading, 2> ft;
  /// CoM by forward kinematics of the measured joints from the planned support sole [m].
  Eigen::Vector3d com_measured_W = Eigen::Vector3d::Zero();
  double base_height = 0.0;  ///< [m] as the robot reports it
  /// The IK's outcome for this sample; converged when holding (no solve: the held joints are
  /// the last solution).
  IkStatus ik = IkStatus::converged;
  /// The measurement passed the loop's checks (finite, within WalkingLoopSettings' ranges).
  /// When false, ft, zmp, com_measured_W and base_height are zero (not the faulty values).
  bool sensors_ok = true;
  LoopMode mode = LoopMode::walking;  ///< the loop's mode while this sample ran
};

/// Summary of one tick (one NMPC period t).
struct LoopTick {
  LoopStatus status = LoopStatus::not_started;
  LoopMode mode = LoopMode::idle;        ///< the loop's mode after the tick
  StopReason reason = StopReason::none;  ///< why the loop is not walking (none while it walks)
  MpcStatus mpc = MpcStatus::solved;
  /// Samples whose IK did not converge (previous joints sent again) or whose joints the robot
  /// rejected as non-finite (previous targets kept).
  int ik_failures = 0;
  /// Ticks in a row, this one included, whose plan is the previous one shifted
  /// (MpcStatus::qp_failed); 0 after a tick that solved or did not run the NMPC.
  int qp_failure_streak = 0;
  /// Wall-clock time of the NMPC's solve() in this tick (its SQP iterations and QPs) [s]; 0 when
  /// the tick ran no NMPC (stopped, fault). For monitoring: steady_clock, no allocation.
  double mpc_seconds = 0.0;
  bool fed_back = false;
  /// The feedback came from the estimator (FeedbackSource::estimator with a started estimate).
  bool estimated = false;
  /// Measured − planned CoM position at the feedback of this tick [m] (zero without one).
  Eigen::Vector2d com_error = Eigen::Vector2d::Zero();
  /// Estimated − planned CoM velocity at the feedback [m/s] (zero without estimator feedback).
  Eigen::Vector2d com_velocity_error = Eigen::Vector2d::Zero();
  /// Why, unless status is ok: the robot's message when it stopped, the NMPC's (MpcResult::
  /// message) when its QP failed or its plan did not converge, the fault's (which sensor, what
  /// streak) in LoopStatus::fault. Also the stop's reason while stopping or stopped on request.
  std::string message;
};

/// The loop of figure 6.1 around a Robot and an inverse kinematics `Ik` with
/// `tree()`, `set_initial_guess(p_W, R_W, q)`, `solve(IkTarget) -> IkResult` and `q()`
/// (CeresInverseKinematics). Robot and solver are borrowed and must outlive the loop.
template <int N, typename Ik, int FootEdges = 4, int HullEdges = 5>
class WalkingLoop {
 public:
  using Mpc = WalkingMpc<double, N, FootEdges, HullEdges>;

  /// @throws walkgen::invalid_argument when the settings are invalid, the robot's joints are not
  ///   all in the solver's tree, the sole links are unknown, or t_feedback is not a positive
  ///   multiple of t.
  WalkingLoop(const WalkingSettings<double>& settings, Robot& robot, Ik& ik,
              WalkingLoopSettings loop = WalkingLoopSettings())
      : loop_(std::move(loop)),
        robot_(robot),
        ik_(ik),
        tree_(ik.tree()),
        ws_(tree_.make_workspace()),
        mpc_(settings),
        interp_(interpolation_settings(settings)),
        estimator_(tree_, robot.info().joint_names, estimator_settings(loop_)) {
    validate(loop_);
    const double ratio = settings.t_feedback / settings.t;
    check_argument(
        std::isfinite(ratio) && ratio >= 1.0 - 1e-9 && std::abs(ratio - std::round(ratio)) < 1e-6,
        "WalkingLoop: t_feedback", "a whole multiple of t = " + std::to_string(settings.t),
        settings.t_feedback);
    feedback_every_ = int(std::lround(ratio));
    sole_[0] = tree_.link_index(loop_.left_sole_link);
    sole_[1] = tree_.link_index(loop_.right_sole_link);
    sensor_[0] = tree_.link_index(loop_.left_ft_sensor_link);
    sensor_[1] = tree_.link_index(loop_.right_ft_sensor_link);
    const auto& names = robot_.info().joint_names;
    check_argument(int(names.size()) == tree_.num_joints(), "WalkingLoop: robot joints",
                   "as many as the IK tree's " + std::to_string(tree_.num_joints()),
                   int(names.size()), "every joint of the tree must be commanded");
    to_tree_.resize(names.size());
    for (std::size_t j = 0; j < names.size(); ++j) to_tree_[j] = tree_.joint_index(names[j]);
    q_tree_.resize(tree_.num_joints());
    q_robot_.resize(Eigen::Index(names.size()));
    const Eigen::VectorXd lower = tree_.lower_limits(), upper = tree_.upper_limits();
    lower_.resize(q_robot_.size());
    upper_.resize(q_robot_.size());
    for (std::size_t j = 0; j < names.size(); ++j) {
      lower_[Eigen::Index(j)] = lower[to_tree_[j]] - loop_.joint_limit_margin;
      upper_[Eigen::Index(j)] = upper[to_tree_[j]] + loop_.joint_limit_margin;
    }
    max_force_ = loop_.max_force_ratio * tree_.mass() * settings.gravity;
    samples_.resize(std::size_t(interp_.samples_per_tick()));
    plan_.resize(samples_.size());
  }

  WalkingLoop(const WalkingLoop&) = delete;
  WalkingLoop& operator=(const WalkingLoop&) = delete;

  /// Begins a walk from the robot's current measurement. The generator keeps the ZMP in the
  /// support sole from its first sample, so a robot standing on both feet first moves its CoM
  /// over the support foot, to the settings' initial CoM (com_x, com_y, com_z), along a
  /// minimum-jerk path of WalkingLoopSettings::transfer_time with both feet where they are
  /// measured. Then the generator's state is set from the measurement (CoM from forward
  /// kinematics, the support sole at the settings' foot pose, the other foot where it is,
  /// standing still) and the velocity command is zero. Also walks on from stopped or a fault:
  /// from stopped in the generator's frame (the support sole where the plan put it, so that
  /// obstacles and poses keep their meaning), from a fault (or idle) at the settings' start.
  /// @return ok (LoopMode::walking); fallen / diverged when the robot stopped or its IMU tilts
  ///   beyond max_tilt (before or during the transfer); fault (LoopMode::fault) on a faulty
  ///   measurement or max_ik_failures command periods in a row without an IK solution (e.g. a CoM
  ///   height the legs cannot reach: the robot keeps standing). ik_failures counts the transfer's
  ///   samples whose IK did not converge (previous joints sent again).
  [[nodiscard]] const LoopTick& start() {
    begin_tick();
    // From a stop the walk goes on in the generator's frame: the robot stands on the soles the
    // plan put down (obstacles and poses keep their meaning); else from the settings' start.
    const bool resume = mode_ == LoopMode::stopped;
    mode_ = LoopMode::idle;
    reason_ = StopReason::none;
    reason_message_.clear();
    qp_streak_ = ik_streak_ = saturated_streak_ = 0;
    centring_ = false;
    last_saturations_ = robot_.output().saturations;
    if (!robot_running() || !measurement_ok(robot_.output(), "start()") || !upright()) {
      return end_tick();
    }
    const WalkingSettings<double>& s = mpc_.settings();
    const Foot support = resume ? mpc_.state().support_foot : s.support_foot;
    const FootPose<double> support_pose =
        resume ? mpc_.state().support : FootPose<double>{s.foot_x, s.foot_y, s.foot_q};
    to_tree_order(robot_.output().q);
    place_on_sole(support, support_pose);
    ik_.set_initial_guess(base_p_W_, base_R_W_, q_tree_);
    estimating_ = loop_.feedback == FeedbackSource::estimator &&
                  estimator_.reset(base_p_W_, robot_.output()) == EstimateStatus::ok;
    TrajectorySample<double> stand;  // the transfer: feet where they are, the CoM moving
    stand.left.motion = FootMotion<double>::at_rest(sole_pose(Foot::left));
    stand.right.motion = FootMotion<double>::at_rest(sole_pose(Foot::right));
    stand.com_q[0] = (stand.left.motion.q.position + stand.right.motion.q.position) / 2.0;
    stand.support_foot = support;
    stand.time = robot_.output().time;
    const Eigen::Vector3d c0 = com_W();
    // The settings' initial CoM relative to their support foot, on `support` at support_pose
    // (mirrored sideways for the other foot).
    const Eigen::Vector2d offset =
        (Eigen::Rotation2Dd(-s.foot_q) *
         Eigen::Vector2d(s.com_x[0] - s.foot_x, s.com_y[0] - s.foot_y))
            .cwiseProduct(Eigen::Vector2d(1.0, support == s.support_foot ? 1.0 : -1.0));
    const Eigen::Vector2d c1_xy = Eigen::Vector2d(support_pose.x, support_pose.y) +
                                  Eigen::Rotation2Dd(support_pose.q) * offset;
    const Eigen::Vector3d c1(c1_xy.x(), c1_xy.y(), s.com_z);
    const double dt = interp_.command_period();
    const int n = std::max(1, int(std::lround(loop_.transfer_time / dt)));
    for (int k = 1; k <= n; ++k) {
      const double r = double(k) / double(n);
      const double blend = r * r * r * (10.0 - 15.0 * r + 6.0 * r * r);  // minimum jerk
      const Eigen::Vector3d c = c0 + blend * (c1 - c0);
      stand.com_x[0] = stand.zmp_x = c.x();
      stand.com_y[0] = stand.zmp_y = c.y();
      stand.com_z = c.z();
      stand.time += dt;
      last_sample_ = stand;
      const bool converged = ik_.solve(ik_target(stand)).status == IkStatus::converged;
      count_ik(converged);  // the previous joints are sent again
      if (!send_and_step(dt, true) || !measurement_ok(robot_.output(), "start()")) {
        return end_tick();
      }
      if (ik_streak_ >= loop_.max_ik_failures) {
        enter_fault(StopReason::ik_failures,
                    "start(): the IK found no joints for the CoM at (" + std::to_string(c.x()) +
                        ", " + std::to_string(c.y()) + ", " + std::to_string(c.z()) + ") m " +
                        std::to_string(ik_streak_) +
                        " command periods in a row (is com_z reachable?): holding the robot");
        return end_tick();
      }
    }
    to_tree_order(robot_.output().q);
    place_on_sole(support, support_pose);
    const Eigen::Vector3d c = com_W();
    if (estimating_) anchor_estimate();
    typename Mpc::State st;
    st.com_x << c.x(), 0.0, 0.0;
    st.com_y << c.y(), 0.0, 0.0;
    st.support_foot = support;
    st.support = support_pose;
    st.swing_origin = sole_pose(other(support));
    st.swing = FootMotion<double>::at_rest(st.swing_origin);
    mpc_.reset(st);
    (void)mpc_.set_command(Eigen::Vector3d::Zero());  // zero is always accepted
    ticks_ = 0;
    mode_ = LoopMode::walking;
    return end_tick();
  }

  /// The velocity command (v_x, v_y [m/s], ω_z [rad/s]) in the robot frame, for the next ticks
  /// (while stopping the loop commands zero; start() sets zero).
  [[nodiscard]] CommandStatus set_command(const Eigen::Vector3d& command) {
    return mpc_.set_command(command);
  }

  /// Stops the walk: the current step finishes along the plan (command zero), then the CoM
  /// moves between the feet and the loop holds the robot (LoopMode::stopping, then stopped;
  /// reason requested). Only while walking; returns the mode after the call.
  LoopMode request_stop() {
    begin_stop(StopReason::requested, "stopping on request");
    return mode_;
  }

  /// One NMPC period: feedback (when due), solve, interpolate, and per command period IK,
  /// joint targets, a robot step and the measurement's checks; samples() holds what happened.
  /// While stopping after the step, stopped or in a fault it runs the same number of command
  /// periods without the NMPC (moving the CoM between the feet, or holding the joints).
  [[nodiscard]] const LoopTick& tick() {
    begin_tick();
    if (mode_ == LoopMode::idle) {
      samples_.clear();  // keeps the capacity
      tick_.message = "WalkingLoop::tick: call start() first";
      return tick_;
    }
    if (robot_stopped()) {
      samples_.clear();
      return end_tick();
    }
    samples_.resize(plan_.size());
    const bool planning = mode_ == LoopMode::walking || (mode_ == LoopMode::stopping && !centring_);
    const char* mpc_message = "";
    if (planning) {
      if (mode_ == LoopMode::stopping) (void)mpc_.set_command(Eigen::Vector3d::Zero());
      if (loop_.com_feedback && ticks_ > 0 && ticks_ % feedback_every_ == 0) feed_back();
    }
    const bool plan_valid = planning && mode_ != LoopMode::fault;  // feedback may find a fault
    if (plan_valid) {
      const auto solve_start = std::chrono::steady_clock::now();
      const MpcResult<double>& solved = mpc_.solve();
      tick_.mpc_seconds =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - solve_start).count();
      tick_.mpc = solved.status;
      mpc_message = solved.message;
      qp_streak_ = solved.status == MpcStatus::qp_failed ? qp_streak_ + 1 : 0;
      tick_.qp_failure_streak = qp_streak_;
      if (qp_streak_ >= loop_.max_qp_failures && mode_ == LoopMode::walking) {
        begin_stop(StopReason::qp_failures, "the NMPC's QP failed " + std::to_string(qp_streak_) +
                                                " ticks in a row (" + mpc_message +
                                                "): stopping after the current step");
      }
      interp_.interpolate(mpc_.tick_plan(), plan_.data());
      if (tick_.fed_back && loop_.smooth_feedback && ticks_ > 0) blend_into_plan();
    } else {
      qp_streak_ = 0;
    }
    const double dt = interp_.command_period();
    for (std::size_t k = 0; k < plan_.size(); ++k) {
      LoopSample& out = samples_[k];
      out.plan = next_sample(plan_valid ? &plan_[k] : nullptr, dt);
      out.mode = mode_;
      const bool solve = mode_ == LoopMode::walking || mode_ == LoopMode::stopping;
      out.ik = IkStatus::converged;
      if (solve) {
        out.ik = ik_.solve(ik_target(out.plan)).status;
        count_ik(out.ik == IkStatus::converged);  // the previous joints stay
      }
      last_sample_ = out.plan;
      const bool running = send_and_step(dt, solve);
      measure(out, out.plan);
      if (running) check_streaks();
      if (!running) {
        samples_.resize(k + 1);  // what happened up to the stop (no reallocation: shrinks)
        return end_tick();
      }
    }
    if (plan_valid) {
      mpc_.advance();
      ++ticks_;
    }
    end_tick();
    if (tick_.status == LoopStatus::ok && plan_valid && tick_.mpc != MpcStatus::solved) {
      tick_.status = tick_.mpc == MpcStatus::not_converged ? LoopStatus::not_converged
                     : tick_.mpc == MpcStatus::relaxed     ? LoopStatus::relaxed
                                                           : LoopStatus::qp_failed;
      tick_.message = mpc_message;  // a failed tick only
    }
    return tick_;
  }

  /// The command periods of the last tick (fewer when the robot stopped during it).
  const std::vector<LoopSample>& samples() const { return samples_; }
  const LoopTick& last_tick() const { return tick_; }
  LoopMode mode() const { return mode_; }
  StopReason reason() const { return reason_; }

  /// The generator, e.g. for obstacles (mpc().set_obstacles()) or its plan.
  Mpc& mpc() { return mpc_; }
  /// The state estimator (updated every command period with FeedbackSource::estimator).
  const BaseEstimator& estimator() const { return estimator_; }
  const Mpc& mpc() const { return mpc_; }
  const WalkingLoopSettings& settings() const { return loop_; }
  long ticks() const { return ticks_; }

 private:
  /// Clears the tick's summary (the message keeps its capacity).
  void begin_tick() {
    tick_.status = LoopStatus::not_started;
    tick_.mpc = MpcStatus::solved;
    tick_.mpc_seconds = 0.0;
    tick_.ik_failures = 0;
    tick_.qp_failure_streak = 0;
    tick_.fed_back = false;
    tick_.estimated = false;
    tick_.com_error.setZero();
    tick_.com_velocity_error.setZero();
    tick_.message.clear();
  }

  /// The tick's mode, reason, status and message from the state machine.
  const LoopTick& end_tick() {
    tick_.mode = mode_;
    tick_.reason = reason_;
    switch (reason_) {
      case StopReason::none:
        tick_.status = mode_ == LoopMode::walking ? LoopStatus::ok : LoopStatus::not_started;
        break;
      case StopReason::requested:  // a requested stop that ended in a fault is not ok
        tick_.status = mode_ == LoopMode::fault ? LoopStatus::fault : LoopStatus::ok;
        break;
      case StopReason::fallen:
        tick_.status = LoopStatus::fallen;
        break;
      case StopReason::diverged:
        tick_.status = LoopStatus::diverged;
        break;
      default:
        tick_.status = LoopStatus::fault;
        break;
    }
    tick_.message = reason_message_;
    return tick_;
  }

  /// Walking → stopping for `reason` (nothing in another mode).
  void begin_stop(StopReason reason, const std::string& message) {
    if (mode_ != LoopMode::walking) return;
    mode_ = LoopMode::stopping;
    reason_ = reason;
    reason_message_ = message;
    finish_time_ = 0.0;
    centring_ = false;
  }

  /// Any mode → fault for `reason`: the last joint targets are held at the last sample's pose.
  void enter_fault(StopReason reason, const std::string& message) {
    mode_ = LoopMode::fault;
    reason_ = reason;
    reason_message_ = message;
    centring_ = false;
    held_ = at_rest(last_sample_);
  }

  bool robot_stopped() const {
    return mode_ == LoopMode::fault &&
           (reason_ == StopReason::fallen || reason_ == StopReason::diverged);
  }

  /// smooth_feedback: adds to the tick's plan (samples at τ = k dt from the restarted state) the
  /// quintic offset that starts at the previous command carried on by dt − the restarted state
  /// (position, velocity, acceleration) and ends at zero where the next tick begins, with its
  /// LIPM ZMP (eq. 2.6–2.7).
  void blend_into_plan() {
    const typename Mpc::State& st = mpc_.state();
    const double dt = interp_.command_period();
    const double T = dt * double(plan_.size());
    const auto offset = [&](const Eigen::Vector3d& was, const Eigen::Vector3d& now) {
      const Eigen::Vector3d carried(was[0] + was[1] * dt + was[2] * dt * dt / 2.0,
                                    was[1] + was[2] * dt, was[2]);
      const Eigen::Vector3d e = carried - now;
      return quintic(T, Sample3<double>{e[0], e[1], e[2]}, Sample3<double>{0.0, 0.0, 0.0});
    };
    const Polynomial<double, 5> ox = offset(last_sample_.com_x, st.com_x);
    const Polynomial<double, 5> oy = offset(last_sample_.com_y, st.com_y);
    const double h_g = mpc_.settings().com_z / mpc_.settings().gravity;
    for (std::size_t k = 0; k < plan_.size(); ++k) {
      const Sample3<double> x = ox.evaluate(dt * double(k)), y = oy.evaluate(dt * double(k));
      TrajectorySample<double>& p = plan_[k];
      p.com_x += Eigen::Vector3d(x.position, x.velocity, x.acceleration);
      p.com_y += Eigen::Vector3d(y.position, y.velocity, y.acceleration);
      p.zmp_x += x.position - h_g * x.acceleration;
      p.zmp_y += y.position - h_g * y.acceleration;
    }
  }

  /// False (fault entered) when the robot reports that it stopped.
  bool robot_running() {
    const RobotOutput& m = robot_.output();
    if (m.status == RobotStatus::ok) return true;
    enter_fault(m.status == RobotStatus::fallen ? StopReason::fallen : StopReason::diverged,
                m.message);
    return false;
  }

  /// The sample to execute next: the plan's (walking; stopping until the step has ended), the
  /// CoM's move between the feet (stopping after the step), the held pose (stopped, fault).
  TrajectorySample<double> next_sample(const TrajectorySample<double>* planned, double dt) {
    if (mode_ == LoopMode::walking && planned) return *planned;
    if (mode_ == LoopMode::stopping && !centring_ && planned) {
      if (!planned->double_support) {
        finish_time_ += dt;
        const WalkingSettings<double>& s = mpc_.settings();
        if (finish_time_ <= s.t_step + s.t) return *planned;
        enter_fault(reason_, reason_message_ + "; the step did not end within t_step: holding");
        held_.time += dt;
        return held_;
      }
      begin_centring(*planned);
    }
    if (mode_ == LoopMode::stopping && centring_) {
      centre_time_ = std::min(centre_time_ + dt, centre_x_.duration);
      TrajectorySample<double> s = centre_from_;
      const Sample3<double> x = centre_x_.evaluate(centre_time_);
      const Sample3<double> y = centre_y_.evaluate(centre_time_);
      s.com_x << x.position, x.velocity, x.acceleration;
      s.com_y << y.position, y.velocity, y.acceleration;
      const double h_g = s.com_z / mpc_.settings().gravity;  // ZMP of the LIPM (eq. 2.6–2.7)
      s.zmp_x = x.position - h_g * x.acceleration;
      s.zmp_y = y.position - h_g * y.acceleration;
      s.time = centre_from_.time + centre_time_;
      if (centre_time_ >= centre_x_.duration) {
        mode_ = LoopMode::stopped;
        centring_ = false;
        held_ = at_rest(s);
      }
      return s;
    }
    held_.time += dt;  // stopped or fault: the held pose
    return held_;
  }

  /// Stopping after the step: from `s` (both feet down) the CoM moves to the middle of the
  /// soles along 5th-order polynomials from its state (position, velocity, acceleration) to
  /// rest, in transfer_time; the feet stay. A CoM still swinging fast toward a sole (the G1
  /// stopping from a walk: its CoM sways at 0.3 m/s) overshoots that sole on the way back when
  /// the move takes the whole transfer_time: the move takes transfer_time · k/8 (k = 8 … 1),
  /// the longest along which the CoM and its ZMP go least beyond the soles' centres (across the
  /// line joining them: beyond half a foot length); a shorter move must go at least 1 mm less
  /// beyond them to be taken.
  void begin_centring(const TrajectorySample<double>& s) {
    centring_ = true;
    centre_time_ = 0.0;
    centre_from_ = at_rest(s);
    centre_from_.com_x = s.com_x;
    centre_from_.com_y = s.com_y;
    const auto& l = centre_from_.left.motion;
    const auto& r = centre_from_.right.motion;
    const Eigen::Vector2d left(l.x.position, l.y.position), right(r.x.position, r.y.position);
    const Eigen::Vector2d middle = (left + right) / 2.0;
    const double h_g = s.com_z / mpc_.settings().gravity;
    const double half_length = mpc_.settings().foot_length / 2.0;
    const double length = (left - right).norm();
    const Eigen::Vector2d unit =
        length > 1e-9 ? Eigen::Vector2d((left - right) / length) : Eigen::Vector2d::UnitY();
    // How far p lies beyond the soles' centres [m] (0 between them).
    const auto beyond = [&](const Eigen::Vector2d& p) {
      if (!(length > 1e-9)) return std::max((p - middle).norm() - half_length, 0.0);
      const Eigen::Vector2d d = p - right;
      const double along = d.dot(unit);
      const double off = std::abs(d.x() * unit.y() - d.y() * unit.x());
      return std::max({-along, along - length, 0.0}) + std::max(off - half_length, 0.0);
    };
    const auto move = [&](double duration) {
      centre_x_ = quintic(duration, Sample3<double>{s.com_x[0], s.com_x[1], s.com_x[2]},
                          Sample3<double>{middle.x(), 0.0, 0.0});
      centre_y_ = quintic(duration, Sample3<double>{s.com_y[0], s.com_y[1], s.com_y[2]},
                          Sample3<double>{middle.y(), 0.0, 0.0});
      double worst = 0.0;
      for (int i = 0; i <= 40; ++i) {
        const Sample3<double> x = centre_x_.evaluate(duration * double(i) / 40.0);
        const Sample3<double> y = centre_y_.evaluate(duration * double(i) / 40.0);
        worst = std::max(
            {worst, beyond({x.position, y.position}),
             beyond({x.position - h_g * x.acceleration, y.position - h_g * y.acceleration})});
      }
      return worst;
    };
    const auto duration = [&](int k) {
      return std::max(loop_.transfer_time * double(k) / 8.0, interp_.command_period());
    };
    int best = 8;
    double least = move(duration(8));
    for (int k = 7; k >= 1; --k) {
      const double worst = move(duration(k));
      if (worst < least - 1e-3) {
        least = worst;
        best = k;
      }
    }
    (void)move(duration(best));
  }

  /// `s` standing still: feet on the ground at rest, CoM and yaw without motion, ZMP under the
  /// CoM, both feet supporting.
  static TrajectorySample<double> at_rest(const TrajectorySample<double>& s) {
    TrajectorySample<double> r = s;
    for (SwingSample<double>* f : {&r.left, &r.right}) {
      f->motion = FootMotion<double>::at_rest(f->motion.pose());
      f->z = {0.0, 0.0, 0.0};
    }
    r.com_x.tail<2>().setZero();
    r.com_y.tail<2>().setZero();
    r.com_q.tail<2>().setZero();
    r.zmp_x = r.com_x[0];
    r.zmp_y = r.com_y[0];
    r.zmp_z = 0.0;
    r.double_support = true;
    return r;
  }

  /// Counts a sample whose IK did not converge, or whose joints the robot rejected, in the
  /// tick's ik_failures and the streak.
  void count_ik(bool converged) {
    ik_streak_ = converged ? 0 : ik_streak_ + 1;
    tick_.ik_failures += !converged;
  }

  /// The streaks after a sample: IK failures → fault; torque saturation → stopping.
  void check_streaks() {
    const long saturations = robot_.output().saturations;
    saturated_streak_ = saturations > last_saturations_ ? saturated_streak_ + 1 : 0;
    last_saturations_ = saturations;
    if (saturated_streak_ >= loop_.max_saturated_periods && mode_ == LoopMode::walking) {
      begin_stop(StopReason::torque_saturation,
                 "motor torques clamped " + std::to_string(saturated_streak_) +
                     " command periods in a row: stopping after the current step");
    }
    if (ik_streak_ >= loop_.max_ik_failures && mode_ != LoopMode::fault) {
      enter_fault(StopReason::ik_failures,
                  "the IK found no joints " + std::to_string(ik_streak_) +
                      " command periods in a row: holding the last solution");
    }
  }

  /// The sample's measurement (ZMP, FK CoM) when the robot's output passes the checks; zeros
  /// and a sensor fault otherwise.
  void measure(LoopSample& out, const TrajectorySample<double>& plan) {
    const RobotOutput& m = robot_.output();
    out.sensors_ok = measurement_ok(m, "tick()");
    if (!out.sensors_ok) {
      out.ft = {};
      out.zmp = MeasuredZmp();
      out.com_measured_W.setZero();
      out.base_height = 0.0;
      return;
    }
    out.ft = m.ft;
    out.base_height = m.base_height;
    to_tree_order(m.q);
    place_on_sole(plan.support_foot, planned_support(plan));
    out.com_measured_W = com_W();
    for (int f = 0; f < 2; ++f) {  // the same wrenches, at the sensor poses of this FK
      ft_fk_[std::size_t(f)] = m.ft[std::size_t(f)];
      ft_fk_[std::size_t(f)].pose_W_S.linear() = link_rotation_W(sensor_[f]);
      ft_fk_[std::size_t(f)].pose_W_S.translation() = link_position_W(sensor_[f]);
    }
    out.zmp = measured_zmp(ft_fk_, robot_.info().ft_sensor_height);
  }

  /// True when every joint position and velocity is finite and in range, both force sensors
  /// read finite, believable wrenches at finite poses and the IMU (if any) finite readings in
  /// its range; otherwise a sensor fault (entered unless
  /// the loop already stopped the robot), with the reading named. `where` begins the message.
  bool measurement_ok(const RobotOutput& m, const char* where) {
    const auto& names = robot_.info().joint_names;
    const Eigen::Index n = Eigen::Index(names.size());
    std::string problem;
    if (m.q.size() != n || m.dq.size() != n) {
      problem = "the robot reports " + std::to_string(m.q.size()) + " joint positions and " +
                std::to_string(m.dq.size()) + " velocities for " + std::to_string(n) + " joints";
    }
    for (Eigen::Index j = 0; problem.empty() && j < n; ++j) {  // strings only for a fault
      if (!(m.q[j] >= lower_[j] && m.q[j] <= upper_[j])) {     // also NaN
        problem = "joint '" + names[std::size_t(j)] + "' position " + std::to_string(m.q[j]) +
                  " rad is outside [" + std::to_string(lower_[j]) + ", " +
                  std::to_string(upper_[j]) + "] (its limits widened by joint_limit_margin)";
      } else if (!(std::abs(m.dq[j]) <= loop_.max_joint_speed)) {
        problem = "joint '" + names[std::size_t(j)] + "' velocity " + std::to_string(m.dq[j]) +
                  " rad/s is beyond max_joint_speed " + std::to_string(loop_.max_joint_speed) +
                  " rad/s";
      }
    }
    for (int f = 0; problem.empty() && f < 2; ++f) {
      const ForceTorqueReading& r = m.ft[std::size_t(f)];
      const char* sensor = f == 0 ? "left force sensor" : "right force sensor";
      if (!r.force_S.allFinite() || !r.torque_S.allFinite() || !r.pose_W_S.matrix().allFinite()) {
        problem = std::string(sensor) + " reads a non-finite wrench or pose";
      } else if (!(r.force_S.norm() <= max_force_)) {
        problem =
            std::string(sensor) + " reads " + std::to_string(r.force_S.norm()) +
            " N, beyond max_force_ratio × the robot's weight = " + std::to_string(max_force_) +
            " N";
      }
    }
    const ImuReading& imu = m.imu;
    if (problem.empty() && imu.available) {
      if (!imu.orientation_W_I.coeffs().allFinite() || !imu.angular_velocity_I.allFinite() ||
          !imu.acceleration_I.allFinite()) {
        problem = "the IMU reads a non-finite orientation, rate or acceleration";
      } else if (!(std::abs(imu.orientation_W_I.norm() - 1.0) <= 1e-3)) {
        problem = "the IMU's orientation quaternion has norm " +
                  std::to_string(imu.orientation_W_I.norm()) + " (not a rotation)";
      } else if (!(imu.angular_velocity_I.norm() <= loop_.max_angular_rate)) {
        problem = "the IMU's rate " + std::to_string(imu.angular_velocity_I.norm()) +
                  " rad/s is beyond max_angular_rate " + std::to_string(loop_.max_angular_rate) +
                  " rad/s";
      } else if (!(imu.acceleration_I.norm() <= loop_.max_acceleration)) {
        problem = "the IMU's acceleration " + std::to_string(imu.acceleration_I.norm()) +
                  " m/s^2 is beyond max_acceleration " + std::to_string(loop_.max_acceleration) +
                  " m/s^2";
      }
    }
    if (problem.empty()) return true;
    if (!robot_stopped())
      enter_fault(StopReason::sensor_fault,
                  std::string(where) + ": " + problem + ": holding the joint targets");
    return false;
  }

  void to_tree_order(const Eigen::VectorXd& q_robot) {
    for (std::size_t j = 0; j < to_tree_.size(); ++j) {
      q_tree_[to_tree_[j]] = q_robot[Eigen::Index(j)];
    }
  }

  /// Sends the joints to the robot (the IK's when `from_ik`, else the last targets again) and
  /// steps it by dt; false (fault fallen or diverged) when the robot stopped. A robot rejects
  /// non-finite joints and keeps its previous targets: such a sample counts as one whose IK
  /// failed.
  bool send_and_step(double dt, bool from_ik) {
    if (from_ik) {
      for (std::size_t j = 0; j < to_tree_.size(); ++j) {
        q_robot_[Eigen::Index(j)] = ik_.q()[to_tree_[j]];
      }
      have_targets_ = true;
    }
    if (from_ik) robot_.set_balance_reference(balance_reference(last_sample_));
    // Holding before any target was sent (a fault at start()): the robot keeps its own.
    if (have_targets_ && robot_.set_joint_targets(q_robot_) != JointCommandStatus::accepted) {
      count_ik(false);
    }
    if (robot_.step(dt) != RobotStatus::ok) return robot_running();
    // A faulty reading leaves the estimate where it was; measurement_ok() reports the reading.
    if (estimating_) estimate_ok_ = estimator_.update(robot_.output(), dt) == EstimateStatus::ok;
    return upright();
  }

  /// False (fault fallen entered) when the robot's IMU tilts beyond max_tilt; true without an
  /// IMU or with a non-finite one (measurement_ok() reports that).
  bool upright() {
    const ImuReading& imu = robot_.output().imu;
    if (!imu.available) return true;
    const double tilt = imu.tilt();
    if (!(tilt > loop_.max_tilt)) return true;
    enter_fault(StopReason::fallen, "the IMU tilts " + std::to_string(tilt) +
                                        " rad from the vertical, beyond max_tilt " +
                                        std::to_string(loop_.max_tilt) + " rad: falling");
    return false;
  }

  /// The balance `s` asks for, in the frame of its support sole.
  static BalanceReference balance_reference(const TrajectorySample<double>& s) {
    const FootPose<double> sole = planned_support(s);
    const Eigen::Rotation2Dd to_sole(-sole.q);
    BalanceReference r;
    r.valid = true;
    r.support = s.support_foot == Foot::left ? 0 : 1;
    r.com = to_sole * Eigen::Vector2d(s.com_x[0] - sole.x, s.com_y[0] - sole.y);
    r.com_velocity = to_sole * Eigen::Vector2d(s.com_x[1], s.com_y[1]);
    r.com_acceleration = to_sole * Eigen::Vector2d(s.com_x[2], s.com_y[2]);
    r.zmp = to_sole * Eigen::Vector2d(s.zmp_x - sole.x, s.zmp_y - sole.y);
    r.com_height = s.com_z;
    return r;
  }

  /// The support sole's pose in a sample of the plan.
  static FootPose<double> planned_support(const TrajectorySample<double>& s) {
    const auto& f = s.foot(s.support_foot);
    return {f.motion.x.position, f.motion.y.position, f.motion.q.position};
  }

  /// Forward kinematics of q_tree_ in the base frame (one FK), and the base pose in W that puts
  /// sole `foot` flat at `pose` (the sole's own tilt relative to the base is kept: a flat sole
  /// gives the true base). com_W(), link_position_W() and link_rotation_W() then map to W.
  void place_on_sole(Foot foot, const FootPose<double>& pose) {
    const int sole = sole_[foot == Foot::left ? 0 : 1];
    tree_.forward_kinematics(Eigen::Vector3d::Zero(), Eigen::Matrix3d::Identity(), q_tree_, ws_);
    const Eigen::Matrix3d& R_base_sole = ws_.rotation_W(sole);
    // Yaw of the sole in the base frame, so that the sole's yaw in W becomes pose.q.
    const double sole_yaw = yaw_of(R_base_sole);
    base_R_W_ = Eigen::AngleAxisd(pose.q - sole_yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    base_p_W_ = Eigen::Vector3d(pose.x, pose.y, 0.0) - base_R_W_ * ws_.position_W(sole);
  }

  Eigen::Vector3d com_W() const { return base_p_W_ + base_R_W_ * tree_.center_of_mass(ws_); }
  Eigen::Vector3d link_position_W(int link) const {
    return base_p_W_ + base_R_W_ * ws_.position_W(link);
  }
  Eigen::Matrix3d link_rotation_W(int link) const { return base_R_W_ * ws_.rotation_W(link); }

  /// The pose (x, y, yaw) of sole `foot` after place_on_sole().
  FootPose<double> sole_pose(Foot foot) const {
    const int sole = sole_[foot == Foot::left ? 0 : 1];
    const Eigen::Vector3d p = link_position_W(sole);
    const Eigen::Matrix3d R = link_rotation_W(sole);
    return {p.x(), p.y(), yaw_of(R)};
  }

  /// The estimator's settings with the loop's sole links.
  static BaseEstimatorSettings estimator_settings(const WalkingLoopSettings& loop) {
    BaseEstimatorSettings s = loop.estimator;
    s.sole_links = {loop.left_sole_link, loop.right_sole_link};
    return s;
  }

  /// The yaw from the estimator's frame to the generator's: the base's of place_on_sole()
  /// (called before) against the estimate's. Positions are fed back relative to the support
  /// sole, so no shift is needed.
  void anchor_estimate() {
    to_generator_ =
        Eigen::Rotation2Dd(yaw_of(base_R_W_) - yaw_of(estimator_.estimate().base_rotation_W));
    estimate_ok_ = true;
  }

  /// §6.3: the CoM of the measured joints, from the support sole where the plan has it; or,
  /// with estimator feedback, the estimated CoM position and velocity in the generator's frame.
  /// The measurement passed its checks after the last sample, so the CoM is finite.
  void feed_back() {
    typename Mpc::State st = mpc_.state();
    Eigen::Vector3d c;
    Eigen::Vector2d v = Eigen::Vector2d(st.com_x[1], st.com_y[1]);
    const bool estimated = estimating_ && estimate_ok_;
    if (estimated) {
      const BaseEstimate& e = estimator_.estimate();
      // Relative to the support sole where the plan has it: a sole that landed off its planned
      // place does not read as a CoM error, a robot tipping over its sole's edge does.
      const std::size_t support = st.support_foot == Foot::left ? 0 : 1;
      const Eigen::Vector2d sole = e.sole_W[support].head<2>();
      c.head<2>() =
          Eigen::Vector2d(st.support.x, st.support.y) + to_generator_ * (e.com_W.head<2>() - sole);
      c.z() = e.com_W.z();
      v = to_generator_ * e.com_velocity_W.head<2>();
    } else {
      to_tree_order(robot_.output().q);
      place_on_sole(st.support_foot, st.support);
      c = com_W();
    }
    if (!c.allFinite() || !v.allFinite()) {
      enter_fault(StopReason::sensor_fault, "feedback: the measured CoM is not finite");
      return;
    }
    tick_.com_error = Eigen::Vector2d(c.x() - st.com_x[0], c.y() - st.com_y[0]);
    const double gain = estimated ? loop_.estimated_position_gain : loop_.feedback_gain;
    st.com_x[0] += gain * tick_.com_error.x();
    st.com_y[0] += gain * tick_.com_error.y();
    if (estimated) {
      tick_.com_velocity_error = Eigen::Vector2d(v.x() - st.com_x[1], v.y() - st.com_y[1]);
      st.com_x[1] += loop_.estimated_velocity_gain * tick_.com_velocity_error.x();
      st.com_y[1] += loop_.estimated_velocity_gain * tick_.com_velocity_error.y();
    }
    mpc_.set_state(st);
    tick_.fed_back = true;
    tick_.estimated = estimated;
  }

  WalkingLoopSettings loop_;
  Robot& robot_;
  Ik& ik_;
  const KinematicTree<double>& tree_;
  typename KinematicTree<double>::Workspace ws_;
  Mpc mpc_;
  WalkingInterpolator<double> interp_;
  BaseEstimator estimator_;
  bool estimating_ = false;   ///< estimator feedback, with the estimate started at start()
  bool estimate_ok_ = false;  ///< the last estimator update took its measurement
  /// The estimator's frame → the generator's: a yaw (anchor_estimate()).
  Eigen::Rotation2Dd to_generator_ = Eigen::Rotation2Dd(0.0);
  int feedback_every_ = 1;
  int sole_[2] = {0, 0};
  int sensor_[2] = {0, 0};
  std::array<ForceTorqueReading, 2> ft_fk_;
  std::vector<Eigen::Index> to_tree_;
  Eigen::VectorXd q_tree_, q_robot_;
  Eigen::VectorXd lower_, upper_;  ///< believable joint positions, robot order
  double max_force_ = 0.0;         ///< [N] believable force-sensor reading
  Eigen::Vector3d base_p_W_ = Eigen::Vector3d::Zero();
  Eigen::Matrix3d base_R_W_ = Eigen::Matrix3d::Identity();
  std::vector<TrajectorySample<double>> plan_;
  std::vector<LoopSample> samples_;
  LoopTick tick_;
  long ticks_ = 0;
  // The safety state machine (docs/safety.md).
  LoopMode mode_ = LoopMode::idle;
  StopReason reason_ = StopReason::none;
  std::string reason_message_;
  int qp_streak_ = 0, ik_streak_ = 0, saturated_streak_ = 0;
  long last_saturations_ = 0;
  bool have_targets_ = false;  ///< q_robot_ holds joints sent to the robot
  double finish_time_ = 0.0;   ///< [s] stopping: time spent finishing the step
  bool centring_ = false;      ///< stopping: the step ended, the CoM moves between the feet
  double centre_time_ = 0.0;
  Polynomial<double, 5> centre_x_, centre_y_;
  TrajectorySample<double> centre_from_, held_, last_sample_;
};

}  // namespace walkgen
