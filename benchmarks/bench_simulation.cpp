// The whole closed loop of thesis figure 6.1 with walkgen's humanoid in MuJoCo, without
// rendering: one NMPC tick (t = 0.4 s simulated: solve, interpolation, 40 IK solves, 200 physics
// steps of 2 ms, CoM feedback, measured ZMP) per iteration, walking forward and turning at
// Heicub's speeds. The counter real_time_factor is simulated seconds per wall-clock second
// (goal ≥ 10); side by side, the parts: the physics alone for the same 0.4 s (the robot standing
// on its position servos) and the NMPC + IK without physics. BM_ClosedLoopTickG1: the same loop
// with the Unitree G1 from its description file (torque motors and their joint controller at
// the physics rate, the balance feed-forward, the Ceres IK sized at run time; t = 0.1 s per
// tick) walking forward at 0.1 m/s.
//   build/release/benchmarks/bench_simulation --benchmark_repetitions=5
//       --benchmark_report_aggregates_only=true   (one command line)
#include <benchmark/benchmark.h>

#include "walkgen/control/pattern_targets.hpp"
#include "walkgen/simulation/simulated_tasks.hpp"
#include "walkgen/yaml/robot_description_loader.hpp"

namespace {

const walkgen::KinematicTree<double>& tree() {
  static const walkgen::KinematicTree<double> t = walkgen::humanoid_tree();
  return t;
}

void report(benchmark::State& state, double simulated_per_iteration) {
  state.counters["real_time_factor"] = benchmark::Counter(
      simulated_per_iteration * double(state.iterations()), benchmark::Counter::kIsRate);
}

/// One tick of `loop` per iteration. `start()` starts the walk and sets its command; it runs
/// again, untimed, every `restart_every` ticks (from the robot's reset).
template <typename Loop, typename Start>
void tick_loop(benchmark::State& state, walkgen::MujocoRobot& robot, Loop& loop, Start start,
               long restart_every) {
  if (!start()) {
    state.SkipWithError("start failed");
    return;
  }
  long ticks = 0;
  for (auto _ : state) {
    if (loop.tick().status != walkgen::LoopStatus::ok) {
      state.SkipWithError("the robot stopped");
      break;
    }
    if (++ticks % restart_every == 0) {
      state.PauseTiming();
      robot.reset();
      const bool started = start();
      state.ResumeTiming();
      if (!started) {
        state.SkipWithError("start failed");
        break;
      }
    }
  }
}

// NMPC + interpolation + IK + MuJoCo, per tick (0.4 s simulated).
void BM_ClosedLoopTick(benchmark::State& state) {
  walkgen::MujocoRobot robot;
  walkgen::HumanoidIk ik(tree());
  const walkgen::WalkingSettings<double> settings = walkgen::walkgen_humanoid_description().walking;
  walkgen::SimLoop loop(settings, robot, ik);
  tick_loop(
      state, robot, loop,
      [&] {
        return loop.start().status == walkgen::LoopStatus::ok &&
               loop.set_command({0.03, 0.0, 0.05}) == walkgen::CommandStatus::accepted;
      },
      1500);  // 10 minutes walked
  report(state, settings.t);
}
BENCHMARK(BM_ClosedLoopTick)->Unit(benchmark::kMillisecond)->UseRealTime();

// The Unitree G1 (torque-driven): NMPC + interpolation + IK + joint controller + MuJoCo, per
// tick (0.1 s simulated).
void BM_ClosedLoopTickG1(benchmark::State& state) {
  const walkgen::RobotDescription g1 = walkgen::find_robot_description("unitree_g1");
  walkgen::MujocoRobot robot(walkgen::mujoco_robot_settings(g1));
  const walkgen::KinematicTree<double> g1_tree = walkgen::robot_kinematic_tree(g1);
  walkgen::CeresInverseKinematics<> ik(g1_tree, walkgen::ceres_ik_settings(g1));
  walkgen::RobotLoop loop(g1.walking, robot, ik, walkgen::loop_settings(g1));
  tick_loop(
      state, robot, loop,
      [&] {
        return loop.start().status == walkgen::LoopStatus::ok &&
               loop.set_command({0.1, 0.0, 0.0}) == walkgen::CommandStatus::accepted;
      },
      600);  // a minute walked
  report(state, g1.walking.t);
}
BENCHMARK(BM_ClosedLoopTickG1)->Unit(benchmark::kMillisecond)->UseRealTime();

// MuJoCo alone: 0.4 s of physics with fixed servo targets (the standing robot).
void BM_PhysicsOnly(benchmark::State& state) {
  walkgen::MujocoRobot robot;
  const walkgen::WalkingSettings<double> settings = walkgen::walkgen_humanoid_description().walking;
  for (auto _ : state) {
    for (int k = 0; k < 40; ++k) {
      if (robot.step(settings.command_period) != walkgen::RobotStatus::ok) {
        state.SkipWithError("the robot stopped");
      }
    }
    benchmark::DoNotOptimize(robot.output().q.data());
  }
  report(state, settings.t);
}
BENCHMARK(BM_PhysicsOnly)->Unit(benchmark::kMillisecond)->UseRealTime();

// The controller alone: one NMPC tick and the 40 IK solves of its samples, no physics.
void BM_ControllerOnly(benchmark::State& state) {
  const walkgen::WalkingSettings<double> settings = walkgen::walkgen_humanoid_description().walking;
  walkgen::WalkingMpc<double, 16> mpc(settings);
  walkgen::WalkingInterpolator<double> interp(walkgen::interpolation_settings(settings));
  std::vector<walkgen::TrajectorySample<double>> samples(std::size_t(interp.samples_per_tick()));
  walkgen::HumanoidIk ik(tree());
  if (mpc.set_command({0.03, 0.0, 0.05}) != walkgen::CommandStatus::accepted ||
      mpc.solve().status != walkgen::MpcStatus::solved) {
    state.SkipWithError("the first tick failed");
    return;
  }
  interp.interpolate(mpc.tick_plan(), samples.data());
  walkgen::start_walk(ik, samples.front());
  for (auto _ : state) {
    if (mpc.solve().status != walkgen::MpcStatus::solved) {
      state.SkipWithError("QP failed");
      break;
    }
    interp.interpolate(mpc.tick_plan(), samples.data());
    for (const auto& s : samples) benchmark::DoNotOptimize(ik.solve(walkgen::ik_target(s)));
    mpc.advance();
  }
  report(state, settings.t);
}
BENCHMARK(BM_ControllerOnly)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
