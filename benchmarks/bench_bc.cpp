// Inference of the behavioural-cloning network (thesis §11.1.1: 4 ms per frame on a GPU): one
// walkgen::VelocityNetwork::step (4 × 4 block averaging of a 320 × 240 RGB image and its
// disparity, the U-Net on the 60 × 80 RGBD frame, one LSTM step) on the CPU, per frame.
// The model is python/bc_train.py's TorchScript export: the file named by the environment
// variable WALKGEN_BC_MODEL, else the bc_pipeline test's (example_output/bc_pipeline/model).
//   WALKGEN_BC_MODEL=model.pt build/release/benchmarks/bench_bc --benchmark_repetitions=5
#include <benchmark/benchmark.h>
#include <torch/torch.h>

#include <cstdio>
#include <cstdlib>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "walkgen/torch/velocity_network.hpp"

namespace {

void BM_VelocityNetworkStep(benchmark::State& state) {
  const char* env = std::getenv("WALKGEN_BC_MODEL");
  const std::string path = env != nullptr ? env
                                          : std::string(WALKGEN_BINARY_DIR) +
                                                "/example_output/bc_pipeline/model/model.pt";
  torch::set_num_threads(int(state.range(0)));
  std::unique_ptr<walkgen::VelocityNetwork> network;
  try {
    network = std::make_unique<walkgen::VelocityNetwork>(path);
  } catch (const walkgen::invalid_argument& e) {  // no model: an error, not a skipped number
    std::fprintf(stderr, "bench_bc: %s\n", e.what());
    std::abort();
  }
  walkgen::CameraImage left;
  left.width = 320;
  left.height = 240;
  left.rgb.resize(320 * 240 * 3);
  std::vector<float> disparity(320 * 240);
  std::mt19937 rng(1);
  for (auto& v : left.rgb) v = std::uint8_t(rng() % 256);
  for (auto& d : disparity) d = float(rng() % 3200) / 100.0f;
  for (auto _ : state) {
    benchmark::DoNotOptimize(network->step(left, disparity.data()));
  }
  state.counters["hidden"] = double(network->hidden());
}
BENCHMARK(BM_VelocityNetworkStep)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
