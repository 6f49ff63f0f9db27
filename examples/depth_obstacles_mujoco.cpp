// Obstacles from stereo depth on the simulated robot (thesis §10.2's three chairs, eq. 2.79):
// walkgen's humanoid looks with its chest cameras (MuJoCo, 320 × 240, baseline 0.068 m) at three
// textured cylinders about 1, 2 and 3 m ahead (tests/opencv/scene_three_cylinders.xml). The depth
// pipeline of §3.1 (thesis defaults N 13, D 32, λ 1e4, σ 1) turns the pair into depth, compared
// here with MuJoCo's exact depth, and both depths into circular obstacles for the NMPC
// (walkgen::obstacles_from_depth; stereo depth where the WLS confidence is not 0).
//
//   depth_obstacles_mujoco [--out DIR]
//
//   --out DIR  output folder, created if missing (default: the working directory)
//
// Writes DIR/depth_mujoco.png (left image | exact depth | stereo depth | ground plane from above
// with the true cylinders in grey and the circles found from stereo depth in red, from exact
// depth in green); docs/img/depth_mujoco.png is its copy. Prints the depth error per cylinder and
// the obstacle centres. --help lists the options. Exits 0; 1 when rendering is unavailable, an
// obstacle is missed or the PNG cannot be written; 2 on a bad command line (one line on stderr).
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>
#include <walkgen/mujoco/mujoco_robot.hpp>
#include <walkgen/opencv/depth_obstacles.hpp>
#include <walkgen/opencv/stereo_depth.hpp>

#include "common/cli.hpp"

namespace {

struct Cylinder {
  double x, y, radius;
};
const Cylinder kCylinders[3] = {{1.07, -0.3, 0.15}, {2.07, 0.3, 0.2}, {3.07, -0.15, 0.2}};

cv::Mat colour_depth(const cv::Mat& depth, double max_depth) {
  cv::Mat scaled, colour;
  depth.convertTo(scaled, CV_8U, -255.0 / max_depth, 255.0);  // near: bright
  cv::applyColorMap(scaled, colour, cv::COLORMAP_JET);
  colour.setTo(cv::Scalar(0, 0, 0), (depth <= 0.0f) | (depth > max_depth));
  return colour;
}

}  // namespace

int main(int argc, char** argv) {
  std::string out = ".";
  CLI::App app{
      "Obstacles from stereo depth on the simulated robot's cameras (thesis §10.2, "
      "eq. 2.79), in MuJoCo",
      "depth_obstacles_mujoco"};
  walkgen_examples::cli_defaults(app);
  app.add_option("--out", out, "output folder for depth_mujoco.png (created if missing)")
      ->type_name("DIR");
  WALKGEN_CLI_PARSE(app, argc, argv);
  std::error_code ec;
  std::filesystem::create_directories(out, ec);  // a failure shows when the PNG is written

  walkgen::MujocoRobotSettings settings;
  settings.model_path = std::string(WALKGEN_SOURCE_DIR) + "/tests/opencv/scene_three_cylinders.xml";
  walkgen::MujocoRobot robot(settings);
  const walkgen::StereoImages& images = robot.render_cameras();
  if (images.status != walkgen::RenderStatus::ok) {
    std::fprintf(stderr, "depth_obstacles_mujoco: %s\n", images.message.c_str());
    return 1;
  }
  const walkgen::CameraImage& left = images.left;
  const walkgen::PinholeIntrinsics k =
      walkgen::pinhole_from_fovy(left.width, left.height, left.fovy);
  const double baseline =
      (images.right.pose_W_C.translation() - left.pose_W_C.translation()).norm();
  const cv::Mat left_rgb(left.height, left.width, CV_8UC3,
                         const_cast<std::uint8_t*>(left.rgb.data()));
  const cv::Mat right_rgb(left.height, left.width, CV_8UC3,
                          const_cast<std::uint8_t*>(images.right.rgb.data()));
  const cv::Mat exact(left.height, left.width, CV_32F, const_cast<float*>(left.depth.data()));

  walkgen::StereoDepthSettings s;
  s.rgb_input = true;
  // Depth only where block matching and the left-right check found something (the dense WLS
  // map also extrapolates into the textureless black sky).
  s.min_confidence = 1.0;
  walkgen::StereoDepth stereo(s, walkgen::ideal_disparity_to_depth(k, baseline));
  const walkgen::StereoDepthFrame& frame = stereo.compute(left_rgb, right_rgb);
  std::printf("camera at (%.3f, %.3f, %.3f) m, f = %.1f px, baseline %.3f m\n",
              left.pose_W_C.translation().x(), left.pose_W_C.translation().y(),
              left.pose_W_C.translation().z(), k.fx, baseline);

  // Obstacles from both depths.
  const walkgen::DepthObstacleSettings os;
  const auto from_exact = walkgen::obstacles_from_depth(exact, k, left.pose_W_C, os);
  const auto from_stereo = walkgen::obstacles_from_depth(frame.depth, k, left.pose_W_C, os);
  int missed = 0;
  for (const Cylinder& c : kCylinders) {
    for (int source = 0; source < 2; ++source) {
      const auto& found = source == 0 ? from_exact : from_stereo;
      double best = 1e9;
      const walkgen::CircleObstacle<double>* nearest = nullptr;
      for (const auto& o : found) {
        const double e = std::hypot(o.x - c.x, o.y - c.y);
        if (e < best) {
          best = e;
          nearest = &o;
        }
      }
      std::printf("cylinder (%.2f, %.2f) r %.2f from %s depth: ", c.x, c.y, c.radius,
                  source == 0 ? "exact " : "stereo");
      if (nearest != nullptr && best < 0.1) {
        std::printf("(%.3f, %.3f) r %.3f, centre error %.3f m\n", nearest->x, nearest->y,
                    nearest->radius, best);
      } else {
        std::printf("missed\n");
        ++missed;
      }
    }
  }
  std::printf("%zu obstacles from exact depth, %zu from stereo depth:", from_exact.size(),
              from_stereo.size());
  for (const auto& o : from_stereo) std::printf(" (%.2f, %.2f) r %.2f", o.x, o.y, o.radius);
  std::printf("\n");

  // The picture: left | exact depth | stereo depth | top view.
  cv::Mat bgr;
  cv::cvtColor(left_rgb, bgr, cv::COLOR_RGB2BGR);
  cv::Mat top(left.height, left.height, CV_8UC3, cv::Scalar(255, 255, 255));
  const double scale = left.height / 4.0;  // 4 m ahead, ±2 m sideways
  auto to_px = [&](double x, double y) {
    return cv::Point(static_cast<int>(top.cols / 2 - y * scale),
                     static_cast<int>(top.rows - 1 - x * scale));
  };
  for (int v = 0; v < frame.depth.rows; v += 2) {  // stereo points above the floor
    for (int u = 0; u < frame.depth.cols; u += 2) {
      const double z = frame.depth.at<float>(v, u);
      if (z <= 0.0 || z > os.max_depth) continue;
      const Eigen::Vector3d p =
          left.pose_W_C * Eigen::Vector3d(z, -(u - k.cx) * z / k.fx, -(v - k.cy) * z / k.fy);
      if (p.z() > os.floor_height)
        cv::circle(top, to_px(p.x(), p.y()), 0, cv::Scalar(200, 150, 100));
    }
  }
  for (const Cylinder& c : kCylinders) {
    cv::circle(top, to_px(c.x, c.y), static_cast<int>(c.radius * scale), cv::Scalar(128, 128, 128),
               2);
  }
  for (const auto& o : from_exact) {
    cv::circle(top, to_px(o.x, o.y), static_cast<int>(o.radius * scale), cv::Scalar(0, 160, 0), 1);
  }
  for (const auto& o : from_stereo) {
    cv::circle(top, to_px(o.x, o.y), static_cast<int>(o.radius * scale), cv::Scalar(0, 0, 255), 1);
  }
  cv::circle(top, to_px(left.pose_W_C.translation().x(), 0.0), 3, cv::Scalar(0, 0, 0), -1);
  std::vector<cv::Mat> panels = {bgr, colour_depth(exact, 4.0), colour_depth(frame.depth, 4.0),
                                 top};
  const char* titles[] = {"left camera", "exact depth (MuJoCo)", "stereo depth (BM + WLS)",
                          "from above: true, exact, stereo"};
  for (std::size_t i = 0; i < panels.size(); ++i) {
    cv::putText(panels[i], titles[i], cv::Point(4, 14), cv::FONT_HERSHEY_SIMPLEX, 0.4,
                cv::Scalar(255, 255, 255), 2);
    cv::putText(panels[i], titles[i], cv::Point(4, 14), cv::FONT_HERSHEY_SIMPLEX, 0.4,
                cv::Scalar(0, 0, 0), 1);
  }
  cv::Mat picture;
  cv::hconcat(panels, picture);
  const std::string path = out + "/depth_mujoco.png";
  if (!cv::imwrite(path, picture)) {
    std::fprintf(stderr, "depth_obstacles_mujoco: cannot write %s\n", path.c_str());
    return 1;
  }
  std::printf("wrote %s\n", path.c_str());
  return missed == 0 ? 0 : 1;
}
