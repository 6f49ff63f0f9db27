/// @file
/// What the Python binding costs per call (issue 25): the same QP solve and the same NMPC tick
/// called from C++ and through the package walkgen in an embedded Python interpreter, side by
/// side in one run. Report the Python/C++ ratio of the medians' CPU times, e.g.
///   build/release/benchmarks/bench_python --benchmark_repetitions=5
///   (add --benchmark_report_aggregates_only=true for the medians alone)
/// Target: an NMPC tick from Python within 1.2x of the C++ tick.

#include <benchmark/benchmark.h>
#include <pybind11/eigen.h>
#include <pybind11/embed.h>
#include <pybind11/numpy.h>

#include <Eigen/Core>
#include <random>

#include "walkgen/mpc/walking_mpc.hpp"
#include "walkgen/qp/dense_qp.hpp"

namespace py = pybind11;

namespace {

/// The interpreter, started once, with the build tree's package on sys.path.
py::module_& walkgen_module() {
  static py::scoped_interpreter interpreter;
  static py::module_ module = [] {
    py::module_::import("sys").attr("path").attr("insert")(0, WALKGEN_PYTHON_DIR);
    return py::module_::import("walkgen");
  }();
  return module;
}

/// A feasible random QP with n variables and m rows (as python/tests/test_dense_qp.py makes).
struct RandomQp {
  Eigen::MatrixXd H, A;
  Eigen::VectorXd g, lb, ub;
  RandomQp(int n, int m) {
    std::mt19937 rng(7);
    std::normal_distribution<double> normal;
    std::uniform_real_distribution<double> spread(0.1, 1.0);
    const auto draw = [&](Eigen::Index r, Eigen::Index c) {
      Eigen::MatrixXd out(r, c);
      for (Eigen::Index i = 0; i < out.size(); ++i) out.data()[i] = normal(rng);
      return out;
    };
    const Eigen::MatrixXd M = draw(n, n);
    H = M * M.transpose() + n * Eigen::MatrixXd::Identity(n, n);
    g = draw(n, 1);
    A = draw(m, n);
    const Eigen::VectorXd centre = A * (0.5 * draw(n, 1));
    lb = centre;
    ub = centre;
    for (int i = 0; i < m; ++i) {
      lb[i] -= spread(rng);
      ub[i] += spread(rng);
    }
  }
};

constexpr int kVars = 24, kRows = 16;

void BM_QpSolve_Cpp(benchmark::State& state) {
  const RandomQp p(kVars, kRows);
  walkgen::DenseQp<double> qp(kVars, kRows);
  for (auto _ : state) {
    (void)qp.init(p.H, p.g, p.A, p.lb, p.ub);
    benchmark::DoNotOptimize(qp.solve().x.data());
  }
  if (qp.result().status != walkgen::QpStatus::solved) state.SkipWithError("QP not solved");
}
BENCHMARK(BM_QpSolve_Cpp);

void BM_QpSolve_Python(benchmark::State& state) {
  py::module_& walkgen = walkgen_module();
  const RandomQp p(kVars, kRows);
  // NumPy arrays made once, as a user's script holds them.
  const py::array H = py::cast(Eigen::MatrixXd(p.H)), g = py::cast(Eigen::VectorXd(p.g)),
                  A = py::cast(Eigen::MatrixXd(p.A)), lb = py::cast(Eigen::VectorXd(p.lb)),
                  ub = py::cast(Eigen::VectorXd(p.ub));
  py::object qp = walkgen.attr("DenseQp")(kVars, kRows);
  py::object solve = qp.attr("solve");
  py::object result;
  for (auto _ : state) result = solve(H, g, A, lb, ub);
  if (!result.attr("ok").cast<bool>()) state.SkipWithError("QP not solved");
}
BENCHMARK(BM_QpSolve_Python);

void BM_MpcTick_Cpp(benchmark::State& state) {
  walkgen::WalkingMpc<double, Eigen::Dynamic> mpc(walkgen::hrp2_settings());
  (void)mpc.set_command(Eigen::Vector3d(0.2, 0.0, 0.0));
  for (auto _ : state) {
    benchmark::DoNotOptimize(mpc.solve().status);
    mpc.advance();
  }
  if (mpc.result().status != walkgen::MpcStatus::solved) state.SkipWithError("tick not solved");
}
BENCHMARK(BM_MpcTick_Cpp);

void BM_MpcTick_Python(benchmark::State& state) {
  py::module_& walkgen = walkgen_module();
  py::object mpc = walkgen.attr("WalkingMpc")(walkgen.attr("WalkingSettings").attr("hrp2")());
  mpc.attr("set_command")(0.2);
  py::object solve = mpc.attr("solve"), advance = mpc.attr("advance");
  py::object result;
  for (auto _ : state) {
    result = solve();
    advance();
  }
  if (!result.attr("ok").cast<bool>()) state.SkipWithError("tick not solved");
}
BENCHMARK(BM_MpcTick_Python);

}  // namespace
