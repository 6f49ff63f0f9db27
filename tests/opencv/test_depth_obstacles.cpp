// Obstacles from depth (issue 6; eq. 2.79's circles from chapter 3's depth): depth images
// ray-cast analytically from a camera 0.8 m above the floor, pitched down like the humanoid's
// chest cameras, looking at vertical cylinders; exact and with stereo-like noise.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <vector>
#include <walkgen/core/math.hpp>
#include <walkgen/mpc/settings.hpp>
#include <walkgen/opencv/depth_obstacles.hpp>
#include "support/expect_error.hpp"

namespace {

struct Cylinder {
  double x, y, radius, height;
};

const walkgen::PinholeIntrinsics kCamera =
    walkgen::pinhole_from_fovy(320, 240, 45.0 * walkgen::kPi / 180.0);

Eigen::Isometry3d camera_pose(double pitch = 0.1) {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() = Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitY()).toRotationMatrix();
  pose.translation() = Eigen::Vector3d(0.0, 0.0, 0.8);
  return pose;
}

// Depth Z along the optical axis of the first hit of each pixel's ray: floor (z = 0) or
// cylinder side or top; 0 where nothing is hit within 10 m.
cv::Mat render(const std::vector<Cylinder>& cylinders, const Eigen::Isometry3d& pose) {
  cv::Mat depth(240, 320, CV_32F, cv::Scalar(0.0f));
  const Eigen::Vector3d o = pose.translation();
  for (int v = 0; v < depth.rows; ++v) {
    for (int u = 0; u < depth.cols; ++u) {
      // Ray with unit optical-axis component: the ray parameter t is Z.
      const Eigen::Vector3d d = pose.linear() * Eigen::Vector3d(1.0, -(u - kCamera.cx) / kCamera.fx,
                                                                -(v - kCamera.cy) / kCamera.fy);
      double best = 10.0;
      if (d.z() < 0.0) best = std::min(best, -o.z() / d.z());
      for (const Cylinder& c : cylinders) {
        const Eigen::Vector2d oc = o.head<2>() - Eigen::Vector2d(c.x, c.y);
        const Eigen::Vector2d dd = d.head<2>();
        const double a = dd.squaredNorm(), b = 2.0 * oc.dot(dd);
        const double disc = b * b - 4.0 * a * (oc.squaredNorm() - c.radius * c.radius);
        if (disc >= 0.0) {
          const double t = (-b - std::sqrt(disc)) / (2.0 * a);
          const double z = o.z() + t * d.z();
          if (t > 0.0 && z >= 0.0 && z <= c.height) best = std::min(best, t);
        }
        if (d.z() < 0.0) {  // the top
          const double t = (c.height - o.z()) / d.z();
          if (t > 0.0 && (o.head<2>() + t * dd - Eigen::Vector2d(c.x, c.y)).norm() <= c.radius) {
            best = std::min(best, t);
          }
        }
      }
      if (best < 10.0) depth.at<float>(v, u) = static_cast<float>(best);
    }
  }
  return depth;
}

const std::vector<Cylinder> kThreeChairs = {
    {1.0, -0.3, 0.15, 0.9}, {2.0, 0.3, 0.2, 0.9}, {3.0, -0.15, 0.2, 0.9}};

}  // namespace

TEST(DepthObstacles, ExactDepthFindsThreeCylinders) {
  const cv::Mat depth = render(kThreeChairs, camera_pose());
  walkgen::DepthObstacleSettings s;
  s.margin = 0.1;
  const auto obstacles = walkgen::obstacles_from_depth(depth, kCamera, camera_pose(), s);
  ASSERT_EQ(obstacles.size(), 3u);
  for (std::size_t i = 0; i < 3; ++i) {
    const Cylinder& c = kThreeChairs[i];
    const double error = std::hypot(obstacles[i].x - c.x, obstacles[i].y - c.y);
    std::printf("cylinder at %.1f m: centre error %.3f m, radius %.3f (true %.2f) m\n", c.x, error,
                obstacles[i].radius, c.radius);
    EXPECT_LT(error, 0.03);
    EXPECT_NEAR(obstacles[i].radius, c.radius, 0.03);
    EXPECT_DOUBLE_EQ(obstacles[i].margin, 0.1);
  }
  // What the NMPC's obstacle constraint (eq. 2.79) accepts.
  walkgen::WalkingSettings<double> walking = walkgen::hrp2_settings();
  walking.obstacles = obstacles;
  EXPECT_NO_THROW(walkgen::validate(walking));
}

TEST(DepthObstacles, StereoLikeNoiseStaysWithinATenthOfAMetre) {
  const cv::Mat exact = render(kThreeChairs, camera_pose());
  // Disparity noise of 0.25 px at f = 290 px, B = 0.068 m: sigma_Z = Z² 0.25 / (f B).
  std::mt19937 rng(7);
  std::normal_distribution<double> noise(0.0, 0.25);
  cv::Mat noisy = exact.clone();
  const double fb = kCamera.fx * 0.068;
  for (int v = 0; v < noisy.rows; ++v) {
    for (int u = 0; u < noisy.cols; ++u) {
      float& z = noisy.at<float>(v, u);
      if (z > 0.0f) z = static_cast<float>(fb / (fb / z + noise(rng)));
    }
  }
  const auto obstacles = walkgen::obstacles_from_depth(noisy, kCamera, camera_pose());
  ASSERT_EQ(obstacles.size(), 3u);
  for (std::size_t i = 0; i < 3; ++i) {
    const double error =
        std::hypot(obstacles[i].x - kThreeChairs[i].x, obstacles[i].y - kThreeChairs[i].y);
    std::printf("noisy, cylinder at %.1f m: centre error %.3f m\n", kThreeChairs[i].x, error);
    EXPECT_LT(error, 0.1);
  }
}

TEST(DepthObstacles, FloorAloneIsNoObstacle) {
  const cv::Mat depth = render({}, camera_pose());
  EXPECT_TRUE(walkgen::obstacles_from_depth(depth, kCamera, camera_pose()).empty());
  // The same scene rotated and shifted in the world: circles move with the camera.
  Eigen::Isometry3d moved = Eigen::Isometry3d::Identity();
  moved.linear() = Eigen::AngleAxisd(0.7, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  moved.translation() = Eigen::Vector3d(1.0, -2.0, 0.0);
  const cv::Mat one = render({kThreeChairs[0]}, camera_pose());
  const auto o = walkgen::obstacles_from_depth(one, kCamera, moved * camera_pose());
  ASSERT_EQ(o.size(), 1u);
  const Eigen::Vector3d expected = moved * Eigen::Vector3d(kThreeChairs[0].x, kThreeChairs[0].y, 0);
  EXPECT_NEAR(o[0].x, expected.x(), 0.03);
  EXPECT_NEAR(o[0].y, expected.y(), 0.03);
}

TEST(DepthObstacles, BadInputGivesClearErrors) {
  auto expect_error = [](auto f, const std::string& part) {
    walkgen_test::expect_invalid_argument(f, {part});
  };
  expect_error([] { walkgen::obstacles_from_depth(cv::Mat(), kCamera, camera_pose()); }, "empty");
  expect_error(
      [] { walkgen::obstacles_from_depth(cv::Mat(240, 320, CV_16U), kCamera, camera_pose()); },
      "CV_32F");
  walkgen::DepthObstacleSettings s;
  s.max_depth = 0.1;
  expect_error(
      [&] { walkgen::obstacles_from_depth(cv::Mat(240, 320, CV_32F), kCamera, camera_pose(), s); },
      "max_depth");
}

TEST(DepthObstacles, SettingsAreValidatedNamingTheField) {
  using S = walkgen::DepthObstacleSettings;
  walkgen_test::expect_rejected<S>(
      S(),
      {{[](S& s) { s.min_depth = 0.0; }, {"DepthObstacleSettings.min_depth", "> 0", "0"}},
       {[](S& s) { s.max_depth = 0.1; }, {"DepthObstacleSettings.max_depth", "min_depth", "0.1"}},
       {[](S& s) { s.max_height = 0.05; },
        {"DepthObstacleSettings.max_height", "floor_height", "0.05"}},
       {[](S& s) { s.cell_size = std::nan(""); }, {"DepthObstacleSettings.cell_size", "nan"}},
       {[](S& s) { s.cluster_gap = -0.1; }, {"DepthObstacleSettings.cluster_gap", ">= 0", "-0.1"}},
       {[](S& s) { s.min_points = 2; }, {"DepthObstacleSettings.min_points", "at least 3", "2"}},
       {[](S& s) { s.pixel_stride = 0; }, {"DepthObstacleSettings.pixel_stride", "0"}},
       {[](S& s) { s.width_quantile = 0.5; },
        {"DepthObstacleSettings.width_quantile", "[0, 0.5)", "0.5"}},
       {[](S& s) { s.min_radius = -1.0; }, {"DepthObstacleSettings.min_radius", "-1"}},
       {[](S& s) { s.margin = -0.2; }, {"DepthObstacleSettings.margin", "-0.2"}},
       {[](S& s) { s.max_relative_step = -0.03; },
        {"DepthObstacleSettings.max_relative_step", "-0.03"}}});
}
