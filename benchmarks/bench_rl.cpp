// Throughput of the reinforcement-learning environments (thesis §11.2): NMPC ticks per second
// of one NmpcGoalEnv, and of 8 environments stepped at once on a StepPool of 1 or 2 threads
// (the vectorised rollouts of walkgen::PpoTrainer). The policy is left out: the actions are a
// fixed slowly varying pattern (forward, turning, backwards), so that the NMPC's QPs see command
// changes as under a policy. Episodes that end are reset, as in training.
#include <benchmark/benchmark.h>

#include <cmath>
#include <vector>

#include "walkgen/learning/environment.hpp"
#include "walkgen/learning/nmpc_environment.hpp"
#include "walkgen/learning/step_pool.hpp"

namespace {

void action_of(long k, int e, float* a) {
  a[0] = static_cast<float>(std::sin(0.05 * k + e));
  a[1] = static_cast<float>(std::cos(0.03 * k + 2 * e));
}

// One environment, one step (ticks_per_step = 2 NMPC ticks) per iteration.
void BM_NmpcEnvStep(benchmark::State& state) {
  walkgen::NmpcGoalSettings s;
  s.obstacles = static_cast<int>(state.range(0));
  walkgen::NmpcGoalEnv<16> env(s, 1);
  long k = 0;
  const long ticks0 = env.ticks();
  float a[2];
  for (auto _ : state) {
    action_of(k++, 0, a);
    if (env.step(a).done()) env.reset();
  }
  state.counters["ticks/s"] =
      benchmark::Counter(static_cast<double>(env.ticks() - ticks0), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_NmpcEnvStep)->Arg(0)->Arg(1)->ArgName("obstacles")->UseRealTime();

// 8 environments, one vectorised step per iteration on a pool of range(0) threads.
void BM_NmpcEnvVector(benchmark::State& state) {
  const int E = 8;
  walkgen::NmpcGoalSettings s;
  std::vector<walkgen::NmpcGoalEnv<16>> envs;
  envs.reserve(E);
  for (int e = 0; e < E; ++e) envs.emplace_back(s, 100 + e);
  walkgen::StepPool pool(static_cast<int>(state.range(0)));
  long k = 0, ticks0 = 0;
  for (const auto& env : envs) ticks0 += env.ticks();
  for (auto _ : state) {
    pool.run(E, [&](int e) {
      float a[2];
      action_of(k, e, a);
      if (envs[e].step(a).done()) envs[e].reset();
    });
    ++k;
  }
  long ticks = -ticks0;
  for (const auto& env : envs) ticks += env.ticks();
  state.counters["ticks/s"] =
      benchmark::Counter(static_cast<double>(ticks), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_NmpcEnvVector)->Arg(1)->Arg(2)->ArgName("threads")->UseRealTime();

// The benchmarking environment of §11.2.1, for scale.
void BM_PointGoalEnvStep(benchmark::State& state) {
  walkgen::PointGoalEnv env({}, 1);
  long k = 0;
  float a[2];
  for (auto _ : state) {
    action_of(k++, 0, a);
    if (env.step(a).done()) env.reset();
  }
}
BENCHMARK(BM_PointGoalEnvStep);

}  // namespace
