// Calibration on OpenCV's 13 stereo chessboard pairs (thesis §3.2, §10.1; issue 6 acceptance):
// left mono RMS <= 0.45 px with f_x within 1 % of OpenCV's shipped 535.9, stereo RMS <= 0.7 px,
// mean epipolar error <= 0.5 px; YAML round trip; clear errors for bad input. Issue 21: every
// malformed or truncated file is refused with walkgen's own error naming the file and the key,
// and a save that fails half-way leaves the previous file as it was.
#include <gtest/gtest.h>
#include <sys/resource.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <set>
#include <string>
#include <vector>
#include <walkgen/opencv/stereo_calibration.hpp>

#include "opencv/data_dir.hpp"
#include "support/enum_strings.hpp"
#include "support/expect_error.hpp"
#include "support/files.hpp"

namespace {

const std::vector<std::string> kViews = {"01", "02", "03", "04", "05", "06", "07",
                                         "08", "09", "11", "12", "13", "14"};

std::vector<std::string> chessboard_files(const std::string& side) {
  const std::string dir = walkgen::test::data_path("opencv_stereo_chessboard");
  std::vector<std::string> files;
  for (const std::string& v : kViews) files.push_back(dir + "/" + side + v + ".jpg");
  return files;
}

std::vector<cv::Mat> read_all(const std::vector<std::string>& files) {
  std::vector<cv::Mat> images;
  for (const std::string& f : files) images.push_back(walkgen::read_image(f));
  return images;
}

using walkgen_test::expect_invalid_argument;

namespace fs = std::filesystem;

const fs::path kReliability = WALKGEN_SOURCE_DIR "/tests/data/reliability/stereo_calibration";

using walkgen_test::fresh_folder;
using walkgen_test::read_bytes;

std::set<std::string> listing(const fs::path& folder) {
  std::set<std::string> names;
  for (const auto& e : fs::directory_iterator(folder)) names.insert(e.path().filename().string());
  return names;
}

/// Lowers the soft limit on the size of files this process writes (RLIMIT_FSIZE): a write past
/// it fails as on a full disk (SIGXFSZ ignored meanwhile). Restores both on destruction.
class FileSizeLimit {
 public:
  explicit FileSizeLimit(rlim_t bytes) {
    previous_handler_ = std::signal(SIGXFSZ, SIG_IGN);
    getrlimit(RLIMIT_FSIZE, &previous_);
    rlimit lowered = previous_;
    lowered.rlim_cur = bytes;
    setrlimit(RLIMIT_FSIZE, &lowered);
  }
  ~FileSizeLimit() {
    setrlimit(RLIMIT_FSIZE, &previous_);
    std::signal(SIGXFSZ, previous_handler_);
  }
  FileSizeLimit(const FileSizeLimit&) = delete;
  FileSizeLimit& operator=(const FileSizeLimit&) = delete;

 private:
  rlimit previous_{};
  void (*previous_handler_)(int) = nullptr;
};

}  // namespace

TEST(StereoCalibration, LeftMonoMatchesOpenCvReference) {
  const std::vector<std::string> files = chessboard_files("left");
  const walkgen::MonoCalibration c = walkgen::calibrate_camera(read_all(files), {}, files);
  EXPECT_EQ(c.status, walkgen::CalibrationStatus::ok);
  EXPECT_STREQ(c.message, "");
  std::printf("left mono: RMS %.4f px, fx %.3f fy %.3f cx %.3f cy %.3f, %zu views\n", c.rms,
              c.camera_matrix.at<double>(0, 0), c.camera_matrix.at<double>(1, 1),
              c.camera_matrix.at<double>(0, 2), c.camera_matrix.at<double>(1, 2),
              c.views_used.size());
  EXPECT_EQ(c.views_used.size(), 13u);
  EXPECT_EQ(c.image_size, cv::Size(640, 480));
  EXPECT_LE(c.rms, 0.45);
  const double fx = c.camera_matrix.at<double>(0, 0);
  EXPECT_NEAR(fx, 535.916, 0.01 * 535.916);                // left_intrinsics.yml, shipped by OpenCV
  EXPECT_DOUBLE_EQ(c.camera_matrix.at<double>(1, 1), fx);  // fix_aspect_ratio
  EXPECT_NEAR(c.camera_matrix.at<double>(0, 2), 342.283, 2.0);
  EXPECT_NEAR(c.camera_matrix.at<double>(1, 2), 235.571, 2.0);
  EXPECT_NEAR(c.distortion.at<double>(0), -0.266, 0.02);  // k1
  ASSERT_EQ(c.view_rms.size(), 13u);
  // The per-view errors follow OpenCV's: view 02 is the worst by far (1.18 px there).
  const auto worst = std::max_element(c.view_rms.begin(), c.view_rms.end());
  EXPECT_EQ(worst - c.view_rms.begin(), 1);
}

TEST(StereoCalibration, StereoPairAndYamlRoundTrip) {
  const std::vector<std::string> left = chessboard_files("left");
  const std::vector<std::string> right = chessboard_files("right");
  const walkgen::StereoCalibration c = walkgen::calibrate_stereo_files(left, right);
  EXPECT_EQ(c.status, walkgen::CalibrationStatus::ok) << c.message;
  EXPECT_EQ(c.left.status, walkgen::CalibrationStatus::ok);
  EXPECT_EQ(c.right.status, walkgen::CalibrationStatus::ok);
  const double baseline = cv::norm(c.translation);
  std::printf(
      "stereo: RMS %.4f px, mean epipolar error %.4f px, |T| %.4f m (%.3f squares), f %.2f, "
      "per-camera RMS %.4f / %.4f px\n",
      c.rms, c.mean_epipolar_error, baseline, baseline / 0.025,
      c.left.camera_matrix.at<double>(0, 0), c.left.rms, c.right.rms);
  EXPECT_EQ(c.views_used.size(), 13u);
  EXPECT_LE(c.rms, 0.7);
  EXPECT_LE(c.mean_epipolar_error, 0.5);
  // Even by the stereo_calib sample's measure (left + right distance per corner pair; OpenCV 4.6
  // gave 0.445 px there).
  EXPECT_LE(2.0 * c.mean_epipolar_error, 0.5);
  EXPECT_NEAR(baseline / 0.025, 3.343, 0.05);  // OpenCV 4.6's stereo_calib: 3.343 squares
  // Right camera to the right of the left one: T along -x in the left camera's frame.
  EXPECT_LT(c.translation.at<double>(0), 0.0);
  // Rectified: both projections share f and c_y; P2's T_x = f * T'_x, Q maps disparity to depth.
  EXPECT_NEAR(c.projection_left.at<double>(1, 2), c.projection_right.at<double>(1, 2), 1e-9);
  const double f = c.projection_left.at<double>(0, 0);
  EXPECT_NEAR(-c.projection_right.at<double>(0, 3) / f, baseline, 1e-6);
  EXPECT_NEAR(c.disparity_to_depth.at<double>(2, 3), f, 1e-9);
  // Z = f B / d through Q at d = 10 px.
  const double w =
      c.disparity_to_depth.at<double>(3, 2) * 10.0 + c.disparity_to_depth.at<double>(3, 3);
  EXPECT_NEAR(f / w, f * baseline / 10.0, 1e-6);

  // Rectified corners lie on the same rows (epipolar lines are rows after rectification).
  bool found_l = false, found_r = false;
  const walkgen::StereoRectifier rectifier(c);
  cv::Mat rl, rr;
  rectifier.rectify(walkgen::read_image(left[0]), walkgen::read_image(right[0]), rl, rr);
  const auto cl = walkgen::find_chessboard(rl, {}, found_l);
  const auto cr = walkgen::find_chessboard(rr, {}, found_r);
  ASSERT_TRUE(found_l && found_r);
  double row_error = 0.0;
  for (std::size_t i = 0; i < cl.size(); ++i) row_error += std::abs(cl[i].y - cr[i].y);
  row_error /= static_cast<double>(cl.size());
  std::printf("rectified pair 01: mean row difference %.3f px\n", row_error);
  EXPECT_LT(row_error, 0.5);

  // YAML round trip.
  const std::string path =
      (std::filesystem::temp_directory_path() / "walkgen_test_stereo_calibration.yml").string();
  walkgen::save_stereo_calibration(c, path);
  const walkgen::StereoCalibration loaded = walkgen::load_stereo_calibration(path);
  EXPECT_EQ(loaded.left.image_size, c.left.image_size);
  EXPECT_LT(cv::norm(loaded.left.camera_matrix, c.left.camera_matrix, cv::NORM_INF), 1e-9);
  EXPECT_LT(cv::norm(loaded.right.distortion, c.right.distortion, cv::NORM_INF), 1e-9);
  EXPECT_LT(cv::norm(loaded.projection_right, c.projection_right, cv::NORM_INF), 1e-9);
  EXPECT_LT(cv::norm(loaded.disparity_to_depth, c.disparity_to_depth, cv::NORM_INF), 1e-9);
  EXPECT_DOUBLE_EQ(loaded.rms, c.rms);
  EXPECT_DOUBLE_EQ(loaded.mean_epipolar_error, c.mean_epipolar_error);
  std::filesystem::remove(path);
}

TEST(StereoCalibration, MissingYamlKeyNamesFileAndKey) {
  const std::string path =
      (std::filesystem::temp_directory_path() / "walkgen_test_missing_key.yml").string();
  {
    cv::FileStorage fs(path, cv::FileStorage::WRITE);
    fs << "image_width" << 640 << "image_height" << 480;
    fs << "K1" << cv::Mat::eye(3, 3, CV_64F) << "D1" << cv::Mat::zeros(1, 5, CV_64F);
  }
  expect_invalid_argument([&] { return walkgen::load_stereo_calibration(path); }, {path, "'K2'"});
  {
    cv::FileStorage fs(path, cv::FileStorage::WRITE);
    fs << "image_width" << 640 << "image_height" << 480;
    fs << "K1" << cv::Mat::eye(2, 2, CV_64F);
  }
  expect_invalid_argument([&] { return walkgen::load_stereo_calibration(path); },
                          {path, "'K1'", "3x3", "2x2"});
  std::filesystem::remove(path);
  expect_invalid_argument([&] { return walkgen::load_stereo_calibration(path); },
                          {path, "missing"});
}

TEST(StereoCalibration, BadInputGivesClearErrors) {
  const std::vector<std::string> left = chessboard_files("left");
  const std::vector<std::string> right = chessboard_files("right");
  // A missing file.
  expect_invalid_argument([&] { walkgen::read_image(left[0] + ".nosuch"); },
                          {".nosuch", "missing"});
  // A board that is not found: the wrong board size.
  walkgen::CalibrationSettings wrong;
  wrong.board.columns = 7;
  wrong.board.rows = 5;
  std::vector<cv::Mat> three(3, walkgen::read_image(left[0]));
  expect_invalid_argument([&] { walkgen::calibrate_camera(three, wrong, {left[0]}); },
                          {left[0], "7x5", "none found"});
  // Images of different sizes.
  std::vector<cv::Mat> mixed = three;
  cv::resize(mixed[2], mixed[2], cv::Size(320, 240));
  expect_invalid_argument([&] { walkgen::calibrate_camera(mixed); },
                          {"view 2", "640x480", "320x240"});
  // An empty image.
  std::vector<cv::Mat> with_empty = three;
  with_empty[1] = cv::Mat();
  expect_invalid_argument([&] { walkgen::calibrate_camera(with_empty); }, {"view 1", "empty"});
  // Different numbers of left and right views.
  expect_invalid_argument([&] { walkgen::calibrate_stereo(three, {three[0]}); },
                          {"right views", "3"});
  // A board hidden in one right view: named, or skipped on request.
  std::vector<cv::Mat> l, r;
  for (int i = 0; i < 4; ++i) {
    l.push_back(walkgen::read_image(left[static_cast<std::size_t>(i)]));
    r.push_back(walkgen::read_image(right[static_cast<std::size_t>(i)]));
  }
  r[2] = cv::Mat(r[2].size(), CV_8U, cv::Scalar(128));
  expect_invalid_argument(
      [&] {
        walkgen::calibrate_stereo(l, r, {}, {"a", "b", "c", "d"});
      },
      {"right 'c'", "none found"});
  walkgen::CalibrationSettings skip;
  skip.skip_views_without_board = true;
  const walkgen::StereoCalibration c = walkgen::calibrate_stereo(l, r, skip);
  EXPECT_EQ(c.views_used, (std::vector<int>{0, 1, 3}));
}

// Issue 21, defect 6: each reproducer let a cv::Exception escape, or loaded although malformed
// (negative size, NaN translation, truncated). Each must give walkgen's own error naming the file
// and the key of the first malformed line, else the first key (in the order the file is read)
// that is wrong.
TEST(StereoCalibration, MalformedFilesGiveWalkgenErrorsNamingFileAndKey) {
  const std::map<std::string, std::string> first_bad_key = {
      {"calib_cvexception_Failed_to_allocate_137438953408_bytes_in.yaml", "D2"},  // rows: garbage
      {"calib_cvexception_Failed_to_allocate_51539607528_bytes_in_.yaml", "R"},   // rows: garbage
      {"calib_cvexception_Invalid_data_type_specification_in_funct.yaml", "K2"},  // dt: atrix
      {"calib_cvexception__data_node_empty___in_function__read_.yaml", "D1"},     // no data
      {"calib_cvexception__dt_empty___in_function__read_.yaml", "Q"},             // no dt
      {"calib_cvexception__sizes_node_empty___in_function__read_.yaml", "K1"},    // no rows
      {"calib_cvexception_isMap___in_function__operator___.yaml", "D2"},          // a string
      // T is 2x3, but the line check sees F's mangled tag (line 53) before any key is read.
      {"calib_cvexception_nelems____m_total___m_channels___in_func.yaml", "F"},
      {"calib_cvexception_readRawData_can_only_be_used_to_read_pla.yaml", "E"},  // "?0."
      {"calib_cvexception_s____0_in_function__setSize_.yaml", "F"},              // no cols
      {"calib_nan_T.yaml", "T"},
      {"calib_negative_size.yaml", "image_width"},
      {"calib_prefix11.yaml", ""},                   // the header cut: "in the header"
      {"calib_prefix2082_loads_rms_0.yaml", "rms"},  // cut before rms
      {"calib_prefix2092_loads_rms_4.09.yaml", "mean_epipolar_error"}  // cut inside rms
  };
  std::size_t files = 0;
  for (const auto& entry : fs::directory_iterator(kReliability)) {
    const std::string name = entry.path().filename().string();
    if (name == "calib_full.yaml") continue;
    ++files;
    try {
      const walkgen::StereoCalibration c = walkgen::load_stereo_calibration(entry.path().string());
      ADD_FAILURE() << name << " loaded (rms " << c.rms << ", image " << c.left.image_size << ")";
    } catch (const walkgen::invalid_argument& e) {
      const std::string message = e.what();
      EXPECT_NE(message.find(name), std::string::npos) << "message '" << message << "'";
      const auto key = first_bad_key.find(name);
      const std::string expected = key == first_bad_key.end() ? "key '"
                                   : key->second.empty()      ? "the header"
                                                              : "key '" + key->second + "'";
      EXPECT_NE(message.find(expected), std::string::npos)
          << name << ": message '" << message << "' lacks " << expected;
    } catch (const std::exception& e) {
      ADD_FAILURE() << name << ": a foreign exception escaped: " << e.what();
    }
  }
  EXPECT_GE(files, first_bad_key.size());
  // The complete file, in the format before the end marker (no walkgen_calibration_format key),
  // still loads.
  const walkgen::StereoCalibration full =
      walkgen::load_stereo_calibration((kReliability / "calib_full.yaml").string());
  EXPECT_EQ(full.left.image_size, cv::Size(640, 480));
  EXPECT_DOUBLE_EQ(full.translation.at<double>(0), -3.33);
  EXPECT_EQ(full.left.distortion.cols, 8);
  EXPECT_DOUBLE_EQ(full.rms, 0.41);
  EXPECT_DOUBLE_EQ(full.mean_epipolar_error, 0.35);
  EXPECT_DOUBLE_EQ(full.left.rms, 0.29);
  EXPECT_DOUBLE_EQ(full.right.rms, 0.31);
}

// Issue 21, defect 6: a file that save_stereo_calibration wrote and that was cut anywhere (a
// crash, a full disk, a copy that stopped) must not load: not with rms 0, not with a cut number.
// Only a prefix that still holds the whole end marker may load, and then with every value.
TEST(StereoCalibration, EveryTruncatedCopyOfASavedFileIsRefused) {
  const walkgen::StereoCalibration c =
      walkgen::load_stereo_calibration((kReliability / "calib_full.yaml").string());
  const fs::path folder = fresh_folder("walkgen_calibration_prefixes");
  const fs::path saved = folder / "saved.yml";
  walkgen::save_stereo_calibration(c, saved.string());
  const std::string text = read_bytes(saved);
  const std::string marker = "\ncomplete: 1";
  const std::size_t at = text.find(marker);
  const std::size_t complete = at == std::string::npos ? text.size() : at + marker.size();
  std::vector<std::string> loaded;
  for (std::size_t n = 0; n < text.size(); ++n) {
    const fs::path cut = folder / "cut.yml";
    std::ofstream(cut, std::ios::binary | std::ios::trunc) << text.substr(0, n);
    try {
      const walkgen::StereoCalibration l = walkgen::load_stereo_calibration(cut.string());
      if (n < complete) {
        loaded.push_back(std::to_string(n) + " bytes (rms " + std::to_string(l.rms) + ")");
      } else {
        EXPECT_DOUBLE_EQ(l.right.rms, c.right.rms);
      }
    } catch (const walkgen::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("cut.yml"), std::string::npos) << e.what();
    } catch (const std::exception& e) {
      ADD_FAILURE() << n << " bytes: a foreign exception escaped: " << e.what();
    }
  }
  EXPECT_TRUE(loaded.empty()) << loaded.size() << " of " << complete
                              << " truncated copies loaded, e.g. "
                              << (loaded.empty() ? "" : loaded.front() + ", " + loaded.back());
}

// Issue 21, defect 7a: a save that fails half-way (here: a full disk, or a calibration that
// would not read back) leaves the previous file complete and loadable, and no temporary file.
TEST(StereoCalibration, AFailedSaveLeavesThePreviousFile) {
  const walkgen::StereoCalibration good =
      walkgen::load_stereo_calibration((kReliability / "calib_full.yaml").string());
  const fs::path folder = fresh_folder("walkgen_calibration_interrupted");
  const std::string path = (folder / "stereo.yml").string();
  walkgen::save_stereo_calibration(good, path);
  const std::string before = read_bytes(path);
  ASSERT_GT(before.size(), 1000u);

  walkgen::StereoCalibration other = good;
  other.rms = 0.5;
  other.translation = good.translation.clone();
  other.translation.at<double>(0) = -3.4;
  {
    const FileSizeLimit full_disk(1000);  // the write stops after 1000 bytes
    expect_invalid_argument([&] { walkgen::save_stereo_calibration(other, path); }, {path});
  }
  EXPECT_EQ(read_bytes(path), before);
  EXPECT_EQ(listing(folder), (std::set<std::string>{"stereo.yml"}));

  other.translation.at<double>(1) = std::nan("");  // load would refuse it: so does save
  expect_invalid_argument([&] { walkgen::save_stereo_calibration(other, path); }, {path, "'T'"});
  EXPECT_EQ(read_bytes(path), before);
  EXPECT_EQ(listing(folder), (std::set<std::string>{"stereo.yml"}));
  const walkgen::StereoCalibration loaded = walkgen::load_stereo_calibration(path);
  EXPECT_DOUBLE_EQ(loaded.translation.at<double>(0), -3.33);
  EXPECT_DOUBLE_EQ(loaded.rms, 0.41);

  // A folder that does not exist.
  expect_invalid_argument(
      [&] { walkgen::save_stereo_calibration(good, (folder / "nowhere" / "s.yml").string()); },
      {"nowhere", "missing"});
}

TEST(StereoCalibration, SettingsAreValidatedNamingTheField) {
  using B = walkgen::ChessboardSettings;
  walkgen_test::expect_rejected<B>(
      B(), {{[](B& b) { b.columns = 1; }, {"ChessboardSettings.columns", "at least 2", "1"}},
            {[](B& b) { b.rows = 0; }, {"ChessboardSettings.rows", "at least 2", "0"}},
            {[](B& b) { b.square_size = -0.025; }, {"ChessboardSettings.square_size", "-0.025"}},
            {[](B& b) { b.subpixel_half_window = 0; },
             {"ChessboardSettings.subpixel_half_window", ">= 1", "0"}}});
  using C = walkgen::CalibrationSettings;
  walkgen_test::expect_rejected<C>(
      C(), {{[](C& c) { c.board.rows = 1; }, {"ChessboardSettings.rows", "1"}},
            {[](C& c) { c.rectify_alpha = 1.5; },
             {"CalibrationSettings.rectify_alpha", "[0, 1]", "1.5"}},
            {[](C& c) { c.rectify_alpha = -0.5; }, {"CalibrationSettings.rectify_alpha", "-0.5"}}});
  walkgen::CalibrationSettings zero;  // both ends of OpenCV's alpha are valid
  zero.rectify_alpha = 0.0;
  EXPECT_NO_THROW(walkgen::validate(zero));
}

TEST(StereoCalibration, StatusStrings) {
  walkgen_test::expect_enum_strings(std::array<walkgen::CalibrationStatus, 2>{
      walkgen::CalibrationStatus::ok, walkgen::CalibrationStatus::non_finite});
  static_assert(to_string(walkgen::CalibrationStatus::non_finite)[0] == 'n');
}
