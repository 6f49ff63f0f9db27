// A picture of walkgen's humanoid (models/walkgen_humanoid.xml) for the docs: MuJoCo loads the
// model standing in its keyframe "stand" and renders it offscreen (EGL, as MujocoRobot renders
// its cameras) from two free cameras, a 3/4 front view and a side view, side by side in one PNG
// (zlib's deflate; no other dependency).
//
//   render_model [--out FILE]          (default humanoid.png; docs/img/humanoid.png is its copy)
#include <mujoco/mujoco.h>
#include <zlib.h>

#include <cstdint>
#include <cstdio>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include "walkgen/mujoco/detail/egl_context.hpp"

namespace {

constexpr int kWidth = 600;  // one view [px]
constexpr int kHeight = 800;

/// An RGB image, rows top to bottom.
struct Image {
  int width = 0, height = 0;
  std::vector<unsigned char> rgb;
};

void append_u32(std::vector<unsigned char>& out, std::uint32_t v) {
  for (int shift = 24; shift >= 0; shift -= 8) out.push_back((v >> shift) & 0xff);
}

void append_chunk(std::vector<unsigned char>& out, const char* type,
                  const std::vector<unsigned char>& data) {
  append_u32(out, std::uint32_t(data.size()));
  const std::size_t start = out.size();
  out.insert(out.end(), type, type + 4);
  out.insert(out.end(), data.begin(), data.end());
  append_u32(out, std::uint32_t(crc32(0, out.data() + start, uInt(out.size() - start))));
}

/// Writes an 8-bit RGB PNG: no filter on any row, one deflated IDAT chunk.
bool write_png(const std::string& path, const Image& image) {
  std::vector<unsigned char> raw;
  const std::size_t row = std::size_t(image.width) * 3;
  for (int y = 0; y < image.height; ++y) {
    raw.push_back(0);  // filter type "none"
    raw.insert(raw.end(), image.rgb.begin() + std::ptrdiff_t(y * row),
               image.rgb.begin() + std::ptrdiff_t((y + 1) * row));
  }
  uLongf size = compressBound(uLong(raw.size()));
  std::vector<unsigned char> deflated(size);
  if (compress2(deflated.data(), &size, raw.data(), uLong(raw.size()), 9) != Z_OK) return false;
  deflated.resize(size);

  std::vector<unsigned char> png = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  std::vector<unsigned char> header;
  append_u32(header, std::uint32_t(image.width));
  append_u32(header, std::uint32_t(image.height));
  header.insert(header.end(), {8, 2, 0, 0, 0});  // 8 bits, RGB, deflate, no filter, no interlace
  append_chunk(png, "IHDR", header);
  append_chunk(png, "IDAT", deflated);
  append_chunk(png, "IEND", {});
  std::FILE* f = std::fopen(path.c_str(), "wb");
  if (f == nullptr) return false;
  const bool ok = std::fwrite(png.data(), 1, png.size(), f) == png.size();
  return std::fclose(f) == 0 && ok;
}

/// Renders one view from a free camera looking at `lookat` and pastes it at column x0 of
/// `out`. The background (nothing drawn, depth 1) becomes a light vertical gradient.
void render_view(const mjModel* m, mjData* d, mjvScene& scene, mjrContext& context,
                 const mjvOption& option, double azimuth, double elevation, Image& out, int x0) {
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
      unsigned char* p =
          &out.rgb[(std::size_t(y) * std::size_t(out.width) + std::size_t(x0 + x)) * 3];
      if (depth[s] >= 1.0f) {
        const double t = double(y) / kHeight;  // sky: light blue at the top to white
        p[0] = static_cast<unsigned char>(200 + 50 * t);
        p[1] = static_cast<unsigned char>(215 + 37 * t);
        p[2] = static_cast<unsigned char>(235 + 20 * t);
      } else {
        std::memcpy(p, &rgb[s * 3], 3);
      }
    }
  }
}

}  // namespace

int main(int argc, char** argv) {
  std::string out_path = "humanoid.png";
  for (int i = 1; i + 1 < argc; i += 2) {
    if (std::strcmp(argv[i], "--out") == 0) out_path = argv[i + 1];
  }
  const std::string xml = std::string(WALKGEN_SOURCE_DIR) + "/models/walkgen_humanoid.xml";
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
    Image image;
    image.width = 2 * kWidth;
    image.height = kHeight;
    image.rgb.assign(std::size_t(image.width) * kHeight * 3, 0);
    // The robot faces +x; a free camera at azimuth a looks along (cos a, sin a).
    render_view(m, data.get(), scene, context, option, 215.0, -15.0, image, 0);     // 3/4 front
    render_view(m, data.get(), scene, context, option, 90.0, -5.0, image, kWidth);  // right side
    if (write_png(out_path, image)) {
      std::printf("render_model: wrote %s (%d x %d px: 3/4 front view, right side view)\n",
                  out_path.c_str(), image.width, image.height);
    } else {
      std::fprintf(stderr, "render_model: cannot write %s\n", out_path.c_str());
      status = 1;
    }
  }
  mjr_freeContext(&context);
  mjv_freeScene(&scene);
  return status;
}
