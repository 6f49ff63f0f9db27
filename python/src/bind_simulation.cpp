/// @file
/// walkgen.Simulation: a robot (walkgen's humanoid, the Unitree G1, any described robot) in MuJoCo
/// under the closed loop of thesis figure 6.1 (NMPC, interpolation, Ceres IK, feedback, safety),
/// with its measurements, the loop's samples and the chest cameras' images as NumPy arrays. Built
/// when the package has walkgen::simulation (WALKGEN_PYTHON_HAVE_SIMULATION).

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cstring>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "arrays.hpp"
#include "bindings.hpp"
#include "walkgen/simulation/humanoid_loop.hpp"
#include "walkgen/simulation/simulated_tasks.hpp"
#include "walkgen/yaml/robot_description_loader.hpp"

namespace walkgen::python {
namespace {

/// A camera image as arrays: rgb (h, w, 3) uint8, depth (h, w) float32 [m], the camera's pose.
py::dict image_dict(const CameraImage& image) {
  py::array_t<std::uint8_t> rgb({image.height, image.width, 3});
  std::memcpy(rgb.mutable_data(), image.rgb.data(), image.rgb.size());
  py::array_t<float> depth({image.height, image.width});
  std::memcpy(depth.mutable_data(), image.depth.data(), image.depth.size() * sizeof(float));
  py::dict out;
  out["rgb"] = rgb;
  out["depth"] = depth;
  out["pose"] = to_numpy(image.pose_W_C.matrix());
  out["fovy"] = image.fovy;
  out["near_clip"] = image.near_clip;
  out["far_clip"] = image.far_clip;
  return out;
}

py::dict ft_dict(const ForceTorqueReading& r) {
  py::dict out;
  out["force"] = to_numpy(r.force_S);
  out["torque"] = to_numpy(r.torque_S);
  out["pose"] = to_numpy(r.pose_W_S.matrix());
  return out;
}

/// The robot, its IK and the loop, built in this order and destroyed in the reverse one (the loop
/// borrows the other two). A robot of kHumanoidJoints joints walks with SimLoop (the fixed-size
/// IK), any other with RobotLoop (the IK sized at run time), as walkgen::with_robot_ik() picks.
class Simulation {
 public:
  Simulation(const std::string& robot, const std::vector<CircleObstacle<double>>& obstacles,
             const std::optional<WalkingSettings<double>>& walking, int view_width, int view_height)
      : description_(find_robot_description(robot)) {
    WalkingSettings<double> ws = walking ? *walking : description_.walking;
    check_argument(ws.n == 16, "Simulation: walking.n", "16 (the closed loop's horizon)",
                   std::to_string(ws.n));
    tree_ = std::make_unique<KinematicTree<double>>(robot_kinematic_tree(description_));
    MujocoRobotSettings ms = mujoco_robot_settings(description_);
    ms.view_width = view_width;
    ms.view_height = view_height;
    for (const auto& o : obstacles) {  // the obstacles stand in the world as cylinders
      SceneObject s;
      s.name = "obstacle_" + std::to_string(ms.objects.size());
      s.shape = SceneShape::cylinder;
      s.position = Eigen::Vector3d(o.x, o.y, 0.0);
      s.size = Eigen::Vector3d(o.radius, o.radius, 1.0);  // taller than the cameras
      ms.objects.push_back(s);
    }
    robot_ = std::make_unique<MujocoRobot>(ms);
    ws.obstacles = obstacles;
    ws = settings_where_standing(ws, *robot_);  // the plan's frame is MuJoCo's world
    if (tree_->num_joints() == kHumanoidJoints) {
      humanoid_ik_ = std::make_unique<HumanoidIk>(*tree_, ceres_ik_settings(description_));
      humanoid_loop_ =
          std::make_unique<SimLoop>(ws, *robot_, *humanoid_ik_, loop_settings(description_));
    } else {
      ik_ = std::make_unique<CeresInverseKinematics<>>(*tree_, ceres_ik_settings(description_));
      loop_ = std::make_unique<RobotLoop>(ws, *robot_, *ik_, loop_settings(description_));
    }
  }

  /// `f(loop)` with the robot's loop (SimLoop or RobotLoop).
  template <typename F>
  decltype(auto) with_loop(F&& f) {
    return humanoid_loop_ ? f(*humanoid_loop_) : f(*loop_);
  }
  template <typename F>
  decltype(auto) with_loop(F&& f) const {
    return humanoid_loop_ ? f(std::as_const(*humanoid_loop_)) : f(std::as_const(*loop_));
  }

  const LoopTick& start() {
    py::gil_scoped_release release;
    return with_loop([](auto& loop) -> const LoopTick& { return loop.start(); });
  }
  const LoopTick& tick() {
    py::gil_scoped_release release;
    return with_loop([](auto& loop) -> const LoopTick& { return loop.tick(); });
  }
  CommandStatus set_command(double vx, double vy, double wz) {
    const Eigen::Vector3d c(vx, vy, wz);
    check_argument(c.allFinite(), "Simulation.set_command", "finite velocities", "NaN or inf");
    return with_loop([&c](auto& loop) { return loop.set_command(c); });
  }
  LoopMode request_stop() {
    return with_loop([](auto& loop) { return loop.request_stop(); });
  }
  LoopMode mode() const {
    return with_loop([](const auto& loop) { return loop.mode(); });
  }
  WalkingState<double> state() const {
    return with_loop([](const auto& loop) { return loop.mpc().state(); });
  }
  MujocoRobot& robot() { return *robot_; }

  /// The last tick's samples, one row per command period.
  py::dict samples() const {
    const auto& s = with_loop(
        [](const auto& loop) -> const std::vector<LoopSample>& { return loop.samples(); });
    const auto k = static_cast<Eigen::Index>(s.size());
    Eigen::MatrixXd com_plan(k, 3), zmp_plan(k, 2), zmp_measured(k, 2), com_measured(k, 3);
    Eigen::VectorXd time(k), base_height(k), zmp_valid(k), sensors_ok(k);
    for (Eigen::Index i = 0; i < k; ++i) {
      const LoopSample& x = s[static_cast<std::size_t>(i)];
      time[i] = x.plan.time;
      com_plan.row(i) << x.plan.com_x[0], x.plan.com_y[0], x.plan.com_z;
      zmp_plan.row(i) << x.plan.zmp_x, x.plan.zmp_y;
      zmp_measured.row(i) = x.zmp.zmp_W.head<2>().transpose();
      com_measured.row(i) = x.com_measured_W.transpose();
      base_height[i] = x.base_height;
      zmp_valid[i] = x.zmp.valid ? 1.0 : 0.0;
      sensors_ok[i] = x.sensors_ok ? 1.0 : 0.0;
    }
    py::dict out;
    out["time"] = to_numpy(time);
    out["com_plan"] = to_numpy(com_plan);
    out["zmp_plan"] = to_numpy(zmp_plan);
    out["zmp_measured"] = to_numpy(zmp_measured);
    out["zmp_valid"] = to_numpy(zmp_valid).attr("astype")("bool");
    out["com_measured"] = to_numpy(com_measured);
    out["base_height"] = to_numpy(base_height);
    out["sensors_ok"] = to_numpy(sensors_ok).attr("astype")("bool");
    return out;
  }

  /// What the robot measures now.
  py::dict output() const {
    const RobotOutput& o = robot_->output();
    py::dict out;
    out["time"] = o.time;
    out["q"] = to_numpy(o.q);
    out["dq"] = to_numpy(o.dq);
    out["tau"] = to_numpy(o.tau);
    out["base_height"] = o.base_height;
    out["saturations"] = o.saturations;
    out["status"] = std::string(to_string(o.status));
    out["message"] = o.message;
    out["ft"] = py::make_tuple(ft_dict(o.ft[0]), ft_dict(o.ft[1]));
    py::dict imu;
    imu["available"] = o.imu.available;
    const Eigen::Quaterniond& q = o.imu.orientation_W_I;
    imu["orientation"] = to_numpy(Eigen::Vector4d(q.w(), q.x(), q.y(), q.z()));
    imu["angular_velocity"] = to_numpy(o.imu.angular_velocity_I);
    imu["acceleration"] = to_numpy(o.imu.acceleration_I);
    imu["tilt"] = o.imu.tilt();
    out["imu"] = imu;
    return out;
  }

  /// MuJoCo's true whole-body CoM (3,) [m].
  py::array_t<double> true_com() {
    const int root = mj_name2id(robot_->model(), mjOBJ_BODY, robot_->settings().base_body.c_str());
    return to_numpy(
        Eigen::Vector3d(Eigen::Map<const Eigen::Vector3d>(robot_->data()->subtree_com + 3 * root)));
  }

  py::dict render_cameras() {
    const StereoImages* images = nullptr;
    {
      py::gil_scoped_release release;
      images = &robot_->render_cameras();
    }
    if (images->status != RenderStatus::ok) throw std::runtime_error(images->message);
    py::dict out;
    out["left"] = image_dict(images->left);
    out["right"] = image_dict(images->right);
    return out;
  }

  py::dict render_view(const py::handle& lookat, double distance, double azimuth, double elevation,
                       int width, int height) {
    const Eigen::Vector3d at = VectorArg(lookat, "lookat", 3).map();
    CameraImage image;
    bool ok = false;
    {
      py::gil_scoped_release release;
      ok = robot_->render_view(at, distance, azimuth, elevation, width, height, image);
    }
    if (!ok) throw std::runtime_error(robot_->render_cameras().message);
    return image_dict(image);
  }

 private:
  RobotDescription description_;
  std::unique_ptr<KinematicTree<double>> tree_;
  std::unique_ptr<MujocoRobot> robot_;
  std::unique_ptr<HumanoidIk> humanoid_ik_;  // a robot of kHumanoidJoints joints
  std::unique_ptr<SimLoop> humanoid_loop_;
  std::unique_ptr<CeresInverseKinematics<>> ik_;  // any other
  std::unique_ptr<RobotLoop> loop_;
};

}  // namespace

void bind_simulation(py::module_& m) {
  py::enum_<LoopStatus> status(m, "LoopStatus", "What a tick of the closed loop ended with.");
  for (LoopStatus s : {LoopStatus::ok, LoopStatus::qp_failed, LoopStatus::fallen,
                       LoopStatus::diverged, LoopStatus::not_started, LoopStatus::not_converged,
                       LoopStatus::fault, LoopStatus::relaxed}) {
    status.value(to_string(s), s);
  }
  enum_as_string(status);
  py::enum_<LoopMode> mode(m, "LoopMode", "Where the loop's safety state machine stands.");
  for (LoopMode s : {LoopMode::idle, LoopMode::walking, LoopMode::stopping, LoopMode::stopped,
                     LoopMode::fault}) {
    mode.value(to_string(s), s);
  }
  enum_as_string(mode);
  py::enum_<StopReason> reason(m, "StopReason", "Why the loop left walking.");
  for (StopReason s : {StopReason::none, StopReason::requested, StopReason::qp_failures,
                       StopReason::ik_failures, StopReason::torque_saturation,
                       StopReason::sensor_fault, StopReason::fallen, StopReason::diverged}) {
    reason.value(to_string(s), s);
  }
  enum_as_string(reason);

  py::class_<LoopTick>(m, "LoopTick", "Summary of one tick (one NMPC period).")
      .def_readonly("status", &LoopTick::status)
      .def_readonly("mode", &LoopTick::mode)
      .def_readonly("reason", &LoopTick::reason)
      .def_readonly("mpc", &LoopTick::mpc)
      .def_readonly("ik_failures", &LoopTick::ik_failures)
      .def_readonly("qp_failure_streak", &LoopTick::qp_failure_streak)
      .def_readonly("mpc_seconds", &LoopTick::mpc_seconds, "wall time of the NMPC's solve [s]")
      .def_readonly("fed_back", &LoopTick::fed_back)
      .def_readonly("estimated", &LoopTick::estimated)
      .def_property_readonly("com_error", [](const LoopTick& t) { return to_numpy(t.com_error); })
      .def_readonly("message", &LoopTick::message)
      .def_property_readonly("ok", [](const LoopTick& t) { return t.status == LoopStatus::ok; })
      .def("__repr__", [](const LoopTick& t) {
        return std::string("LoopTick(") + to_string(t.status) + ", mode " + to_string(t.mode) +
               (t.message.empty() ? "" : ": " + t.message) + ")";
      });

  py::class_<Simulation>(m, "Simulation",
                         "A robot in MuJoCo (walkgen's humanoid, the Unitree G1, any described "
                         "robot), walking under the closed loop (NMPC, interpolation, Ceres IK, "
                         "feedback, safe stop).")
      .def(py::init<const std::string&, const std::vector<CircleObstacle<double>>&,
                    const std::optional<WalkingSettings<double>>&, int, int>(),
           py::arg("robot") = "walkgen_humanoid",
           py::arg("obstacles") = std::vector<CircleObstacle<double>>{},
           py::arg("walking") = py::none(), py::arg("view_width") = 640,
           py::arg("view_height") = 480,
           "robot: a name or description file; obstacles: CircleObstacle, placed in the world "
           "and in the generator's constraints; walking: WalkingSettings (default the robot's).")
      .def("start", &Simulation::start, py::return_value_policy::copy,
           "Stands the robot and starts walking (status 'ok' when it stands).")
      .def("tick", &Simulation::tick, py::return_value_policy::copy,
           "One NMPC period: plan, interpolate, IK and physics at the command period.")
      .def("set_command", &Simulation::set_command, py::arg("vx"), py::arg("vy") = 0.0,
           py::arg("wz") = 0.0, "Velocity command; 'accepted' or 'clamped'.")
      .def("request_stop", &Simulation::request_stop, "Finishes the step and stands on both feet.")
      .def_property_readonly("mode", &Simulation::mode)
      .def("state", &Simulation::state, "The generator's state (a copy).")
      .def("samples", &Simulation::samples,
           "The last tick's samples: time, com_plan, zmp_plan, zmp_measured, zmp_valid, "
           "com_measured, base_height, sensors_ok.")
      .def("output", &Simulation::output,
           "What the robot measures: time, q, dq, tau, base_height, ft, imu, status.")
      .def("true_com", &Simulation::true_com, "MuJoCo's whole-body CoM (3,) [m].")
      .def_property_readonly("joint_names",
                             [](Simulation& s) { return s.robot().info().joint_names; })
      .def(
          "push",
          [](Simulation& s, const py::handle& force, double start, double duration) {
            s.robot().push(VectorArg(force, "force", 3).map(), start, duration);
          },
          py::arg("force"), py::arg("start"), py::arg("duration"),
          "A force [N] on the base from simulated time start for duration seconds.")
      .def("render_cameras", &Simulation::render_cameras,
           "The chest cameras' images: {'left': {rgb, depth, pose, ...}, 'right': ...}. "
           "RuntimeError when rendering is unavailable (no EGL).")
      .def("render_view", &Simulation::render_view, py::arg("lookat"), py::arg("distance") = 2.5,
           py::arg("azimuth") = 135.0, py::arg("elevation") = -20.0, py::arg("width") = 640,
           py::arg("height") = 480, "An outside view of the scene: {rgb, depth, pose, ...}.");
}

}  // namespace walkgen::python
