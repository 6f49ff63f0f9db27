/// @file
/// The navigation episode of thesis §11.1 (walkgen/navigation/navigation_episode.hpp) a tick at a
/// time: walkgen's humanoid in a room (make_navigation_scene), what its chest cameras see (left
/// RGB, the WLS disparity of the pair, the exact depth) and the scripted expert's command. The
/// engine of walkgen.envs.NavigationEnv. Built with walkgen::navigation
/// (WALKGEN_PYTHON_HAVE_NAVIGATION).

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cstring>
#include <memory>
#include <string>

#include "arrays.hpp"
#include "bindings.hpp"
#include "walkgen/navigation/navigation_episode.hpp"
#include "walkgen/navigation/scripted_expert.hpp"

namespace walkgen::python {
namespace {

/// One episode at a time; reset() starts the next.
class NavigationCore {
 public:
  NavigationCore(double time_limit, double reach_distance) {
    options_.time_limit = time_limit;
    options_.reach_distance = reach_distance;
    validate(options_);
  }

  /// A new episode in the scene of `task` and `seed`; returns done() (true when the robot did
  /// not start or cannot render).
  bool reset(const std::string& task, long long seed) {
    // The old episode ends first: what follows may throw, and leaves no episode behind then.
    observed_ = false;
    episode_.reset();
    expert_.reset();
    check_argument(seed >= 0 && seed <= 0xffffffffLL, "NavigationEnv: scene seed", "0 to 2^32 - 1",
                   seed);
    scene_ =
        make_navigation_scene(navigation_task_from_string(task), static_cast<std::uint32_t>(seed));
    {
      py::gil_scoped_release release;
      episode_ = std::make_unique<NavigationEpisode>(scene_, options_);
    }
    expert_ = std::make_unique<ScriptedExpert>(scene_, heicub_settings<double>().max_command);
    return episode_->done();
  }

  /// Renders and computes the disparity: {"rgb", "disparity", "depth"} of the left camera.
  py::dict observe() {
    const NavigationEpisode& e = started();
    check_argument(e.can_observe(), "NavigationEnv: observe", "an episode that started",
                   "one that did not (" + e.result().message + ")");
    const NavigationObservation* o = nullptr;
    {
      py::gil_scoped_release release;
      o = &episode_->observe();
    }
    observation_ = *o;  // its images stay valid until the next observe()
    observed_ = true;
    const CameraImage& left = o->images->left;
    py::array_t<std::uint8_t> rgb({left.height, left.width, 3});
    std::memcpy(rgb.mutable_data(), left.rgb.data(), left.rgb.size());
    py::array_t<float> depth({left.height, left.width});
    std::memcpy(depth.mutable_data(), left.depth.data(), left.depth.size() * sizeof(float));
    const cv::Mat& d = *o->disparity;  // CV_32F, continuous
    py::array_t<float> disparity({d.rows, d.cols});
    for (int r = 0; r < d.rows; ++r) {
      std::memcpy(disparity.mutable_data(r, 0), d.ptr<float>(r),
                  static_cast<std::size_t>(d.cols) * sizeof(float));
    }
    py::dict out;
    out["rgb"] = rgb;
    out["disparity"] = disparity;
    out["depth"] = depth;
    return out;
  }

  /// The scripted expert's command for the last observation (walkgen/navigation/
  /// scripted_expert.hpp: it knows the scene).
  py::array_t<double> expert_command() {
    check_argument(observed_ && expert_ != nullptr, "NavigationEnv: expert_command",
                   "an observation of this tick", "none",
                   "call it after reset() or step(), before the next step()");
    return to_numpy((*expert_)(observation_));
  }

  /// One NMPC tick with `command` (v_x, v_y, ω_z), clipped to max_command(); returns done().
  bool step(const py::handle& command) {
    NavigationEpisode& e = started();
    check_argument(!e.done(), "NavigationEnv: step", "an episode that goes on",
                   "one that has ended", "call reset()");
    Eigen::Vector3d c = VectorArg(command, "action", 3).map();
    for (int i = 0; i < 3; ++i) c[i] = std::isfinite(c[i]) ? c[i] : 0.0;
    observed_ = false;
    py::gil_scoped_release release;
    return e.step(c);
  }

  const NavigationResult& result() { return started().result(); }
  double distance() { return started().result().final_distance; }
  double time() { return started().result().time; }
  double time_limit() { return started().time_limit(); }
  py::array_t<double> max_command() const {
    return to_numpy((0.95 * heicub_settings<double>().max_command).eval());
  }
  py::tuple image_size() {
    const RobotInfo& info = started().robot().info();
    return py::make_tuple(info.image_height, info.image_width);
  }
  py::dict scene() const {
    py::dict out;
    out["task"] = std::string(to_string(scene_.task));
    out["seed"] = scene_.seed;
    out["target"] = to_numpy(scene_.target);
    out["chairs"] = scene_.chairs;
    out["has_person"] = scene_.has_person;
    return out;
  }
  py::array_t<double> true_com() {
    const Eigen::Vector2d c = walkgen::true_com(started().robot());
    return to_numpy(c);
  }

 private:
  NavigationEpisode& started() {
    check_argument(episode_ != nullptr, "NavigationEnv", "an episode", "none",
                   "call reset() first");
    return *episode_;
  }
  NavigationOptions options_;
  NavigationScene scene_;
  std::unique_ptr<NavigationEpisode> episode_;
  std::unique_ptr<ScriptedExpert> expert_;
  NavigationObservation observation_;
  bool observed_ = false;
};

}  // namespace

void bind_navigation(py::module_& m) {
  py::class_<NavigationCore>(m, "_NavigationCore")
      .def(py::init<double, double>(), py::arg("time_limit") = 0.0, py::arg("reach_distance") = 0.3)
      .def("reset", &NavigationCore::reset, py::arg("task"), py::arg("seed"))
      .def("observe", &NavigationCore::observe)
      .def("expert_command", &NavigationCore::expert_command)
      .def("step", &NavigationCore::step, py::arg("command"))
      .def_property_readonly("status",
                             [](NavigationCore& c) { return to_string(c.result().status); })
      .def_property_readonly("message", [](NavigationCore& c) { return c.result().message; })
      .def_property_readonly("distance", &NavigationCore::distance)
      .def_property_readonly("time", &NavigationCore::time)
      .def_property_readonly("time_limit", &NavigationCore::time_limit)
      .def_property_readonly("max_command", &NavigationCore::max_command)
      .def_property_readonly("image_size", &NavigationCore::image_size)
      .def_property_readonly("scene", &NavigationCore::scene)
      .def("true_com", &NavigationCore::true_com);
}

}  // namespace walkgen::python
