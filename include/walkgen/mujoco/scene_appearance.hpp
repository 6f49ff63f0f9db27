#pragma once
/// @file
/// How a navigation room looks (thesis §11.1; issue 27): the light, the floor, the cameras'
/// pose and noise (WorldAppearance, applied by MujocoRobot) and the target's colour, size and
/// shape, the distractor's and the walls' colours (applied by NavigationScene::objects()), as
/// settings. For a network that learns from the chest cameras: random_scene_appearance() draws
/// a look from training ranges per episode (domain randomisation), and the named shifts
/// (SceneShift) put a room outside those ranges, to measure how a network copes with looks it
/// never saw (held-out shifts). Part of walkgen::mujoco.

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "walkgen/core/exceptions.hpp"
#include "walkgen/core/math.hpp"
#include "walkgen/mujoco/mujoco_robot.hpp"

namespace walkgen {

/// RGB (each in [0, 1]) of a hue [deg] (any angle; 0 red, 120 green, 240 blue), a saturation and
/// a value (each in [0, 1]).
inline Eigen::Vector3d rgb_from_hsv(double hue_deg, double saturation, double value) {
  const double h = std::fmod(std::fmod(hue_deg, 360.0) + 360.0, 360.0) / 60.0;
  const double c = value * saturation;
  const double x = c * (1.0 - std::abs(std::fmod(h, 2.0) - 1.0));
  Eigen::Vector3d rgb;
  switch (static_cast<int>(h)) {
    case 0:
      rgb << c, x, 0.0;
      break;
    case 1:
      rgb << x, c, 0.0;
      break;
    case 2:
      rgb << 0.0, c, x;
      break;
    case 3:
      rgb << 0.0, x, c;
      break;
    case 4:
      rgb << x, 0.0, c;
      break;
    default:
      rgb << c, 0.0, x;
      break;
  }
  return rgb.array() + (value - c);
}

/// Hue [deg] in [0, 360), saturation and value (each in [0, 1]) of an RGB colour (each in
/// [0, 1]); the hue of a grey is 0.
inline Eigen::Vector3d hsv_from_rgb(const Eigen::Vector3d& rgb) {
  const double max = rgb.maxCoeff(), min = rgb.minCoeff(), c = max - min;
  double hue = 0.0;
  if (c > 0.0) {
    if (max == rgb.x()) {
      hue = 60.0 * std::fmod((rgb.y() - rgb.z()) / c + 6.0, 6.0);
    } else if (max == rgb.y()) {
      hue = 60.0 * ((rgb.z() - rgb.x()) / c + 2.0);
    } else {
      hue = 60.0 * ((rgb.x() - rgb.y()) / c + 4.0);
    }
  }
  return {hue, max > 0.0 ? c / max : 0.0, max};
}

/// The distractor of a target of colour `target_rgb`: an object "of similar colour" (thesis
/// §11.1.2), its hue 15° further (red → orange), as saturated, a little brighter.
inline Eigen::Vector3d distractor_rgb_for(const Eigen::Vector3d& target_rgb) {
  const Eigen::Vector3d hsv = hsv_from_rgb(target_rgb);
  return rgb_from_hsv(hsv.x() + 15.0, hsv.y(), std::min(1.0, hsv.z() + 0.05));
}

/// The look of a navigation room. The defaults are the rooms as they always were (a red-orange
/// cylinder 1 m tall, an orange-red distractor, beige walls, the model's light and floor).
struct SceneAppearance {
  /// The light, floor, camera pose and pixel noise (MujocoRobotSettings::appearance).
  WorldAppearance world;
  Eigen::Vector3d target_rgb = Eigen::Vector3d(0.9, 0.12, 0.04);  ///< each in [0, 1]
  /// [m] half the target's width: the cylinder's and the sphere's radius, half a box's side.
  double target_radius = 0.06;
  /// [m] the target's top above the floor. Taller than the chest cameras (0.75 m), so that the
  /// target stays in view up to the end of the way: a 0.35 m extinguisher on the floor leaves
  /// the view at its bottom within 0.85 m, and the last turns toward it could not be seen, nor
  /// learned. A sphere is a ball of target_radius with its top there (on an invisible stand).
  double target_height = 1.0;
  SceneShape target_shape = SceneShape::cylinder;
  /// The distractor box's colour (distractor_rgb_for() the target's, when drawn or shifted).
  Eigen::Vector3d distractor_rgb = Eigen::Vector3d(0.95, 0.35, 0.05);
  /// The walls' colour (speckled with a darker shade of it).
  Eigen::Vector3d wall_rgb = Eigen::Vector3d(0.75, 0.72, 0.62);
};

/// Checks a room's look (NavigationEpisode's constructor calls this).
/// @throws walkgen::invalid_argument naming the first bad field.
inline void validate(const SceneAppearance& a) {
  validate(a.world, "SceneAppearance.world");
  check_argument(detail::is_rgb(a.target_rgb), "SceneAppearance.target_rgb", "values in [0, 1]",
                 detail::vector_text(a.target_rgb));
  check_argument(std::isfinite(a.target_radius) && a.target_radius > 0.0 && a.target_radius <= 0.5,
                 "SceneAppearance.target_radius", "a radius in (0, 0.5] m", a.target_radius);
  check_argument(std::isfinite(a.target_height) && a.target_height > 0.0 && a.target_height <= 3.0,
                 "SceneAppearance.target_height", "a height in (0, 3] m", a.target_height);
  check_argument(a.target_shape <= SceneShape::sphere, "SceneAppearance.target_shape",
                 "box, cylinder or sphere", int(a.target_shape));
  check_argument(a.target_shape != SceneShape::sphere || a.target_height >= 2.0 * a.target_radius,
                 "SceneAppearance.target_height", "at least the sphere's diameter",
                 std::to_string(a.target_height) + " m for a radius of " +
                     std::to_string(a.target_radius) + " m");
  check_argument(detail::is_rgb(a.distractor_rgb), "SceneAppearance.distractor_rgb",
                 "values in [0, 1]", detail::vector_text(a.distractor_rgb));
  check_argument(detail::is_rgb(a.wall_rgb), "SceneAppearance.wall_rgb", "values in [0, 1]",
                 detail::vector_text(a.wall_rgb));
}

/// A closed interval [min, max] that random_scene_appearance() draws from uniformly.
struct AppearanceRange {
  double min = 0.0;
  double max = 0.0;

  bool contains(double v) const { return v >= min && v <= max; }
};

/// The training ranges of random_scene_appearance(). The defaults exclude every SceneShift:
/// the light at 0.45–1.5 of the model's (dim: 0.25), from within 45° of straight down (side
/// light: 79°), target hues from magenta-red through orange and yellow to green, −25°…130°
/// (blue: 225°), 0.8–1.25 m tall (small: 0.6 m), checker, gradient or speckle floors (new
/// floor: tiles).
struct AppearanceRanges {
  AppearanceRange light_intensity{0.45, 1.5};    ///< WorldAppearance::light_intensity
  AppearanceRange ambient_intensity{0.45, 1.5};  ///< WorldAppearance::ambient_intensity
  /// [deg] the light's direction from straight down, toward an azimuth drawn in [0°, 360°).
  AppearanceRange light_tilt{0.0, 55.0};
  /// [deg] the target's hue; drawn in [min, max] and wrapped into [0°, 360°) (−25°: 335°).
  AppearanceRange target_hue{-25.0, 130.0};
  AppearanceRange target_saturation{0.6, 1.0};
  AppearanceRange target_value{0.55, 1.0};
  AppearanceRange target_radius{0.045, 0.09};  ///< [m]
  AppearanceRange target_height{0.65, 1.25};   ///< [m]
  /// Shapes of the target, one drawn (equally likely). A box-shaped target is still told from
  /// the distractor box of similar colour by its height (0.3 m); a sphere (a ball at the
  /// target's height, on nothing) is left out.
  std::vector<SceneShape> target_shapes{SceneShape::cylinder, SceneShape::box};
  /// Floor textures, one drawn (equally likely).
  std::vector<FloorTexture> floor_textures{FloorTexture::checker, FloorTexture::gradient,
                                           FloorTexture::speckle};
  /// Each channel of the floor's first colour; the second is it + floor_contrast (at most 1).
  AppearanceRange floor_channel{0.12, 0.5};
  AppearanceRange floor_contrast{0.08, 0.35};
  /// Each channel of the walls' colour, drawn between these.
  Eigen::Vector3d wall_rgb_min = Eigen::Vector3d(0.6, 0.57, 0.47);
  Eigen::Vector3d wall_rgb_max = Eigen::Vector3d(0.9, 0.87, 0.77);
  /// [m] each axis of WorldAppearance::camera_offset drawn in ±this.
  double camera_offset = 0.01;
  /// [rad] each angle of WorldAppearance::camera_rotation drawn in ±this.
  double camera_rotation = 0.03;
  AppearanceRange pixel_noise{0.0, 6.0};  ///< [grey levels] WorldAppearance::pixel_noise
};

/// Checks training ranges (random_scene_appearance() calls this).
/// @throws walkgen::invalid_argument naming the first bad field.
inline void validate(const AppearanceRanges& r) {
  auto check = [](const AppearanceRange& range, const char* where, double lo, double hi,
                  const char* expected) {
    check_argument(std::isfinite(range.min) && std::isfinite(range.max) && range.min >= lo &&
                       range.min <= range.max && range.max <= hi,
                   where, expected,
                   "[" + std::to_string(range.min) + ", " + std::to_string(range.max) + "]");
  };
  check(r.light_intensity, "AppearanceRanges.light_intensity", 0.0, 10.0, "0 <= min <= max <= 10");
  check(r.ambient_intensity, "AppearanceRanges.ambient_intensity", 0.0, 10.0,
        "0 <= min <= max <= 10");
  check(r.light_tilt, "AppearanceRanges.light_tilt", 0.0, 90.0, "0 <= min <= max <= 90 deg");
  check(r.target_hue, "AppearanceRanges.target_hue", -360.0, 360.0,
        "-360 <= min <= max <= 360 deg");
  check(r.target_saturation, "AppearanceRanges.target_saturation", 0.0, 1.0,
        "0 <= min <= max <= 1");
  check(r.target_value, "AppearanceRanges.target_value", 0.0, 1.0, "0 <= min <= max <= 1");
  check(r.target_radius, "AppearanceRanges.target_radius", 1e-3, 0.5,
        "0.001 <= min <= max <= 0.5 m");
  check(r.target_height, "AppearanceRanges.target_height", 1e-3, 3.0, "0.001 <= min <= max <= 3 m");
  check(r.floor_channel, "AppearanceRanges.floor_channel", 0.0, 1.0, "0 <= min <= max <= 1");
  check(r.floor_contrast, "AppearanceRanges.floor_contrast", 0.0, 1.0, "0 <= min <= max <= 1");
  check(r.pixel_noise, "AppearanceRanges.pixel_noise", 0.0, 100.0, "0 <= min <= max <= 100");
  check_argument(!r.target_shapes.empty(), "AppearanceRanges.target_shapes", "at least one shape",
                 "none");
  for (SceneShape s : r.target_shapes) {
    check_argument(s <= SceneShape::sphere, "AppearanceRanges.target_shapes",
                   "box, cylinder or sphere", int(s));
  }
  check_argument(!r.floor_textures.empty(), "AppearanceRanges.floor_textures",
                 "at least one texture", "none");
  for (FloorTexture t : r.floor_textures) {
    check_argument(t <= FloorTexture::tiles, "AppearanceRanges.floor_textures",
                   "model, checker, gradient, speckle or tiles", int(t));
  }
  check_argument(detail::is_rgb(r.wall_rgb_min) && detail::is_rgb(r.wall_rgb_max) &&
                     (r.wall_rgb_min.array() <= r.wall_rgb_max.array()).all(),
                 "AppearanceRanges.wall_rgb_min, wall_rgb_max", "colours in [0, 1], min <= max",
                 detail::vector_text(r.wall_rgb_min) + ", " + detail::vector_text(r.wall_rgb_max));
  check_argument(std::isfinite(r.camera_offset) && r.camera_offset >= 0.0 && r.camera_offset <= 0.1,
                 "AppearanceRanges.camera_offset", "a bound in [0, 0.1] m", r.camera_offset);
  check_argument(
      std::isfinite(r.camera_rotation) && r.camera_rotation >= 0.0 && r.camera_rotation <= 0.5,
      "AppearanceRanges.camera_rotation", "a bound in [0, 0.5] rad", r.camera_rotation);
}

/// A look drawn from `ranges` (uniformly in each range), the same for the same seed and
/// ranges; the distractor's colour follows the target's (distractor_rgb_for()), the pixel
/// noise's seed is drawn too.
/// @throws walkgen::invalid_argument for invalid ranges (validate()).
inline SceneAppearance random_scene_appearance(std::uint32_t seed,
                                               const AppearanceRanges& ranges = {}) {
  validate(ranges);
  // Another stream than the room's layout (make_navigation_scene) of the same seed.
  std::mt19937 rng(seed * 2246822519u + 374761393u);
  auto uniform = [&rng](double a, double b) {
    return a == b ? a : std::uniform_real_distribution<double>(a, b)(rng);
  };
  auto draw = [&uniform](const AppearanceRange& r) { return uniform(r.min, r.max); };
  auto pick = [&rng](std::size_t n) {
    return std::uniform_int_distribution<std::size_t>(0, n - 1)(rng);
  };
  SceneAppearance a;
  WorldAppearance& w = a.world;
  w.light_intensity = draw(ranges.light_intensity);
  w.ambient_intensity = draw(ranges.ambient_intensity);
  const double tilt = draw(ranges.light_tilt) * kPi / 180.0;
  const double azimuth = uniform(0.0, 2.0 * kPi);
  w.light_direction = Eigen::Vector3d(std::sin(tilt) * std::cos(azimuth),
                                      std::sin(tilt) * std::sin(azimuth), -std::cos(tilt));
  w.floor_texture = ranges.floor_textures[pick(ranges.floor_textures.size())];
  for (int i = 0; i < 3; ++i) w.floor_rgb1[i] = draw(ranges.floor_channel);
  w.floor_rgb2 = (w.floor_rgb1.array() + draw(ranges.floor_contrast)).min(1.0);
  for (int i = 0; i < 3; ++i) {
    w.camera_offset[i] = uniform(-ranges.camera_offset, ranges.camera_offset);
    w.camera_rotation[i] = uniform(-ranges.camera_rotation, ranges.camera_rotation);
  }
  w.pixel_noise = draw(ranges.pixel_noise);
  w.noise_seed = static_cast<std::uint32_t>(rng());
  const double hue = draw(ranges.target_hue);
  a.target_rgb = rgb_from_hsv(hue, draw(ranges.target_saturation), draw(ranges.target_value));
  a.target_radius = draw(ranges.target_radius);
  a.target_height = draw(ranges.target_height);
  a.target_shape = ranges.target_shapes[pick(ranges.target_shapes.size())];
  if (a.target_shape == SceneShape::sphere) {
    a.target_height = std::max(a.target_height, 2.0 * a.target_radius);
  }
  a.distractor_rgb = distractor_rgb_for(a.target_rgb);
  for (int i = 0; i < 3; ++i)
    a.wall_rgb[i] = uniform(ranges.wall_rgb_min[i], ranges.wall_rgb_max[i]);
  return a;
}

/// Held-out shifts of a room's look: each outside the default AppearanceRanges, to evaluate on
/// looks that training never saw (apply_scene_shift()).
enum class SceneShift : std::uint8_t {
  none,          ///< the look as it is
  dim,           ///< light and ambient light at 0.25 of the model's
  side_light,    ///< the sun from the robot's left at the start (+y), 11° above the horizon
  blue_target,   ///< a blue target (hue 225°, saturation 0.9, value 0.85) and distractor
  small_target,  ///< the target 0.6 m tall, below the chest cameras
  new_floor,     ///< a tiled floor: beige tiles (0.66, 0.5, 0.34), brown joints
};

/// The enumerator's name ("none", "dim", ...), as scene_shift_from_string() reads it;
/// "unknown" for a value out of range.
constexpr const char* to_string(SceneShift s) noexcept {
  switch (s) {
    case SceneShift::none:
      return "none";
    case SceneShift::dim:
      return "dim";
    case SceneShift::side_light:
      return "side_light";
    case SceneShift::blue_target:
      return "blue_target";
    case SceneShift::small_target:
      return "small_target";
    case SceneShift::new_floor:
      return "new_floor";
  }
  return "unknown";
}

/// Every shift, in enum order.
inline std::vector<SceneShift> all_scene_shifts() {
  return {SceneShift::none,        SceneShift::dim,          SceneShift::side_light,
          SceneShift::blue_target, SceneShift::small_target, SceneShift::new_floor};
}

/// @throws walkgen::invalid_argument for an unknown name, listing the names.
inline SceneShift scene_shift_from_string(const std::string& name) {
  std::string names;
  for (SceneShift s : all_scene_shifts()) {
    if (name == to_string(s)) return s;
    names += (names.empty() ? "" : ", ") + std::string(to_string(s));
  }
  check_argument(false, "scene_shift_from_string", "one of " + names, "'" + name + "'");
  return SceneShift::none;
}

/// `base` with `shift` applied (the fields the shift names replaced, the others kept).
inline SceneAppearance apply_scene_shift(SceneAppearance base, SceneShift shift) {
  switch (shift) {
    case SceneShift::none:
      break;
    case SceneShift::dim:
      base.world.light_intensity = 0.25;
      base.world.ambient_intensity = 0.25;
      break;
    case SceneShift::side_light:
      base.world.light_direction = Eigen::Vector3d(0.0, -1.0, -0.2);
      break;
    case SceneShift::blue_target:
      base.target_rgb = rgb_from_hsv(225.0, 0.9, 0.85);
      base.distractor_rgb = distractor_rgb_for(base.target_rgb);
      break;
    case SceneShift::small_target:
      base.target_height = 0.6;
      break;
    case SceneShift::new_floor:
      base.world.floor_texture = FloorTexture::tiles;
      base.world.floor_rgb1 = Eigen::Vector3d(0.66, 0.5, 0.34);
      base.world.floor_rgb2 = Eigen::Vector3d(0.3, 0.2, 0.12);
      break;
  }
  return base;
}

/// The columns of appearance_csv_row(), comma-separated (no line end).
inline std::string appearance_csv_header() {
  return "light_intensity,ambient_intensity,light_dir_x,light_dir_y,light_dir_z,floor_texture,"
         "floor_r1,floor_g1,floor_b1,floor_r2,floor_g2,floor_b2,camera_dx,camera_dy,camera_dz,"
         "camera_roll,camera_pitch,camera_yaw,pixel_noise,noise_seed,target_r,target_g,target_b,"
         "target_radius,target_height,target_shape,distractor_r,distractor_g,distractor_b,"
         "wall_r,wall_g,wall_b";
}

/// One CSV row of `a` (no line end): the columns of appearance_csv_header(), enums by name, the
/// light direction empty where it is the model's.
inline std::string appearance_csv_row(const SceneAppearance& a) {
  std::ostringstream os;
  os.precision(9);
  auto put = [&os](const Eigen::Vector3d& v) {
    os << ',' << v.x() << ',' << v.y() << ',' << v.z();
  };
  const WorldAppearance& w = a.world;
  os << w.light_intensity << ',' << w.ambient_intensity;
  if (w.light_direction) {
    put(*w.light_direction);
  } else {
    os << ",,,";
  }
  os << ',' << to_string(w.floor_texture);
  put(w.floor_rgb1);
  put(w.floor_rgb2);
  put(w.camera_offset);
  put(w.camera_rotation);
  os << ',' << w.pixel_noise << ',' << w.noise_seed;
  put(a.target_rgb);
  os << ',' << a.target_radius << ',' << a.target_height << ',' << to_string(a.target_shape);
  put(a.distractor_rgb);
  put(a.wall_rgb);
  return os.str();
}

}  // namespace walkgen
