// Push recovery (issue 24 item 6): how hard a kick the walking robot survives, by direction and
// gait phase. The closed loop of a robot (walkgen's humanoid, the Unitree G1, any described robot:
// NMPC, interpolation, IK, MuJoCo) walks forward at --speed (0.03 m/s); a force on the base for
// 0.1 s changes the robot's momentum by M Δv (M its whole
// mass, so that the CoM's velocity changes by Δv); the walk goes on for 4 s after the push.
// Survived: the loop reports no fall (the IMU's tilt, the base height) and the robot stands or
// walks at the end (a safe stop for QP failures counts as survived: the robot is up).
//
//   push_recovery [--robot R] [--speed V] [--out DIR] [--max-dv V] [--dv-step V]
//                 [--directions LIST] [--phases LIST] [--require-survival V]
//                 [--terrains LIST] [--distance D]
//                 [--max-offset V] [--feedback SOURCE] [--position-gain G]
//                 [--velocity-gain G] [--smooth-feedback] [--no-plot]
//     --robot R             walkgen_humanoid (default) or unitree_g1 (models/R/robot.yaml), or the
//                           path of a robot description file (docs/robots.md)
//     --speed V             the walk's forward command [m/s] (default 0.03)
//     --out DIR             output folder, created if missing (default: .)
//     --max-dv V            the largest velocity change [m/s] (default 0.6)
//     --dv-step V           the sweep's step [m/s] (default 0.05)
//     --directions LIST     forward, backward, left, right (default: all four)
//     --phases LIST         ss_start, ss_middle, ss_end (of single support), ds (the middle of
//                           double support) (default: all four)
//     --require-survival V  exit 1 unless every kick up to V m/s was survived (for tests)
//     --terrains LIST       straight walks of --distance without kicks on: flat, slope_up,
//                           slope_down, slope_left, slope_right (5°) (default: all five; the
//                           2 cm step needs scene objects that collide with the robot: not yet)
//     --distance D          how far each terrain walk goes [m] (default 2)
//     --max-offset V        exit 1 unless every slope walk got its distance and ended within V m
//                           of the line it started on (for tests)
//     --feedback SOURCE     the CoM fed back to the NMPC: kinematics (the measured joints from
//                           the planned support sole), estimator (BaseEstimator's position and
//                           velocity) or none; default: the description's (balance.nmpc_feedback:
//                           kinematics for walkgen's humanoid, none for the G1)
//     --position-gain G     estimator feedback: fraction of the CoM position error fed back
//                           (default 0.3, WalkingLoopSettings::estimated_position_gain)
//     --velocity-gain G     estimator feedback: fraction of the CoM velocity error (default 0.3)
//     --smooth-feedback     the executed CoM blends into each restarted plan over the tick
//                           instead of jumping to it (WalkingLoopSettings::smooth_feedback)
//     --no-plot             CSV only (the plot needs /usr/bin/python3 with matplotlib)
// The command line is parsed by CLI11 (examples/common/cli.hpp): --help lists every option.
//
// Writes push_summary.csv (robot,direction,phase,delta_v,survived; one row per kick, written
// atomically), terrain_summary.csv (robot,terrain,survived,distance,offset,yaw: one row per
// terrain walk; distance and offset [m] of the base along and across the walk, yaw [rad] its
// final heading) and push_survival.png (python/plot_push_survival.py: the survival map). Prints a
// line per kick and the largest survived kick per direction and phase. Exit status 0 when every
// kick ran and the files were written (and --require-survival held), 1 otherwise, 2 on a bad
// command line.
#include <sys/wait.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "common/cli.hpp"
#include "walkgen/core/atomic_file.hpp"
#include "walkgen/simulation/simulated_tasks.hpp"
#include "walkgen/yaml/robot_description_loader.hpp"

namespace {

constexpr double kPushDuration = 0.1;  ///< [s] the issue's kick: a velocity change over 0.1 s
constexpr double kAfter = 4.0;         ///< [s] walked after the push

/// The robot and how it walks: its description, the loop's settings and the forward command.
struct Setup {
  walkgen::RobotDescription robot;
  walkgen::WalkingLoopSettings loop;
  Eigen::Vector3d command{0.03, 0.0, 0.0};  ///< forward [m/s], sideways, yaw rate
};

/// Builds `setup`'s robot in MuJoCo from `ms` (mujoco_robot_settings() of its description, with
/// a push, a slope or objects added), its IK and closed loop (the plan's frame MuJoCo's world),
/// starts the walk with the command and returns body(robot, loop); when the walk does not start,
/// on_failure(message).
template <typename Body, typename OnFailure>
auto walk_with(const Setup& setup, const walkgen::MujocoRobotSettings& ms,
               const std::function<void(walkgen::MujocoRobot&)>& before, Body&& body,
               OnFailure&& on_failure) {
  walkgen::MujocoRobot robot(ms);
  if (before) before(robot);
  const walkgen::WalkingSettings<double> walking =
      walkgen::settings_where_standing(setup.robot.walking, robot);
  return walkgen::with_robot_ik(setup.robot, [&](auto& ik) {
    walkgen::WalkingLoop<16, std::decay_t<decltype(ik)>> loop(walking, robot, ik, setup.loop);
    if (loop.start().status != walkgen::LoopStatus::ok ||
        loop.set_command(setup.command) != walkgen::CommandStatus::accepted) {
      return on_failure(loop.last_tick().message);
    }
    return body(robot, loop);
  });
}

/// When each phase's push starts [s], from a walk without pushes: in the second step's single
/// support (the first is the walk's start) and the double support after it.
struct PhaseTimes {
  std::map<std::string, double> start;
  std::string error;  // empty when found
};

PhaseTimes phase_times(const Setup& setup) {
  return walk_with(
      setup, walkgen::mujoco_robot_settings(setup.robot), nullptr,
      [](walkgen::MujocoRobot&, auto& loop) {
        PhaseTimes p;
        // Intervals of single support (ss) and double support (ds), in order.
        std::vector<std::pair<bool, std::pair<double, double>>> intervals;  // (ds, [t0, t1])
        for (int k = 0; k < 240 && intervals.size() < 6; ++k) {
          if (loop.tick().status != walkgen::LoopStatus::ok) {
            p.error = "the unpushed walk failed: " + loop.last_tick().message;
            return p;
          }
          for (const auto& s : loop.samples()) {
            if (intervals.empty() || intervals.back().first != s.plan.double_support) {
              intervals.push_back({s.plan.double_support, {s.plan.time, s.plan.time}});
            }
            intervals.back().second.second = s.plan.time;
          }
        }
        // The second complete single support and the double support after it.
        int singles = 0;
        for (std::size_t i = 1; i + 2 < intervals.size(); ++i) {  // [0] may be cut by the start
          if (intervals[i].first || ++singles < 2) continue;
          const auto [s0, s1] = intervals[i].second;
          const auto [d0, d1] = intervals[i + 1].second;
          p.start["ss_start"] = s0 + 0.05;
          p.start["ss_middle"] = 0.5 * (s0 + s1) - 0.5 * kPushDuration;
          p.start["ss_end"] = s1 - kPushDuration - 0.05;
          p.start["ds"] = 0.5 * (d0 + d1) - 0.5 * kPushDuration;
          return p;
        }
        p.error = "no complete single support in the unpushed walk";
        return p;
      },
      [](const std::string& message) {
        PhaseTimes p;
        p.error = "the unpushed walk did not start: " + message;
        return p;
      });
}

/// One kick: true when the robot did not fall.
bool survives(const Setup& setup, const Eigen::Vector3d& force, double at, std::string& how) {
  return walk_with(
      setup, walkgen::mujoco_robot_settings(setup.robot),
      [&](walkgen::MujocoRobot& robot) { robot.push(force, at, kPushDuration); },
      [&](walkgen::MujocoRobot& robot, auto& loop) {
        while (robot.output().time < at + kAfter) {
          const walkgen::LoopTick& t = loop.tick();
          if (t.status == walkgen::LoopStatus::fallen ||
              t.status == walkgen::LoopStatus::diverged) {
            how = t.message;
            return false;
          }
          if (t.mode == walkgen::LoopMode::fault) {  // held: survived if it stays up
            how = t.message;
          }
        }
        if (how.empty()) how = to_string(loop.mode());
        return robot.output().status == walkgen::RobotStatus::ok;
      },
      [&](const std::string& message) {
        how = "did not start: " + message;
        return false;
      });
}

Eigen::Vector3d direction_vector(const std::string& d) {
  if (d == "forward") return Eigen::Vector3d::UnitX();
  if (d == "backward") return -Eigen::Vector3d::UnitX();
  if (d == "left") return Eigen::Vector3d::UnitY();
  return -Eigen::Vector3d::UnitY();  // right
}

/// The terrains of the straight walk (issue 24 item 6): the flat floor, slopes of kSlope up,
/// down, rising to the left or to the right of the walk, and a kStepHeight step up.
constexpr double kSlope = 5.0 * 3.14159265358979323846 / 180.0;  ///< [rad] 5°
constexpr double kStepHeight = 0.02;                             ///< [m]
constexpr double kStepAt = 0.3;  ///< [m] ahead of the start, where the step's edge runs across

/// How a straight walk on a terrain ended.
struct TerrainWalk {
  bool survived = false;
  double distance = 0.0;  ///< [m] the base's progress along the walk (x)
  /// [m] how far the base's mean over the last gait cycle is from its mean over the first,
  /// across the walk (y); the base's last position when it walked less than two cycles
  double offset = 0.0;
  double yaw = 0.0;   ///< [rad] the base's heading at the end
  double time = 0.0;  ///< [s] walked
  std::string how;
};

/// Walks the setup's command straight until the base is `distance` ahead, the robot falls or twice
/// the time the distance needs has passed.
TerrainWalk walk_on(const Setup& setup, const std::string& terrain, double distance) {
  walkgen::MujocoRobotSettings ms = walkgen::mujoco_robot_settings(setup.robot);
  if (terrain == "slope_up") ms.slope.x() = kSlope;
  if (terrain == "slope_down") ms.slope.x() = -kSlope;
  if (terrain == "slope_left") ms.slope.y() = kSlope;
  if (terrain == "slope_right") ms.slope.y() = -kSlope;
  if (terrain == "step") {
    walkgen::SceneObject box;
    box.name = "step";
    box.size = Eigen::Vector3d(2.0 * distance + 2.0, 2.0, kStepHeight);
    box.position = Eigen::Vector3d(kStepAt + box.size.x() / 2.0, 0.0, 0.0);
    box.rgb = Eigen::Vector3d(0.6, 0.6, 0.6);
    ms.objects.push_back(box);
  }
  return walk_with(
      setup, ms, nullptr,
      [&](walkgen::MujocoRobot& robot, auto& loop) {
        const int base = mj_name2id(robot.model(), mjOBJ_BODY, ms.base_body.c_str());
        const auto base_xy = [&] {
          return Eigen::Vector2d(robot.data()->xpos[3 * base], robot.data()->xpos[3 * base + 1]);
        };
        TerrainWalk w;
        const Eigen::Vector2d start = base_xy();
        // The base sways from foot to foot: the line is that of its mean over a gait cycle (two
        // steps), the first one walked against the last.
        const auto& s = loop.mpc().settings();
        const std::size_t cycle = std::size_t(2 * s.samples_per_step());
        std::vector<double> sway;
        const double limit = robot.output().time + 2.0 * distance / setup.command.x();
        while (base_xy().x() - start.x() < distance && robot.output().time < limit) {
          const walkgen::LoopTick& t = loop.tick();
          if (t.status == walkgen::LoopStatus::fallen ||
              t.status == walkgen::LoopStatus::diverged || t.mode == walkgen::LoopMode::fault ||
              t.mode == walkgen::LoopMode::stopped) {
            w.how = t.message;
            break;
          }
          sway.push_back(base_xy().y());
        }
        const auto mean = [&](std::size_t first) {
          double sum = 0.0;
          for (std::size_t i = first; i < first + cycle; ++i) sum += sway[i];
          return sum / double(cycle);
        };
        const Eigen::Vector2d end = base_xy();
        w.distance = end.x() - start.x();
        w.offset = sway.size() >= 2 * cycle ? std::abs(mean(sway.size() - cycle) - mean(0))
                                            : std::abs(end.y() - start.y());
        w.yaw = walkgen::yaw_of(robot.output().imu.orientation_W_I.toRotationMatrix());
        w.time = robot.output().time;
        w.survived = robot.output().status == walkgen::RobotStatus::ok && w.how.empty();
        if (w.how.empty()) w.how = w.distance >= distance ? "reached" : "out of time";
        return w;
      },
      [](const std::string& message) {
        TerrainWalk w;
        w.how = "did not start: " + message;
        return w;
      });
}

/// Writes `header` and the rows `body` streams to `path` atomically; false (and a message on
/// stderr) when it cannot.
template <typename Body>
bool write_csv(const std::string& path, const char* header, const Body& body) {
  try {
    walkgen::write_atomically(path, [&](const std::string& temp) {
      std::ofstream out(temp);
      out << header << '\n';
      body(out);
      out.close();
      if (!out) throw std::runtime_error("cannot write " + temp);
    });
  } catch (const std::exception& e) {
    std::fprintf(stderr, "push_recovery: %s\n", e.what());
    return false;
  }
  return true;
}

bool succeeded(int status) { return status != -1 && WIFEXITED(status) && WEXITSTATUS(status) == 0; }

}  // namespace

int main(int argc, char** argv) {
  std::string robot_name = "walkgen_humanoid", out_dir = ".";
  double max_dv = 0.6, dv_step = 0.05, required = 0.0;
  bool no_plot = false;
  std::vector<std::string> directions = {"forward", "backward", "left", "right"};
  std::vector<std::string> phases = {"ss_start", "ss_middle", "ss_end", "ds"};
  std::vector<std::string> terrains = {"flat", "slope_up", "slope_down", "slope_left",
                                       "slope_right"};
  double distance = 2.0, max_offset = 0.0;
  std::string feedback;  // default: the description's
  double speed = 0.03;
  std::optional<double> position_gain, velocity_gain;
  bool smooth_feedback = false;
  CLI::App app{
      "Kicks the walking robot in MuJoCo (a force on the base for 0.1 s) in four directions at "
      "four gait phases and sweeps the velocity change: push_summary.csv and a survival map",
      "push_recovery"};
  walkgen_examples::cli_defaults(app);
  app.add_option("--robot", robot_name,
                 "the robot: walkgen_humanoid or unitree_g1 (models/NAME/robot.yaml), or the "
                 "path of a robot description file (docs/robots.md)");
  app.add_option("--speed", speed, "the walk's forward command [m/s], within the robot's limit")
      ->check(CLI::Range(0.0, 5.0) & walkgen_examples::positive);
  app.add_option("--out", out_dir, "output folder, created if missing");
  app.add_option("--max-dv", max_dv, "the largest velocity change of the sweep [m/s]")
      ->check(CLI::Range(0.0, 5.0) & walkgen_examples::positive);
  app.add_option("--dv-step", dv_step, "the step of the sweep [m/s]")
      ->check(CLI::Range(0.0, 5.0) & walkgen_examples::positive);
  app.add_option("--directions", directions, "kick directions (world frame; the robot walks +x)")
      ->check(CLI::IsMember({"forward", "backward", "left", "right"}))
      ->delimiter(',');
  app.add_option("--phases", phases,
                 "gait phases: start, middle, end of single support; middle of double support")
      ->check(CLI::IsMember({"ss_start", "ss_middle", "ss_end", "ds"}))
      ->delimiter(',');
  app.add_option("--require-survival", required,
                 "exit 1 unless every kick up to this velocity change was survived [m/s]")
      ->check(CLI::Range(0.0, 5.0));
  app.add_option("--terrains", terrains,
                 "straight walks without kicks: flat, slope_up, slope_down, slope_left, "
                 "slope_right (5 degrees), step (2 cm up)")
      ->check(
          CLI::IsMember({"flat", "slope_up", "slope_down", "slope_left", "slope_right", "step"}))
      ->delimiter(',');
  app.add_option("--distance", distance, "how far each terrain walk goes [m]")
      ->check(CLI::Range(0.0, 10.0) & walkgen_examples::positive);
  app.add_option("--max-offset", max_offset,
                 "exit 1 unless every slope walk reached --distance within this of its line [m]")
      ->check(CLI::Range(0.0, 10.0));
  app.add_option("--feedback", feedback,
                 "the CoM fed back to the NMPC: kinematics (the measured joints from the planned "
                 "support sole), estimator (position and velocity of the state estimator) or "
                 "none; default: the robot description's (balance.nmpc_feedback)")
      ->check(CLI::IsMember({"kinematics", "estimator", "none"}))
      ->default_str("");
  app.add_option("--position-gain", position_gain,
                 "estimator feedback: fraction of the CoM position error fed back (default 0.3)")
      ->check(CLI::Range(0.0, 1.0));
  app.add_option("--velocity-gain", velocity_gain,
                 "estimator feedback: fraction of the CoM velocity error fed back (default 0.3)")
      ->check(CLI::Range(0.0, 1.0));
  app.add_flag("--smooth-feedback", smooth_feedback,
               "blend the executed CoM into each restarted plan over the tick instead of jumping "
               "(WalkingLoopSettings::smooth_feedback)");
  app.add_flag("--no-plot", no_plot,
               "CSV only, no push_survival.png (plotting needs /usr/bin/python3 with matplotlib)");
  WALKGEN_CLI_PARSE(app, argc, argv);

  std::error_code ec;
  std::filesystem::create_directories(out_dir, ec);
  if (ec) {
    std::fprintf(stderr, "push_recovery: cannot create %s: %s\n", out_dir.c_str(),
                 ec.message().c_str());
    return 1;
  }
  Setup setup;
  try {
    setup.robot = walkgen::find_robot_description(robot_name);
  } catch (const walkgen::invalid_argument& e) {
    std::fprintf(stderr, "push_recovery: --robot: %s\n", e.what());
    return 2;
  }
  if (speed > setup.robot.walking.max_command.x()) {
    std::fprintf(stderr, "push_recovery: --speed %g m/s is beyond %s's limit of %g m/s\n", speed,
                 setup.robot.name.c_str(), setup.robot.walking.max_command.x());
    return 2;
  }
  setup.command.x() = speed;
  setup.loop = walkgen::loop_settings(setup.robot);
  if (feedback.empty()) {
    feedback = !setup.loop.com_feedback                                    ? "none"
               : setup.loop.feedback == walkgen::FeedbackSource::estimator ? "estimator"
                                                                           : "kinematics";
  }
  setup.loop.com_feedback = feedback != "none";
  if (feedback != "none") {
    setup.loop.feedback = feedback == "estimator" ? walkgen::FeedbackSource::estimator
                                                  : walkgen::FeedbackSource::kinematics;
  }
  if (position_gain) setup.loop.estimated_position_gain = *position_gain;
  if (velocity_gain) setup.loop.estimated_velocity_gain = *velocity_gain;
  if (smooth_feedback) setup.loop.smooth_feedback = true;
  double mass = 0.0;
  PhaseTimes times;
  try {
    times = phase_times(setup);
    walkgen::MujocoRobot probe(walkgen::mujoco_robot_settings(setup.robot));
    mass = mj_getTotalmass(probe.model());
  } catch (const walkgen::invalid_argument& e) {
    std::fprintf(stderr, "push_recovery: --robot %s: %s\n", robot_name.c_str(), e.what());
    return 2;
  }
  if (!times.error.empty()) {
    std::fprintf(stderr, "push_recovery: %s\n", times.error.c_str());
    return 1;
  }
  const int steps = int(std::floor(max_dv / dv_step + 1e-9));
  std::printf(
      "push_recovery: %s, %.2f kg, walking %.2f m/s, %s feedback; %zu directions x %zu phases "
      "x %d kicks of %g..%g m/s over %g s\n",
      setup.robot.name.c_str(), mass, speed, feedback.c_str(), directions.size(), phases.size(),
      steps, dv_step, steps * dv_step, kPushDuration);
  struct Row {
    std::string direction, phase;
    double dv;
    bool survived;
  };
  std::vector<Row> rows;
  bool required_held = true;
  for (const std::string& d : directions) {
    for (const std::string& ph : phases) {
      double best = 0.0;
      bool fell = false;
      for (int i = 1; i <= steps; ++i) {
        const double dv = i * dv_step;
        std::string how;
        const bool ok = survives(setup, mass * dv / kPushDuration * direction_vector(d),
                                 times.start.at(ph), how);
        rows.push_back({d, ph, dv, ok});
        std::printf("  %-8s %-9s dv %.2f m/s: %s (%s)\n", d.c_str(), ph.c_str(), dv,
                    ok ? "survived" : "FELL", how.c_str());
        std::fflush(stdout);
        if (ok && !fell) best = dv;
        fell = fell || !ok;
        if (!ok && dv <= required + 1e-9) required_held = false;
      }
      std::printf("%s at %s: survives up to %.2f m/s\n", d.c_str(), ph.c_str(), best);
    }
  }
  struct TerrainRow {
    std::string terrain;
    TerrainWalk walk;
  };
  std::vector<TerrainRow> walks;
  bool offset_held = true;
  for (const std::string& terrain : terrains) {
    const TerrainWalk w = walk_on(setup, terrain, distance);
    walks.push_back({terrain, w});
    std::printf(
        "terrain %-11s: %s, %.3f m ahead, %.1f mm off the line, yaw %.3f rad, %.1f s (%s)\n",
        terrain.c_str(), w.survived ? "up" : "FELL", w.distance, 1e3 * w.offset, w.yaw, w.time,
        w.how.c_str());
    std::fflush(stdout);
    if (max_offset > 0.0 && terrain.rfind("slope", 0) == 0 &&
        !(w.survived && w.distance >= distance && w.offset <= max_offset)) {
      offset_held = false;
    }
  }
  const std::string terrain_csv = out_dir + "/terrain_summary.csv";
  const std::string csv = out_dir + "/push_summary.csv";
  const bool written =
      write_csv(terrain_csv, "robot,terrain,survived,distance,offset,yaw",
                [&](std::ostream& out) {
                  for (const TerrainRow& r : walks) {
                    out << setup.robot.name << ',' << r.terrain << ',' << (r.walk.survived ? 1 : 0)
                        << ',' << r.walk.distance << ',' << r.walk.offset << ',' << r.walk.yaw
                        << '\n';
                  }
                }) &&
      write_csv(csv, "robot,direction,phase,delta_v,survived", [&](std::ostream& out) {
        for (const Row& r : rows) {
          out << setup.robot.name << ',' << r.direction << ',' << r.phase << ',' << r.dv << ','
              << (r.survived ? 1 : 0) << '\n';
        }
      });
  if (!written) return 1;
  std::printf("push_recovery: wrote %s (%zu walks)\n", terrain_csv.c_str(), walks.size());
  std::printf("push_recovery: wrote %s (%zu kicks)\n", csv.c_str(), rows.size());
  std::fflush(stdout);
  if (!no_plot) {
    const std::string cmd = walkgen_examples::python_command("plot_push_survival.py", csv);
    if (!succeeded(std::system(cmd.c_str()))) {
      std::fprintf(stderr, "push_recovery: plotting failed: %s\n", cmd.c_str());
      return 1;
    }
  }
  if (!offset_held) {
    std::fprintf(stderr,
                 "push_recovery: a slope walk fell, fell short of %g m or ended more than %g m "
                 "off its line\n",
                 distance, max_offset);
    return 1;
  }
  if (!required_held) {
    std::fprintf(stderr, "push_recovery: a kick of at most %g m/s was not survived\n", required);
    return 1;
  }
  return 0;
}
