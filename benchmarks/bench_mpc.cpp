// Google Benchmark timings of the NMPC walking generator (docs/design.md convention 16).
//
//   build/release/benchmarks/bench_mpc --benchmark_repetitions=10
//       --benchmark_report_aggregates_only=true   (one command line; portable x86-64 build)
// and the same with build/bench/ (cmake --preset bench: built with -march=native).
//
// Families, each for N = 8, 16, 32, 64 preview samples (HRP-2 preset, t_step 0.8 s, t 0.1 s):
//   BM_Tick{Straight,Obstacle}<N>   one full tick: set_command + solve() (cost and constraint
//                                  assembly, Gauss–Newton linearisation, QP) + advance()
//                                  (LIPM step, swing foot, plan shift)
//   BM_QpOfTick<N>                 the QP alone: init() + warm solve() on the problems the
//                                  straight walk produced (so tick − QP = assembly + bookkeeping)
//   BM_Interpolate                 the 20 command-period samples of one tick
// N = 8 (a preview of one step) cannot avoid the obstacle: its QP fails (capture-point
// constraint) and BM_TickObstacle<8> reports the error. BM_Tick*: a tick with correction
// iterations (docs/tuning.md) counts both QPs.
// Counters: qp_changes = active-set changes per QP, vars/rows = QP size.

#include <benchmark/benchmark.h>

#include <vector>

#include "walkgen/interpolation/trajectory.hpp"
#include "walkgen/mpc/walking_mpc.hpp"
#include "walkgen/scenarios/walking_scenarios.hpp"

namespace {

walkgen::WalkingSettings<double> settings(int n) {
  auto s = walkgen::hrp2_settings<double>();
  s.n = n;
  s.nwsr = 1000;  // the thesis's 100 active-set changes do not cover a cold start at N = 64
  return s;
}

template <int N>
void BM_Tick(benchmark::State& state, const char* scenario) {
  const walkgen::Scenario sc = walkgen::scenario(scenario);
  auto s = settings(N);
  s.obstacles = sc.obstacles;
  walkgen::WalkingMpc<double, N> mpc(s);
  long changes = 0, ticks = 0, active = 0;
  for (auto _ : state) {
    if (mpc.set_command(sc.command(int(ticks % 200))) != walkgen::CommandStatus::accepted) {
      state.SkipWithError("command rejected");
      break;
    }
    const auto& r = mpc.solve();
    if (r.status != walkgen::MpcStatus::solved) {
      state.SkipWithError("QP failed");
      break;
    }
    changes += r.qp_iterations;
    active += mpc.workspace().qp.result().active_set_size;
    mpc.advance();
    ++ticks;
  }
  state.counters["qp_changes"] = double(changes) / double(ticks);
  state.counters["active"] = double(active) / double(ticks);
  state.counters["vars"] = double(mpc.num_vars());
  state.counters["rows"] = double(mpc.num_rows());
}

template <int N>
void BM_TickStraight(benchmark::State& state) {
  BM_Tick<N>(state, "straight");
}
template <int N>
void BM_TickObstacle(benchmark::State& state) {
  BM_Tick<N>(state, "obstacle");
}

struct CapturedQp {
  Eigen::MatrixXd H;
  Eigen::VectorXd g, lb, ub, l, u;
  Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> A;
};

template <int N>
void BM_QpOfTick(benchmark::State& state) {
  walkgen::WalkingMpc<double, N> mpc(settings(N));
  if (mpc.set_command({0.1, 0.0, 0.0}) != walkgen::CommandStatus::accepted) {
    state.SkipWithError("command rejected");
    return;
  }
  std::vector<CapturedQp> qps;
  for (int k = 0; k < 200; ++k) {
    if (mpc.solve().status != walkgen::MpcStatus::solved) {
      state.SkipWithError("QP failed while capturing");
      return;
    }
    const auto& w = mpc.workspace().qp.problem();
    qps.push_back({w.H, w.g, w.lb, w.ub, w.l, w.u, w.A});
    mpc.advance();
  }
  walkgen::DenseQp<double> qp(mpc.num_vars(), mpc.num_rows());
  std::size_t k = 0;
  for (auto _ : state) {
    const CapturedQp& p = qps[k];
    qp.init(p.H, p.g, p.A, p.lb, p.ub, p.l, p.u);
    if (qp.solve().status != walkgen::QpStatus::solved) {
      state.SkipWithError("QP failed");
      break;
    }
    k = (k + 1) % qps.size();
  }
}

void BM_Interpolate(benchmark::State& state) {
  const auto s = settings(16);
  walkgen::WalkingMpc<double, 16> mpc(s);
  walkgen::WalkingInterpolator<double> interp(walkgen::interpolation_settings(s));
  std::vector<walkgen::TrajectorySample<double>> out(std::size_t(interp.samples_per_tick()));
  if (mpc.set_command({0.1, 0.0, 0.0}) != walkgen::CommandStatus::accepted) {
    state.SkipWithError("command rejected");
    return;
  }
  for (int k = 0; k <= 13; ++k) {  // mid-swing: 13 ticks walked, the 14th solved
    if (mpc.solve().status != walkgen::MpcStatus::solved) {
      state.SkipWithError("QP failed");
      return;
    }
    if (k < 13) mpc.advance();
  }
  for (auto _ : state) {
    interp.interpolate(mpc.tick_plan(), out.data());
    benchmark::DoNotOptimize(out.data());
  }
}

}  // namespace

BENCHMARK_TEMPLATE(BM_TickStraight, 8);
BENCHMARK_TEMPLATE(BM_TickStraight, 16);
BENCHMARK_TEMPLATE(BM_TickStraight, 32);
BENCHMARK_TEMPLATE(BM_TickStraight, 64);
BENCHMARK_TEMPLATE(BM_TickObstacle, 8);
BENCHMARK_TEMPLATE(BM_TickObstacle, 16);
BENCHMARK_TEMPLATE(BM_TickObstacle, 32);
BENCHMARK_TEMPLATE(BM_TickObstacle, 64);
BENCHMARK_TEMPLATE(BM_QpOfTick, 8);
BENCHMARK_TEMPLATE(BM_QpOfTick, 16);
BENCHMARK_TEMPLATE(BM_QpOfTick, 32);
BENCHMARK_TEMPLATE(BM_QpOfTick, 64);
BENCHMARK(BM_Interpolate);
BENCHMARK_MAIN();
