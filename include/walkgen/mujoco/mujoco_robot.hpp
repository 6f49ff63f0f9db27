#pragma once
/// @file
/// MuJoCo simulation backend of the robot interface (walkgen/robot/robot.hpp). Target
/// walkgen::mujoco (Debian: libmujoco-dev, and libegl1 + libegl-mesa0 for the cameras); the core
/// never includes this header.
///
/// Loads an MJCF (walkgen's humanoid, models/walkgen_humanoid.xml, unless told otherwise), maps
/// the joint names to MuJoCo joints, position actuators and `<joint>_pos` sensors and the ankle
/// sensor sites to their `<site>_force` / `<site>_torque` sensors by name, runs headless at the
/// model's timestep, and renders the chest cameras offscreen through EGL (Mesa's surfaceless
/// platform, software rendering). Divergence (non-finite state, MuJoCo's bad-acceleration reset)
/// and falls (base below fall_height_ratio of its height in the initial keyframe) stop the robot
/// and are reported in its status.

#include <mujoco/mujoco.h>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "walkgen/core/data_dir.hpp"
#include "walkgen/core/exceptions.hpp"
#include "walkgen/core/math.hpp"
#include "walkgen/mujoco/detail/egl_context.hpp"
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

/// How a MujocoRobot maps our names onto the model. The defaults describe walkgen's humanoid
/// (walkgen_humanoid_description()); mujoco_robot_settings() takes them from any description.
struct MujocoRobotSettings {
  /// MJCF file; empty: humanoid_mjcf_path().
  std::string model_path;
  /// Our joints, in command/measurement order; each needs a MuJoCo joint of that name, a
  /// position actuator of that name on it and a jointpos sensor "<name>_pos".
  std::vector<std::string> joint_names = walkgen_humanoid_description().joint_names;
  /// Ankle sensor sites (left, right) with force/torque sensors "<site>_force", "<site>_torque".
  std::array<std::string, 2> ft_sensor_sites = walkgen_humanoid_description().ft_sensor_frames;
  /// Chest cameras (left, right).
  std::array<std::string, 2> cameras = walkgen_humanoid_description().cameras;
  /// The floating base, whose height tells a fall.
  std::string base_body = walkgen_humanoid_description().base_body;
  /// Initial state (qpos, ctrl); empty: the model's qpos0 with zero targets.
  std::string keyframe = walkgen_humanoid_description().stand_keyframe;
  /// Fallen when the base is below this fraction of its initial height.
  double fall_height_ratio = 0.8;
  /// Static objects added to the world of the model (the model file itself is not changed).
  std::vector<SceneObject> objects;
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
    check_argument((o.rgb.array() >= 0.0).all() && (o.rgb.array() <= 1.0).all(),
                   (where + " rgb").c_str(), "values in [0, 1]", "out of range");
  }
}

/// The settings that load `robot`'s MJCF with its names (joints, ankle sensor sites, cameras,
/// base, standing keyframe); the rest at their defaults.
inline MujocoRobotSettings mujoco_robot_settings(const RobotDescription& robot) {
  MujocoRobotSettings s;
  s.model_path = robot.mjcf_path;
  s.joint_names = robot.joint_names;
  s.ft_sensor_sites = robot.ft_sensor_frames;
  s.cameras = robot.cameras;
  s.base_body = robot.base_body;
  s.keyframe = robot.stand_keyframe;
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
    info_.joint_names = settings_.joint_names;
    info_.timestep = model_->opt.timestep;
    info_.ft_sensor_height = custom_numeric("ft_sensor_height", 0, 0.0);
    info_.image_width = static_cast<int>(custom_numeric("camera_resolution", 0, 320));
    info_.image_height = static_cast<int>(custom_numeric("camera_resolution", 1, 240));
    check_positive("MujocoRobot: <numeric name='ft_sensor_height'>", info_.ft_sensor_height,
                   "a sensor height > 0 m in the model's <custom> section");
    const int n = static_cast<int>(settings_.joint_names.size());
    q_target_ = Eigen::VectorXd::Zero(n);
    output_.q.resize(n);
    output_.dq.resize(n);
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

  [[nodiscard]] RobotStatus step(double duration) override {
    check_positive("MujocoRobot::step: duration", duration, "a finite duration > 0 s");
    if (output_.status != RobotStatus::ok) return output_.status;
    for (std::size_t i = 0; i < joints_.size(); ++i)
      data_->ctrl[joints_[i].actuator] = q_target_[i];
    const long steps = std::max(1L, std::lround(duration / model_->opt.timestep));
    for (long k = 0; k < steps; ++k) {
      mj_step(model_.get(), data_.get());
      if (check_state()) break;
    }
    if (output_.status == RobotStatus::ok) mj_forward(model_.get(), data_.get());  // fresh sensors
    read_output();
    return output_.status;
  }

  [[nodiscard]] const StereoImages& render_cameras() override {
    if (!renderer_ready()) return images_;
    for (int c = 0; c < 2; ++c)
      render_camera(camera_ids_[c], c == 0 ? images_.left : images_.right);
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

  void reset() override {
    mj_resetData(model_.get(), data_.get());
    if (keyframe_ >= 0) {
      mj_resetDataKeyframe(model_.get(), data_.get(), keyframe_);
      for (std::size_t i = 0; i < joints_.size(); ++i) {
        q_target_[static_cast<Eigen::Index>(i)] =
            model_->key_ctrl[keyframe_ * model_->nu + joints_[i].actuator];
      }
    } else {
      q_target_.setZero();
    }
    mj_forward(model_.get(), data_.get());
    output_.status = RobotStatus::ok;
    output_.message.clear();
    read_output();
  }

 private:
  struct JointMap {
    int qpos;      ///< address in qpos
    int dof;       ///< address in qvel
    int actuator;  ///< index in ctrl
    int sensor;    ///< address of the jointpos sensor in sensordata
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
    if (settings_.objects.empty()) {
      model_.reset(mj_loadXML(path.c_str(), nullptr, error, sizeof(error)));
    } else {
      model_.reset(load_with_objects(path, error, sizeof(error)));
    }
    std::string reason(error);  // MuJoCo's message spans lines: make it one
    std::replace(reason.begin(), reason.end(), '\n', ' ');
    while (!reason.empty() && reason.back() == ' ') reason.pop_back();
    check_argument(model_ != nullptr, "MujocoRobot: model_path", "a valid MJCF file",
                   "'" + path + "' (MuJoCo: " + reason + ")");
    data_.reset(mj_makeData(model_.get()));
    check_argument(data_ != nullptr, "MujocoRobot", "memory for the simulation data of",
                   "'" + path + "'");
  }

  /// The MJCF of `path` with settings_.objects inserted at the end of its worldbody, loaded
  /// from memory (MuJoCo's virtual file system: asset files of the model, if any, must then be
  /// found from the working directory; walkgen's humanoid has none).
  mjModel* load_with_objects(const std::string& path, char* error, int error_size) const {
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
    const std::string name = "walkgen_scene.xml";
    mj_makeEmptyFileVFS(vfs.get(), name.c_str(), int(xml.size()));
    const int index = mj_findFileVFS(vfs.get(), name.c_str());
    std::memcpy(vfs->filedata[index], xml.data(), xml.size());
    mjModel* m = mj_loadXML(name.c_str(), vfs.get(), error, error_size);
    mj_deleteVFS(vfs.get());
    return m;
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

  void map_names() {
    const mjModel* m = model_.get();
    std::vector<std::string> missing;
    for (const std::string& name : settings_.joint_names) {
      JointMap map{-1, -1, -1, -1};
      const int joint = mj_name2id(m, mjOBJ_JOINT, name.c_str());
      if (joint < 0 || (m->jnt_type[joint] != mjJNT_HINGE && m->jnt_type[joint] != mjJNT_SLIDE)) {
        missing.push_back("joint '" + name + "'");
      } else {
        map.qpos = m->jnt_qposadr[joint];
        map.dof = m->jnt_dofadr[joint];
      }
      const int actuator = mj_name2id(m, mjOBJ_ACTUATOR, name.c_str());
      if (actuator < 0 || m->actuator_trntype[actuator] != mjTRN_JOINT ||
          m->actuator_trnid[2 * actuator] != joint) {
        missing.push_back("actuator '" + name + "' on joint '" + name + "'");
      } else {
        map.actuator = actuator;
      }
      map.sensor = sensor_address(name + "_pos", mjSENS_JOINTPOS, 1, missing);
      joints_.push_back(map);
    }
    for (int f = 0; f < 2; ++f) {
      const std::string& site = settings_.ft_sensor_sites[f];
      ft_sites_[f] = mj_name2id(m, mjOBJ_SITE, site.c_str());
      if (ft_sites_[f] < 0) missing.push_back("site '" + site + "'");
      ft_force_[f] = sensor_address(site + "_force", mjSENS_FORCE, 3, missing);
      ft_torque_[f] = sensor_address(site + "_torque", mjSENS_TORQUE, 3, missing);
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
    if (!missing.empty()) {
      std::string list;
      for (const std::string& s : missing) list += (list.empty() ? "" : ", ") + s;
      throw invalid_argument("MujocoRobot: '" + settings_.model_path +
                             "' lacks what the settings name: " + list +
                             " (hint: MujocoRobotSettings names joints, actuators, sensors, "
                             "sites, cameras, the base body and the keyframe)");
    }
    check_argument(m->nu == static_cast<int>(joints_.size()), "MujocoRobot: actuators",
                   std::to_string(joints_.size()) + " (one per joint name)", m->nu,
                   "every actuator of the model must be driven by a named joint");
  }

  /// Entry `index` of <custom><numeric name=...>, or `fallback` when the model has none.
  double custom_numeric(const char* name, int index, double fallback) const {
    const int id = mj_name2id(model_.get(), mjOBJ_NUMERIC, name);
    if (id < 0 || model_->numeric_size[id] <= index) return fallback;
    return model_->numeric_data[model_->numeric_adr[id] + index];
  }

  /// Checks the state after a physics step; true when the robot stopped.
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
      output_.q[k] = d->sensordata[joints_[i].sensor];
      output_.dq[k] = d->qvel[joints_[i].dof];
    }
    for (int f = 0; f < 2; ++f) {
      // MuJoCo reports the wrench the parent (leg) exerts on the child (foot): negate it.
      ForceTorqueReading& r = output_.ft[f];
      r.force_S = -Eigen::Map<const Eigen::Vector3d>(d->sensordata + ft_force_[f]);
      r.torque_S = -Eigen::Map<const Eigen::Vector3d>(d->sensordata + ft_torque_[f]);
      r.pose_W_S = pose(d->site_xpos + 3 * ft_sites_[f], d->site_xmat + 9 * ft_sites_[f]);
    }
    output_.base_height = d->xpos[3 * base_body_ + 2];
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
  std::array<int, 2> ft_torque_{{-1, -1}};
  std::array<int, 2> camera_ids_{{-1, -1}};
  int base_body_ = -1;
  int keyframe_ = -1;
  Eigen::VectorXd q_target_;
  RobotOutput output_;

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
};

}  // namespace walkgen
