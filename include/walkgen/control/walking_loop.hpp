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
/// The world frame is the generator's: at start() the robot is placed so that its support sole
/// (WalkingSettings::support_foot) is at the settings' foot pose, flat on the ground. A real
/// robot measures no base pose, and neither does the loop: the measured CoM is forward
/// kinematics from the current support sole, assumed where the plan put it (as the thesis does).

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "walkgen/control/pattern_targets.hpp"
#include "walkgen/core/exceptions.hpp"
#include "walkgen/core/foot.hpp"
#include "walkgen/core/math.hpp"
#include "walkgen/interpolation/trajectory.hpp"
#include "walkgen/kinematics/ik_target.hpp"
#include "walkgen/kinematics/kinematic_tree.hpp"
#include "walkgen/mpc/walking_mpc.hpp"
#include "walkgen/robot/robot.hpp"
#include "walkgen/robot/robot_description.hpp"

namespace walkgen {

/// What a tick of the loop ended with. Anything but ok, qp_failed or not_converged stops the
/// walk.
enum class LoopStatus : std::uint8_t {
  ok,           ///< the tick's samples were executed
  qp_failed,    ///< the NMPC kept its previous (shifted) plan, which was executed; see MpcStatus
  fallen,       ///< the robot reports a fall (RobotStatus::fallen); the loop stops
  diverged,     ///< the simulation diverged (RobotStatus::diverged); the loop stops
  not_started,  ///< tick() before start(), or after the robot stopped
  /// the NMPC's plan, executed, violates its nonlinear constraints by more than sqp_tolerance
  /// (MpcStatus::not_converged; LoopTick::mpc and the generator's result say by how much)
  not_converged,
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
  }
  return "unknown";
}

/// Settings of the loop itself; the generator's are WalkingSettings (t, command_period,
/// t_feedback), the solver's its own.
struct WalkingLoopSettings {
  /// Feed the measured CoM back to the NMPC every WalkingSettings::t_feedback (§6.3).
  bool com_feedback = true;
  /// Fraction of the measured − planned CoM position fed back, in (0, 1]. Velocity and
  /// acceleration stay the plan's: differentiated joint measurements are too noisy to help.
  double feedback_gain = 1.0;
  /// Sole links of the tree (left, right): where the IK puts the feet and the feedback starts.
  /// Defaults: walkgen's humanoid (walkgen_humanoid_description()); loop_settings() takes them
  /// from any description.
  std::string left_sole_link = walkgen_humanoid_description().sole_frames[0];
  std::string right_sole_link = walkgen_humanoid_description().sole_frames[1];
  /// Frames of the ankle force-torque sensors in the tree (left, right): where the robot's
  /// readings are (the soles for a robot that reports contact forces instead).
  std::string left_ft_sensor_link = walkgen_humanoid_description().ft_sensor_frames[0];
  std::string right_ft_sensor_link = walkgen_humanoid_description().ft_sensor_frames[1];
  /// [s] start(): time to move the CoM from where it stands over the support foot.
  double transfer_time = 2.0;
};

/// Checks the loop's own settings (the sole and sensor links are checked against the IK's tree
/// by WalkingLoop's constructor, which calls this).
/// @throws walkgen::invalid_argument naming the first bad field.
inline void validate(const WalkingLoopSettings& s) {
  check_argument(s.feedback_gain > 0.0 && s.feedback_gain <= 1.0,
                 "WalkingLoopSettings.feedback_gain", "a fraction in (0, 1]", s.feedback_gain);
  check_argument(std::isfinite(s.transfer_time) && s.transfer_time >= 0.0,
                 "WalkingLoopSettings.transfer_time", "a duration >= 0 [s]", s.transfer_time);
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
  return s;
}

/// One command period of the loop: what was planned and what was measured after it.
struct LoopSample {
  TrajectorySample<double> plan;  ///< the interpolated pattern (CoM, ZMP, feet), world frame
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
  IkStatus ik = IkStatus::converged;
};

/// Summary of one tick (one NMPC period t).
struct LoopTick {
  LoopStatus status = LoopStatus::not_started;
  MpcStatus mpc = MpcStatus::solved;
  /// Samples whose IK did not converge (previous joints sent again) or whose joints the robot
  /// rejected as non-finite (previous targets kept).
  int ik_failures = 0;
  bool fed_back = false;
  /// Measured − planned CoM position at the feedback of this tick [m] (zero without one).
  Eigen::Vector2d com_error = Eigen::Vector2d::Zero();
  /// Why, unless status is ok: the robot's message when it stopped, the NMPC's (MpcResult::
  /// message) when its QP failed or its plan did not converge.
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
        interp_(interpolation_settings(settings)) {
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
  /// standing still).
  /// @return ok, or fallen / diverged when the robot stopped during the transfer; ik_failures
  ///   counts the transfer's samples whose IK did not converge (previous joints sent again).
  [[nodiscard]] const LoopTick& start() {
    tick_ = LoopTick();
    started_ = false;
    const WalkingSettings<double>& s = mpc_.settings();
    const Foot support = s.support_foot;
    const FootPose<double> support_pose{s.foot_x, s.foot_y, s.foot_q};
    to_tree_order(robot_.output().q);
    place_on_sole(support, support_pose);
    ik_.set_initial_guess(base_p_W_, base_R_W_, q_tree_);
    IkTarget target;
    const FootPose<double> feet[2] = {sole_pose(Foot::left), sole_pose(Foot::right)};
    target.left_foot = {Eigen::Vector3d(feet[0].x, feet[0].y, 0.0), feet[0].q};
    target.right_foot = {Eigen::Vector3d(feet[1].x, feet[1].y, 0.0), feet[1].q};
    target.hold_upright((feet[0].q + feet[1].q) / 2.0);
    const Eigen::Vector3d c0 = com_W();
    const Eigen::Vector3d c1(s.com_x[0], s.com_y[0], s.com_z);
    const double dt = interp_.command_period();
    const int n = std::max(1, int(std::lround(loop_.transfer_time / dt)));
    for (int k = 1; k <= n; ++k) {
      const double r = double(k) / double(n);
      const double blend = r * r * r * (10.0 - 15.0 * r + 6.0 * r * r);  // minimum jerk
      target.com_W = c0 + blend * (c1 - c0);
      tick_.ik_failures += ik_.solve(target).status != IkStatus::converged;  // previous joints
      if (!send_and_step(dt)) return tick_;
    }
    to_tree_order(robot_.output().q);
    place_on_sole(support, support_pose);
    const Eigen::Vector3d c = com_W();
    typename Mpc::State st;
    st.com_x << c.x(), 0.0, 0.0;
    st.com_y << c.y(), 0.0, 0.0;
    st.support_foot = support;
    st.support = support_pose;
    st.swing_origin = sole_pose(other(support));
    st.swing = FootMotion<double>::at_rest(st.swing_origin);
    mpc_.reset(st);
    samples_.resize(plan_.size());
    ticks_ = 0;
    started_ = true;
    tick_.status = LoopStatus::ok;
    return tick_;
  }

  /// The velocity command (v_x, v_y [m/s], ω_z [rad/s]) in the robot frame, for the next ticks.
  [[nodiscard]] CommandStatus set_command(const Eigen::Vector3d& command) {
    return mpc_.set_command(command);
  }

  /// One NMPC period: feedback (when due), solve, interpolate, and per command period IK,
  /// joint targets and a robot step. samples() holds what happened.
  [[nodiscard]] const LoopTick& tick() {
    tick_ = LoopTick();
    if (!started_) {
      tick_.message = "WalkingLoop::tick: call start() first (or the robot stopped)";
      return tick_;
    }
    if (loop_.com_feedback && ticks_ > 0 && ticks_ % feedback_every_ == 0) feed_back();
    const MpcResult<double>& solved = mpc_.solve();
    tick_.mpc = solved.status;
    const char* mpc_message = solved.message;
    interp_.interpolate(mpc_.tick_plan(), plan_.data());
    const double dt = interp_.command_period();
    for (std::size_t k = 0; k < plan_.size(); ++k) {
      LoopSample& out = samples_[k];
      out.plan = plan_[k];
      out.ik = ik_.solve(ik_target(plan_[k])).status;
      tick_.ik_failures += out.ik != IkStatus::converged;  // the previous joints stay
      const bool running = send_and_step(dt);
      const RobotOutput& m = robot_.output();
      out.ft = m.ft;
      out.base_height = m.base_height;
      to_tree_order(m.q);
      place_on_sole(plan_[k].support_foot, planned_support(plan_[k]));
      out.com_measured_W = com_W();
      for (int f = 0; f < 2; ++f) {  // the same wrenches, at the sensor poses of this FK
        ft_fk_[std::size_t(f)] = m.ft[std::size_t(f)];
        ft_fk_[std::size_t(f)].pose_W_S.linear() = link_rotation_W(sensor_[f]);
        ft_fk_[std::size_t(f)].pose_W_S.translation() = link_position_W(sensor_[f]);
      }
      out.zmp = measured_zmp(ft_fk_, robot_.info().ft_sensor_height);
      if (!running) {
        samples_.resize(k + 1);  // what happened up to the stop (no reallocation: shrinks)
        return tick_;
      }
    }
    mpc_.advance();
    ++ticks_;
    tick_.status = tick_.mpc == MpcStatus::solved          ? LoopStatus::ok
                   : tick_.mpc == MpcStatus::not_converged ? LoopStatus::not_converged
                                                           : LoopStatus::qp_failed;
    if (tick_.status != LoopStatus::ok) tick_.message = mpc_message;  // a failed tick only
    return tick_;
  }

  /// The command periods of the last tick (fewer when the robot stopped during it).
  const std::vector<LoopSample>& samples() const { return samples_; }
  const LoopTick& last_tick() const { return tick_; }

  /// The generator, e.g. for obstacles (mpc().set_obstacles()) or its plan.
  Mpc& mpc() { return mpc_; }
  const Mpc& mpc() const { return mpc_; }
  const WalkingLoopSettings& settings() const { return loop_; }
  long ticks() const { return ticks_; }

 private:
  void to_tree_order(const Eigen::VectorXd& q_robot) {
    for (std::size_t j = 0; j < to_tree_.size(); ++j) {
      q_tree_[to_tree_[j]] = q_robot[Eigen::Index(j)];
    }
  }

  /// Sends the IK's joints to the robot and steps it by dt; false (status and message set,
  /// the loop stopped) when the robot stopped. A robot rejects non-finite joints and keeps its
  /// previous targets: such a sample counts as one whose IK failed.
  bool send_and_step(double dt) {
    for (std::size_t j = 0; j < to_tree_.size(); ++j) {
      q_robot_[Eigen::Index(j)] = ik_.q()[to_tree_[j]];
    }
    if (robot_.set_joint_targets(q_robot_) != JointCommandStatus::accepted) ++tick_.ik_failures;
    const RobotStatus rs = robot_.step(dt);
    if (rs == RobotStatus::ok) return true;
    tick_.status = rs == RobotStatus::fallen ? LoopStatus::fallen : LoopStatus::diverged;
    tick_.message = robot_.output().message;
    started_ = false;
    return false;
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

  /// §6.3: the CoM of the measured joints, from the support sole where the plan has it.
  void feed_back() {
    const RobotOutput& m = robot_.output();
    to_tree_order(m.q);
    typename Mpc::State st = mpc_.state();
    place_on_sole(st.support_foot, st.support);
    const Eigen::Vector3d c = com_W();
    tick_.com_error = Eigen::Vector2d(c.x() - st.com_x[0], c.y() - st.com_y[0]);
    st.com_x[0] += loop_.feedback_gain * tick_.com_error.x();
    st.com_y[0] += loop_.feedback_gain * tick_.com_error.y();
    mpc_.set_state(st);  // throws on non-finite measurements
    tick_.fed_back = true;
  }

  WalkingLoopSettings loop_;
  Robot& robot_;
  Ik& ik_;
  const KinematicTree<double>& tree_;
  typename KinematicTree<double>::Workspace ws_;
  Mpc mpc_;
  WalkingInterpolator<double> interp_;
  int feedback_every_ = 1;
  int sole_[2] = {0, 0};
  int sensor_[2] = {0, 0};
  std::array<ForceTorqueReading, 2> ft_fk_;
  std::vector<Eigen::Index> to_tree_;
  Eigen::VectorXd q_tree_, q_robot_;
  Eigen::Vector3d base_p_W_ = Eigen::Vector3d::Zero();
  Eigen::Matrix3d base_R_W_ = Eigen::Matrix3d::Identity();
  std::vector<TrajectorySample<double>> plan_;
  std::vector<LoopSample> samples_;
  LoopTick tick_;
  long ticks_ = 0;
  bool started_ = false;
};

}  // namespace walkgen
