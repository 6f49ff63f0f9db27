// Packaging check of the OpenCV adapter: a program built against walkgen::opencv must compile,
// link against OpenCV (with ximgproc) and turn a shifted random-dot pair into the right depth.
#include <cmath>
#include <cstdio>
#include <walkgen/opencv/stereo_depth.hpp>

int main() {
  cv::Mat right(120, 160, CV_8U);
  cv::randu(right, 0, 255);
  cv::Mat left = cv::Mat::zeros(right.size(), CV_8U);
  right(cv::Rect(0, 0, 150, 120)).copyTo(left(cv::Rect(10, 0, 150, 120)));  // disparity 10 px
  walkgen::PinholeIntrinsics k;
  k.fx = k.fy = 100.0;
  walkgen::StereoDepth depth({}, walkgen::ideal_disparity_to_depth(k, 0.1));
  const float z = depth.compute(left, right).depth.at<float>(60, 80);
  std::printf("depth at the centre: %g m (expected 1 m)\n", z);
  if (std::abs(z - 1.0f) > 0.02f) {
    std::fprintf(stderr, "wrong answer\n");
    return 1;
  }
  return 0;
}
