#pragma once
// The walking scenarios of thesis §9.1 (figures 9.1–9.3) with the HRP-2 preset, shared by the
// generator's tests, the walking example and the benchmark: straight, sideways, curved, turn on
// the spot, a changing command sequence and obstacle avoidance.

#include <Eigen/Core>
#include <cmath>
#include <string>
#include <vector>

#include "walkgen/interpolation/trajectory.hpp"
#include "walkgen/mpc/walking_mpc.hpp"

namespace walkgen_test {

using Vector3d = Eigen::Vector3d;

struct Scenario {
  std::string name;
  std::vector<walkgen::CircleObstacle<double>> obstacles;
  int ticks = 200;
  /// Command at a tick, (v_x, v_y, ω_z) in the robot frame.
  Vector3d command(int tick) const {
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

inline Scenario scenario(const std::string& name) {
  for (const auto& s : walking_scenarios()) {
    if (s.name == name) return s;
  }
  return {};
}

/// A footstep as it landed (or the initial stance).
struct Landing {
  double time;
  walkgen::Foot foot;
  walkgen::FootPose<double> pose;
};

/// Everything a scenario run produced.
struct ScenarioRun {
  std::vector<walkgen::TrajectorySample<double>> samples;  // every command period
  std::vector<walkgen::CommandStatus> commands;            // every tick: set_command()'s outcome
  std::vector<walkgen::MpcResult<double>> results;         // every tick
  std::vector<walkgen::WalkingState<double>> states;       // every tick, before solve()
  std::vector<walkgen::WalkingPlan<double>> plans;         // every tick, after solve()
  std::vector<Landing> landings;                           // initial feet, then every landing
};

/// Runs a scenario with settings s on a generator of horizon N.
template <int N = Eigen::Dynamic>
ScenarioRun run_scenario(const Scenario& sc, walkgen::WalkingSettings<double> s) {
  s.obstacles = sc.obstacles;
  walkgen::WalkingMpc<double, N> mpc(s);
  walkgen::WalkingInterpolator<double> interp(s);
  ScenarioRun run;
  const auto& st0 = mpc.state();
  run.landings.push_back({0.0, st0.support_foot, st0.support});
  run.landings.push_back({0.0, walkgen::other(st0.support_foot), st0.swing_origin});
  std::vector<walkgen::TrajectorySample<double>> buffer(std::size_t(interp.samples_per_tick()));
  for (int k = 0; k < sc.ticks; ++k) {
    run.commands.push_back(mpc.set_command(sc.command(k)));
    run.states.push_back(mpc.state());
    run.results.push_back(mpc.solve());
    run.plans.push_back(mpc.plan());
    interp.interpolate(mpc, buffer.data());
    run.samples.insert(run.samples.end(), buffer.begin(), buffer.end());
    const long steps = mpc.state().step_count;
    mpc.advance();
    if (mpc.state().step_count != steps) {
      run.landings.push_back({mpc.state().time, mpc.state().support_foot, mpc.state().support});
    }
  }
  return run;
}

/// Steady-state walking velocity of a run: the CoM velocity in the robot frame (x, y) and the
/// yaw rate, from `cycles` consecutive gait cycles (2 steps of `cycle` ticks each) starting at
/// tick `first`. The CoM sways and, turning, circles the turning centre, so the velocity is that
/// of its mean over each gait cycle (every command-period sample), rotated into the heading
/// between two consecutive cycles. Needs first + (cycles + 1) cycle ≤ ticks.
inline Vector3d mean_velocity(const ScenarioRun& run, int first, int cycles, int cycle, double t) {
  const std::size_t per_tick = run.samples.size() / run.states.size();
  auto mean_of_cycle = [&](int tick) {
    Vector3d m = Vector3d::Zero();  // x, y, heading
    const std::size_t a = std::size_t(tick) * per_tick, b = std::size_t(tick + cycle) * per_tick;
    for (std::size_t i = a; i < b && i < run.samples.size(); ++i) {
      const auto& o = run.samples[i];
      m += Vector3d(o.com_x[0], o.com_y[0],
                    (o.left.motion.q.position + o.right.motion.q.position) / 2);
    }
    return Vector3d(m / double(b - a));
  };
  Vector3d mean = Vector3d::Zero();
  for (int c = 0; c < cycles; ++c) {
    const Vector3d a = mean_of_cycle(first + c * cycle);
    const Vector3d b = mean_of_cycle(first + (c + 1) * cycle);
    const double q = (a[2] + b[2]) / 2, dx = b[0] - a[0], dy = b[1] - a[1];
    mean += Vector3d(std::cos(q) * dx + std::sin(q) * dy, -std::sin(q) * dx + std::cos(q) * dy,
                     b[2] - a[2]);
  }
  return mean / (cycles * cycle * t);
}

}  // namespace walkgen_test
