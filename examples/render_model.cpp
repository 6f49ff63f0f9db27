// A picture of walkgen's humanoid (models/walkgen_humanoid.xml) for the docs: MuJoCo loads the
// model standing in its keyframe "stand" and renders it offscreen (EGL, as MujocoRobot renders
// its cameras) from two free cameras, a 3/4 front view and a side view (600 x 800 px each), side
// by side in one image written through OpenCV (cv::imwrite; built when walkgen::opencv is).
//
//   render_model [--out FILE]
//     --out FILE  the image; its extension picks the format (default humanoid.png;
//                 docs/img/humanoid.png is its copy)
// The command line is parsed by CLI11 (examples/common/cli.hpp): --help lists every option with
// its default and exits 0; an unknown option or a bad value exits 2 with one line on stderr.
// Exits 1 when the model cannot be loaded or rendered, or the image cannot be written.
#include <mujoco/mujoco.h>

#include <cstdio>
#include <memory>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <string>
#include <vector>

#include "common/cli.hpp"
#include "walkgen/core/data_dir.hpp"
#include "walkgen/mujoco/detail/egl_context.hpp"

namespace {

constexpr int kWidth = 600;  // one view [px]
constexpr int kHeight = 800;

/// Renders one view from a free camera looking at `lookat` and pastes it at column x0 of
/// `out` (8-bit BGR, OpenCV's order). The background (nothing drawn, depth 1) becomes a light
/// vertical gradient.
void render_view(const mjModel* m, mjData* d, mjvScene& scene, mjrContext& context,
                 const mjvOption& option, double azimuth, double elevation, cv::Mat& out, int x0) {
  mjvCamera camera;
  mjv_defaultFreeCamera(m, &camera);
  camera.lookat[0] = 0.0;
  camera.lookat[1] = 0.0;
  camera.lookat[2] = 0.4;
  camera.distance = 1.45;
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

}  // namespace

int main(int argc, char** argv) {
  std::string out_path = "humanoid.png";
  CLI::App app{
      "Renders walkgen's humanoid, modelled on Heicub (thesis §5), standing in MuJoCo: a "
      "3/4 front and a side view for the docs",
      "render_model"};
  walkgen_examples::cli_defaults(app);
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
  const std::string xml = walkgen::humanoid_mjcf_path();
  char error[1000] = "";
  std::unique_ptr<mjModel, void (*)(mjModel*)> model(
      mj_loadXML(xml.c_str(), nullptr, error, sizeof(error)), mj_deleteModel);
  if (model == nullptr) {
    std::fprintf(stderr, "render_model: cannot load %s: %s\n", xml.c_str(), error);
    return 1;
  }
  mjModel* m = model.get();
  std::unique_ptr<mjData, void (*)(mjData*)> data(mj_makeData(m), mj_deleteData);
  const int stand = mj_name2id(m, mjOBJ_KEY, "stand");
  if (stand < 0) {
    std::fprintf(stderr, "render_model: the model has no keyframe \"stand\"\n");
    return 1;
  }
  mj_resetDataKeyframe(m, data.get(), stand);
  mj_forward(m, data.get());

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
    render_view(m, data.get(), scene, context, option, 215.0, -15.0, image, 0);     // 3/4 front
    render_view(m, data.get(), scene, context, option, 90.0, -5.0, image, kWidth);  // right side
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
