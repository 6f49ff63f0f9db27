// Google Benchmark timings of the depth pipeline of thesis §3.1 (walkgen::StereoDepth) against
// the bare OpenCV calls it makes, in the same binary, on one 320 × 240 colour pair (Middlebury
// Aloe resized, from WALKGEN_TEST_DATA_DIR), with the thesis's N 13, D 32, λ 1e4, σ 1 (§10.2: 7.4
// ms on an i7-7700HQ).
//
//   build/opencv/benchmarks/bench_depth --benchmark_repetitions=10
//       --benchmark_report_aggregates_only=true   (one command line)
//
// Families (wall-clock time: OpenCV runs parts of block matching on its own threads):
//   BM_Walkgen/pad           StereoDepth::compute(): grey, left padding, BM left + right, WLS,
//                            crop, disparity → depth through Q
//   BM_BareOpenCv/pad/0      the same OpenCV calls written out, up to the disparity in pixels
//                            (no depth: less work than BM_Walkgen, the strict comparison)
//   BM_BareOpenCv/pad/1      ... and depth through Q by cv::reprojectImageTo3D (X, Y, Z)
//   .../nopad (arg 0)        the same without the left padding (pad_left false)
//   BM_BlockMatchingOnly     StereoDepth with wls false: grey, padding, BM left, depth

#include <benchmark/benchmark.h>

#include <cstdio>
#include <cstdlib>
#include <string>
#include <walkgen/opencv/stereo_depth.hpp>

namespace {

struct Pair {
  cv::Mat left, right;
};

const Pair& aloe_320x240() {
  static const Pair pair = [] {
    const std::string dir = std::string(WALKGEN_TEST_DATA_DIR) + "/opencv_aloe_middlebury2006";
    Pair p;
    try {
      cv::resize(walkgen::read_image(dir + "/aloeL.jpg", cv::IMREAD_COLOR), p.left,
                 cv::Size(320, 240), 0, 0, cv::INTER_AREA);
      cv::resize(walkgen::read_image(dir + "/aloeR.jpg", cv::IMREAD_COLOR), p.right,
                 cv::Size(320, 240), 0, 0, cv::INTER_AREA);
    } catch (const walkgen::invalid_argument& e) {
      std::fprintf(stderr, "bench_depth: %s (set -DWALKGEN_TEST_DATA_DIR)\n", e.what());
      std::exit(1);
    }
    return p;
  }();
  return pair;
}

cv::Mat rig_q() {
  return walkgen::ideal_disparity_to_depth(walkgen::pinhole_from_fovy(320, 240, 0.785398), 0.068);
}

void BM_Walkgen(benchmark::State& state) {
  const Pair& p = aloe_320x240();
  walkgen::StereoDepthSettings s;
  s.pad_left = state.range(0) != 0;
  walkgen::StereoDepth depth(s, rig_q());
  for (auto _ : state) {
    const walkgen::StereoDepthFrame& f = depth.compute(p.left, p.right);
    benchmark::DoNotOptimize(f.depth.data);
  }
  state.SetLabel(s.pad_left ? "pad" : "nopad");
}

// What StereoDepth::compute() does, as a user would write it with OpenCV alone.
void BM_BareOpenCv(benchmark::State& state) {
  const Pair& p = aloe_320x240();
  const bool pad_left = state.range(0) != 0;
  const bool reproject = state.range(1) != 0;
  const int d = 32, pad = pad_left ? d : 0;
  cv::Ptr<cv::StereoBM> bm = cv::StereoBM::create(d, 13);
  bm->setPreFilterType(cv::StereoBM::PREFILTER_XSOBEL);
  cv::Ptr<cv::ximgproc::DisparityWLSFilter> wls = cv::ximgproc::createDisparityWLSFilter(bm);
  wls->setLambda(1e4);
  wls->setSigmaColor(1.0);
  cv::Ptr<cv::StereoMatcher> right_bm = cv::ximgproc::createRightMatcher(bm);
  const cv::Mat q = rig_q();
  cv::Mat gl, gr, pl, pr, dl, dr, filtered, disparity, xyz;
  for (auto _ : state) {
    cv::cvtColor(p.left, gl, cv::COLOR_BGR2GRAY);
    cv::cvtColor(p.right, gr, cv::COLOR_BGR2GRAY);
    if (pad_left) {
      cv::copyMakeBorder(gl, pl, 0, 0, pad, 0, cv::BORDER_REPLICATE);
      cv::copyMakeBorder(gr, pr, 0, 0, pad, 0, cv::BORDER_REPLICATE);
    } else {
      pl = gl;
      pr = gr;
    }
    bm->compute(pl, pr, dl);
    right_bm->compute(pr, pl, dr);
    wls->filter(dl, pl, filtered, dr);
    filtered(cv::Rect(pad, 0, p.left.cols, p.left.rows)).convertTo(disparity, CV_32F, 1.0 / 16.0);
    if (reproject) cv::reprojectImageTo3D(disparity, xyz, q);
    benchmark::DoNotOptimize(disparity.data);
    benchmark::DoNotOptimize(xyz.data);
  }
  state.SetLabel(std::string(pad_left ? "pad" : "nopad") +
                 (reproject ? ", depth by reprojectImageTo3D" : ", disparity only"));
}

void BM_BlockMatchingOnly(benchmark::State& state) {
  const Pair& p = aloe_320x240();
  walkgen::StereoDepthSettings s;
  s.wls = false;
  walkgen::StereoDepth depth(s, rig_q());
  for (auto _ : state) {
    const walkgen::StereoDepthFrame& f = depth.compute(p.left, p.right);
    benchmark::DoNotOptimize(f.depth.data);
  }
}

}  // namespace

BENCHMARK(BM_Walkgen)->Arg(1)->Arg(0)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_BareOpenCv)
    ->Args({1, 0})
    ->Args({0, 0})
    ->Args({1, 1})
    ->Args({0, 1})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK(BM_BlockMatchingOnly)->Unit(benchmark::kMillisecond)->UseRealTime();
