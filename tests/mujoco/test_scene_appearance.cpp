// walkgen::SceneAppearance and WorldAppearance (issue 27): the rooms' look as settings. The
// defaults change nothing; bad settings are named; the same seed draws the same look within the
// training ranges, and every held-out shift lies outside them; and what the chest camera sees
// follows: dim light darkens the image, a blue target is blue in it, pixel noise has its
// standard deviation, the camera pair moves as one.
#include "walkgen/mujoco/scene_appearance.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <memory>
#include <set>
#include <string>

#include "support/enum_strings.hpp"
#include "support/expect_error.hpp"
#include "support/files.hpp"
#include "walkgen/mujoco/navigation_scene.hpp"

namespace {

using walkgen::AppearanceRanges;
using walkgen::FloorTexture;
using walkgen::MujocoRobot;
using walkgen::MujocoRobotSettings;
using walkgen::NavigationTask;
using walkgen::SceneAppearance;
using walkgen::SceneShape;
using walkgen::SceneShift;
using walkgen::WorldAppearance;

/// The hue [deg] wrapped into [min, min + 360), to compare with a hue range.
double hue_from(double hue, double min) { return min + std::fmod(hue - min + 720.0, 360.0); }

/// The angle [deg] between a light's direction and straight down.
double tilt_deg(const Eigen::Vector3d& direction) {
  return std::acos(-direction.normalized().z()) * 180.0 / walkgen::kPi;
}

/// The left chest camera's image in `scene` with its look.
walkgen::CameraImage render_left(const walkgen::NavigationScene& scene) {
  MujocoRobotSettings settings;
  settings.objects = scene.objects();
  settings.appearance = scene.appearance.world;
  MujocoRobot robot(settings);
  EXPECT_EQ(robot.step(0.02), walkgen::RobotStatus::ok);
  const walkgen::StereoImages& images = robot.render_cameras();
  EXPECT_EQ(images.status, walkgen::RenderStatus::ok) << images.message;
  return images.left;
}

double mean_of(const std::vector<std::uint8_t>& v) {
  double sum = 0.0;
  for (std::uint8_t x : v) sum += x;
  return sum / double(v.size());
}

TEST(SceneAppearance, DefaultsKeepTheRoomsAndTheModelAsTheyWere) {
  const auto scene = walkgen::make_navigation_scene(NavigationTask::distractor, 4);
  std::set<std::string> seen;
  for (const walkgen::SceneObject& o : scene.objects()) {
    seen.insert(o.name);
    if (o.name == "target") {  // the red-orange cylinder of every room so far
      EXPECT_EQ(o.shape, SceneShape::cylinder);
      EXPECT_EQ(o.size, Eigen::Vector3d(0.06, 0.06, 1.0));
      EXPECT_EQ(o.rgb, Eigen::Vector3d(0.9, 0.12, 0.04));
      EXPECT_EQ(o.position, Eigen::Vector3d(scene.target.x(), scene.target.y(), 0.0));
    } else if (o.name == "distractor") {
      EXPECT_EQ(o.rgb, Eigen::Vector3d(0.95, 0.35, 0.05));
      EXPECT_EQ(o.size, Eigen::Vector3d(0.15, 0.15, 0.3));
    } else if (o.name.rfind("wall_", 0) == 0) {
      EXPECT_EQ(o.rgb, Eigen::Vector3d(0.75, 0.72, 0.62));
    }
  }
  EXPECT_EQ(seen.count("target") + seen.count("distractor") + seen.count("wall_3"), 3u);

  // The model with the default appearance is the model of the file: lights, headlight,
  // textures, materials, the floor's material and the cameras' poses.
  char error[1000] = "";
  std::unique_ptr<mjModel, void (*)(mjModel*)> file(
      mj_loadXML(walkgen::humanoid_mjcf_path().c_str(), nullptr, error, sizeof(error)),
      mj_deleteModel);
  ASSERT_NE(file, nullptr) << error;
  MujocoRobotSettings settings;
  settings.objects = scene.objects();
  MujocoRobot robot(settings);
  const mjModel* m = robot.model();
  ASSERT_EQ(m->nlight, file->nlight);
  for (int i = 0; i < 3 * m->nlight; ++i) {
    EXPECT_EQ(m->light_diffuse[i], file->light_diffuse[i]);
    EXPECT_EQ(m->light_specular[i], file->light_specular[i]);
    EXPECT_EQ(m->light_ambient[i], file->light_ambient[i]);
    EXPECT_EQ(m->light_dir[i], file->light_dir[i]);
    EXPECT_EQ(m->light_pos[i], file->light_pos[i]);
  }
  for (int i = 0; i < 3; ++i) {
    EXPECT_EQ(m->vis.headlight.diffuse[i], file->vis.headlight.diffuse[i]);
    EXPECT_EQ(m->vis.headlight.ambient[i], file->vis.headlight.ambient[i]);
  }
  int textured = 0;
  for (const auto& o : settings.objects) textured += o.textured;
  EXPECT_EQ(m->ntex, file->ntex + textured);  // no floor texture added
  EXPECT_EQ(m->nmat, file->nmat + textured);
  const int floor = mj_name2id(m, mjOBJ_GEOM, "floor");
  EXPECT_EQ(m->geom_matid[floor], mj_name2id(m, mjOBJ_MATERIAL, "floor"));
  ASSERT_EQ(m->ncam, file->ncam);
  for (int i = 0; i < 3 * m->ncam; ++i) EXPECT_EQ(m->cam_pos[i], file->cam_pos[i]);
  for (int i = 0; i < 4 * m->ncam; ++i) EXPECT_EQ(m->cam_quat[i], file->cam_quat[i]);

  // A noise seed without noise changes no pixel.
  auto seeded = scene;
  seeded.appearance.world.noise_seed = 12345;
  const walkgen::CameraImage a = render_left(scene), b = render_left(seeded);
  EXPECT_EQ(a.rgb, b.rgb);
}

TEST(SceneAppearance, BadSettingsAreNamedWithTheirField) {
  walkgen_test::expect_rejected<SceneAppearance>(
      SceneAppearance(),
      {{[](SceneAppearance& a) { a.world.light_intensity = -0.5; },
        {"SceneAppearance.world.light_intensity", "[0, 10]", "-0.5"}},
       {[](SceneAppearance& a) { a.world.ambient_intensity = std::nan(""); },
        {"SceneAppearance.world.ambient_intensity", "nan"}},
       {[](SceneAppearance& a) { a.world.light_direction = Eigen::Vector3d::Zero(); },
        {"SceneAppearance.world.light_direction", "non-zero"}},
       {[](SceneAppearance& a) { a.world.floor_rgb2.y() = 1.5; },
        {"SceneAppearance.world.floor_rgb2", "[0, 1]", "1.5"}},
       {[](SceneAppearance& a) { a.world.camera_offset.x() = 0.2; },
        {"SceneAppearance.world.camera_offset", "0.1 m"}},
       {[](SceneAppearance& a) { a.world.camera_rotation.z() = -1.0; },
        {"SceneAppearance.world.camera_rotation", "0.5 rad"}},
       {[](SceneAppearance& a) { a.world.pixel_noise = -1.0; },
        {"SceneAppearance.world.pixel_noise", "-1"}},
       {[](SceneAppearance& a) { a.target_rgb.z() = -0.1; },
        {"SceneAppearance.target_rgb", "[0, 1]"}},
       {[](SceneAppearance& a) { a.target_radius = 0.0; },
        {"SceneAppearance.target_radius", "(0, 0.5] m", "0"}},
       {[](SceneAppearance& a) { a.target_height = 4.0; },
        {"SceneAppearance.target_height", "(0, 3] m", "4"}},
       {[](SceneAppearance& a) {
          a.target_shape = SceneShape::sphere;
          a.target_radius = 0.4;
          a.target_height = 0.5;
        },
        {"SceneAppearance.target_height", "diameter"}},
       {[](SceneAppearance& a) { a.wall_rgb.x() = 2.0; }, {"SceneAppearance.wall_rgb"}},
       {[](SceneAppearance& a) { a.distractor_rgb.x() = 2.0; },
        {"SceneAppearance.distractor_rgb"}}});
  walkgen_test::expect_rejected<MujocoRobotSettings>(
      MujocoRobotSettings(), {{[](MujocoRobotSettings& s) { s.appearance.light_intensity = 11.0; },
                               {"MujocoRobotSettings.appearance.light_intensity", "11"}}});
  walkgen_test::expect_rejected<AppearanceRanges>(
      AppearanceRanges(), {{[](AppearanceRanges& r) {
                              r.light_intensity = {1.5, 0.5};
                            },
                            {"AppearanceRanges.light_intensity", "min <= max"}},
                           {[](AppearanceRanges& r) { r.light_tilt.max = 100.0; },
                            {"AppearanceRanges.light_tilt", "90 deg"}},
                           {[](AppearanceRanges& r) { r.target_shapes.clear(); },
                            {"AppearanceRanges.target_shapes", "none"}},
                           {[](AppearanceRanges& r) { r.floor_textures.clear(); },
                            {"AppearanceRanges.floor_textures", "none"}},
                           {[](AppearanceRanges& r) { r.wall_rgb_min.x() = 0.95; },
                            {"AppearanceRanges.wall_rgb_min, wall_rgb_max", "min <= max"}},
                           {[](AppearanceRanges& r) { r.camera_offset = -0.01; },
                            {"AppearanceRanges.camera_offset", "[0, 0.1] m"}}});
  walkgen_test::expect_invalid_argument(
      [] { (void)walkgen::scene_shift_from_string("fog"); },
      {"scene_shift_from_string", "'fog'",
       "none, dim, side_light, blue_target, small_target, new_floor"});

  // What the model must have: a floor to retexture, a directional light to turn.
  std::string xml = walkgen_test::read_bytes(walkgen::humanoid_mjcf_path());
  for (const char* element : {"<geom name=\"floor\"", "<light name=\"sun\""}) {
    const std::size_t at = xml.find(element);
    ASSERT_NE(at, std::string::npos) << element;
    xml.erase(at, xml.find('\n', at) - at);
  }
  const std::string path =
      (walkgen_test::fresh_folder("scene_appearance") / "no_floor_no_sun.xml").string();
  std::ofstream(path) << xml;
  MujocoRobotSettings bare;
  bare.model_path = path;
  bare.appearance.floor_texture = FloorTexture::checker;
  walkgen_test::expect_invalid_argument(
      [&] { MujocoRobot robot(bare); },
      {"MujocoRobotSettings.appearance.floor_texture", "plane geom", "no_floor_no_sun.xml"});
  bare.appearance.floor_texture = FloorTexture::model;
  bare.appearance.light_direction = Eigen::Vector3d(1.0, 0.0, -1.0);
  walkgen_test::expect_invalid_argument([&] { MujocoRobot robot(bare); },
                                        {"MujocoRobotSettings.appearance.light_direction",
                                         "directional light", "no_floor_no_sun.xml"});
}

TEST(SceneAppearance, TheSameSeedDrawsTheSameLookWithinTheTrainingRanges) {
  const AppearanceRanges r;
  std::set<std::string> looks;
  std::set<SceneShape> shapes;
  std::set<FloorTexture> floors;
  for (std::uint32_t seed = 0; seed < 300; ++seed) {
    const SceneAppearance a = walkgen::random_scene_appearance(seed, r);
    const std::string row = walkgen::appearance_csv_row(a);
    EXPECT_EQ(row, walkgen::appearance_csv_row(walkgen::random_scene_appearance(seed, r)));
    EXPECT_TRUE(looks.insert(row).second) << "seed " << seed << " repeats a look";
    EXPECT_NO_THROW(walkgen::validate(a));
    const WorldAppearance& w = a.world;
    EXPECT_TRUE(r.light_intensity.contains(w.light_intensity)) << w.light_intensity;
    EXPECT_TRUE(r.ambient_intensity.contains(w.ambient_intensity));
    ASSERT_TRUE(w.light_direction.has_value());
    EXPECT_LE(tilt_deg(*w.light_direction), r.light_tilt.max + 1e-9);
    const Eigen::Vector3d hsv = walkgen::hsv_from_rgb(a.target_rgb);
    EXPECT_TRUE(r.target_hue.contains(hue_from(hsv.x(), r.target_hue.min))) << hsv.x();
    EXPECT_NEAR(hsv.y(), std::clamp(hsv.y(), r.target_saturation.min, r.target_saturation.max),
                1e-12);
    EXPECT_NEAR(hsv.z(), std::clamp(hsv.z(), r.target_value.min, r.target_value.max), 1e-12);
    EXPECT_TRUE(r.target_radius.contains(a.target_radius));
    EXPECT_TRUE(r.target_height.contains(a.target_height));
    shapes.insert(a.target_shape);
    floors.insert(w.floor_texture);
    for (int i = 0; i < 3; ++i) {
      EXPECT_TRUE(r.floor_channel.contains(w.floor_rgb1[i]));
      EXPECT_GE(w.floor_rgb2[i], w.floor_rgb1[i]);
      EXPECT_GE(a.wall_rgb[i], r.wall_rgb_min[i]);
      EXPECT_LE(a.wall_rgb[i], r.wall_rgb_max[i]);
      EXPECT_LE(std::abs(w.camera_offset[i]), r.camera_offset);
      EXPECT_LE(std::abs(w.camera_rotation[i]), r.camera_rotation);
    }
    EXPECT_TRUE(r.pixel_noise.contains(w.pixel_noise));
    // The distractor stays of similar colour: its hue 15° further.
    const double distractor_hue = walkgen::hsv_from_rgb(a.distractor_rgb).x();
    EXPECT_NEAR(std::remainder(distractor_hue - hsv.x(), 360.0), 15.0, 1e-6);
  }
  EXPECT_EQ(shapes, (std::set<SceneShape>{SceneShape::cylinder, SceneShape::box}));
  EXPECT_EQ(floors.size(), r.floor_textures.size());
  // Colour conversions: the primaries and the default target (hue 5.6°).
  EXPECT_TRUE(walkgen::rgb_from_hsv(240.0, 1.0, 1.0).isApprox(Eigen::Vector3d(0, 0, 1)));
  EXPECT_TRUE(walkgen::rgb_from_hsv(-240.0, 1.0, 0.5).isApprox(Eigen::Vector3d(0, 0.5, 0)));
  const Eigen::Vector3d target = SceneAppearance().target_rgb;
  const Eigen::Vector3d hsv = walkgen::hsv_from_rgb(target);
  EXPECT_NEAR(hsv.x(), 60.0 * 0.08 / 0.86, 1e-9);
  EXPECT_TRUE(walkgen::rgb_from_hsv(hsv.x(), hsv.y(), hsv.z()).isApprox(target, 1e-12));
}

TEST(SceneAppearance, EveryHeldOutShiftLiesOutsideTheTrainingRanges) {
  walkgen_test::expect_enum_strings(std::array<SceneShift, 6>{
      SceneShift::none, SceneShift::dim, SceneShift::side_light, SceneShift::blue_target,
      SceneShift::small_target, SceneShift::new_floor});
  walkgen_test::expect_enum_strings(std::array<FloorTexture, 5>{
      FloorTexture::model, FloorTexture::checker, FloorTexture::gradient, FloorTexture::speckle,
      FloorTexture::tiles});
  for (SceneShift s : walkgen::all_scene_shifts()) {
    EXPECT_EQ(walkgen::scene_shift_from_string(to_string(s)), s);
  }
  const AppearanceRanges r;
  const SceneAppearance base;
  auto shifted = [&](SceneShift s) { return walkgen::apply_scene_shift(base, s); };
  EXPECT_EQ(walkgen::appearance_csv_row(shifted(SceneShift::none)),
            walkgen::appearance_csv_row(base));

  const SceneAppearance dim = shifted(SceneShift::dim);
  EXPECT_EQ(dim.world.light_intensity, 0.25);
  EXPECT_LT(dim.world.light_intensity, r.light_intensity.min);
  EXPECT_LT(dim.world.ambient_intensity, r.ambient_intensity.min);

  const SceneAppearance side = shifted(SceneShift::side_light);
  ASSERT_TRUE(side.world.light_direction.has_value());
  const double tilt = tilt_deg(*side.world.light_direction);
  std::printf("side light: %.1f deg from straight down (training: up to %.0f)\n", tilt,
              r.light_tilt.max);
  EXPECT_GT(tilt, r.light_tilt.max + 20.0);
  EXPECT_LT(tilt, 90.0);  // still from above

  const SceneAppearance blue = shifted(SceneShift::blue_target);
  const Eigen::Vector3d hsv = walkgen::hsv_from_rgb(blue.target_rgb);
  std::printf("blue target: rgb (%.2f %.2f %.2f), hue %.0f deg (training: %.0f to %.0f)\n",
              blue.target_rgb.x(), blue.target_rgb.y(), blue.target_rgb.z(), hsv.x(),
              r.target_hue.min, r.target_hue.max);
  EXPECT_FALSE(r.target_hue.contains(hue_from(hsv.x(), r.target_hue.min)));
  EXPECT_GT(hue_from(hsv.x(), r.target_hue.min) - r.target_hue.max, 60.0);  // far from green
  EXPECT_GT(blue.target_rgb.z(), 2.0 * blue.target_rgb.y());
  EXPECT_GT(walkgen::hsv_from_rgb(blue.distractor_rgb).x(), 200.0);  // similar colour: blue too

  const SceneAppearance small = shifted(SceneShift::small_target);
  EXPECT_EQ(small.target_height, 0.6);
  EXPECT_LT(small.target_height, r.target_height.min);

  const SceneAppearance floor = shifted(SceneShift::new_floor);
  EXPECT_EQ(floor.world.floor_texture, FloorTexture::tiles);
  for (FloorTexture t : r.floor_textures) EXPECT_NE(t, floor.world.floor_texture);
  EXPECT_GT(floor.world.floor_rgb1.x(), r.floor_channel.max);

  // A shift on a drawn look replaces only its own fields.
  const SceneAppearance drawn = walkgen::random_scene_appearance(9);
  const SceneAppearance drawn_dim = walkgen::apply_scene_shift(drawn, SceneShift::dim);
  EXPECT_EQ(drawn_dim.world.light_intensity, 0.25);
  EXPECT_EQ(drawn_dim.target_rgb, drawn.target_rgb);
  EXPECT_EQ(drawn_dim.world.floor_texture, drawn.world.floor_texture);
  for (SceneShift s : walkgen::all_scene_shifts()) {
    EXPECT_NO_THROW(walkgen::validate(walkgen::apply_scene_shift(drawn, s))) << to_string(s);
  }
}

TEST(SceneAppearance, DimLightDarkensTheChestCameraImage) {
  auto scene = walkgen::make_navigation_scene(NavigationTask::straight, 1);
  const double bright = mean_of(render_left(scene).rgb);
  scene.appearance = walkgen::apply_scene_shift(scene.appearance, SceneShift::dim);
  const double dim = mean_of(render_left(scene).rgb);
  std::printf("mean brightness: default %.1f, dim %.1f (ratio %.2f)\n", bright, dim, dim / bright);
  EXPECT_GT(bright, 40.0);
  EXPECT_LT(dim, 0.45 * bright);  // the light at a quarter: about a quarter of the brightness
  EXPECT_GT(dim, 0.1 * bright);
}

TEST(SceneAppearance, ABlueTargetIsBlueInTheChestCameraImage) {
  auto scene = walkgen::make_navigation_scene(NavigationTask::straight, 2);
  const walkgen::CameraImage red = render_left(scene);
  scene.appearance = walkgen::apply_scene_shift(scene.appearance, SceneShift::blue_target);
  const walkgen::CameraImage blue = render_left(scene);
  // The target's pixels: those the colour changed.
  int target = 0, red_before = 0, blue_now = 0;
  for (std::size_t p = 0; p + 2 < red.rgb.size(); p += 3) {
    int change = 0;
    for (int c = 0; c < 3; ++c) change += std::abs(int(red.rgb[p + c]) - int(blue.rgb[p + c]));
    if (change < 120) continue;  // not the floor's dim reflection of it
    ++target;
    red_before += red.rgb[p] > red.rgb[p + 2] + 30 && red.rgb[p] > red.rgb[p + 1] + 30;
    blue_now += blue.rgb[p + 2] > blue.rgb[p] + 30 && blue.rgb[p + 2] > blue.rgb[p + 1] + 30;
  }
  std::printf("target pixels %d: red-dominant before %d, blue-dominant now %d\n", target,
              red_before, blue_now);
  EXPECT_GT(target, 300);  // 1.5-2.5 m ahead, 0.12 m wide and taller than the view
  EXPECT_GT(red_before, 0.9 * target);
  EXPECT_GT(blue_now, 0.9 * target);
}

TEST(SceneAppearance, PixelNoiseHasItsStandardDeviationAndItsSeed) {
  auto scene = walkgen::make_navigation_scene(NavigationTask::obstacle, 3);
  const walkgen::CameraImage clean = render_left(scene);
  const double sigma = 8.0;
  scene.appearance.world.pixel_noise = sigma;
  scene.appearance.world.noise_seed = 5;
  const walkgen::CameraImage noisy = render_left(scene);
  EXPECT_EQ(noisy.rgb, render_left(scene).rgb);  // the same seed, the same noise
  EXPECT_EQ(noisy.depth, clean.depth);           // depth stays exact
  double sum = 0.0, squares = 0.0;
  long n = 0;
  for (std::size_t i = 0; i < clean.rgb.size(); ++i) {
    if (clean.rgb[i] < 4 * sigma || clean.rgb[i] > 255 - 4 * sigma) continue;  // no clipping
    const double d = double(noisy.rgb[i]) - double(clean.rgb[i]);
    sum += d;
    squares += d * d;
    ++n;
  }
  ASSERT_GT(n, 10000);
  const double rms = std::sqrt(squares / double(n));
  std::printf("pixel noise %.1f: rms deviation %.3f, mean %.3f over %ld channels\n", sigma, rms,
              sum / double(n), n);
  EXPECT_NEAR(rms, sigma, 0.05 * sigma);  // rounding adds 1/12 to the variance
  EXPECT_NEAR(sum / double(n), 0.0, 0.2);
  scene.appearance.world.noise_seed = 6;
  EXPECT_NE(noisy.rgb, render_left(scene).rgb);
}

TEST(SceneAppearance, SideLightAndANewFloorChangeWhatTheCameraSees) {
  auto scene = walkgen::make_navigation_scene(NavigationTask::straight, 1);
  const walkgen::CameraImage before = render_left(scene);
  auto side = scene;
  side.appearance = walkgen::apply_scene_shift(scene.appearance, SceneShift::side_light);
  auto floor = scene;
  floor.appearance = walkgen::apply_scene_shift(scene.appearance, SceneShift::new_floor);
  const walkgen::CameraImage lit = render_left(side), tiled = render_left(floor);
  // The bottom rows see the floor only.
  auto bottom_change = [&](const walkgen::CameraImage& image) {
    double change = 0.0;
    const std::size_t from = std::size_t(200) * image.width * 3;
    for (std::size_t i = from; i < image.rgb.size(); ++i) {
      change += std::abs(double(image.rgb[i]) - double(before.rgb[i]));
    }
    return change / double(image.rgb.size() - from);
  };
  std::printf("mean change of the floor's pixels: side light %.1f, new floor %.1f\n",
              bottom_change(lit), bottom_change(tiled));
  EXPECT_GT(bottom_change(lit), 5.0);
  EXPECT_GT(bottom_change(tiled), 20.0);
  // The floor's new material keeps the model's repeat.
  MujocoRobotSettings settings;
  settings.appearance = floor.appearance.world;
  MujocoRobot robot(settings);
  const mjModel* m = robot.model();
  const int geom = mj_name2id(m, mjOBJ_GEOM, "floor");
  const int material = m->geom_matid[geom];
  const int model_floor = mj_name2id(m, mjOBJ_MATERIAL, "floor");
  EXPECT_NE(material, model_floor);
  EXPECT_EQ(m->mat_texrepeat[2 * material], m->mat_texrepeat[2 * model_floor]);
  EXPECT_EQ(m->mat_reflectance[material], m->mat_reflectance[model_floor]);
}

TEST(SceneAppearance, TheCameraPairMovesAsOne) {
  MujocoRobot still{MujocoRobotSettings()};
  MujocoRobotSettings settings;
  settings.appearance.camera_offset = Eigen::Vector3d(0.01, -0.005, 0.008);
  settings.appearance.camera_rotation = Eigen::Vector3d(0.02, 0.03, -0.025);
  MujocoRobot moved(settings);
  const walkgen::StereoImages& a = still.render_cameras();
  ASSERT_EQ(a.status, walkgen::RenderStatus::ok) << a.message;
  const walkgen::CameraImage left = a.left, right = a.right;
  const walkgen::StereoImages& b = moved.render_cameras();
  ASSERT_EQ(b.status, walkgen::RenderStatus::ok) << b.message;
  auto middle = [](const walkgen::CameraImage& l, const walkgen::CameraImage& r) {
    return Eigen::Vector3d(0.5 * (l.pose_W_C.translation() + r.pose_W_C.translation()));
  };
  // The middle of the pair moves by the offset (in the chest's frame: the same length).
  EXPECT_NEAR((middle(b.left, b.right) - middle(left, right)).norm(),
              settings.appearance.camera_offset.norm(), 1e-9);
  // The baseline keeps its length and stays rectified (both cameras turn alike).
  EXPECT_NEAR((b.left.pose_W_C.translation() - b.right.pose_W_C.translation()).norm(), 0.068, 1e-9);
  EXPECT_TRUE(b.left.pose_W_C.linear().isApprox(b.right.pose_W_C.linear(), 1e-12));
  const Eigen::Vector3d baseline_C =
      b.left.pose_W_C.linear().transpose() *
      (b.left.pose_W_C.translation() - b.right.pose_W_C.translation());
  EXPECT_NEAR(baseline_C.y(), 0.068, 1e-9);  // along the cameras' own y
  // Each camera turns by the rotation's angle.
  const double angle =
      Eigen::AngleAxisd(walkgen::detail::rotation_from_rpy(settings.appearance.camera_rotation))
          .angle();
  const double turned =
      Eigen::AngleAxisd(b.left.pose_W_C.linear() * left.pose_W_C.linear().transpose()).angle();
  EXPECT_NEAR(turned, angle, 1e-9);
  EXPECT_NE(b.left.rgb, left.rgb);
}

}  // namespace
