#pragma once
/// @file
/// MuJoCo simulation backend of the robot interface (walkgen/robot/robot.hpp). Target
/// walkgen::mujoco (Debian: libmujoco-dev, and libegl1 + libegl-mesa0 for the cameras); the core
/// never includes this header.
///
/// Loads an MJCF (walkgen's humanoid, models/walkgen_humanoid.xml, unless told otherwise), maps
/// the joint names to MuJoCo joints, the actuators and jointpos sensors on them (measured
/// positions are qpos where a joint has no sensor) and the ankle sensor sites to their
/// `<site>_force` / `<site>_torque` sensors by name (the IMU site to `<site>_quat`, `<site>_gyro`,
/// `<site>_acc`), runs headless at the model's timestep, and
/// renders the chest cameras offscreen through EGL (Mesa's surfaceless platform, software
/// rendering). Divergence (non-finite state, MuJoCo's bad-acceleration reset) and falls (base
/// below fall_height_ratio of its height in the initial state) stop the robot and are reported
/// in its status.
///
/// Two drives (RobotInfo::drive): position servos (MuJoCo `<position>` actuators, the model's
/// gains) take the joint targets as their control; torque motors (`<motor>`) are driven by
/// walkgen's JointTorqueController at every physics step, on the targets interpolated over the
/// command period, with the settings' gains, a feed-forward torque (JointFeedforward) and the
/// motors' ctrlrange as torque limits. Motors on joints the settings do not name get zero torque.
///
/// A robot without ankle sensors (no ft_sensor_sites) reports the contact forces on each foot as
/// its force-torque readings, at the sole frames (RobotInfo::ft_sensor_height 0): the wrench the
/// ground exerts on the foot's bodies, from MuJoCo's contact forces (mj_contactForce), so that
/// measured_zmp() gives the centre of pressure.

#include <mujoco/mujoco.h>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <memory>
#include <optional>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "walkgen/core/data_dir.hpp"
#include "walkgen/core/exceptions.hpp"
#include "walkgen/core/math.hpp"
#include "walkgen/kinematics/kinematic_tree.hpp"
#include "walkgen/mujoco/detail/egl_context.hpp"
#include "walkgen/robot/joint_control.hpp"
#include "walkgen/robot/robot.hpp"
#include "walkgen/robot/robot_description.hpp"

namespace walkgen {

/// Shapes of SceneObject.
enum class SceneShape : std::uint8_t { box, cylinder, sphere };

/// "box", "cylinder" or "sphere", e.g. for logs; "unknown" for a value out of range.
constexpr const char* to_string(SceneShape shape) noexcept {
  switch (shape) {
    case SceneShape::box:
      return "box";
    case SceneShape::cylinder:
      return "cylinder";
    case SceneShape::sphere:
      return "sphere";
  }
  return "unknown";
}

/// A static object added to the model's world (a target, a chair, a wall): one geom in a body of
/// its own, standing on the floor unless position.z says otherwise.
struct SceneObject {
  std::string name;  ///< MuJoCo body and geom name (letters, digits, '_' or '-'), unique
  SceneShape shape = SceneShape::box;
  /// Centre of the object's base on the floor [m]: the geom is lifted by half its height.
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  double yaw = 0.0;  ///< [rad] about z
  /// box: length (x), width (y), height [m]; cylinder: radius, unused, height; sphere: radius.
  Eigen::Vector3d size = Eigen::Vector3d(0.1, 0.1, 0.1);
  Eigen::Vector3d rgb = Eigen::Vector3d(0.8, 0.2, 0.1);  ///< colour, each in [0, 1]
  bool collides = true;  ///< false: visible only (the robot walks through it)
  /// A speckle texture in the object's colour instead of a flat one: stereo block matching
  /// needs texture to find the object (thesis §3.1).
  bool textured = false;
  /// A mocap body that MujocoRobot::set_object_position() moves (a walking person, say); it
  /// is not moved by contacts.
  bool movable = false;
};

/// The floor of WorldAppearance: the model's own, or one of MuJoCo's builtin 2-D textures in
/// two colours (rgb1, rgb2), repeated as the model's floor material repeats.
enum class FloorTexture : std::uint8_t {
  model,     ///< the model's own floor material, unchanged
  checker,   ///< squares of rgb1 and rgb2
  gradient,  ///< rgb1 fading into rgb2 across each repeat
  speckle,   ///< rgb1 with random dots of rgb2 (MuJoCo's flat texture, mark "random")
  tiles,     ///< rgb1 tiles with joints of rgb2 (MuJoCo's flat texture, mark "edge")
};

/// "model", "checker", "gradient", "speckle" or "tiles"; "unknown" for a value out of range.
constexpr const char* to_string(FloorTexture t) noexcept {
  switch (t) {
    case FloorTexture::model:
      return "model";
    case FloorTexture::checker:
      return "checker";
    case FloorTexture::gradient:
      return "gradient";
    case FloorTexture::speckle:
      return "speckle";
    case FloorTexture::tiles:
      return "tiles";
  }
  return "unknown";
}

/// How the model's own world and the chest cameras look (MujocoRobotSettings::appearance): the
/// light, the floor, small offsets of the camera pair and noise on its images, e.g. drawn at
/// random per episode so that a network trained on the images does not learn one look (domain
/// randomisation; walkgen/mujoco/scene_appearance.hpp draws them). The defaults leave the model
/// as its file describes it: the same images as without these settings.
struct WorldAppearance {
  /// Scale of the diffuse and specular light of every light of the model and of MuJoCo's
  /// headlight (which follows the rendering camera): 0.25 is a room lit at a quarter.
  double light_intensity = 1.0;
  /// Scale of the ambient light of every light and of the headlight.
  double ambient_intensity = 1.0;
  /// Direction the light travels in the world frame (not normalised; (0, 0, -1) straight down)
  /// for every directional light of the world body, each placed as far from the origin as it
  /// was, against that direction (shadows); unset: the model's own.
  std::optional<Eigen::Vector3d> light_direction;
  /// The floor (the world body's plane geoms); model: unchanged, and the colours unused.
  FloorTexture floor_texture = FloorTexture::model;
  Eigen::Vector3d floor_rgb1 = Eigen::Vector3d(0.2, 0.3, 0.4);  ///< each in [0, 1]
  Eigen::Vector3d floor_rgb2 = Eigen::Vector3d(0.3, 0.4, 0.5);  ///< each in [0, 1]
  /// [m] the chest camera pair moved, in the frame of the body that carries the cameras (the
  /// chest of walkgen's humanoid: x forward, y left, z up); the pair moves as one (its
  /// baseline stays rectified). Needs both cameras in one body or in joint-free bodies with one
  /// parent; unused for a robot without cameras.
  Eigen::Vector3d camera_offset = Eigen::Vector3d::Zero();
  /// [rad] roll, pitch, yaw (about x, y, z of that frame, R = Rz Ry Rx) of the camera pair about
  /// the middle between its cameras; pitch > 0 tilts the cameras down.
  Eigen::Vector3d camera_rotation = Eigen::Vector3d::Zero();
  /// Standard deviation of Gaussian noise added to every channel of every pixel of the chest
  /// cameras' RGB images [grey levels of 0–255] (rounded, clipped), before anything (stereo
  /// matching, recording) sees them; the depth images stay exact. 0: none.
  double pixel_noise = 0.0;
  /// Seed of the pixel noise: a robot's images are the same for the same seed and steps.
  std::uint32_t noise_seed = 0;
};

namespace detail {

/// Whether every channel of `rgb` is in [0, 1] (NaN is not).
inline bool is_rgb(const Eigen::Vector3d& rgb) {
  return (rgb.array() >= 0.0).all() && (rgb.array() <= 1.0).all();
}

}  // namespace detail

/// Checks a world appearance; `where` names it in the messages ("WorldAppearance",
/// "MujocoRobotSettings.appearance", ...).
/// @throws walkgen::invalid_argument naming the first bad field.
inline void validate(const WorldAppearance& a, const std::string& where = "WorldAppearance") {
  auto field = [&where](const char* name) { return where + "." + name; };
  auto scale_ok = [](double k) { return std::isfinite(k) && k >= 0.0 && k <= 10.0; };
  check_argument(scale_ok(a.light_intensity), field("light_intensity").c_str(),
                 "a scale in [0, 10]", a.light_intensity);
  check_argument(scale_ok(a.ambient_intensity), field("ambient_intensity").c_str(),
                 "a scale in [0, 10]", a.ambient_intensity);
  check_argument(
      !a.light_direction || (a.light_direction->allFinite() && a.light_direction->norm() > 1e-9),
      field("light_direction").c_str(), "a finite non-zero direction (or none: the model's)",
      a.light_direction ? detail::vector_text(*a.light_direction) : "");
  check_argument(a.floor_texture <= FloorTexture::tiles, field("floor_texture").c_str(),
                 "model, checker, gradient, speckle or tiles", int(a.floor_texture));
  check_argument(detail::is_rgb(a.floor_rgb1), field("floor_rgb1").c_str(), "values in [0, 1]",
                 detail::vector_text(a.floor_rgb1));
  check_argument(detail::is_rgb(a.floor_rgb2), field("floor_rgb2").c_str(), "values in [0, 1]",
                 detail::vector_text(a.floor_rgb2));
  check_argument(a.camera_offset.allFinite() && a.camera_offset.cwiseAbs().maxCoeff() <= 0.1,
                 field("camera_offset").c_str(), "finite offsets within ±0.1 m",
                 detail::vector_text(a.camera_offset));
  check_argument(a.camera_rotation.allFinite() && a.camera_rotation.cwiseAbs().maxCoeff() <= 0.5,
                 field("camera_rotation").c_str(), "finite angles within ±0.5 rad",
                 detail::vector_text(a.camera_rotation));
  check_argument(std::isfinite(a.pixel_noise) && a.pixel_noise >= 0.0 && a.pixel_noise <= 100.0,
                 field("pixel_noise").c_str(), "a standard deviation in [0, 100] grey levels",
                 a.pixel_noise);
}

/// The feed-forward torque of a torque-driven robot's joint controller.
enum class JointFeedforward : std::uint8_t {
  none,     ///< PD only
  gravity,  ///< MuJoCo's bias forces (gravity, Coriolis, centrifugal) at the measured state
  /// The bias forces minus the joint torques through which the feet carry the robot's weight:
  /// vertical forces summing to m g, at the ground projection of the CoM, shared between the
  /// feet in contact by where the CoM lies between them (the torques a standing or slowly
  /// walking robot needs; the bias forces alone treat the legs as hanging).
  weight,
  /// As weight, with the contact forces that move the CoM as the pattern asks
  /// (Robot::set_balance_reference): the CoM acceleration c̈ = c̈_ref + balance_kp (c_ref − c) +
  /// balance_kd (ċ_ref − ċ) in the plane, the feet pushing with m (g + c̈) at the ZMP of that
  /// acceleration, c − c_z c̈ / g. c and ċ relative to the support sole: what the IMU and the
  /// joint encoders tell a real robot. Without a reference (none since the start or reset()):
  /// weight.
  balance,
};

/// "none", "gravity" or "weight", e.g. for logs; "unknown" for a value out of range.
constexpr const char* to_string(JointFeedforward f) noexcept {
  switch (f) {
    case JointFeedforward::none:
      return "none";
    case JointFeedforward::gravity:
      return "gravity";
    case JointFeedforward::weight:
      return "weight";
    case JointFeedforward::balance:
      return "balance";
  }
  return "unknown";
}

/// How a MujocoRobot maps our names onto the model. The defaults describe walkgen's humanoid
/// (walkgen_humanoid_description()); mujoco_robot_settings() takes them from any description.
struct MujocoRobotSettings {
  /// MJCF file; empty: humanoid_mjcf_path().
  std::string model_path;
  /// Our joints, in command/measurement order; each needs a MuJoCo hinge or slide joint of
  /// that name with one actuator on it (all position servos or all motors).
  std::vector<std::string> joint_names = walkgen_humanoid_description().joint_names;
  /// Ankle sensor sites (left, right) with force/torque sensors "<site>_force", "<site>_torque";
  /// none (two empty names): the contact forces at the sole frames are the readings.
  std::array<std::string, 2> ft_sensor_sites = walkgen_humanoid_description().ft_sensor_frames;
  /// Sole frames (left, right): sites of the model or added `frames`.
  std::array<std::string, 2> sole_frames = walkgen_humanoid_description().sole_frames;
  /// Frames added to bodies of the model (RobotDescription::frames), e.g. soles.
  std::vector<FrameDescription> frames = walkgen_humanoid_description().frames;
  /// Chest cameras (left, right); none (two empty names): render_cameras() is unavailable.
  std::array<std::string, 2> cameras = walkgen_humanoid_description().cameras;
  /// IMU site with sensors "<site>_quat" (framequat), "<site>_gyro", "<site>_acc"; empty: no
  /// IMU (RobotOutput::imu.available false).
  std::string imu_site = walkgen_humanoid_description().imu_site;
  /// The floating base, whose height tells a fall.
  std::string base_body = walkgen_humanoid_description().base_body;
  /// Initial state (qpos, ctrl); empty: the model's qpos0 with stand_pose's joints, the base
  /// lowered or raised until the lower sole touches the floor (z = 0).
  std::string keyframe = walkgen_humanoid_description().stand_keyframe;
  /// The standing posture where there is no keyframe (RobotDescription::stand_pose).
  std::vector<JointAngle> stand_pose = walkgen_humanoid_description().stand_pose;
  /// Torque drive: PD gains per joint, joint_names order (joint_gains() of a description);
  /// every commanded joint of a torque-driven robot needs finite gains. Empty: none given.
  Eigen::VectorXd kp, kd;
  /// Torque drive: the controller's feed-forward torque.
  JointFeedforward feedforward = JointFeedforward::weight;
  /// JointFeedforward::balance: feedback gains on the CoM position [1/s^2] and velocity [1/s].
  double balance_kp = 20.0, balance_kd = 8.0;
  /// Fallen when the base is below this fraction of its initial height.
  double fall_height_ratio = 0.8;
  /// Static objects added to the world of the model (the model file itself is not changed).
  std::vector<SceneObject> objects;
  /// The light, floor, camera pose offsets and image noise (the model file itself is not
  /// changed); the defaults: the model's own.
  WorldAppearance appearance;
  /// [rad] the floor's slope, as gravity tilted against the world: (along x, across y). A
  /// positive x slope is uphill walking forward (gravity pulls toward −x), a positive y slope
  /// rises to the left (gravity pulls toward −y). The floor, the feet and the frames stay level
  /// in the world, so the whole scene is the inclined plane seen from its own frame.
  Eigen::Vector2d slope = Eigen::Vector2d::Zero();
  /// Largest image of MujocoRobot::render_view() [px] (sizes the offscreen buffer).
  int view_width = 640;
  int view_height = 480;
};

/// Checks the settings that do not need the model (MujocoRobot's constructor calls this; the
/// names are then looked up in the model).
/// @throws walkgen::invalid_argument naming the first bad field (and object).
inline void validate(const MujocoRobotSettings& s) {
  check_argument(!s.joint_names.empty(), "MujocoRobotSettings.joint_names", "at least one joint",
                 "none");
  check_argument(s.fall_height_ratio > 0.0 && s.fall_height_ratio < 1.0,
                 "MujocoRobotSettings.fall_height_ratio", "a fraction in (0, 1)",
                 s.fall_height_ratio);
  check_argument(s.view_width >= 1 && s.view_width <= 16384, "MujocoRobotSettings.view_width",
                 "a width in [1, 16384] px", s.view_width);
  check_argument(s.view_height >= 1 && s.view_height <= 16384, "MujocoRobotSettings.view_height",
                 "a height in [1, 16384] px", s.view_height);
  const auto n = static_cast<Eigen::Index>(s.joint_names.size());
  check_argument((s.kp.size() == 0 && s.kd.size() == 0) || (s.kp.size() == n && s.kd.size() == n),
                 "MujocoRobotSettings.kp, kd", "none or one gain per joint name each",
                 std::to_string(s.kp.size()) + ", " + std::to_string(s.kd.size()));
  check_argument(s.slope.allFinite() && (s.slope.cwiseAbs().array() <= 0.5).all(),
                 "MujocoRobotSettings.slope", "finite angles within ±0.5 rad",
                 std::to_string(s.slope.x()) + ", " + std::to_string(s.slope.y()));
  check_argument(s.sole_frames[0].empty() == s.sole_frames[1].empty(),
                 "MujocoRobotSettings.sole_frames", "two names (left, right) or none",
                 "'" + s.sole_frames[0] + "', '" + s.sole_frames[1] + "'");
  for (const SceneObject& o : s.objects) {
    bool name_ok = !o.name.empty();
    for (char c : o.name)
      name_ok = name_ok && (std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-');
    check_argument(name_ok, "MujocoRobotSettings.objects: name", "letters, digits, '_' or '-'",
                   "'" + o.name + "'");
    const std::string where = "MujocoRobotSettings.objects: '" + o.name + "'";
    check_argument(o.position.allFinite() && std::isfinite(o.yaw) && o.size.allFinite() &&
                       (o.size.array() > 0.0).all(),
                   where.c_str(), "a finite pose and sizes > 0", "NaN, inf or a size <= 0");
    check_argument(detail::is_rgb(o.rgb), (where + " rgb").c_str(), "values in [0, 1]",
                   "out of range");
  }
  check_argument(std::isfinite(s.balance_kp) && std::isfinite(s.balance_kd) &&
                     s.balance_kp >= 0.0 && s.balance_kd >= 0.0,
                 "MujocoRobotSettings.balance_kp, balance_kd", "finite gains >= 0",
                 std::to_string(s.balance_kp) + ", " + std::to_string(s.balance_kd));
  validate(s.appearance, "MujocoRobotSettings.appearance");
}

/// The settings that load `robot`'s MJCF with its names (joints, ankle sensor sites, soles and
/// added frames, cameras, base, standing keyframe or pose) and its joint groups' gains; the rest
/// at their defaults.
inline MujocoRobotSettings mujoco_robot_settings(const RobotDescription& robot) {
  MujocoRobotSettings s;
  s.model_path = robot.mjcf_path;
  s.joint_names = robot.joint_names;
  s.ft_sensor_sites = robot.ft_sensor_frames;
  s.sole_frames = robot.sole_frames;
  s.frames = robot.frames;
  s.cameras = robot.cameras;
  s.imu_site = robot.imu_site;
  s.base_body = robot.base_body;
  s.keyframe = robot.stand_keyframe;
  s.stand_pose = robot.stand_pose;
  if (!robot.joint_groups.empty()) {
    const JointGains gains = joint_gains(robot);
    s.kp = gains.kp;
    s.kd = gains.kd;
  }
  if (robot.balance.contact_feedforward) {
    s.feedforward = JointFeedforward::balance;
    s.balance_kp = robot.balance.com_kp;
    s.balance_kd = robot.balance.com_kd;
  }
  return s;
}

/// A simulated robot in MuJoCo. Not copyable (owns the model, data and GL context).
class MujocoRobot final : public Robot {
 public:
  /// @throws walkgen::invalid_argument for invalid settings (validate()), when the model cannot
  ///   be read (naming the file and MuJoCo's message), or names are missing from it (listing
  ///   every one), or the model has actuators that are not ours.
  explicit MujocoRobot(MujocoRobotSettings settings = {}) : settings_(std::move(settings)) {
    validate(settings_);
    if (settings_.model_path.empty()) settings_.model_path = humanoid_mjcf_path();
    load_model();
    map_names();
    apply_appearance();
    info_.joint_names = settings_.joint_names;
    info_.timestep = model_->opt.timestep;
    info_.image_width = static_cast<int>(custom_numeric("camera_resolution", 0, 320));
    info_.image_height = static_cast<int>(custom_numeric("camera_resolution", 1, 240));
    if (has_ft_sensors()) {
      info_.ft_sensor_height = custom_numeric("ft_sensor_height", 0, 0.0);
      check_positive("MujocoRobot: <numeric name='ft_sensor_height'>", info_.ft_sensor_height,
                     "a sensor height > 0 m in the model's <custom> section");
    }
    const int n = static_cast<int>(settings_.joint_names.size());
    q_target_ = Eigen::VectorXd::Zero(n);
    q_from_ = Eigen::VectorXd::Zero(n);
    q_ref_ = Eigen::VectorXd::Zero(n);
    dq_ref_ = Eigen::VectorXd::Zero(n);
    tau_ff_ = Eigen::VectorXd::Zero(n);
    q_now_ = Eigen::VectorXd::Zero(n);
    dq_now_ = Eigen::VectorXd::Zero(n);
    output_.q.resize(n);
    output_.dq.resize(n);
    output_.tau = Eigen::VectorXd::Zero(n);
    jacobian_.resize(static_cast<std::size_t>(3 * model_->nv));
    if (info_.drive == JointDrive::torque) make_controller();
    reset();
    info_.nominal_base_height = output_.base_height;
    info_.fall_height = settings_.fall_height_ratio * info_.nominal_base_height;
  }

  ~MujocoRobot() override {
    if (scene_made_) mjv_freeScene(&scene_);
    if (render_context_made_ && gl_ != nullptr && gl_->make_current()) {
      mjr_freeContext(&render_context_);
    }
  }
  MujocoRobot(const MujocoRobot&) = delete;
  MujocoRobot& operator=(const MujocoRobot&) = delete;

  const RobotInfo& info() const override { return info_; }
  const RobotOutput& output() const override { return output_; }
  const MujocoRobotSettings& settings() const { return settings_; }

  /// The MuJoCo model and data, e.g. to push the robot or read contacts in tests.
  const mjModel* model() const { return model_.get(); }
  mjData* data() { return data_.get(); }

  [[nodiscard]] JointCommandStatus set_joint_targets(
      const Eigen::Ref<const Eigen::VectorXd>& q_target) override {
    check_argument(q_target.size() == q_target_.size(), "MujocoRobot::set_joint_targets",
                   std::to_string(q_target_.size()) + " joint targets (one per joint name)",
                   q_target.size());
    if (!q_target.allFinite()) return JointCommandStatus::rejected;
    q_target_ = q_target;
    return JointCommandStatus::accepted;
  }

  void set_balance_reference(const BalanceReference& reference) override { balance_ = reference; }

  [[nodiscard]] RobotStatus step(double duration) override {
    check_positive("MujocoRobot::step: duration", duration, "a finite duration > 0 s");
    if (output_.status != RobotStatus::ok) return output_.status;
    const long steps = std::max(1L, std::lround(duration / model_->opt.timestep));
    if (info_.drive == JointDrive::position) {
      for (std::size_t i = 0; i < joints_.size(); ++i)
        data_->ctrl[joints_[i].actuator] = q_target_[static_cast<Eigen::Index>(i)];
      for (long k = 0; k < steps; ++k) {
        apply_push();
        mj_step(model_.get(), data_.get());
        if (check_state()) break;
      }
    } else {
      // The targets ramp from the previous command to this one over the period (the IK's
      // samples are positions at the period's ends): velocity reference = the ramp's slope.
      dq_ref_ = (q_target_ - q_from_) / (double(steps) * model_->opt.timestep);
      for (long k = 0; k < steps; ++k) {
        q_ref_ = q_from_ + (double(k + 1) / double(steps)) * (q_target_ - q_from_);
        apply_push();
        mj_step1(model_.get(), data_.get());  // positions, velocities, contacts, bias forces
        apply_joint_torques();
        mj_step2(model_.get(), data_.get());
        if (check_state()) break;
      }
      q_from_ = q_target_;
    }
    if (output_.status == RobotStatus::ok) mj_forward(model_.get(), data_.get());  // fresh sensors
    read_output();
    return output_.status;
  }

  [[nodiscard]] const StereoImages& render_cameras() override {
    if (camera_ids_[0] < 0) {
      images_.status = RenderStatus::unavailable;
      images_.message =
          "rendering unavailable: the robot has no cameras (MujocoRobotSettings::"
          "cameras is empty)";
      return images_;
    }
    if (!renderer_ready()) return images_;
    for (int c = 0; c < 2; ++c)
      render_camera(camera_ids_[c], c == 0 ? images_.left : images_.right);
    if (settings_.appearance.pixel_noise > 0.0) {
      add_pixel_noise(images_.left);
      add_pixel_noise(images_.right);
    }
    images_.status = RenderStatus::ok;
    images_.message.clear();
    return images_;
  }

  /// Renders the scene from a free camera looking at `lookat` (world frame, [m]) from
  /// `distance` [m], azimuth and elevation [deg] (MuJoCo's convention: azimuth 0 looks along +x,
  /// elevation < 0 looks down), RGB and depth, at most view_width × view_height of the settings.
  /// @return false (and nothing rendered) when rendering is unavailable; render_cameras()'
  ///   message says why.
  /// @throws walkgen::invalid_argument for a size beyond the settings' view size or a
  ///   non-finite view.
  [[nodiscard]] bool render_view(const Eigen::Vector3d& lookat, double distance, double azimuth,
                                 double elevation, int width, int height, CameraImage& image) {
    check_argument(width >= 1 && height >= 1 && width <= settings_.view_width &&
                       height <= settings_.view_height,
                   "MujocoRobot::render_view: size",
                   "within MujocoRobotSettings view_width x view_height = " +
                       std::to_string(settings_.view_width) + " x " +
                       std::to_string(settings_.view_height),
                   std::to_string(width) + " x " + std::to_string(height));
    check_argument(lookat.allFinite() && std::isfinite(distance) && distance > 0.0 &&
                       std::isfinite(azimuth) && std::isfinite(elevation),
                   "MujocoRobot::render_view", "a finite view with distance > 0", "NaN or inf");
    if (!renderer_ready()) return false;
    mjvCamera camera;
    mjv_defaultFreeCamera(model_.get(), &camera);
    for (int i = 0; i < 3; ++i) camera.lookat[i] = lookat[i];
    camera.distance = distance;
    camera.azimuth = azimuth;
    camera.elevation = elevation;
    render_into(camera, width, height, image);
    image.fovy = model_->vis.global.fovy * kPi / 180.0;
    return true;
  }

  /// Moves a movable scene object (SceneObject::movable): `position` is the centre of its base,
  /// as in SceneObject::position; it takes effect from the next step.
  /// @throws walkgen::invalid_argument for an unknown or unmovable object or a non-finite position.
  void set_object_position(const std::string& name, const Eigen::Vector3d& position) {
    check_argument(position.allFinite(), "MujocoRobot::set_object_position", "a finite position",
                   "NaN or inf");
    for (const SceneObject& o : settings_.objects) {
      if (o.name != name) continue;
      check_argument(o.movable, "MujocoRobot::set_object_position",
                     "a movable object (SceneObject::movable)", "'" + name + "'");
      const int body = mj_name2id(model_.get(), mjOBJ_BODY, name.c_str());
      const int mocap = model_->body_mocapid[body];
      const double half_height = o.shape == SceneShape::sphere ? o.size.x() : o.size.z() / 2.0;
      data_->mocap_pos[3 * mocap + 0] = position.x();
      data_->mocap_pos[3 * mocap + 1] = position.y();
      data_->mocap_pos[3 * mocap + 2] = position.z() + half_height;
      return;
    }
    check_argument(false, "MujocoRobot::set_object_position", "the name of a scene object",
                   "'" + name + "'");
  }

  /// Pushes the robot: `force_W` [N] (world frame) on the base body, at its centre of mass,
  /// from simulated time `start_time` for `duration` seconds (a kick: the robot's momentum
  /// changes by force_W · duration). A later call replaces the push; reset() cancels it.
  /// @throws walkgen::invalid_argument for a non-finite force or start time, or a duration
  ///   not > 0.
  void push(const Eigen::Vector3d& force_W, double start_time, double duration) {
    check_argument(force_W.allFinite() && std::isfinite(start_time), "MujocoRobot::push",
                   "a finite force and start time", "NaN or inf");
    check_positive("MujocoRobot::push: duration", duration, "a finite duration > 0 s");
    push_force_ = force_W;
    push_from_ = start_time;
    push_to_ = start_time + duration;
  }

  void reset() override {
    push_from_ = push_to_ = 0.0;
    balance_ = BalanceReference();  // a new walk hands its own
    mj_resetData(model_.get(), data_.get());
    if (keyframe_ >= 0) {
      mj_resetDataKeyframe(model_.get(), data_.get(), keyframe_);
    } else {
      place_in_stand_pose();
    }
    for (std::size_t i = 0; i < joints_.size(); ++i) {
      const auto k = static_cast<Eigen::Index>(i);
      q_target_[k] = keyframe_ >= 0 && info_.drive == JointDrive::position
                         ? model_->key_ctrl[keyframe_ * model_->nu + joints_[i].actuator]
                         : data_->qpos[joints_[i].qpos];
    }
    q_from_ = q_target_;
    for (int a = 0; a < model_->nu && info_.drive == JointDrive::torque; ++a) data_->ctrl[a] = 0.0;
    // Position servos hold the initial pose from the first moment (without a keyframe the
    // controls would be zero, and the first measurement would feel the servos pull).
    for (std::size_t i = 0; i < joints_.size() && info_.drive == JointDrive::position; ++i) {
      data_->ctrl[joints_[i].actuator] = q_target_[static_cast<Eigen::Index>(i)];
    }
    mj_forward(model_.get(), data_.get());
    output_.status = RobotStatus::ok;
    output_.message.clear();
    output_.saturations = 0;
    output_.tau.setZero();
    read_output();
  }

  /// The contact forces on each foot (the wrench the ground and anything else outside the foot
  /// exerts on the foot's bodies) as force-torque readings at the frames of output().ft: the
  /// ankle sensor sites, or the soles when the robot has no sensors (then output().ft itself).
  /// A check of the sensors, or of the centre of pressure: measured_zmp(contact_ft(),
  /// info().ft_sensor_height) is MuJoCo's contact centre of pressure.
  const std::array<ForceTorqueReading, 2>& contact_ft() {
    for (int f = 0; f < 2; ++f) {
      ForceTorqueReading& r = contact_ft_[std::size_t(f)];
      r.pose_W_S = has_ft_sensors() ? pose(data_->site_xpos + 3 * ft_sites_[f],
                                           data_->site_xmat + 9 * ft_sites_[f])
                                    : sole_pose_W(f);
    }
    contact_wrenches(contact_ft_);
    return contact_ft_;
  }

 private:
  struct JointMap {
    int qpos;      ///< address in qpos
    int dof;       ///< address in qvel
    int actuator;  ///< index in ctrl
    int sensor;    ///< address of the jointpos sensor in sensordata, -1: read qpos
  };
  /// A frame fixed to a body: p_W = xpos(body) + xmat(body) * position.
  struct BodyFrame {
    int body = -1;
    Eigen::Vector3d position = Eigen::Vector3d::Zero();
    Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
  };
  struct ModelDeleter {
    void operator()(mjModel* m) const { mj_deleteModel(m); }
  };
  struct DataDeleter {
    void operator()(mjData* d) const { mj_deleteData(d); }
  };

  void load_model() {
    const std::string& path = settings_.model_path;
    check_argument(!path.empty(), "MujocoRobot: model_path", "an MJCF file", "''",
                   "no data folder is known (walkgen::data_dir() is empty): link walkgen's CMake "
                   "target, set the environment variable WALKGEN_DATA_DIR, or pass a path");
    check_argument(std::ifstream(path).good(), "MujocoRobot: model_path", "a readable MJCF file",
                   "'" + path + "' (cannot be opened)");
    char error[1000] = "";
    if (settings_.objects.empty() && settings_.appearance.floor_texture == FloorTexture::model) {
      model_.reset(mj_loadXML(path.c_str(), nullptr, error, sizeof(error)));
    } else {
      model_.reset(load_with_additions(path, error, sizeof(error)));
    }
    std::string reason(error);  // MuJoCo's message spans lines: make it one
    std::replace(reason.begin(), reason.end(), '\n', ' ');
    while (!reason.empty() && reason.back() == ' ') reason.pop_back();
    check_argument(model_ != nullptr, "MujocoRobot: model_path", "a valid MJCF file",
                   "'" + path + "' (MuJoCo: " + reason + ")");
    data_.reset(mj_makeData(model_.get()));
    check_argument(data_ != nullptr, "MujocoRobot", "memory for the simulation data of",
                   "'" + path + "'");
    if (!settings_.slope.isZero()) {  // gravity of the model's size, tilted by the slope
      const Eigen::Vector3d down =
          (Eigen::AngleAxisd(-settings_.slope.y(), Eigen::Vector3d::UnitX()) *
           Eigen::AngleAxisd(settings_.slope.x(), Eigen::Vector3d::UnitY()) *
           Eigen::Vector3d(0.0, 0.0, -1.0));
      const double g = Eigen::Map<const Eigen::Vector3d>(model_->opt.gravity).norm();
      Eigen::Map<Eigen::Vector3d>(model_->opt.gravity) = g * down;
    }
  }

  /// Name of the floor's texture and material that a WorldAppearance adds (not a name that a
  /// SceneObject can have).
  static constexpr const char* kFloorMaterial = "walkgen.floor";

  /// The MJCF of `path` with settings_.objects inserted at the end of its worldbody and the
  /// appearance's floor texture and material in an <asset> section of their own, loaded from
  /// memory (MuJoCo's virtual file system); the files the model includes and its meshes are
  /// read from the model's folder, as when it is loaded from its file.
  mjModel* load_with_additions(const std::string& path, char* error, int error_size) const {
    std::ifstream in(path);
    std::stringstream text;
    text << in.rdbuf();
    std::string xml = text.str();
    const std::size_t end = xml.rfind("</worldbody>");
    check_argument(end != std::string::npos, "MujocoRobot: model_path",
                   "an MJCF with a <worldbody> to add objects to", "'" + path + "'");
    std::ostringstream bodies, assets;
    bodies.precision(17);
    assets.precision(17);
    for (const SceneObject& o : settings_.objects) {  // checked by validate()
      const double half_height = o.shape == SceneShape::sphere ? o.size.x() : o.size.z() / 2.0;
      bodies << "    <body name=\"" << o.name << "\" pos=\"" << o.position.x() << ' '
             << o.position.y() << ' ' << o.position.z() + half_height << "\" euler=\"0 0 " << o.yaw
             << '"' << (o.movable ? " mocap=\"true\"" : "") << ">\n      <geom name=\"" << o.name
             << "\" ";
      switch (o.shape) {
        case SceneShape::box:
          bodies << "type=\"box\" size=\"" << o.size.x() / 2.0 << ' ' << o.size.y() / 2.0 << ' '
                 << half_height << '"';
          break;
        case SceneShape::cylinder:
          bodies << "type=\"cylinder\" size=\"" << o.size.x() << ' ' << half_height << '"';
          break;
        case SceneShape::sphere:
          bodies << "type=\"sphere\" size=\"" << o.size.x() << '"';
          break;
      }
      if (o.textured) {
        const Eigen::Vector3d dark = 0.35 * o.rgb;
        assets << "    <texture name=\"walkgen_" << o.name
               << "\" type=\"cube\" builtin=\"flat\" mark=\"random\" random=\"0.5\" rgb1=\""
               << o.rgb.x() << ' ' << o.rgb.y() << ' ' << o.rgb.z() << "\" markrgb=\"" << dark.x()
               << ' ' << dark.y() << ' ' << dark.z() << "\" width=\"128\" height=\"128\"/>\n"
               << "    <material name=\"walkgen_" << o.name << "\" texture=\"walkgen_" << o.name
               << "\" texuniform=\"true\"/>\n";
        bodies << " material=\"walkgen_" << o.name << '"';
      } else {
        bodies << " rgba=\"" << o.rgb.x() << ' ' << o.rgb.y() << ' ' << o.rgb.z() << " 1\"";
      }
      if (!o.collides) bodies << " contype=\"0\" conaffinity=\"0\"";
      bodies << "/>\n    </body>\n";
    }
    xml.insert(end, bodies.str());
    add_floor_asset(assets);
    if (!assets.str().empty()) {  // an <asset> section of their own, first in the model
      const std::size_t root = xml.find("<mujoco");
      const std::size_t open_end = root == std::string::npos ? root : xml.find('>', root);
      check_argument(open_end != std::string::npos, "MujocoRobot: model_path",
                     "an MJCF with a <mujoco> element", "'" + path + "'");
      xml.insert(open_end + 1, "\n  <asset>\n" + assets.str() + "  </asset>\n");
    }
    // The VFS is large (MuJoCo 2.2: fixed arrays of file names): on the heap, once.
    auto vfs = std::make_unique<mjVFS>();
    mj_defaultVFS(vfs.get());
    // Named as if beside the model file: MuJoCo strips the folder to find it in the VFS, and
    // resolves the model's own includes and mesh files from that folder on disk.
    const std::string name =
        (std::filesystem::path(path).parent_path() / "walkgen_scene_with_objects.xml").string();
    mj_makeEmptyFileVFS(vfs.get(), name.c_str(), int(xml.size()));
    const int index = mj_findFileVFS(vfs.get(), name.c_str());
    std::memcpy(vfs->filedata[index], xml.data(), xml.size());
    mjModel* m = mj_loadXML(name.c_str(), vfs.get(), error, error_size);
    mj_deleteVFS(vfs.get());
    return m;
  }

  /// The texture and material kFloorMaterial of the appearance's floor, if it has its own.
  void add_floor_asset(std::ostream& assets) const {
    const WorldAppearance& a = settings_.appearance;
    if (a.floor_texture == FloorTexture::model) return;
    const Eigen::Vector3d& c1 = a.floor_rgb1;
    const Eigen::Vector3d& c2 = a.floor_rgb2;
    const FloorTexture t = a.floor_texture;
    const bool marked = t == FloorTexture::speckle || t == FloorTexture::tiles;
    const char* builtin = t == FloorTexture::gradient ? "gradient" : marked ? "flat" : "checker";
    // Marks are texels: on a 64-texel texture the dots and joints are ~1 cm, large enough for
    // the cameras (and stereo matching) to see; the model's floor has 512.
    const int texels = marked ? 64 : 512;
    assets << "    <texture name=\"" << kFloorMaterial << "\" type=\"2d\" builtin=\"" << builtin
           << '"';
    if (t == FloorTexture::speckle) assets << " mark=\"random\" random=\"0.3\"";
    if (t == FloorTexture::tiles) assets << " mark=\"edge\"";
    assets << " rgb1=\"" << c1.x() << ' ' << c1.y() << ' ' << c1.z() << '"'
           << (marked ? " markrgb=\"" : " rgb2=\"") << c2.x() << ' ' << c2.y() << ' ' << c2.z()
           << "\" width=\"" << texels << "\" height=\"" << texels << "\"/>\n"
           << "    <material name=\"" << kFloorMaterial << "\" texture=\"" << kFloorMaterial
           << "\" texrepeat=\"8 8\"/>\n";
  }

  /// The appearance's light, floor material and camera pose, on the loaded model (before the
  /// first mj_forward, which places lights and cameras).
  void apply_appearance() {
    const WorldAppearance& a = settings_.appearance;
    mjModel* m = model_.get();
    auto scale = [](float* rgb, double k) {
      for (int i = 0; i < 3; ++i) rgb[i] = static_cast<float>(rgb[i] * k);
    };
    for (int l = 0; l < m->nlight; ++l) {
      scale(m->light_diffuse + 3 * l, a.light_intensity);
      scale(m->light_specular + 3 * l, a.light_intensity);
      scale(m->light_ambient + 3 * l, a.ambient_intensity);
    }
    scale(m->vis.headlight.diffuse, a.light_intensity);
    scale(m->vis.headlight.specular, a.light_intensity);
    scale(m->vis.headlight.ambient, a.ambient_intensity);
    if (a.light_direction) {
      const Eigen::Vector3d d = a.light_direction->normalized();
      int lights = 0;
      for (int l = 0; l < m->nlight; ++l) {
        if (!m->light_directional[l] || m->light_bodyid[l] != 0) continue;
        Eigen::Map<Eigen::Vector3d> pos(m->light_pos + 3 * l);
        pos = -pos.norm() * d;  // as far away as before, against the light
        Eigen::Map<Eigen::Vector3d>(m->light_dir + 3 * l) = d;
        ++lights;
      }
      check_argument(lights > 0, "MujocoRobotSettings.appearance.light_direction",
                     "a model with a directional light in its world body",
                     "'" + settings_.model_path + "' without one");
    }
    if (a.floor_texture != FloorTexture::model) {
      const int material = mj_name2id(m, mjOBJ_MATERIAL, kFloorMaterial);
      int floors = 0;
      for (int g = 0; g < m->ngeom; ++g) {
        if (m->geom_bodyid[g] != 0 || m->geom_type[g] != mjGEOM_PLANE) continue;
        const int before = m->geom_matid[g];
        if (before >= 0 && floors == 0) {  // the floor's repeat and reflection stay
          m->mat_texrepeat[2 * material] = m->mat_texrepeat[2 * before];
          m->mat_texrepeat[2 * material + 1] = m->mat_texrepeat[2 * before + 1];
          m->mat_texuniform[material] = m->mat_texuniform[before];
          m->mat_reflectance[material] = m->mat_reflectance[before];
        }
        m->geom_matid[g] = material;
        ++floors;
      }
      check_argument(floors > 0, "MujocoRobotSettings.appearance.floor_texture",
                     "a model with a floor (a plane geom of the world body)",
                     "'" + settings_.model_path + "' without one");
    }
    if (camera_ids_[0] >= 0 && (!a.camera_offset.isZero() || !a.camera_rotation.isZero())) {
      move_cameras(a.camera_offset, detail::rotation_from_rpy(a.camera_rotation));
    }
    noise_rng_.seed(a.noise_seed);
  }

  /// Moves the camera pair as one: rotated by R about the middle between the cameras and
  /// shifted by `offset`, both in the frame of the body that carries them (or of the parent of
  /// the joint-free bodies that carry one each).
  void move_cameras(const Eigen::Vector3d& offset, const Eigen::Matrix3d& R) {
    mjModel* m = model_.get();
    auto from_pos_quat = [](const mjtNum* pos, const mjtNum* quat) {  // quat: w, x, y, z
      Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
      T.linear() = Eigen::Quaterniond(quat[0], quat[1], quat[2], quat[3]).normalized().matrix();
      T.translation() = Eigen::Map<const Eigen::Vector3d>(pos);
      return T;
    };
    std::array<int, 2> body{};
    std::array<Eigen::Isometry3d, 2> F_b, F_c;  // body and camera in the common frame F
    for (int i = 0; i < 2; ++i) body[i] = m->cam_bodyid[camera_ids_[i]];
    const bool one_body = body[0] == body[1];
    const bool siblings = m->body_parentid[body[0]] == m->body_parentid[body[1]] &&
                          m->body_jntnum[body[0]] == 0 && m->body_jntnum[body[1]] == 0;
    check_argument(
        one_body || siblings, "MujocoRobotSettings.appearance: camera_offset, camera_rotation",
        "cameras in one body or in joint-free bodies of one parent",
        "cameras '" + settings_.cameras[0] + "', '" + settings_.cameras[1] + "' elsewhere",
        "leave the camera pose at zero for this model");
    for (int i = 0; i < 2; ++i) {
      const int c = camera_ids_[i];
      F_b[i] = one_body ? Eigen::Isometry3d::Identity()
                        : from_pos_quat(m->body_pos + 3 * body[i], m->body_quat + 4 * body[i]);
      F_c[i] = F_b[i] * from_pos_quat(m->cam_pos + 3 * c, m->cam_quat + 4 * c);
    }
    const Eigen::Vector3d middle = 0.5 * (F_c[0].translation() + F_c[1].translation());
    for (int i = 0; i < 2; ++i) {
      const int c = camera_ids_[i];
      Eigen::Isometry3d moved = Eigen::Isometry3d::Identity();
      moved.linear() = R * F_c[i].linear();
      moved.translation() = middle + R * (F_c[i].translation() - middle) + offset;
      const Eigen::Isometry3d b_c = F_b[i].inverse() * moved;
      Eigen::Map<Eigen::Vector3d>(m->cam_pos + 3 * c) = b_c.translation();
      const Eigen::Quaterniond q(b_c.linear());
      m->cam_quat[4 * c + 0] = q.w();
      m->cam_quat[4 * c + 1] = q.x();
      m->cam_quat[4 * c + 2] = q.y();
      m->cam_quat[4 * c + 3] = q.z();
    }
  }

  /// Gaussian noise of the appearance's pixel_noise on every channel of `image` (rounded,
  /// clipped to 0–255), from the robot's noise stream.
  void add_pixel_noise(CameraImage& image) {
    std::normal_distribution<double> noise(0.0, settings_.appearance.pixel_noise);
    for (std::uint8_t& v : image.rgb) {
      v = static_cast<std::uint8_t>(
          std::clamp(std::lround(double(v) + noise(noise_rng_)), long(0), long(255)));
    }
  }

  /// The sensor `name` of `type` and `dim` values, or -1 (and `name` added to `missing`).
  int sensor_address(const std::string& name, int type, int dim,
                     std::vector<std::string>& missing) {
    const int id = mj_name2id(model_.get(), mjOBJ_SENSOR, name.c_str());
    if (id < 0 || model_->sensor_type[id] != type || model_->sensor_dim[id] != dim) {
      missing.push_back("sensor '" + name + "'");
      return -1;
    }
    return model_->sensor_adr[id];
  }

  /// The sole frame `name`: a site of the model or a frame the settings add; body -1 (and the
  /// name added to `missing`) when neither.
  BodyFrame find_frame(const std::string& name, std::vector<std::string>& missing) const {
    const mjModel* m = model_.get();
    BodyFrame frame;
    const int site = mj_name2id(m, mjOBJ_SITE, name.c_str());
    if (site >= 0) {
      frame.body = m->site_bodyid[site];
      frame.position = Eigen::Map<const Eigen::Vector3d>(m->site_pos + 3 * site);
      const mjtNum* q = m->site_quat + 4 * site;  // w, x, y, z
      frame.rotation = Eigen::Quaterniond(q[0], q[1], q[2], q[3]).normalized().toRotationMatrix();
      return frame;
    }
    for (const FrameDescription& f : settings_.frames) {
      if (f.name != name) continue;
      frame.body = mj_name2id(m, mjOBJ_BODY, f.body.c_str());
      if (frame.body < 0) {
        missing.push_back("body '" + f.body + "' (of frame '" + name + "')");
        return frame;
      }
      frame.position = f.xyz;
      frame.rotation = detail::rotation_from_rpy(f.rpy);
      return frame;
    }
    missing.push_back("site or added frame '" + name + "'");
    return frame;
  }

  void map_names() {
    const mjModel* m = model_.get();
    std::vector<std::string> missing;
    std::vector<bool> ours(static_cast<std::size_t>(m->nu), false);
    int motors = 0;
    for (const std::string& name : settings_.joint_names) {
      JointMap map{-1, -1, -1, -1};
      const int joint = mj_name2id(m, mjOBJ_JOINT, name.c_str());
      if (joint < 0 || (m->jnt_type[joint] != mjJNT_HINGE && m->jnt_type[joint] != mjJNT_SLIDE)) {
        missing.push_back("joint '" + name + "'");
        joints_.push_back(map);
        continue;
      }
      map.qpos = m->jnt_qposadr[joint];
      map.dof = m->jnt_dofadr[joint];
      for (int a = 0; a < m->nu && map.actuator < 0; ++a) {
        if (m->actuator_trntype[a] == mjTRN_JOINT && m->actuator_trnid[2 * a] == joint) {
          map.actuator = a;
        }
      }
      if (map.actuator < 0) {
        missing.push_back("an actuator on joint '" + name + "'");
      } else {
        ours[static_cast<std::size_t>(map.actuator)] = true;
        const int a = map.actuator;
        const bool motor =
            m->actuator_gaintype[a] == mjGAIN_FIXED && m->actuator_biastype[a] == mjBIAS_NONE;
        const bool servo =
            m->actuator_gaintype[a] == mjGAIN_FIXED && m->actuator_biastype[a] == mjBIAS_AFFINE &&
            m->actuator_biasprm[mjNBIAS * a + 1] == -m->actuator_gainprm[mjNGAIN * a];
        check_argument(motor || servo,
                       ("MujocoRobot: the actuator on joint '" + name + "'").c_str(),
                       "a <motor> or a <position> servo", "another kind of actuator");
        motors += motor;
      }
      for (int k = 0; k < m->nsensor && map.sensor < 0; ++k) {
        if (m->sensor_type[k] == mjSENS_JOINTPOS && m->sensor_objid[k] == joint) {
          map.sensor = m->sensor_adr[k];
        }
      }
      joints_.push_back(map);
    }
    if (has_ft_sensors()) {
      for (int f = 0; f < 2; ++f) {
        const std::string& site = settings_.ft_sensor_sites[f];
        ft_sites_[f] = mj_name2id(m, mjOBJ_SITE, site.c_str());
        if (ft_sites_[f] < 0) missing.push_back("site '" + site + "'");
        ft_force_[f] = sensor_address(site + "_force", mjSENS_FORCE, 3, missing);
        ft_torque_[f] = sensor_address(site + "_torque", mjSENS_TORQUE, 3, missing);
      }
    }
    if (!settings_.imu_site.empty()) {
      const std::string& site = settings_.imu_site;
      imu_quat_ = sensor_address(site + "_quat", mjSENS_FRAMEQUAT, 4, missing);
      imu_gyro_ = sensor_address(site + "_gyro", mjSENS_GYRO, 3, missing);
      imu_acc_ = sensor_address(site + "_acc", mjSENS_ACCELEROMETER, 3, missing);
    }
    for (int f = 0; f < 2; ++f) {
      if (!settings_.sole_frames[0].empty())
        soles_[f] = find_frame(settings_.sole_frames[f], missing);
      if (settings_.cameras[0].empty()) continue;
      camera_ids_[f] = mj_name2id(m, mjOBJ_CAMERA, settings_.cameras[f].c_str());
      if (camera_ids_[f] < 0) missing.push_back("camera '" + settings_.cameras[f] + "'");
    }
    base_body_ = mj_name2id(m, mjOBJ_BODY, settings_.base_body.c_str());
    if (base_body_ < 0) missing.push_back("body '" + settings_.base_body + "'");
    keyframe_ = -1;
    if (!settings_.keyframe.empty()) {
      keyframe_ = mj_name2id(m, mjOBJ_KEY, settings_.keyframe.c_str());
      if (keyframe_ < 0) missing.push_back("keyframe '" + settings_.keyframe + "'");
    }
    for (const JointAngle& a : settings_.stand_pose) {  // used without a keyframe only
      if (keyframe_ >= 0 || !settings_.keyframe.empty()) break;
      bool named = false;
      for (const std::string& j : settings_.joint_names) named = named || j == a.joint;
      if (!named) missing.push_back("stand_pose joint '" + a.joint + "' among the joint names");
    }
    if (!missing.empty()) {
      std::string list;
      for (const std::string& s : missing) list += (list.empty() ? "" : ", ") + s;
      throw invalid_argument("MujocoRobot: '" + settings_.model_path +
                             "' lacks what the settings name: " + list +
                             " (hint: MujocoRobotSettings names joints, sensor sites, soles, "
                             "cameras, the base body and the keyframe; the model has " +
                             model_inventory() + ")");
    }
    const int n = static_cast<int>(joints_.size());
    check_argument(motors == 0 || motors == n, "MujocoRobot: actuators",
                   "all position servos or all motors",
                   std::to_string(motors) + " motors of " + std::to_string(n) + " joints");
    info_.drive = motors > 0 ? JointDrive::torque : JointDrive::position;
    for (int a = 0; a < m->nu; ++a) {  // servos of other joints would hold them at 0 rad
      const bool motor = m->actuator_biastype[a] == mjBIAS_NONE;
      check_argument(
          ours[static_cast<std::size_t>(a)] || (info_.drive == JointDrive::torque && motor),
          "MujocoRobot: actuators", std::to_string(n) + " (one per joint name)", m->nu,
          "every actuator of the model must be driven by a named joint, or be a motor "
          "(then it gets zero torque)");
    }
    // Each body's foot (0 left, 1 right, -1 neither): the sole body and its descendants.
    foot_of_body_.assign(static_cast<std::size_t>(m->nbody), -1);
    for (int b = 1; b < m->nbody; ++b) {
      for (int a = b; a > 0; a = m->body_parentid[a]) {
        for (int f = 0; f < 2; ++f) {
          if (soles_[f].body == a) foot_of_body_[static_cast<std::size_t>(b)] = f;
        }
      }
    }
    check_argument(has_ft_sensors() || soles_[0].body >= 0, "MujocoRobot: sole_frames",
                   "sole frames for the contact readings of a robot without ankle sensors", "none");
  }

  /// What a model has, for error messages: its joints and sites.
  std::string model_inventory() const {
    const mjModel* m = model_.get();
    std::string joints, sites;
    for (int j = 0; j < m->njnt; ++j) {
      if (m->jnt_type[j] != mjJNT_FREE)
        joints += (joints.empty() ? "" : ", ") +
                  std::string(mj_id2name(m, mjOBJ_JOINT, j) ? mj_id2name(m, mjOBJ_JOINT, j) : "?");
    }
    for (int k = 0; k < m->nsite; ++k) {
      const char* name = mj_id2name(m, mjOBJ_SITE, k);
      sites += (sites.empty() ? "" : ", ") + std::string(name ? name : "?");
    }
    return "joints [" + joints + "], sites [" + sites + "]";
  }

  bool has_ft_sensors() const { return !settings_.ft_sensor_sites[0].empty(); }

  /// The joint controller of a torque-driven robot: the settings' gains, ctrlrange limits.
  void make_controller() {
    const auto n = static_cast<Eigen::Index>(joints_.size());
    std::string without;
    for (Eigen::Index i = 0; i < n; ++i) {
      const bool has = settings_.kp.size() == n && std::isfinite(settings_.kp[i]) &&
                       std::isfinite(settings_.kd[i]);
      if (!has)
        without += (without.empty() ? "'" : ", '") + settings_.joint_names[std::size_t(i)] + "'";
    }
    check_argument(without.empty(), "MujocoRobot: torque-driven joints", "PD gains for every one",
                   "none for " + without,
                   "add the joints to a joint group (joint_groups: {name: {joints, kp, kd}}) of "
                   "the robot description, or set MujocoRobotSettings::kp and kd");
    Eigen::VectorXd lo(n), hi(n);
    for (Eigen::Index i = 0; i < n; ++i) {
      const int a = joints_[std::size_t(i)].actuator;
      const bool limited = model_->actuator_ctrllimited[a] != 0;
      lo[i] = limited ? model_->actuator_ctrlrange[2 * a] : -mjMAXVAL;
      hi[i] = limited ? model_->actuator_ctrlrange[2 * a + 1] : mjMAXVAL;
    }
    controller_.emplace(settings_.kp, settings_.kd, lo, hi);
  }

  /// The world pose of sole `f`.
  Eigen::Isometry3d sole_pose_W(int f) const {
    const BodyFrame& s = soles_[f];
    const Eigen::Isometry3d body = pose(data_->xpos + 3 * s.body, data_->xmat + 9 * s.body);
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.linear() = body.linear() * s.rotation;
    T.translation() = body * s.position;
    return T;
  }

  /// Without a keyframe: the stand pose's joints set, the base moved vertically so that the
  /// lower sole is at z = 0 (touching the floor; the model's qpos0 when there are no soles).
  void place_in_stand_pose() {
    for (const JointAngle& a : settings_.stand_pose) {
      for (std::size_t i = 0; i < joints_.size(); ++i) {
        if (settings_.joint_names[i] == a.joint) data_->qpos[joints_[i].qpos] = a.angle;
      }
    }
    mj_kinematics(model_.get(), data_.get());
    const int root_joint =
        model_->body_jntnum[base_body_] > 0 ? model_->body_jntadr[base_body_] : -1;
    if (soles_[0].body < 0 || root_joint < 0 || model_->jnt_type[root_joint] != mjJNT_FREE) return;
    const double lowest =
        std::min(sole_pose_W(0).translation().z(), sole_pose_W(1).translation().z());
    data_->qpos[model_->jnt_qposadr[root_joint] + 2] -= lowest;
  }

  /// Sets the motors' torques for the state after mj_step1 (torque drive).
  void apply_joint_torques() {
    const mjData* d = data_.get();
    for (std::size_t i = 0; i < joints_.size(); ++i) {
      const auto k = static_cast<Eigen::Index>(i);
      q_now_[k] = d->qpos[joints_[i].qpos];
      dq_now_[k] = d->qvel[joints_[i].dof];
    }
    feedforward_torques();
    const JointTorqueResult r =
        controller_->compute(q_ref_, dq_ref_, tau_ff_, q_now_, dq_now_, output_.tau);
    output_.saturations += r.saturated;
    for (std::size_t i = 0; i < joints_.size(); ++i) {
      data_->ctrl[joints_[i].actuator] = output_.tau[static_cast<Eigen::Index>(i)];
    }
  }

  /// tau_ff_ for the settings' JointFeedforward at the current state (after mj_step1).
  void feedforward_torques() {
    const mjModel* m = model_.get();
    mjData* d = data_.get();
    if (settings_.feedforward == JointFeedforward::none) {
      tau_ff_.setZero();
      return;
    }
    for (std::size_t i = 0; i < joints_.size(); ++i) {
      tau_ff_[static_cast<Eigen::Index>(i)] = d->qfrc_bias[joints_[i].dof];
    }
    if (settings_.feedforward == JointFeedforward::gravity) return;
    std::array<bool, 2> contact{{false, false}};
    for (int c = 0; c < d->ncon; ++c) {
      const int f1 = foot_of_body_[std::size_t(m->geom_bodyid[d->contact[c].geom1])];
      const int f2 = foot_of_body_[std::size_t(m->geom_bodyid[d->contact[c].geom2])];
      if (f1 >= 0 && f2 != f1) contact[std::size_t(f1)] = true;
      if (f2 >= 0 && f1 != f2) contact[std::size_t(f2)] = true;
    }
    if (!contact[0] && !contact[1]) return;
    // The CoM's ground projection r, shared between the soles s_L, s_R by its place along
    // the segment between them; each foot's force at its sole shifted by the same offset, so
    // that the forces' centre of pressure is r.
    Eigen::Vector3d r(d->subtree_com[3 * base_body_], d->subtree_com[3 * base_body_ + 1], 0.0);
    const Eigen::Vector3d s[2] = {sole_pose_W(0).translation(), sole_pose_W(1).translation()};
    Eigen::Vector3d acceleration = Eigen::Vector3d::Zero();  // of the CoM, in the plane
    if (settings_.feedforward == JointFeedforward::balance && balance_.valid) {
      const int f = balance_.support;
      const Eigen::Isometry3d sole = sole_pose_W(f);
      const double yaw = std::atan2(sole.linear()(1, 0), sole.linear()(0, 0));
      const Eigen::Rotation2Dd R(yaw);
      mj_subtreeVel(m, d);
      const Eigen::Vector2d c = r.head<2>();
      const Eigen::Vector2d v(d->subtree_linvel[3 * base_body_],
                              d->subtree_linvel[3 * base_body_ + 1]);
      const Eigen::Vector2d c_ref = sole.translation().head<2>() + R * balance_.com;
      const Eigen::Vector2d a = R * balance_.com_acceleration + settings_.balance_kp * (c_ref - c) +
                                settings_.balance_kd * (R * balance_.com_velocity - v);
      const double height = d->subtree_com[3 * base_body_ + 2] - sole.translation().z();
      const double g = -m->opt.gravity[2];
      r.head<2>() = c - height / g * a;
      acceleration.head<2>() = a;
    }
    double left = contact[0] ? 1.0 : 0.0;
    if (contact[0] && contact[1]) {
      const Eigen::Vector2d between = (s[0] - s[1]).head<2>();
      const double length2 = between.squaredNorm();
      left =
          length2 > 1e-12 ? std::clamp((r - s[1]).head<2>().dot(between) / length2, 0.0, 1.0) : 0.5;
    }
    const Eigen::Vector3d centre = left * s[0] + (1.0 - left) * s[1];
    const double weight = m->body_subtreemass[base_body_] * -m->opt.gravity[2];
    for (int f = 0; f < 2; ++f) {
      const double share = f == 0 ? left : 1.0 - left;
      if (share <= 0.0) continue;
      Eigen::Vector3d point = s[f] + (r - centre);
      point.z() = s[f].z();
      mj_jac(m, d, jacobian_.data(), nullptr, point.data(), soles_[f].body);
      const double mass = m->body_subtreemass[base_body_];
      for (std::size_t i = 0; i < joints_.size(); ++i) {
        // The ground pushes the foot up with share * m g (and sideways with share * m c̈):
        // tau -= J^T f.
        const auto dof = std::size_t(joints_[i].dof);
        tau_ff_[static_cast<Eigen::Index>(i)] -=
            share * (jacobian_[2 * std::size_t(m->nv) + dof] * weight +
                     mass * (jacobian_[dof] * acceleration.x() +
                             jacobian_[std::size_t(m->nv) + dof] * acceleration.y()));
      }
    }
  }

  /// The contact wrenches on each foot, at the poses already in `readings`.
  void contact_wrenches(std::array<ForceTorqueReading, 2>& readings) const {
    const mjModel* m = model_.get();
    const mjData* d = data_.get();
    Eigen::Vector3d force[2] = {Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()};
    Eigen::Vector3d torque[2] = {Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()};
    for (int c = 0; c < d->ncon; ++c) {
      const mjContact& con = d->contact[c];
      const int f1 = foot_of_body_[std::size_t(m->geom_bodyid[con.geom1])];
      const int f2 = foot_of_body_[std::size_t(m->geom_bodyid[con.geom2])];
      if (f1 == f2) continue;
      mjtNum local[6];
      mj_contactForce(m, d, c, local);
      // The contact frame's rows are the normal (from geom1 to geom2) and two tangents; the
      // force acts on geom2, its opposite on geom1.
      const Eigen::Map<const Eigen::Matrix<mjtNum, 3, 3, Eigen::RowMajor>> frame(con.frame);
      const Eigen::Vector3d on_geom2 =
          frame.transpose() * Eigen::Vector3d(local[0], local[1], local[2]);
      const Eigen::Vector3d at(con.pos[0], con.pos[1], con.pos[2]);
      for (int f = 0; f < 2; ++f) {
        const double sign = f2 == f ? 1.0 : f1 == f ? -1.0 : 0.0;
        if (sign == 0.0) continue;
        const Eigen::Vector3d on_foot = sign * on_geom2;
        force[f] += on_foot;
        torque[f] += (at - readings[std::size_t(f)].pose_W_S.translation()).cross(on_foot);
      }
    }
    for (int f = 0; f < 2; ++f) {
      ForceTorqueReading& r = readings[std::size_t(f)];
      r.force_S = r.pose_W_S.linear().transpose() * force[f];
      r.torque_S = r.pose_W_S.linear().transpose() * torque[f];
    }
  }

  /// Entry `index` of <custom><numeric name=...>, or `fallback` when the model has none.
  double custom_numeric(const char* name, int index, double fallback) const {
    const int id = mj_name2id(model_.get(), mjOBJ_NUMERIC, name);
    if (id < 0 || model_->numeric_size[id] <= index) return fallback;
    return model_->numeric_data[model_->numeric_adr[id] + index];
  }

  /// Checks the state after a physics step; true when the robot stopped.
  /// The force of push() on the base while the step at data_->time lies in its interval.
  void apply_push() {
    const double t = data_->time, half = 0.5 * model_->opt.timestep;
    const bool pushing = t >= push_from_ - half && t < push_to_ - half;
    for (int i = 0; i < 3; ++i) {
      data_->xfrc_applied[6 * base_body_ + i] = pushing ? push_force_[i] : 0.0;
    }
  }

  bool check_state() {
    const mjModel* m = model_.get();
    const mjData* d = data_.get();
    bool finite = d->warning[mjWARN_BADQACC].number == 0 &&
                  d->warning[mjWARN_BADQPOS].number == 0 && d->warning[mjWARN_BADQVEL].number == 0;
    for (int i = 0; finite && i < m->nq; ++i) finite = std::isfinite(d->qpos[i]);
    for (int i = 0; finite && i < m->nv; ++i) finite = std::isfinite(d->qvel[i]);
    std::ostringstream os;
    if (!finite) {
      output_.status = RobotStatus::diverged;
      os << "simulation diverged at t = " << d->time << " s (non-finite or unstable state)";
    } else if (d->xpos[3 * base_body_ + 2] < info_.fall_height) {
      output_.status = RobotStatus::fallen;
      os << "fallen at t = " << d->time << " s: base height " << d->xpos[3 * base_body_ + 2]
         << " m < " << info_.fall_height << " m";
    } else {
      return false;
    }
    output_.message = os.str();
    return true;
  }

  static Eigen::Isometry3d pose(const mjtNum* pos, const mjtNum* mat) {
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.linear() = Eigen::Map<const Eigen::Matrix<mjtNum, 3, 3, Eigen::RowMajor>>(mat);
    T.translation() = Eigen::Map<const Eigen::Vector3d>(pos);
    return T;
  }

  void read_output() {
    const mjData* d = data_.get();
    output_.time = d->time;
    for (std::size_t i = 0; i < joints_.size(); ++i) {
      const auto k = static_cast<Eigen::Index>(i);
      const JointMap& j = joints_[i];
      output_.q[k] = j.sensor >= 0 ? d->sensordata[j.sensor] : d->qpos[j.qpos];
      output_.dq[k] = d->qvel[j.dof];
      if (info_.drive == JointDrive::position) output_.tau[k] = d->actuator_force[j.actuator];
    }
    if (has_ft_sensors()) {
      for (int f = 0; f < 2; ++f) {
        // MuJoCo reports the wrench the parent (leg) exerts on the child (foot): negate it.
        ForceTorqueReading& r = output_.ft[f];
        r.force_S = -Eigen::Map<const Eigen::Vector3d>(d->sensordata + ft_force_[f]);
        r.torque_S = -Eigen::Map<const Eigen::Vector3d>(d->sensordata + ft_torque_[f]);
        r.pose_W_S = pose(d->site_xpos + 3 * ft_sites_[f], d->site_xmat + 9 * ft_sites_[f]);
      }
    } else {
      for (int f = 0; f < 2; ++f) output_.ft[std::size_t(f)].pose_W_S = sole_pose_W(f);
      contact_wrenches(output_.ft);
    }
    output_.base_height = d->xpos[3 * base_body_ + 2];
    ImuReading& imu = output_.imu;
    imu.available = imu_quat_ >= 0;
    if (imu.available) {
      const mjtNum* q = d->sensordata + imu_quat_;  // w, x, y, z
      imu.orientation_W_I = Eigen::Quaterniond(q[0], q[1], q[2], q[3]);
      imu.angular_velocity_I = Eigen::Map<const Eigen::Vector3d>(d->sensordata + imu_gyro_);
      imu.acceleration_I = Eigen::Map<const Eigen::Vector3d>(d->sensordata + imu_acc_);
    }
  }

  /// Creates the GL context and MuJoCo's renderer once; false (status set) when impossible.
  bool renderer_ready() {
    if (gl_ == nullptr) {
      gl_ = std::make_unique<detail::EglContext>();
      if (gl_->make_current()) {
        model_->vis.global.offwidth =
            std::max({model_->vis.global.offwidth, info_.image_width, settings_.view_width});
        model_->vis.global.offheight =
            std::max({model_->vis.global.offheight, info_.image_height, settings_.view_height});
        // No multisampling: a resolved multisample depth buffer holds one sample per pixel, off the
        // pixel's centre (a third of a pixel, 1.6 % of the depth at 10 m on the floor).
        model_->vis.quality.offsamples = 0;
        mjv_defaultScene(&scene_);
        mjv_makeScene(model_.get(), &scene_, 2000);
        scene_made_ = true;
        mjv_defaultOption(&vis_option_);
        mjr_defaultContext(&render_context_);
        mjr_makeContext(model_.get(), &render_context_, mjFONTSCALE_100);
        render_context_made_ = true;
        mjr_setBuffer(mjFB_OFFSCREEN, &render_context_);
        if (render_context_.currentBuffer != mjFB_OFFSCREEN) {
          render_error_ = "MuJoCo has no offscreen framebuffer in this GL context";
        }
      } else {
        render_error_ = gl_->error();
      }
    }
    if (render_error_.empty() && !gl_->make_current()) render_error_ = gl_->error();
    if (!render_error_.empty()) {
      images_.status = RenderStatus::unavailable;
      images_.message = "rendering unavailable: " + render_error_;
      return false;
    }
    return true;
  }

  void render_camera(int camera_id, CameraImage& image) {
    mjvCamera camera;
    mjv_defaultCamera(&camera);
    camera.type = mjCAMERA_FIXED;
    camera.fixedcamid = camera_id;
    render_into(camera, info_.image_width, info_.image_height, image);
    image.fovy = model_->cam_fovy[camera_id] * kPi / 180.0;
    // MuJoCo's camera looks along its -z with y up; ours looks along x with z up.
    const Eigen::Isometry3d mujoco_camera =
        pose(data_->cam_xpos + 3 * camera_id, data_->cam_xmat + 9 * camera_id);
    Eigen::Matrix3d C_from_mujoco;
    C_from_mujoco << 0, 0, -1, -1, 0, 0, 0, 1, 0;  // rows: our x, y, z in MuJoCo's camera frame
    image.pose_W_C = mujoco_camera;
    image.pose_W_C.linear() = mujoco_camera.linear() * C_from_mujoco.transpose();
  }

  /// Renders `camera` into image (w × h, RGB and depth in metres, top row first).
  void render_into(const mjvCamera& camera, int w, int h, CameraImage& image) {
    mjv_updateScene(model_.get(), data_.get(), &vis_option_, nullptr,
                    const_cast<mjvCamera*>(&camera), mjCAT_ALL, &scene_);
    const mjrRect viewport{0, 0, w, h};
    mjr_render(viewport, &scene_, &render_context_);
    rgb_flipped_.resize(static_cast<std::size_t>(w) * h * 3);
    depth_flipped_.resize(static_cast<std::size_t>(w) * h);
    mjr_readPixels(rgb_flipped_.data(), depth_flipped_.data(), viewport, &render_context_);

    image.width = w;
    image.height = h;
    image.rgb.resize(rgb_flipped_.size());
    image.depth.resize(depth_flipped_.size());
    // The clipping planes MuJoCo's frustum used (the model's znear, zfar times its extent).
    image.near_clip = scene_.camera[0].frustum_near;
    image.far_clip = scene_.camera[0].frustum_far;
    const double n = image.near_clip;
    const double f = image.far_clip;
    for (int row = 0; row < h; ++row) {  // OpenGL's rows start at the bottom
      const std::size_t src = static_cast<std::size_t>(h - 1 - row) * w;
      const std::size_t dst = static_cast<std::size_t>(row) * w;
      std::copy_n(rgb_flipped_.data() + 3 * src, 3 * w, image.rgb.data() + 3 * dst);
      for (int col = 0; col < w; ++col) {  // depth buffer [0, 1] -> metres (perspective)
        const double z = depth_flipped_[src + col];
        image.depth[dst + col] = static_cast<float>(n * f / (f - z * (f - n)));
      }
    }
  }

  MujocoRobotSettings settings_;
  RobotInfo info_;
  std::unique_ptr<mjModel, ModelDeleter> model_;
  std::unique_ptr<mjData, DataDeleter> data_;
  std::vector<JointMap> joints_;
  std::array<int, 2> ft_sites_{{-1, -1}};
  std::array<int, 2> ft_force_{{-1, -1}};
  int imu_quat_ = -1, imu_gyro_ = -1, imu_acc_ = -1;  ///< sensordata addresses, -1: no IMU
  std::array<int, 2> ft_torque_{{-1, -1}};
  std::array<int, 2> camera_ids_{{-1, -1}};
  std::array<BodyFrame, 2> soles_;
  std::vector<int> foot_of_body_;
  int base_body_ = -1;
  Eigen::Vector3d push_force_ = Eigen::Vector3d::Zero();  ///< [N] push(), world frame
  double push_from_ = 0.0, push_to_ = 0.0;                ///< [s] push()'s interval
  int keyframe_ = -1;
  Eigen::VectorXd q_target_;
  RobotOutput output_;
  std::array<ForceTorqueReading, 2> contact_ft_;

  // Torque drive: the controller and its buffers (sized once).
  std::optional<JointTorqueController> controller_;
  BalanceReference balance_;  ///< set_balance_reference(): JointFeedforward::balance
  Eigen::VectorXd q_from_, q_ref_, dq_ref_, tau_ff_, q_now_, dq_now_;
  std::vector<mjtNum> jacobian_;  ///< 3 x nv, row-major (mj_jac)

  // Rendering, created on the first render_cameras().
  std::unique_ptr<detail::EglContext> gl_;
  std::string render_error_;
  mjvScene scene_{};
  mjvOption vis_option_{};
  mjrContext render_context_{};
  bool scene_made_ = false;
  bool render_context_made_ = false;
  std::vector<unsigned char> rgb_flipped_;
  std::vector<float> depth_flipped_;
  StereoImages images_;
  std::mt19937 noise_rng_;  ///< the chest cameras' pixel noise (WorldAppearance::noise_seed)
};

}  // namespace walkgen
