// Fuzz harness for walkgen::load_stereo_calibration (issue 21, defect 6; tests/fuzz/README.md):
// the input bytes are a calibration file. Only walkgen::invalid_argument may escape (never a
// cv::Exception, never an allocation of what the file claims); a file that loads has every
// matrix of its documented shape and finite, a positive image size within 1..100000 px and
// finite rms values >= 0, and saving it again gives a file that loads to the same values.
#include <unistd.h>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <walkgen/opencv/stereo_calibration.hpp>

#include "fuzz/fuzz_support.hpp"

namespace {

namespace fs = std::filesystem;

// One folder per process, so that parallel fuzzing jobs do not share files.
const fs::path& work_folder() {
  static const fs::path folder = [] {
    fs::path f = fs::temp_directory_path() /
                 ("walkgen_fuzz_stereo_calibration_" + std::to_string(::getpid()));
    fs::create_directories(f);
    return f;
  }();
  return folder;
}

bool finite_of_shape(const cv::Mat& m, int rows, int cols) {
  return m.rows == rows && m.cols == cols && m.type() == CV_64F && cv::checkRange(m);
}

std::string shape(const cv::Mat& m) {
  return std::to_string(m.rows) + "x" + std::to_string(m.cols) + " type " +
         std::to_string(m.type());
}

void check_invariants(const walkgen::StereoCalibration& c, const char* what) {
  const std::string w = what;
  for (const walkgen::MonoCalibration* mono : {&c.left, &c.right}) {
    const cv::Size s = mono->image_size;
    WALKGEN_FUZZ_CHECK(
        s.width >= 1 && s.height >= 1 && s.width <= 100000 && s.height <= 100000,
        w + ": image size " + std::to_string(s.width) + "x" + std::to_string(s.height));
    WALKGEN_FUZZ_CHECK(finite_of_shape(mono->camera_matrix, 3, 3),
                       w + ": K " + shape(mono->camera_matrix));
    const int n = mono->distortion.cols;
    WALKGEN_FUZZ_CHECK(n == 4 || n == 5 || n == 8 || n == 12 || n == 14,
                       w + ": D " + shape(mono->distortion));
    WALKGEN_FUZZ_CHECK(finite_of_shape(mono->distortion, 1, n),
                       w + ": D " + shape(mono->distortion));
    WALKGEN_FUZZ_CHECK(std::isfinite(mono->rms) && mono->rms >= 0.0,
                       w + ": camera rms " + std::to_string(mono->rms));
  }
  WALKGEN_FUZZ_CHECK(c.left.image_size == c.right.image_size, w + ": image sizes differ");
  WALKGEN_FUZZ_CHECK(finite_of_shape(c.rotation, 3, 3), w + ": R " + shape(c.rotation));
  WALKGEN_FUZZ_CHECK(finite_of_shape(c.translation, 3, 1), w + ": T " + shape(c.translation));
  WALKGEN_FUZZ_CHECK(finite_of_shape(c.essential, 3, 3), w + ": E " + shape(c.essential));
  WALKGEN_FUZZ_CHECK(finite_of_shape(c.fundamental, 3, 3), w + ": F " + shape(c.fundamental));
  WALKGEN_FUZZ_CHECK(finite_of_shape(c.rectification_left, 3, 3), w + ": R1");
  WALKGEN_FUZZ_CHECK(finite_of_shape(c.rectification_right, 3, 3), w + ": R2");
  WALKGEN_FUZZ_CHECK(finite_of_shape(c.projection_left, 3, 4), w + ": P1");
  WALKGEN_FUZZ_CHECK(finite_of_shape(c.projection_right, 3, 4), w + ": P2");
  WALKGEN_FUZZ_CHECK(finite_of_shape(c.disparity_to_depth, 4, 4), w + ": Q");
  WALKGEN_FUZZ_CHECK(std::isfinite(c.rms) && c.rms >= 0.0, w + ": rms " + std::to_string(c.rms));
  WALKGEN_FUZZ_CHECK(std::isfinite(c.mean_epipolar_error) && c.mean_epipolar_error >= 0.0,
                     w + ": mean epipolar error " + std::to_string(c.mean_epipolar_error));
}

bool same(const cv::Mat& a, const cv::Mat& b) {
  return a.size() == b.size() && a.type() == b.type() && cv::norm(a, b, cv::NORM_INF) == 0.0;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const fs::path input = work_folder() / "input.yml";
  {
    std::ofstream out(input, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  }
  walkgen::StereoCalibration c;
  const bool loaded = walkgen_fuzz::only_walkgen_errors(
      "load_stereo_calibration", [&] { c = walkgen::load_stereo_calibration(input.string()); });
  if (!loaded) return 0;
  check_invariants(c, "loaded");

  // What loads saves, and the saved file loads to the same values (atomically replaced: no
  // temporary file is left).
  const fs::path again = work_folder() / "saved.yml";
  walkgen::StereoCalibration r;
  const bool round_trip = walkgen_fuzz::only_walkgen_errors("save + load", [&] {
    walkgen::save_stereo_calibration(c, again.string());
    r = walkgen::load_stereo_calibration(again.string());
  });
  WALKGEN_FUZZ_CHECK(round_trip, "a loaded calibration did not save and load again");
  check_invariants(r, "saved and loaded");
  WALKGEN_FUZZ_CHECK(r.left.image_size == c.left.image_size && r.rms == c.rms &&
                         r.mean_epipolar_error == c.mean_epipolar_error &&
                         r.left.rms == c.left.rms && r.right.rms == c.right.rms,
                     "the round trip changed a scalar");
  WALKGEN_FUZZ_CHECK(same(r.left.camera_matrix, c.left.camera_matrix) &&
                         same(r.left.distortion, c.left.distortion) &&
                         same(r.right.camera_matrix, c.right.camera_matrix) &&
                         same(r.right.distortion, c.right.distortion) &&
                         same(r.rotation, c.rotation) && same(r.translation, c.translation) &&
                         same(r.essential, c.essential) && same(r.fundamental, c.fundamental) &&
                         same(r.rectification_left, c.rectification_left) &&
                         same(r.rectification_right, c.rectification_right) &&
                         same(r.projection_left, c.projection_left) &&
                         same(r.projection_right, c.projection_right) &&
                         same(r.disparity_to_depth, c.disparity_to_depth),
                     "the round trip changed a matrix");
  std::size_t files = 0;
  for (const auto& e : fs::directory_iterator(work_folder())) {
    (void)e;
    ++files;
  }
  WALKGEN_FUZZ_CHECK(files == 2, "a temporary file was left next to saved.yml");
  return 0;
}
