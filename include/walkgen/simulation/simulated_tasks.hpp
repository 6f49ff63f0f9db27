#pragma once
/// @file
/// The four test tasks of thesis §9.2 with walkgen's humanoid in MuJoCo, closed loop (figure
/// 6.1, SimLoop): walk to a target object, steered by GoToTarget instead of the
/// thesis's keyboard user, with what each run measured (reached, time, ZMP statistics). Run by
/// examples/walking_simulation, tests/mujoco/test_walking_loop.cpp and bench_simulation.
///
/// World frame = the generator's: the robot starts at the origin facing +x (left sole at
/// (0, 0.07)). Heicub's settings (Table 6.1) unchanged: 0.034 m/s and 0.075 rad/s at most.
///
/// Target simulation: needs humanoid (Ceres, URDF) and mujoco.

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include "walkgen/core/exceptions.hpp"
#include "walkgen/mujoco/robot_model.hpp"
#include "walkgen/simulation/humanoid_loop.hpp"

namespace walkgen {

/// A task: walk until the CoM is within kTaskReachDistance of the target object.
struct SimTask {
  std::string name;                                  ///< straight, curved, obstacle or scan
  std::string description;                           ///< one line for people
  Eigen::Vector2d target = Eigen::Vector2d::Zero();  ///< the target object's centre [m]
  std::vector<CircleObstacle<double>> obstacles;     ///< NMPC obstacles (eq. 2.79 circles)
  double time_limit = 120.0;                         ///< [s] simulated
};

/// Success: the true CoM (MuJoCo) ends within this distance of the target's centre [m].
constexpr double kTaskReachDistance = 0.25;
/// The steering stops this far from the target (the object is 0.05 m in radius and the toes
/// reach 0.1 m ahead of the CoM).
constexpr double kTaskStopDistance = 0.2;

/// §9.2: straight 2 m; a target on the left (curved walk); a chair on the straight way (obstacle
/// avoidance); the target behind the robot (environmental scan: turn 180° first). `scale` < 1
/// gives shorter versions (distances scaled, the obstacle's size kept).
/// @throws walkgen::invalid_argument unless scale is finite and > 0.
inline std::vector<SimTask> section_9_2_tasks(double scale = 1.0) {
  check_positive("walkgen::section_9_2_tasks: scale", scale);
  std::vector<SimTask> tasks;
  tasks.push_back({"straight", "walk 2 m straight to the target", {2.0 * scale, 0.0}, {}, 0.0});
  tasks.push_back({"curved",
                   "the target is ahead on the left: curved walk",
                   {1.2 * scale, 1.0 * scale},
                   {},
                   0.0});
  // The chair: 0.2 m square (radius 0.15 m around its centre) on the straight way; the margin
  // keeps the footstep centres half a foot length (0.1 m) away.
  tasks.push_back({"obstacle",
                   "a chair on the straight way to the target",
                   {2.0 * scale, 0.0},
                   {{1.0 * scale, 0.05, 0.15, 0.12}},
                   0.0});
  tasks.push_back({"scan",
                   "start facing away: turn 180 degrees, then walk to the target",
                   {-1.5 * scale, 0.3 * scale},
                   {},
                   0.0});
  for (auto& t : tasks) {
    // Walking at 0.032 m/s, turning at 0.071 rad/s, plus a margin for detours and the stop.
    const double path = t.target.norm() + (t.obstacles.empty() ? 0.0 : 0.3);
    const double turn = std::abs(std::atan2(t.target.y(), t.target.x()));
    t.time_limit = 20.0 + 1.5 * (path / 0.032 + turn / 0.071);
  }
  return tasks;
}

/// The objects of a task's scene: the target (a red-orange cylinder standing for the fire
/// extinguisher) and a chair-like box per obstacle.
inline std::vector<SceneObject> task_objects(const SimTask& task) {
  std::vector<SceneObject> objects;
  SceneObject target;
  target.name = "target";
  target.shape = SceneShape::cylinder;
  target.position = Eigen::Vector3d(task.target.x(), task.target.y(), 0.0);
  target.size = Eigen::Vector3d(0.05, 0.05, 0.35);
  target.rgb = Eigen::Vector3d(0.9, 0.15, 0.05);
  objects.push_back(target);
  for (std::size_t i = 0; i < task.obstacles.size(); ++i) {
    const auto& o = task.obstacles[i];
    SceneObject chair;
    chair.name = "obstacle_" + std::to_string(i);
    chair.shape = SceneShape::box;
    chair.position = Eigen::Vector3d(o.x, o.y, 0.0);
    const double side = o.radius * std::sqrt(2.0);  // the square inscribed in the circle
    chair.size = Eigen::Vector3d(side, side, 0.3);
    chair.rgb = Eigen::Vector3d(0.35, 0.25, 0.15);
    objects.push_back(chair);
  }
  return objects;
}

/// One command period of a task run (positions in the world frame [m]).
struct TaskRow {
  double time = 0.0;                                  ///< the plan's time [s]
  Eigen::Vector3d command = Eigen::Vector3d::Zero();  ///< (v_x, v_y, ω_z) of the tick
  Eigen::Vector2d com_plan = Eigen::Vector2d::Zero(), zmp_plan = Eigen::Vector2d::Zero();
  Eigen::Vector2d zmp_measured = Eigen::Vector2d::Zero();  ///< plan frame (FK), see LoopSample
  Eigen::Vector2d zmp_true = Eigen::Vector2d::Zero();      ///< MuJoCo's world, true sensor poses
  Eigen::Vector2d com_true = Eigen::Vector2d::Zero();      ///< MuJoCo's whole-body CoM
  double support_margin = 0.0;  ///< of zmp_true in the true support polygon [m]
  double base_height = 0.0;     ///< [m]
  bool zmp_valid = false;       ///< both ZMP measurements are valid (a foot on the ground)
};

/// What a task run measured.
struct TaskResult {
  bool reached = false;  ///< the steering stopped, and the true CoM is within kTaskReachDistance
  bool stopped = false;  ///< the steering reported the target reached
  LoopStatus status =
      LoopStatus::ok;  ///< ok unless the robot fell/diverged or a fault stopped the walk
  std::string message;
  double final_distance = 0.0;  ///< true CoM to the target's centre [m]
  double time = 0.0;            ///< simulated [s], transfer excluded
  /// Smallest distance of a sole centre in contact (true pose) to an obstacle's centre [m].
  double min_obstacle_distance = 1e9;
  int qp_failures = 0, ik_failures = 0;
  /// steering commands the loop did not walk as given (non-finite: rejected; too large: clamped)
  int rejected_commands = 0;
  double min_base_height = 1e9;
  std::vector<TaskRow> rows;  ///< every command period

  /// NMPC ZMP vs measured ZMP (plan frame) over the samples with a valid measurement [m].
  void zmp_distance(double& mean, double& stddev) const {
    double s = 0.0, s2 = 0.0;
    long n = 0;
    for (const auto& r : rows) {
      if (!r.zmp_valid) continue;
      const double d = (r.zmp_measured - r.zmp_plan).norm();
      s += d;
      s2 += d * d;
      ++n;
    }
    mean = n > 0 ? s / double(n) : 0.0;
    stddev = n > 1 ? std::sqrt(std::max(0.0, s2 / double(n) - mean * mean)) : 0.0;
  }
  /// The robot fell (the loop stopped with LoopStatus::fallen; a diverged simulation is not a
  /// fall, see status).
  bool fallen() const { return status == LoopStatus::fallen; }
  /// [m/s] Mean speed over the task: the true CoM's displacement from the first row (the end
  /// of the first command period) to the last over the time between them, the net progress
  /// (the sway of the steps cancels out; the standing start counts as time). 0 with fewer than
  /// two rows or no time between them.
  double mean_speed() const { return net_speed(&TaskRow::com_true); }
  /// [m/s] The same for the planned CoM.
  double planned_mean_speed() const { return net_speed(&TaskRow::com_plan); }

  /// Fraction of the samples with a valid measurement whose true ZMP is in the true polygon.
  double inside_fraction() const {
    long n = 0, in = 0;
    for (const auto& r : rows) {
      if (!r.zmp_valid) continue;
      ++n;
      in += r.support_margin >= 0.0;
    }
    return n > 0 ? double(in) / double(n) : 0.0;
  }

 private:
  double net_speed(Eigen::Vector2d TaskRow::*com) const {
    if (rows.size() < 2) return 0.0;
    const double dt = rows.back().time - rows.front().time;
    return dt > 0.0 ? (rows.back().*com - rows.front().*com).norm() / dt : 0.0;
  }
};

/// `robot` (default walkgen's humanoid) in MuJoCo with the objects of `task`.
inline MujocoRobotSettings task_robot_settings(
    const SimTask& task, const RobotDescription& robot = walkgen_humanoid_description()) {
  MujocoRobotSettings s = mujoco_robot_settings(robot);
  s.objects = task_objects(task);
  s.view_width = 960;  // walking_simulation --video films at up to 960 x 540
  s.view_height = 540;
  return s;
}

/// `robot`'s walking settings (RobotDescription::walking; walkgen's humanoid: Heicub's) with the
/// task's obstacles.
inline WalkingSettings<double> task_walking_settings(
    const SimTask& task, const RobotDescription& robot = walkgen_humanoid_description()) {
  WalkingSettings<double> s = robot.walking;
  s.obstacles = task.obstacles;
  return s;
}

/// The kinematic tree the closed loop of `robot` uses: from its URDF when the description names
/// one, else from its MJCF (plus the frames the description adds).
/// @throws walkgen::invalid_argument when the model cannot be read or lacks a name of `robot`.
inline KinematicTree<double> robot_kinematic_tree(const RobotDescription& robot) {
  return robot.urdf_path.empty() ? robot_kinematic_tree_from_mjcf(robot)
                                 : kinematic_tree_from_urdf_file(robot.urdf_path);
}

/// The closed loop of any robot described by a file: horizon 16, the Ceres IK sized at run
/// time (walkgen's humanoid has SimLoop, with its joint count fixed at compile time).
using RobotLoop = WalkingLoop<16, CeresInverseKinematics<>>;

/// Calls `walk(ik)` with the Ceres IK of `robot` (ceres_ik_settings(robot)) on its kinematic
/// tree: HumanoidIk (fixed-size, SimLoop's) for a robot of kHumanoidJoints joints,
/// CeresInverseKinematics<> (sized at run time, RobotLoop's) otherwise; returns what `walk`
/// returns. `walk` is generic in the IK's type, e.g. to build a WalkingLoop<16, Ik>.
/// @throws walkgen::invalid_argument when the robot's models cannot be read or lack a name of
///   the description.
template <typename Walk>
decltype(auto) with_robot_ik(const RobotDescription& robot, Walk&& walk) {
  const KinematicTree<double> tree = robot_kinematic_tree(robot);
  if (tree.num_joints() == kHumanoidJoints) {
    HumanoidIk ik(tree, ceres_ik_settings(robot));
    return walk(ik);
  }
  CeresInverseKinematics<> ik(tree, ceres_ik_settings(robot));
  return walk(ik);
}

/// `settings` (a robot's walking settings) moved into MuJoCo's world, where `robot` stands: the
/// walk starts on the left sole where the model put it, the initial CoM moved with it.
/// walkgen's humanoid stands exactly at its settings' foot pose; they come back unchanged.
inline WalkingSettings<double> settings_where_standing(WalkingSettings<double> settings,
                                                       const MujocoRobot& robot) {
  const Eigen::Vector2d sole = robot.output().ft[0].pose_W_S.translation().head<2>();
  const Eigen::Vector2d shift = sole - Eigen::Vector2d(settings.foot_x, settings.foot_y);
  if (shift.norm() > 1e-6) {
    settings.foot_x += shift.x();
    settings.foot_y += shift.y();
    settings.com_x[0] += shift.x();
    settings.com_y[0] += shift.y();
  }
  return settings;
}

/// What run_task() shows its caller after every tick: the robot, the generator's state (plan
/// frame = MuJoCo's world) and the result so far.
using TaskTickCallback =
    std::function<void(MujocoRobot&, const WalkingState<double>&, const TaskResult&)>;

namespace detail {

/// run_task() with the loop's IK `ik` (on `robot`'s tree, set up for it).
template <typename Ik>
TaskResult run_task_with(const SimTask& task, const RobotDescription& description, Ik& ik,
                         double settle, const TaskTickCallback& on_tick) {
  TaskResult result;
  MujocoRobot robot(task_robot_settings(task, description));
  // The plan's frame is MuJoCo's world.
  const WalkingSettings<double> settings =
      settings_where_standing(task_walking_settings(task, description), robot);
  WalkingLoop<16, Ik> loop(settings, robot, ik, loop_settings(description));
  const std::array<Eigen::Vector2d, 4> sole_region = sole_corners(description);
  const LoopTick& started = loop.start();
  const double t0 = robot.output().time;
  if (started.status != LoopStatus::ok) {
    result.status = started.status;
    result.message = started.message;
    return result;
  }
  GoToTargetSettings steering_settings;
  steering_settings.stop_distance = kTaskStopDistance;
  GoToTarget steering(task.target, settings.max_command, task.obstacles, steering_settings);
  double stopped_at = -1.0;
  while (robot.output().time - t0 < task.time_limit) {
    const GoToTargetCommand cmd = steering(measured_walking_pose(robot.output()));
    result.rejected_commands += loop.set_command(cmd.command) != CommandStatus::accepted;
    if (cmd.reached && stopped_at < 0.0) {
      result.stopped = true;
      stopped_at = robot.output().time;
    }
    const LoopTick& tick = loop.tick();
    // not solved, not relaxed (a relaxed plan comes from a solved elastic QP:
    // WalkingSettings::soft)
    result.qp_failures += tick.mpc != MpcStatus::solved && tick.mpc != MpcStatus::relaxed;
    result.ik_failures += tick.ik_failures;
    for (const LoopSample& s : loop.samples()) {
      TaskRow row;
      row.time = s.plan.time;
      row.command = cmd.command;
      row.com_plan = Eigen::Vector2d(s.plan.com_x[0], s.plan.com_y[0]);
      row.zmp_plan = Eigen::Vector2d(s.plan.zmp_x, s.plan.zmp_y);
      row.zmp_measured = s.zmp.zmp_W.head<2>();
      const MeasuredZmp truth = measured_zmp(s.ft, robot.info().ft_sensor_height);
      row.zmp_true = truth.zmp_W.head<2>();
      row.zmp_valid = s.zmp.valid && truth.valid;
      row.support_margin =
          support_polygon_margin(truth, s.ft, robot.info().ft_sensor_height, sole_region);
      row.base_height = s.base_height;
      for (int f = 0; f < 2; ++f) {  // soles on the ground, at their true poses
        if (!truth.in_contact[std::size_t(f)]) continue;
        const Eigen::Vector2d sole_xy = s.ft[std::size_t(f)].pose_W_S.translation().head<2>();
        for (const auto& o : task.obstacles) {
          result.min_obstacle_distance =
              std::min(result.min_obstacle_distance, (sole_xy - Eigen::Vector2d(o.x, o.y)).norm());
        }
      }
      result.min_base_height = std::min(result.min_base_height, s.base_height);
      result.rows.push_back(row);
    }
    // The true CoM at the end of the tick (the rows of a tick share it).
    const Eigen::Vector2d com = true_com(robot);
    for (std::size_t k = result.rows.size() - loop.samples().size(); k < result.rows.size(); ++k) {
      result.rows[k].com_true = com;
    }
    if (on_tick) on_tick(robot, loop.mpc().state(), result);
    if (tick.status == LoopStatus::fallen || tick.status == LoopStatus::diverged ||
        tick.status == LoopStatus::fault) {
      result.status = tick.status;
      result.message = tick.message;
      break;
    }
    if (stopped_at >= 0.0 && robot.output().time - stopped_at >= settle) break;
  }
  result.time = robot.output().time - t0;
  result.final_distance = (true_com(robot) - task.target).norm();
  result.reached = result.status == LoopStatus::ok && result.stopped &&
                   result.final_distance <= kTaskReachDistance;
  return result;
}

}  // namespace detail

/// Runs `task` closed loop with `robot` (a description: models/NAME/robot.yaml through
/// find_robot_description(), or walkgen_humanoid_description()) until the steering stops (plus
/// `settle` seconds standing), the time limit, or a fall. The loop is WalkingLoop<16, Ik> with
/// the Ceres IK of ceres_ik_settings(robot): fixed-size (SimLoop's) for a robot of
/// kHumanoidJoints joints, sized at run time (RobotLoop's) otherwise. `on_tick(robot, state,
/// result)` runs after every tick (e.g. to render). Numerical outcomes (QP and IK failures, a
/// fall) are in the result, never thrown.
/// @throws walkgen::invalid_argument when the robot's models cannot be loaded or lack a name of
///   the description.
inline TaskResult run_task(const SimTask& task, const RobotDescription& robot, double settle = 2.0,
                           const TaskTickCallback& on_tick = nullptr) {
  return with_robot_ik(
      robot, [&](auto& ik) { return detail::run_task_with(task, robot, ik, settle, on_tick); });
}

/// run_task() with walkgen's humanoid.
inline TaskResult run_task(const SimTask& task, double settle = 2.0,
                           const TaskTickCallback& on_tick = nullptr) {
  return run_task(task, walkgen_humanoid_description(), settle, on_tick);
}

}  // namespace walkgen
