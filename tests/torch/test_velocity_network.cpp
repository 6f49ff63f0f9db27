// walkgen::VelocityNetwork, the behavioural-cloning network in the C++ loop, against the Python
// side that trained it: on the frames of a recorded episode, the C++ pre-processing (4 × 4 block
// means, scaling), the 5-frame feature window (the first frame standing in for the frames
// before it) and the TorchScript methods must give the commands that python/bc_train.py's own
// pre-processing and model give (tests/torch/bc_pipeline.sh writes them to reference.csv).
// Needs the bc_pipeline test's output (the ctest fixture bc_model).
#include "walkgen/torch/velocity_network.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <opencv2/imgcodecs.hpp>
#include <sstream>
#include <string>
#include <vector>

namespace {

const std::string kOut = WALKGEN_BC_OUTPUT;  // bc_pipeline's output folder

struct Reference {
  std::string rgb, disparity;
  double vx = 0.0, omega = 0.0;  // the network's output in [-1, 1]
};

std::vector<Reference> read_reference() {
  std::ifstream in(kOut + "/reference.csv");
  std::vector<Reference> rows;
  std::string line;
  std::getline(in, line);  // header
  while (std::getline(in, line)) {
    std::istringstream s(line);
    Reference r;
    std::getline(s, r.rgb, ',');
    std::getline(s, r.disparity, ',');
    char comma = 0;
    s >> r.vx >> comma >> r.omega;
    rows.push_back(r);
  }
  return rows;
}

walkgen::CameraImage load_rgb(const std::string& path) {
  const cv::Mat bgr = cv::imread(path, cv::IMREAD_COLOR);
  walkgen::CameraImage image;
  image.width = bgr.cols;
  image.height = bgr.rows;
  image.rgb.resize(std::size_t(bgr.total()) * 3);
  for (int v = 0; v < bgr.rows; ++v) {
    for (int u = 0; u < bgr.cols; ++u) {
      const cv::Vec3b p = bgr.at<cv::Vec3b>(v, u);
      const std::size_t i = 3 * (std::size_t(v) * std::size_t(bgr.cols) + std::size_t(u));
      image.rgb[i] = p[2];
      image.rgb[i + 1] = p[1];
      image.rgb[i + 2] = p[0];
    }
  }
  return image;
}

TEST(VelocityNetwork, GivesThePythonModelsCommandsOnARecordedEpisode) {
  const std::vector<Reference> rows = read_reference();
  ASSERT_GE(rows.size(), 8u) << "run the bc_pipeline test first (it writes " << kOut
                             << "/reference.csv)";
  walkgen::VelocityNetwork network(kOut + "/model/model.pt");
  EXPECT_EQ(network.sequence(), 5);
  const Eigen::Vector2d max(0.034, 0.075);
  double largest = 0.0;
  for (const Reference& r : rows) {
    const walkgen::CameraImage left = load_rgb(kOut + "/data/" + r.rgb);
    const cv::Mat stored = cv::imread(kOut + "/data/" + r.disparity, cv::IMREAD_UNCHANGED);
    ASSERT_FALSE(left.rgb.empty() || stored.empty()) << r.rgb;
    cv::Mat disparity;
    stored.convertTo(disparity, CV_32F, 1.0 / 16.0);  // the recorder stores 16 × px
    const Eigen::Vector3d c = network.step(left, disparity.ptr<float>());
    EXPECT_NEAR(c.x(), max.x() * r.vx, 1e-4 * max.x()) << r.rgb;
    EXPECT_NEAR(c.z(), max.y() * r.omega, 1e-4 * max.y()) << r.rgb;
    EXPECT_EQ(c.y(), 0.0);
    largest = std::max(largest, std::abs(r.omega) + std::abs(r.vx));
  }
  EXPECT_GT(largest, 1e-3);  // a model that outputs something, so the comparison means something
  // After reset() the first frame again fills the window: the first command comes back.
  network.reset();
  const walkgen::CameraImage left = load_rgb(kOut + "/data/" + rows[0].rgb);
  std::vector<float> disparity(std::size_t(left.width * left.height));
  const cv::Mat stored = cv::imread(kOut + "/data/" + rows[0].disparity, cv::IMREAD_UNCHANGED);
  for (std::size_t i = 0; i < disparity.size(); ++i) {
    disparity[i] = float(stored.at<std::uint16_t>(int(i)) / 16.0);
  }
  EXPECT_NEAR(network.step(left, disparity.data()).z(), max.y() * rows[0].omega, 1e-4 * max.y());
}

TEST(VelocityNetwork, BadModelOrImageThrows) {
  EXPECT_THROW(walkgen::VelocityNetwork("/nonexistent/model.pt"), walkgen::invalid_argument);
  walkgen::VelocityNetwork network(kOut + "/model/model.pt");
  walkgen::CameraImage odd;
  odd.width = 321;  // not a multiple of the 4 × 4 blocks
  odd.height = 240;
  odd.rgb.resize(321 * 240 * 3);
  std::vector<float> disparity(321 * 240, 1.0f);
  EXPECT_THROW(network.step(odd, disparity.data()), walkgen::invalid_argument);
  walkgen::CameraImage ok;
  ok.width = 320;
  ok.height = 240;
  ok.rgb.resize(100);  // fewer bytes than the size says
  EXPECT_THROW(network.step(ok, disparity.data()), walkgen::invalid_argument);
  // NaN disparity (no match) reads as unknown, never as a NaN command.
  ok.rgb.assign(320 * 240 * 3, 128);
  std::vector<float> nan(320 * 240, std::nanf(""));
  EXPECT_TRUE(network.step(ok, nan.data()).allFinite());
}

}  // namespace
