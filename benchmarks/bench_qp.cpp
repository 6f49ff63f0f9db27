// Google Benchmark timings of walkgen::DenseQp (docs/design.md convention 16).
//
//   build/release/benchmarks/bench_qp --benchmark_repetitions=10
//       --benchmark_report_aggregates_only=true   (one command line)
//
// Families:
//   BM_Random{Cold,WarmUpdate}/n   manufactured problems with n variables and 2n rows: a cold
//                                  init()+solve(), and update()+solve() after a small change of
//                                  g and the bounds (warm start + factorisation reuse).
//   BM_Walking*                    the walking-like sequence walkgen::WalkingQpSequence
//                                  (68 variables, 106 rows, 220 ticks cycled):
//     Cold        init() + cold solve()          per tick (no warm start)
//     WarmInit    init() + warm solve()          per tick (new H and A each tick)
//     Init        init() alone                   (factorisation of H and validation)
//     WarmUpdate  update() + warm solve()        CoM feedback within a tick: only g and bounds
//                                                change, H/A and active-set factors are reused.

#include <benchmark/benchmark.h>

#include <chrono>
#include <random>
#include <vector>

#include "walkgen/qp/dense_qp.hpp"
#include "walkgen/scenarios/manufactured_qp.hpp"
#include "walkgen/scenarios/walking_qp_sequence.hpp"

namespace {

using walkgen::DenseQp;
using walkgen::QpStatus;
using Seq = walkgen::WalkingQpSequence;

// Per-solve counters: changes = active-set changes per solve, active = active-set size.
struct SolveStats {
  long changes = 0, active = 0, solves = 0;
  /// False (and the benchmark marked as failed) when `r` is not solved: leave the loop then.
  [[nodiscard]] bool add(benchmark::State& state, const walkgen::QpResult<double>& r) {
    if (r.status != QpStatus::solved) {
      state.SkipWithError("not solved");
      return false;
    }
    changes += r.iterations;
    active += r.active_set_size;
    ++solves;
    return true;
  }
  void report(benchmark::State& state) const {
    const double n = static_cast<double>(std::max(1L, solves));
    state.counters["changes"] = static_cast<double>(changes) / n;
    state.counters["active"] = static_cast<double>(active) / n;
  }
};

// Sizes n of the random families (n variables, 2n rows).
void random_sizes(benchmark::internal::Benchmark* b) {
  for (int n : {10, 25, 50, 100, 150}) b->Arg(n);
  b->Unit(benchmark::kMicrosecond);
}

void BM_RandomCold(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  walkgen::QpFactory f(123);
  const auto p = f.make(n, 2 * n, walkgen::QpKind::generic);
  DenseQp<double> qp(n, 2 * n);
  qp.settings().warm_start = false;
  SolveStats stats;
  for (auto _ : state) {
    qp.init(p.H, p.g, p.A, p.lb, p.ub, p.l, p.u);
    const auto& r = qp.solve();
    if (!stats.add(state, r)) break;
  }
  stats.report(state);
}
BENCHMARK(BM_RandomCold)->Apply(random_sizes);

void BM_RandomWarmUpdate(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  walkgen::QpFactory f(123);
  const auto p = f.make(n, 2 * n, walkgen::QpKind::generic);
  // Eight variants: g perturbed by 1 %, feasible set shifted by a small δx.
  std::vector<walkgen::QpProblem> variants(8, p);
  for (auto& v : variants) {
    Eigen::VectorXd dx(n);
    for (int j = 0; j < n; ++j) {
      v.g[j] += 0.01 * f.normal() * (1.0 + std::abs(p.g[j]));
      dx[j] = 0.001 * f.normal();
    }
    v.lb += p.A * dx;
    v.ub += p.A * dx;
    v.l += dx;
    v.u += dx;
  }
  DenseQp<double> qp(n, 2 * n);
  qp.init(p.H, p.g, p.A, p.lb, p.ub, p.l, p.u);
  if (qp.solve().status != QpStatus::solved) {
    state.SkipWithError("the unperturbed QP is not solved");
    return;
  }
  SolveStats stats;
  std::size_t k = 0;
  for (auto _ : state) {
    const auto& v = variants[k++ % variants.size()];
    qp.update(v.g, v.lb, v.ub, v.l, v.u);
    const auto& r = qp.solve();
    if (!stats.add(state, r)) break;
  }
  stats.report(state);
}
BENCHMARK(BM_RandomWarmUpdate)->Apply(random_sizes);

// The walking sequence, built once: each tick's QP and, for the update path, the same tick with
// the CoM measured up to ±2 mm off (8 variants).
struct WalkingData {
  std::vector<walkgen::WalkingQp> ticks;
  std::vector<std::vector<walkgen::WalkingQp>> feedback;
  WalkingData() {
    Seq seq;
    DenseQp<double> qp(Seq::kVars, Seq::kRows);
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> offset(-0.002, 0.002);
    for (int t = 0; t < 220; ++t) {
      const Seq::Command cmd = Seq::demo_command(t);
      ticks.push_back(seq.build(cmd));
      feedback.emplace_back();
      for (int v = 0; v < 8; ++v) {
        Seq measured = seq;
        measured.set_com_offset(offset(rng), offset(rng));
        feedback.back().push_back(measured.build(cmd));
      }
      const auto& w = ticks.back();
      qp.init(w.H, w.g, w.A, w.lb, w.ub);
      seq.advance(qp.solve().x);
    }
  }
};
const WalkingData& walking() {
  static const WalkingData data;
  return data;
}

void walking_ticks(benchmark::State& state, bool warm) {
  const auto& data = walking();
  DenseQp<double> qp(Seq::kVars, Seq::kRows);
  qp.settings().warm_start = warm;
  SolveStats stats;
  std::size_t k = 0;
  for (auto _ : state) {
    const auto& w = data.ticks[k++ % data.ticks.size()];
    qp.init(w.H, w.g, w.A, w.lb, w.ub);
    const auto& r = qp.solve();
    if (!stats.add(state, r)) break;
  }
  stats.report(state);
}
void BM_WalkingCold(benchmark::State& state) { walking_ticks(state, false); }
void BM_WalkingWarmInit(benchmark::State& state) { walking_ticks(state, true); }
BENCHMARK(BM_WalkingCold)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_WalkingWarmInit)->Unit(benchmark::kMicrosecond);

void BM_WalkingInit(benchmark::State& state) {
  const auto& data = walking();
  DenseQp<double> qp(Seq::kVars, Seq::kRows);
  std::size_t k = 0;
  for (auto _ : state) {
    const auto& w = data.ticks[k++ % data.ticks.size()];
    benchmark::DoNotOptimize(qp.init(w.H, w.g, w.A, w.lb, w.ub));
  }
}
BENCHMARK(BM_WalkingInit)->Unit(benchmark::kMicrosecond);

void BM_WalkingWarmUpdate(benchmark::State& state) {
  // Manual timing: only update() + solve() are timed; moving to the next tick (init() and a
  // solve of the tick's own QP) happens outside the measured region every 8 solves.
  const auto& data = walking();
  DenseQp<double> qp(Seq::kVars, Seq::kRows);
  SolveStats stats;
  std::size_t tick = 0, variant = 8;
  for (auto _ : state) {
    if (variant == 8) {
      const auto& w = data.ticks[tick];
      qp.init(w.H, w.g, w.A, w.lb, w.ub);
      if (qp.solve().status != QpStatus::solved) {
        state.SkipWithError("the tick's QP not solved");
        break;
      }
      variant = 0;
    }
    const auto& v = data.feedback[tick][variant];
    const auto start = std::chrono::steady_clock::now();
    qp.update(v.g, v.lb, v.ub);
    const auto& r = qp.solve();
    const auto stop = std::chrono::steady_clock::now();
    state.SetIterationTime(std::chrono::duration<double>(stop - start).count());
    if (!r.reused_factorization) {
      state.SkipWithError("factorisation not reused");
      break;
    }
    if (!stats.add(state, r)) break;
    if (++variant == 8) tick = (tick + 1) % data.ticks.size();
  }
  stats.report(state);
}
BENCHMARK(BM_WalkingWarmUpdate)->UseManualTime()->Unit(benchmark::kMicrosecond);

}  // namespace
