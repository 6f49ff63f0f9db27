#pragma once
// The walking scenarios of thesis §9.1 (figures 9.1–9.3) with the HRP-2 preset, shared by the
// generator's tests, the walking example and the benchmark: straight, sideways, curved, turn on
// the spot, a changing command sequence and obstacle avoidance.

#include <Eigen/Core>
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
    mpc.set_command(sc.command(k));
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

}  // namespace walkgen_test
