// walkgen::DemonstrationRecorder (thesis §7.1.2, figure 7.2): images and commands in a folder
// with an index file, read back exactly; bad input and malformed index lines give clear errors.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <opencv2/imgcodecs.hpp>
#include <string>
#include <walkgen/opencv/demonstration_recorder.hpp>

#include "support/expect_error.hpp"

namespace {

walkgen::CameraImage gradient_image(int w, int h, int shift) {
  walkgen::CameraImage im;
  im.width = w;
  im.height = h;
  im.rgb.resize(std::size_t(w) * std::size_t(h) * 3);
  for (int v = 0; v < h; ++v) {
    for (int u = 0; u < w; ++u) {
      const std::size_t i = (std::size_t(v) * std::size_t(w) + std::size_t(u)) * 3;
      im.rgb[i] = std::uint8_t((u + shift) % 256);  // R
      im.rgb[i + 1] = std::uint8_t(v % 256);        // G
      im.rgb[i + 2] = 200;                          // B
    }
  }
  return im;
}

TEST(DemonstrationRecorder, WritesImagesAndAnIndexThatReadsBackExactly) {
  const std::string folder = ::testing::TempDir() + "walkgen_demo_recorder";
  std::filesystem::remove_all(folder);
  {
    walkgen::DemonstrationRecorder a(folder, "scan_7");
    for (int k = 0; k < 3; ++k) {
      cv::Mat disparity(24, 32, CV_32F, cv::Scalar(0.0f));
      disparity.at<float>(5, 7) = 12.5f + float(k);  // a sixteenth-pixel value
      disparity.at<float>(6, 7) = -1.0f;             // unknown -> 0
      a.record(0.4 * k, gradient_image(32, 24, k), disparity, {0.01 * k, 0.0, -0.02 * k});
    }
    EXPECT_EQ(a.samples(), 3);
    walkgen::DemonstrationRecorder b(folder, "straight_1");  // a second episode appends
    b.record(0.0, gradient_image(32, 24, 9), cv::Mat(24, 32, CV_32F, cv::Scalar(3.0f)),
             {0.03, 0.0, 0.0});
  }
  const auto entries = walkgen::read_demonstration_index(folder);
  ASSERT_EQ(entries.size(), 4u);
  EXPECT_EQ(entries[2].episode, "scan_7");
  EXPECT_EQ(entries[3].episode, "straight_1");
  EXPECT_NEAR(entries[2].time, 0.8, 1e-12);
  EXPECT_NEAR(entries[2].command.x(), 0.02, 1e-12);
  EXPECT_NEAR(entries[2].command.z(), -0.04, 1e-12);
  const cv::Mat bgr = cv::imread(folder + "/" + entries[1].rgb, cv::IMREAD_UNCHANGED);
  ASSERT_EQ(bgr.type(), CV_8UC3);
  EXPECT_EQ(bgr.at<cv::Vec3b>(3, 10), cv::Vec3b(200, 3, 11));  // B, G, R of pixel (u 10, v 3)
  const cv::Mat fixed = cv::imread(folder + "/" + entries[1].disparity, cv::IMREAD_UNCHANGED);
  ASSERT_EQ(fixed.type(), CV_16U);
  EXPECT_EQ(fixed.at<std::uint16_t>(5, 7), 16 * 13.5);
  EXPECT_EQ(fixed.at<std::uint16_t>(6, 7), 0);
}

TEST(DemonstrationRecorder, BadInputAndMalformedIndexesGiveClearErrors) {
  const std::string folder = ::testing::TempDir() + "walkgen_demo_recorder_bad";
  std::filesystem::remove_all(folder);
  walkgen_test::expect_invalid_argument([&] { walkgen::DemonstrationRecorder(folder, "a b"); },
                                        {"episode", "'a b'"});
  walkgen::DemonstrationRecorder r(folder, "ok");
  const cv::Mat small(10, 10, CV_32F, cv::Scalar(1.0f));
  walkgen_test::expect_invalid_argument(
      [&] {
        r.record(0.0, gradient_image(32, 24, 0), small, {0, 0, 0});
      },
      {"disparity", "32x24", "10x10"});
  walkgen_test::expect_invalid_argument(
      [&] {
        r.record(0.0, gradient_image(10, 10, 0), small, {std::nan(""), 0, 0});
      },
      {"finite"});
  walkgen_test::expect_invalid_argument(
      [&] { r.record(0.0, walkgen::CameraImage(), small, Eigen::Vector3d::Zero()); },
      {"left image"});
  std::ofstream(folder + "/index.txt", std::ios::app) << "rgb/x.png disparity/x.png ep 0.5 0.1\n";
  walkgen_test::expect_invalid_argument([&] { return walkgen::read_demonstration_index(folder); },
                                        {"index.txt:2", "v_x v_y omega"});
  walkgen_test::expect_invalid_argument(
      [&] { return walkgen::read_demonstration_index(folder + "/nowhere"); }, {"missing"});
}

// Every file under `folder` with its bytes.
std::map<std::string, std::string> snapshot(const std::string& folder) {
  std::map<std::string, std::string> files;
  for (const auto& e : std::filesystem::recursive_directory_iterator(folder)) {
    if (!e.is_regular_file()) continue;
    std::ifstream in(e.path(), std::ios::binary);
    files[e.path().string()] =
        std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  }
  return files;
}

// The files that differ between two snapshots (missing, new or changed).
std::string changes(const std::map<std::string, std::string>& before,
                    const std::map<std::string, std::string>& after) {
  std::string out;
  for (const auto& [path, bytes] : before) {
    const auto a = after.find(path);
    if (a == after.end())
      out += " missing " + path;
    else if (a->second != bytes)
      out += " changed " + path;
  }
  for (const auto& [path, bytes] : after) {
    if (before.count(path) == 0) out += " new " + path;
  }
  return out;
}

// Issue 21, defect 7c: recording an episode name again would overwrite its images and add its
// lines to index.txt a second time (the index then disagrees with the files). The recorder
// refuses, naming the episode and the folder, and changes nothing.
TEST(DemonstrationRecorder, AnEpisodeNameAlreadyInTheFolderIsRefused) {
  const std::string folder = ::testing::TempDir() + "walkgen_demo_recorder_again";
  std::filesystem::remove_all(folder);
  const cv::Mat disparity(24, 32, CV_32F, cv::Scalar(2.0f));
  {
    walkgen::DemonstrationRecorder first(folder, "scan_7");
    for (int k = 0; k < 2; ++k) {
      first.record(0.4 * k, gradient_image(32, 24, k), disparity, {0.01 * k, 0.0, 0.0});
    }
  }
  const auto before = snapshot(folder);
  ASSERT_EQ(before.size(), 5u);  // index.txt, 2 rgb, 2 disparity
  walkgen_test::expect_invalid_argument(
      [&] {
        walkgen::DemonstrationRecorder again(folder, "scan_7");  // a second run, same name
        again.record(0.0, gradient_image(32, 24, 5), disparity, {0.05, 0.0, 0.0});
      },
      {"'scan_7'", folder, "index.txt", "hint"});
  EXPECT_EQ(changes(before, snapshot(folder)), "");
  EXPECT_EQ(walkgen::read_demonstration_index(folder).size(), 2u);

  // Images of the episode without index lines (a run stopped before its index was written, or
  // an index restored from a backup) are refused too.
  std::filesystem::remove(folder + "/index.txt");
  const auto images_only = snapshot(folder);
  walkgen_test::expect_invalid_argument(
      [&] { walkgen::DemonstrationRecorder again(folder, "scan_7"); },
      {"'scan_7'", folder, "rgb/scan_7_000000.png"});
  EXPECT_EQ(changes(images_only, snapshot(folder)), "");

  // Other names, also ones that start alike, are free.
  walkgen::DemonstrationRecorder other(folder, "scan");
  other.record(0.0, gradient_image(32, 24, 1), disparity, {0.0, 0.0, 0.0});
  walkgen::DemonstrationRecorder longer(folder, "scan_70");
  EXPECT_EQ(longer.samples(), 0);
}

}  // namespace
