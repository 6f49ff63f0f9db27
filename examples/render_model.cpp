// A picture of a robot for the docs: MuJoCo loads the model of a robot description file
// (docs/robots.md), standing in its stand keyframe or, without one, in its stand pose with the
// soles on the floor, and renders it offscreen (EGL, as MujocoRobot renders its cameras) from two
// free cameras, a 3/4 front view and a side view (600 x 800 px each), side by side in one image
// written through OpenCV (cv::imwrite; built when walkgen::opencv is).
//
//   render_model [--robot NAME|PATH] [--out FILE]
//     --robot     walkgen_humanoid (default) or unitree_g1, or a robot.yaml
//     --out FILE  the image; its extension picks the format (default humanoid.png;
//                 docs/img/humanoid.png and docs/img/unitree_g1.png are its copies)
// The command line is parsed by CLI11 (examples/common/cli.hpp): --help lists every option with
// its default and exits 0; an unknown option or a bad value exits 2 with one line on stderr.
// Exits 1 when the model cannot be loaded or rendered, or the image cannot be written.
#include <mujoco/mujoco.h>

#include <Eigen/Core>
#include <algorithm>
#include <cstdio>
#include <memory>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <string>
#include <vector>

#include "common/cli.hpp"
#include "walkgen/mujoco/detail/egl_context.hpp"
#include "walkgen/mujoco/robot_model.hpp"
#include "walkgen/yaml/robot_description_loader.hpp"

namespace {

constexpr int kWidth = 600;  // one view [px]
constexpr int kHeight = 800;

/// Renders one view from a free camera looking at `lookat` and pastes it at column x0 of
/// `out` (8-bit BGR, OpenCV's order). The background (nothing drawn, depth 1) becomes a light
/// vertical gradient.
/// The camera looks at 0.9 × the CoM's height from 3.2 × that height (0.4 m and 1.45 m for
/// walkgen's humanoid), so that any robot fills the view alike.
void render_view(const mjModel* m, mjData* d, mjvScene& scene, mjrContext& context,
                 const mjvOption& option, const Eigen::Vector3d& com, double azimuth,
                 double elevation, cv::Mat& out, int x0) {
  mjvCamera camera;
  mjv_defaultFreeCamera(m, &camera);
  camera.lookat[0] = com.x();
  camera.lookat[1] = com.y();
  camera.lookat[2] = 0.9 * com.z();
  camera.distance = 3.2 * com.z();
  camera.azimuth = azimuth;
  camera.elevation = elevation;
  mjv_updateScene(m, d, &option, nullptr, &camera, mjCAT_ALL, &scene);
  const mjrRect viewport{0, 0, kWidth, kHeight};
  mjr_render(viewport, &scene, &context);
  std::vector<unsigned char> rgb(std::size_t(kWidth) * kHeight * 3);
  std::vector<float> depth(std::size_t(kWidth) * kHeight);
  mjr_readPixels(rgb.data(), depth.data(), viewport, &context);
  for (int y = 0; y < kHeight; ++y) {  // OpenGL's rows run bottom to top
    const int source_row = kHeight - 1 - y;
    for (int x = 0; x < kWidth; ++x) {
      const std::size_t s = std::size_t(source_row) * kWidth + std::size_t(x);
      cv::Vec3b& p = out.at<cv::Vec3b>(y, x0 + x);
      if (depth[s] >= 1.0f) {
        const double t = double(y) / kHeight;  // sky: light blue at the top to white
        p = cv::Vec3b(static_cast<unsigned char>(235 + 20 * t),
                      static_cast<unsigned char>(215 + 37 * t),
                      static_cast<unsigned char>(200 + 50 * t));
      } else {
        p = cv::Vec3b(rgb[s * 3 + 2], rgb[s * 3 + 1], rgb[s * 3]);
      }
    }
  }
}

/// Puts `robot` in its stand keyframe, or in its stand pose with the base upright above the
/// origin and the lower sole on the floor. Returns the whole-body CoM.
Eigen::Vector3d stand(const walkgen::RobotDescription& robot, const mjModel* m, mjData* d) {
  const int key =
      robot.stand_keyframe.empty() ? -1 : mj_name2id(m, mjOBJ_KEY, robot.stand_keyframe.c_str());
  const int base = mj_name2id(m, mjOBJ_BODY, robot.base_body.c_str());
  if (key >= 0) {
    mj_resetDataKeyframe(m, d, key);
  } else {
    const walkgen::KinematicTree<double> tree = walkgen::robot_kinematic_tree_from_mjcf(robot);
    const Eigen::VectorXd q = walkgen::stand_configuration(tree, robot);
    auto ws = tree.make_workspace();
    tree.forward_kinematics(Eigen::Vector3d::Zero(), Eigen::Matrix3d::Identity(), q, ws);
    const double lowest = std::min(ws.position_W(tree.link_index(robot.sole_frames[0])).z(),
                                   ws.position_W(tree.link_index(robot.sole_frames[1])).z());
    mj_resetData(m, d);
    const int free = m->jnt_qposadr[m->body_jntadr[base]];
    const double base_pose[7] = {0.0, 0.0, -lowest, 1.0, 0.0, 0.0, 0.0};  // upright
    std::copy_n(base_pose, 7, d->qpos + free);
    for (int i = 0; i < tree.num_joints(); ++i) {
      const std::string& name = tree.joint_names()[std::size_t(i)];
      d->qpos[m->jnt_qposadr[mj_name2id(m, mjOBJ_JOINT, name.c_str())]] = q[i];
    }
  }
  mj_forward(m, d);
  return Eigen::Vector3d::Map(d->subtree_com + 3 * base);
}

}  // namespace

int main(int argc, char** argv) {
  std::string out_path = "humanoid.png";
  std::string robot_name = "walkgen_humanoid";
  CLI::App app{
      "Renders a robot standing in MuJoCo (walkgen's humanoid, modelled on Heicub, thesis §5, "
      "or any robot description file): a 3/4 front and a side view for the docs",
      "render_model"};
  walkgen_examples::cli_defaults(app);
  app.add_option("--robot", robot_name,
                 "a robot: walkgen_humanoid or unitree_g1 (models/NAME/robot.yaml), or the path "
                 "of a robot.yaml (docs/robots.md)");
  app.add_option("--out", out_path,
                 "the image (two views of 600 x 800 px side by side); its extension picks the "
                 "format, e.g. .png")
      ->check(CLI::Validator(
          [](std::string& path) -> std::string {
            if (cv::haveImageWriter(path)) return {};
            return "OpenCV cannot write an image named '" + path + "' (expected e.g. FILE.png)";
          },
          "FILE"));
  WALKGEN_CLI_PARSE(app, argc, argv);
  walkgen::RobotDescription robot;
  walkgen::detail::LoadedModel model;
  try {
    robot = walkgen::find_robot_description(robot_name);
    model = walkgen::detail::load_mjcf(robot.mjcf_path, "render_model");
    walkgen::check_robot_against_model(robot, *model.m);
  } catch (const walkgen::invalid_argument& e) {
    std::fprintf(stderr, "render_model: %s\n", e.what());
    return 1;
  }
  mjModel* m = model.m.get();
  std::unique_ptr<mjData, void (*)(mjData*)> data(mj_makeData(m), mj_deleteData);
  Eigen::Vector3d com;
  try {
    com = stand(robot, m, data.get());
  } catch (const walkgen::invalid_argument& e) {
    std::fprintf(stderr, "render_model: %s\n", e.what());
    return 1;
  }

  walkgen::detail::EglContext gl;
  if (!gl.make_current()) {
    std::fprintf(stderr, "render_model: no OpenGL context: %s\n", gl.error().c_str());
    return 1;
  }
  m->vis.global.offwidth = kWidth;
  m->vis.global.offheight = kHeight;
  m->vis.quality.shadowsize = 4096;
  m->vis.headlight.ambient[0] = m->vis.headlight.ambient[1] = m->vis.headlight.ambient[2] = 0.25f;
  m->vis.headlight.diffuse[0] = m->vis.headlight.diffuse[1] = m->vis.headlight.diffuse[2] = 0.4f;
  mjvScene scene;
  mjv_defaultScene(&scene);
  mjv_makeScene(m, &scene, 2000);
  mjvOption option;
  mjv_defaultOption(&option);
  for (int g = 0; g < mjNGROUP; ++g) option.sitegroup[g] = 0;  // no sensor or camera sites
  mjrContext context;
  mjr_defaultContext(&context);
  mjr_makeContext(m, &context, mjFONTSCALE_100);
  mjr_setBuffer(mjFB_OFFSCREEN, &context);
  int status = 0;
  if (context.currentBuffer != mjFB_OFFSCREEN) {
    std::fprintf(stderr, "render_model: MuJoCo has no offscreen framebuffer\n");
    status = 1;
  } else {
    cv::Mat image(kHeight, 2 * kWidth, CV_8UC3, cv::Scalar(0, 0, 0));
    // The robot faces +x; a free camera at azimuth a looks along (cos a, sin a).
    render_view(m, data.get(), scene, context, option, com, 215.0, -15.0, image, 0);  // 3/4 front
    render_view(m, data.get(), scene, context, option, com, 90.0, -5.0, image, kWidth);  // side
    bool written = false;
    try {
      written = cv::imwrite(out_path, image);
    } catch (const cv::Exception&) {  // e.g. the folder does not exist
    }
    if (written) {
      std::printf("render_model: wrote %s (%d x %d px: 3/4 front view, right side view)\n",
                  out_path.c_str(), image.cols, image.rows);
    } else {
      std::fprintf(stderr, "render_model: cannot write %s\n", out_path.c_str());
      status = 1;
    }
  }
  mjr_freeContext(&context);
  mjv_freeScene(&scene);
  return status;
}
