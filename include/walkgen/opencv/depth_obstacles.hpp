#pragma once
/// @file
/// Obstacles from a depth image: the robot's depth (stereo, §3.1, or a simulator's) turned into
/// circles in the world frame that the NMPC's obstacle constraint accepts (eq. 2.79,
/// walkgen::CircleObstacle). The thesis left obstacle perception to its network; this closes the
/// loop between chapter 3 and eq. 2.79. OpenCV adapter: target walkgen::opencv.
///
/// Steps, each a setting of DepthObstacleSettings:
///   1. back-projection of every pixel with a depth in [min_depth, max_depth] through the pinhole
///      model (eq. 3.9 inverted): p_C = Z (1, −(u − c_x)/f_x, −(v − c_y)/f_y) in walkgen's camera
///      frame (x along the optical axis, y left, z up, as walkgen::CameraImage::pose_W_C), then
///      p_W = pose_W_C p_C;
///   2. the floor (z_W ≤ floor_height), what is above max_height and pixels on depth edges
///      (max_relative_step) are dropped;
///   3. the rest is binned on the ground plane in cells of cell_size and clustered by 8-connected
///      occupied cells, gaps up to cluster_gap closed;
///   4. each cluster of at least min_points points becomes a circle from its silhouette as seen
///      from the camera: radius r = half its width across the line of sight (robust quantiles),
///      centre r behind its nearest point on the line of sight through the middle of its width
///      (found from the median range of the points in the middle half of the width, robust to
///      depth noise). For a cylinder this is its axis and radius; a box gets the circle of its
///      front face's width (add margin for its corners).
///
/// Errors (convention 10): an empty or non-CV_32F depth image, or invalid settings, throw
/// walkgen::invalid_argument. Pixels without depth (0, NaN, ∞) are ignored.

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>
#include <string>
#include <vector>

#include "walkgen/core/exceptions.hpp"
#include "walkgen/core/obstacle.hpp"
#include "walkgen/opencv/stereo_depth.hpp"

namespace walkgen {

/// How obstacles are extracted from depth; lengths in metres.
struct DepthObstacleSettings {
  double min_depth = 0.2;     ///< [m] nearer depths are ignored (inside the robot, or noise)
  double max_depth = 4.0;     ///< [m] farther depths are ignored (stereo error grows with Z²)
  double floor_height = 0.1;  ///< [m] points at or below this world height are floor
  double max_height = 2.0;    ///< [m] points above are ignored (ceiling, overhangs)
  double cell_size = 0.05;    ///< [m] ground-plane grid for clustering
  /// [m] points this close on the ground plane (to within a cell) join one cluster; wider gaps
  /// split. Larger: noisy depth (far stereo) holds together, near obstacles merge.
  double cluster_gap = 0.1;
  int min_points = 30;   ///< clusters with fewer points are noise
  int pixel_stride = 1;  ///< back-project every stride-th pixel in u and v
  /// Pixels whose depth differs from a horizontal neighbour's by more than this fraction of
  /// their own are dropped: "flying pixels" that stereo smoothing leaves on the edges between a
  /// near and a far object, which would otherwise form phantom obstacles between them. 0 keeps
  /// every pixel.
  double max_relative_step = 0.03;
  /// [0, 0.5) fraction of points ignored at each side of a cluster's width (outliers).
  double width_quantile = 0.02;
  double min_radius = 0.05;  ///< [m] smaller circles are enlarged to this
  double margin = 0.0;       ///< [m] CircleObstacle::margin of every obstacle (foot, safety)
};

/// Checks the extraction's settings (depth_to_points() and obstacles_from_depth() call this).
/// @throws walkgen::invalid_argument naming the first bad field.
inline void validate(const DepthObstacleSettings& s) {
  check_positive("DepthObstacleSettings.min_depth", s.min_depth);
  check_argument(s.max_depth > s.min_depth, "DepthObstacleSettings.max_depth",
                 "a depth > min_depth", s.max_depth);
  check_argument(s.max_height > s.floor_height, "DepthObstacleSettings.max_height",
                 "a height > floor_height", s.max_height);
  check_positive("DepthObstacleSettings.cell_size", s.cell_size);
  check_non_negative("DepthObstacleSettings.cluster_gap", s.cluster_gap);
  check_argument(s.min_points >= 3, "DepthObstacleSettings.min_points", "at least 3", s.min_points);
  check_argument(s.pixel_stride >= 1, "DepthObstacleSettings.pixel_stride", "at least 1",
                 s.pixel_stride);
  check_argument(s.width_quantile >= 0.0 && s.width_quantile < 0.5,
                 "DepthObstacleSettings.width_quantile", "a fraction in [0, 0.5)",
                 s.width_quantile);
  check_non_negative("DepthObstacleSettings.min_radius", s.min_radius);
  check_non_negative("DepthObstacleSettings.margin", s.margin);
  check_non_negative("DepthObstacleSettings.max_relative_step", s.max_relative_step);
}

namespace detail {

/// The q-quantile of `values` (reordered).
inline double quantile(std::vector<double>& values, double q) {
  const std::size_t i =
      std::min(values.size() - 1, static_cast<std::size_t>(q * static_cast<double>(values.size())));
  std::nth_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(i), values.end());
  return values[i];
}

}  // namespace detail

/// Back-projects a depth image into world points above the floor (steps 1–2), appended to
/// `points_W` as (x, y, z).
/// @param depth CV_32F, Z [m] along the optical axis, row-major from the top-left pixel.
/// @throws walkgen::invalid_argument for an empty or non-CV_32F image or invalid settings.
inline void depth_to_points(const cv::Mat& depth, const PinholeIntrinsics& k,
                            const Eigen::Isometry3d& pose_W_C, const DepthObstacleSettings& s,
                            std::vector<Eigen::Vector3d>& points_W) {
  validate(s);
  check_argument(
      !depth.empty() && depth.type() == CV_32F, "walkgen::depth_to_points: depth",
      "a non-empty CV_32F image of depths [m]",
      depth.empty() ? std::string("an empty image") : "type " + std::to_string(depth.type()));
  check_positive("walkgen::depth_to_points: fx", k.fx);
  check_positive("walkgen::depth_to_points: fy", k.fy);
  for (int v = 0; v < depth.rows; v += s.pixel_stride) {
    const float* row = depth.ptr<float>(v);
    for (int u = 0; u < depth.cols; u += s.pixel_stride) {
      const double z = row[u];
      if (!(z >= s.min_depth && z <= s.max_depth)) continue;  // also NaN
      if (s.max_relative_step > 0.0) {
        const double step = s.max_relative_step * z;
        if ((u > 0 && !(std::abs(row[u - 1] - z) <= step)) ||
            (u + 1 < depth.cols && !(std::abs(row[u + 1] - z) <= step))) {
          continue;
        }
      }
      const Eigen::Vector3d p_C(z, -(u - k.cx) * z / k.fx, -(v - k.cy) * z / k.fy);
      const Eigen::Vector3d p_W = pose_W_C * p_C;
      if (p_W.z() <= s.floor_height || p_W.z() > s.max_height) continue;
      points_W.push_back(p_W);
    }
  }
}

/// Obstacles seen in a depth image, as circles in the world frame (steps 1–4), nearest first.
/// @param depth CV_32F, Z [m] along the optical axis (StereoDepthFrame::depth, or a simulator's).
/// @param k the depth image's intrinsics (for a stereo pair: the rectified left camera's).
/// @param pose_W_C the camera in the world: x along the optical axis, y left, z up.
/// @throws walkgen::invalid_argument for an empty or non-CV_32F image or invalid settings.
inline std::vector<CircleObstacle<double>> obstacles_from_depth(
    const cv::Mat& depth, const PinholeIntrinsics& k, const Eigen::Isometry3d& pose_W_C,
    const DepthObstacleSettings& s = {}) {
  std::vector<Eigen::Vector3d> points;
  depth_to_points(depth, k, pose_W_C, s, points);
  std::vector<CircleObstacle<double>> obstacles;
  if (points.size() < static_cast<std::size_t>(s.min_points)) return obstacles;

  // 3. Ground-plane grid and its 8-connected components.
  double x_min = points[0].x(), x_max = x_min, y_min = points[0].y(), y_max = y_min;
  for (const Eigen::Vector3d& p : points) {
    x_min = std::min(x_min, p.x());
    x_max = std::max(x_max, p.x());
    y_min = std::min(y_min, p.y());
    y_max = std::max(y_max, p.y());
  }
  const int cols = static_cast<int>((x_max - x_min) / s.cell_size) + 1;
  const int rows = static_cast<int>((y_max - y_min) / s.cell_size) + 1;
  cv::Mat occupied = cv::Mat::zeros(rows, cols, CV_8U);
  std::vector<cv::Point> cell(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    cell[i] = cv::Point(static_cast<int>((points[i].x() - x_min) / s.cell_size),
                        static_cast<int>((points[i].y() - y_min) / s.cell_size));
    occupied.at<std::uint8_t>(cell[i]) = 1;
  }
  const int grow = static_cast<int>(std::ceil(0.5 * s.cluster_gap / s.cell_size));
  if (grow > 0) {
    cv::dilate(occupied, occupied,
               cv::getStructuringElement(cv::MORPH_RECT, cv::Size(2 * grow + 1, 2 * grow + 1)));
  }
  cv::Mat labels;
  const int count = cv::connectedComponents(occupied, labels, 8, CV_32S);
  std::vector<std::vector<std::size_t>> members(static_cast<std::size_t>(count));
  for (std::size_t i = 0; i < points.size(); ++i) {
    members[static_cast<std::size_t>(labels.at<int>(cell[i]))].push_back(i);
  }

  // 4. A circle from each cluster's silhouette.
  const Eigen::Vector2d camera = pose_W_C.translation().head<2>();
  std::vector<double> across, along;
  for (int c = 1; c < count; ++c) {
    const std::vector<std::size_t>& m = members[static_cast<std::size_t>(c)];
    if (m.size() < static_cast<std::size_t>(s.min_points)) continue;
    Eigen::Vector2d mean = Eigen::Vector2d::Zero();
    for (std::size_t i : m) mean += points[i].head<2>();
    mean /= static_cast<double>(m.size());
    Eigen::Vector2d direction = mean - camera;
    if (direction.norm() < 1e-9) continue;
    Eigen::Vector2d centre = mean;
    double radius = 0.0;
    for (int pass = 0; pass < 2; ++pass) {  // the second pass looks through the first's centre
      direction.normalize();
      const Eigen::Vector2d normal(-direction.y(), direction.x());
      across.clear();
      for (std::size_t i : m) across.push_back(normal.dot(points[i].head<2>() - camera));
      const double lo = detail::quantile(across, s.width_quantile);
      const double hi = detail::quantile(across, 1.0 - s.width_quantile);
      // Points spread about evenly across a width: the quantiles cut 2 q of it.
      radius = std::max(0.5 * (hi - lo) / (1.0 - 2.0 * s.width_quantile), s.min_radius);
      const double middle = 0.5 * (lo + hi);
      // The surface facing the camera: the median range of the points in the middle half of
      // the width. On a circle of radius r these lie (1 − cos(asin(1/4))) r ≈ 0.032 r behind
      // its nearest point (median |offset| r/4), so the centre is 0.968 r behind that median.
      along.clear();
      for (std::size_t i : m) {
        const Eigen::Vector2d p = points[i].head<2>() - camera;
        if (std::abs(normal.dot(p) - middle) <= 0.25 * (hi - lo)) along.push_back(direction.dot(p));
      }
      if (along.empty()) break;
      const double surface = detail::quantile(along, 0.5);
      centre = camera + direction * (surface + 0.968 * radius) + normal * middle;
      direction = centre - camera;
    }
    CircleObstacle<double> o;
    o.x = centre.x();
    o.y = centre.y();
    o.radius = radius;
    o.margin = s.margin;
    obstacles.push_back(o);
  }
  std::sort(obstacles.begin(), obstacles.end(),
            [&](const CircleObstacle<double>& a, const CircleObstacle<double>& b) {
              return (Eigen::Vector2d(a.x, a.y) - camera).squaredNorm() <
                     (Eigen::Vector2d(b.x, b.y) - camera).squaredNorm();
            });
  return obstacles;
}

}  // namespace walkgen
