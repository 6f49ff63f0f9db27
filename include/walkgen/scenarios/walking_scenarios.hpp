#pragma once
/// @file
/// The walking scenarios of thesis §9.1 (figures 9.1–9.3): straight, sideways, curved, turn on
/// the spot, a changing command sequence and obstacle avoidance, with the HRP-2 preset
/// (walking_scenarios(), run_scenario()), and the same scenarios at Heicub's speeds
/// (heicub_walk()). Shared by the generator's tests, the walking examples and the benchmarks.
///
/// Depends on the core only (Eigen).

#include <Eigen/Core>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "walkgen/core/exceptions.hpp"
#include "walkgen/interpolation/trajectory.hpp"
#include "walkgen/mpc/walking_mpc.hpp"

namespace walkgen {

/// A scenario of §9.1 with the HRP-2 preset (0.1 s ticks): its name, its obstacles and the
/// command at each tick. walking_scenarios() lists them; scenario() finds one by name.
struct Scenario {
  std::string name;  ///< straight, sideways, curved, turn, sequence or obstacle
  std::vector<CircleObstacle<double>> obstacles;  ///< eq. 2.79 circles (obstacle: one)
  int ticks = 200;                                ///< NMPC ticks of the run (20 s)
  /// Command at a tick, (v_x [m/s], v_y [m/s], ω_z [rad/s]) in the robot frame. "sequence"
  /// changes it every 40 ticks: forward, curve left, sideways, curve right, stop.
  Eigen::Vector3d command(int tick) const {
    if (name == "straight") return {0.1, 0.0, 0.0};
    if (name == "sideways") return {0.0, 0.1, 0.0};
    if (name == "curved") return {0.1, 0.0, 0.1};
    if (name == "turn") return {0.0, 0.0, 0.2};
    if (name == "obstacle") return {0.2, 0.0, 0.0};
    // "sequence": forward, curve left, sideways, curve right, stop.
    if (tick < 40) return {0.1, 0.0, 0.0};
    if (tick < 80) return {0.1, 0.0, 0.1};
    if (tick < 120) return {0.0, 0.1, 0.0};
    if (tick < 160) return {0.1, 0.0, -0.1};
    return {0.0, 0.0, 0.0};
  }
};

/// The six scenarios of §9.1, in the order of the thesis's figures.
inline std::vector<Scenario> walking_scenarios() {
  std::vector<Scenario> all;
  for (const char* name : {"straight", "sideways", "curved", "turn", "sequence", "obstacle"}) {
    Scenario s;
    s.name = name;
    if (s.name == "obstacle") s.obstacles.push_back({1.6, 1.0, 1.0, 0.4});
    all.push_back(s);
  }
  return all;
}

/// The scenario called `name`.
/// @throws walkgen::invalid_argument when no scenario has that name.
inline Scenario scenario(const std::string& name) {
  for (const auto& s : walking_scenarios()) {
    if (s.name == name) return s;
  }
  throw invalid_argument(detail::expected_got(
      "walkgen::scenario", "straight, sideways, curved, turn, sequence or obstacle",
      "'" + name + "'"));
}

/// A footstep as it landed (or the initial stance).
struct Landing {
  double time;            ///< [s] when it landed (0 for the initial stance)
  Foot foot;              ///< which foot landed
  FootPose<double> pose;  ///< where, in the world frame
};

/// Everything a scenario run produced.
struct ScenarioRun {
  std::vector<TrajectorySample<double>> samples;  ///< every command period
  std::vector<CommandStatus> commands;            ///< every tick: set_command()'s outcome
  std::vector<MpcResult<double>> results;         ///< every tick
  std::vector<WalkingState<double>> states;       ///< every tick, before solve()
  std::vector<WalkingPlan<double>> plans;         ///< every tick, after solve()
  std::vector<Landing> landings;                  ///< initial feet, then every landing
};

/// Runs `ticks` NMPC ticks with settings s on a generator of horizon N, the command at tick k
/// being command(k) (v_x, v_y, ω_z), interpolated at the command period. A rejected or clamped
/// command or a failed solve does not stop the run: it is in `commands` and `results`.
/// @throws walkgen::invalid_argument when the settings are invalid (WalkingMpc's constructor).
template <int N = Eigen::Dynamic, typename Command>
ScenarioRun run_commands(const WalkingSettings<double>& s, const Command& command, int ticks) {
  WalkingMpc<double, N> mpc(s);
  WalkingInterpolator<double> interp(interpolation_settings(s));
  ScenarioRun run;
  const auto& st0 = mpc.state();
  run.landings.push_back({0.0, st0.support_foot, st0.support});
  run.landings.push_back({0.0, other(st0.support_foot), st0.swing_origin});
  std::vector<TrajectorySample<double>> buffer(std::size_t(interp.samples_per_tick()));
  for (int k = 0; k < ticks; ++k) {
    run.commands.push_back(mpc.set_command(command(k)));
    run.states.push_back(mpc.state());
    run.results.push_back(mpc.solve());
    run.plans.push_back(mpc.plan());
    interp.interpolate(mpc.tick_plan(), buffer.data());
    run.samples.insert(run.samples.end(), buffer.begin(), buffer.end());
    const long steps = mpc.state().step_count;
    mpc.advance();
    if (mpc.state().step_count != steps) {
      run.landings.push_back({mpc.state().time, mpc.state().support_foot, mpc.state().support});
    }
  }
  return run;
}

/// Runs a scenario with settings s (its obstacles replaced by the scenario's) on a generator of
/// horizon N (run_commands()).
/// @throws walkgen::invalid_argument when the settings are invalid (WalkingMpc's constructor).
template <int N = Eigen::Dynamic>
ScenarioRun run_scenario(const Scenario& sc, WalkingSettings<double> s) {
  s.obstacles = sc.obstacles;
  return run_commands<N>(
      s, [&sc](int k) { return sc.command(k); }, sc.ticks);
}

/// Steady-state walking velocity of a run: the CoM velocity in the robot frame (x, y) and the
/// yaw rate, from `cycles` consecutive gait cycles (2 steps of `cycle` ticks each) starting at
/// tick `first`. The CoM sways and, turning, circles the turning centre, so the velocity is that
/// of its mean over each gait cycle (every command-period sample), rotated into the heading
/// between two consecutive cycles. `t` is the tick period [s]; the result is (v_x [m/s],
/// v_y [m/s], ω_z [rad/s]).
/// @throws walkgen::invalid_argument unless first ≥ 0, cycles ≥ 1, cycle ≥ 1 and
///   first + (cycles + 1) cycle ≤ the run's ticks.
inline Eigen::Vector3d mean_velocity(const ScenarioRun& run, int first, int cycles, int cycle,
                                     double t) {
  check_argument(first >= 0 && cycles >= 1 && cycle >= 1 &&
                     long(first) + long(cycles + 1) * long(cycle) <= long(run.states.size()),
                 "walkgen::mean_velocity", "first + (cycles + 1) cycle <= the run's ticks",
                 std::to_string(first) + " + " + std::to_string(cycles + 1) + " * " +
                     std::to_string(cycle) + " with " + std::to_string(run.states.size()) +
                     " ticks");
  check_positive("walkgen::mean_velocity: t", t);
  const std::size_t per_tick = run.samples.size() / run.states.size();
  auto mean_of_cycle = [&](int tick) {
    Eigen::Vector3d m = Eigen::Vector3d::Zero();  // x, y, heading
    const std::size_t a = std::size_t(tick) * per_tick, b = std::size_t(tick + cycle) * per_tick;
    for (std::size_t i = a; i < b && i < run.samples.size(); ++i) {
      const auto& o = run.samples[i];
      m += Eigen::Vector3d(o.com_x[0], o.com_y[0],
                           (o.left.motion.q.position + o.right.motion.q.position) / 2);
    }
    return Eigen::Vector3d(m / double(b - a));
  };
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (int c = 0; c < cycles; ++c) {
    const Eigen::Vector3d a = mean_of_cycle(first + c * cycle);
    const Eigen::Vector3d b = mean_of_cycle(first + (c + 1) * cycle);
    const double q = (a[2] + b[2]) / 2, dx = b[0] - a[0], dy = b[1] - a[1];
    mean += Eigen::Vector3d(std::cos(q) * dx + std::sin(q) * dy,
                            -std::sin(q) * dx + std::cos(q) * dy, b[2] - a[2]);
  }
  return mean / (cycles * cycle * t);
}

/// The scenarios at Heicub's speeds, within heicub_settings().max_command = (0.034 m/s,
/// 0.0045 m/s, 0.075 rad/s): the command (v_x, v_y, ω_z) of scenario `name` at tick k (0.4 s
/// ticks). "sequence" changes it every `phase` ticks: forward, curve left, sideways, curve
/// right, stop. "obstacle" walks straight at the obstacle of heicub_obstacle().
/// @throws walkgen::invalid_argument when no scenario has that name, or phase < 1.
inline Eigen::Vector3d heicub_scenario_command(const std::string& name, int k, int phase) {
  if (name == "straight" || name == "obstacle") return {0.034, 0.0, 0.0};
  if (name == "sideways") return {0.0, 0.0045, 0.0};
  if (name == "curved") return {0.03, 0.0, 0.06};
  if (name == "turn") return {0.0, 0.0, 0.075};
  check_argument(name == "sequence", "walkgen::heicub_scenario_command",
                 "straight, sideways, curved, turn, sequence or obstacle", "'" + name + "'");
  check_argument(phase >= 1, "walkgen::heicub_scenario_command: phase", "ticks >= 1", phase);
  switch (k / phase) {
    case 0:
      return {0.034, 0.0, 0.0};
    case 1:
      return {0.03, 0.0, 0.075};
    case 2:
      return {0.0, 0.0045, 0.0};
    case 3:
      return {0.03, 0.0, -0.075};
    default:
      return {0.0, 0.0, 0.0};
  }
}

/// The obstacle of scenario `name` at Heicub's scale: for "obstacle", a circle across the left
/// foot's straight path 0.45 m ahead (radius 0.1 m, margin 0.05 m), which the walk steps around
/// and past within 64 ticks; none for the other scenarios.
inline std::vector<CircleObstacle<double>> heicub_obstacle(const std::string& name) {
  if (name != "obstacle") return {};
  return {{0.45, 0.2, 0.1, 0.05}};
}

/// How a heicub_walk() ended.
enum class PatternWalkStatus : std::uint8_t {
  ok,  ///< every tick's command was accepted and its NMPC solved
  /// a tick's command was not walked as given: rejected (NaN) or clamped to max_command
  /// (PatternWalk::command says which)
  command_rejected,
  mpc_failed,  ///< a tick's NMPC did not solve (PatternWalk::mpc says how)
};

/// The enumerator's name ("ok", "command_rejected", "mpc_failed"); "unknown" out of range.
constexpr const char* to_string(PatternWalkStatus status) noexcept {
  switch (status) {
    case PatternWalkStatus::ok:
      return "ok";
    case PatternWalkStatus::command_rejected:
      return "command_rejected";
    case PatternWalkStatus::mpc_failed:
      return "mpc_failed";
  }
  return "unknown";
}

/// A walk of the generator interpolated at the command period (heicub_walk()).
struct PatternWalk {
  std::vector<TrajectorySample<double>> samples;  ///< every command period of the ticks walked
  int ticks = 0;  ///< NMPC ticks walked: all that were asked for, unless a tick failed
  PatternWalkStatus status = PatternWalkStatus::ok;
  std::string message;  ///< which tick failed and how; empty when ok()
  /// The failed tick's outcomes in detail; accepted and solved when every tick succeeded.
  CommandStatus command = CommandStatus::accepted;
  MpcStatus mpc = MpcStatus::solved;

  bool ok() const { return status == PatternWalkStatus::ok; }
};

/// A Heicub walk (thesis Table 6.1: heicub_settings() unchanged, com_z = 0.45 m, which the
/// humanoid's standing CoM matches, plus `obstacles`) of `ticks` NMPC ticks on a generator of
/// horizon 16, the command at tick k being command(k) (v_x, v_y, ω_z), interpolated at the
/// command period. The walk stops at the first tick whose command is rejected or whose NMPC
/// does not solve (a walk other than the one asked for): then ok() is false and `samples` ends
/// before that tick.
/// @throws walkgen::invalid_argument when ticks < 1 or an obstacle is invalid.
template <typename Command>
PatternWalk heicub_walk(const Command& command, int ticks,
                        const std::vector<CircleObstacle<double>>& obstacles = {}) {
  check_argument(ticks >= 1, "walkgen::heicub_walk: ticks", "ticks >= 1", ticks);
  WalkingSettings<double> s = heicub_settings();
  s.obstacles = obstacles;
  WalkingMpc<double, 16> mpc(s);
  WalkingInterpolator<double> interp(interpolation_settings(s));
  PatternWalk walk;
  walk.samples.resize(std::size_t(ticks) * std::size_t(interp.samples_per_tick()));
  for (int k = 0; k < ticks; ++k) {
    walk.command = mpc.set_command(command(k));
    walk.mpc = mpc.solve().status;
    if (walk.command != CommandStatus::accepted || walk.mpc != MpcStatus::solved) {
      walk.status = walk.command != CommandStatus::accepted ? PatternWalkStatus::command_rejected
                                                            : PatternWalkStatus::mpc_failed;
      walk.message = "heicub_walk: tick " + std::to_string(k) + ": command " +
                     to_string(walk.command) + ", NMPC " + to_string(walk.mpc);
      walk.samples.resize(std::size_t(k) * std::size_t(interp.samples_per_tick()));
      return walk;
    }
    interp.interpolate(mpc.tick_plan(),
                       walk.samples.data() + std::size_t(k * interp.samples_per_tick()));
    mpc.advance();
    walk.ticks = k + 1;
  }
  return walk;
}

/// A Heicub walk at a constant command (v_x, v_y, ω_z).
inline PatternWalk heicub_walk(const Eigen::Vector3d& command, int ticks) {
  return heicub_walk([&command](int) { return command; }, ticks);
}

}  // namespace walkgen
