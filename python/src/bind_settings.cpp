/// @file
/// walkgen.WalkingSettings (walkgen/mpc/settings.hpp): the presets, YAML loading
/// (walkgen/yaml/settings_loader.hpp, the thesis's key names) and every field as an attribute.
/// Fields are checked when a WalkingMpc is built from them, or by validate().

#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <sstream>
#include <string>
#include <vector>

#include "arrays.hpp"
#include "bindings.hpp"
#include "walkgen/core/obstacle.hpp"
#include "walkgen/mpc/settings.hpp"
#include "walkgen/yaml/settings_loader.hpp"

namespace walkgen::python {
namespace {

using Settings = WalkingSettings<double>;
using Obstacle = CircleObstacle<double>;

/// A vector field of fixed size as a NumPy property (a copy: assign the whole vector to change).
template <typename Part, typename Vector>
void vector_property(py::class_<Settings>& c, const char* name, Vector Part::*field,
                     const char* doc) {
  c.def_property(
      name, [field](const Settings& s) { return to_numpy(s.*field); },
      [field, name](Settings& s, const py::object& value) {
        s.*field =
            VectorArg(value, std::string("WalkingSettings.") + name, Vector::RowsAtCompileTime)
                .map();
      },
      doc);
}

/// A polygon field (k × 2 vertices) as a NumPy property.
void polygon_property(py::class_<Settings>& c, const char* name,
                      Settings::Polygon RobotGeometry<double>::*field, const char* doc) {
  c.def_property(
      name, [field](const Settings& s) { return to_numpy(s.*field); },
      [field, name](Settings& s, const py::object& value) {
        const std::string where = std::string("WalkingSettings.") + name;
        const py::array_t<double, py::array::c_style> a = as_float_array(value, where);
        if (a.ndim() != 2 || a.shape(1) != 2) {
          throw invalid_argument(detail::expected_got(where.c_str(), "vertices of shape (k, 2)",
                                                      "shape " + shape_string(a)));
        }
        s.*field = MatrixArg(a, where, a.shape(0), 2).map(a.shape(0), 2);
      },
      doc);
}

std::string obstacle_repr(const Obstacle& o) {
  std::ostringstream os;
  os << "CircleObstacle(x=" << o.x << ", y=" << o.y << ", radius=" << o.radius
     << ", margin=" << o.margin << ")";
  return os.str();
}

}  // namespace

void bind_settings(py::module_& m) {
  py::enum_<Foot> foot(m, "Foot", "Which foot (str() gives 'left' or 'right').");
  foot.value("left", Foot::left).value("right", Foot::right);
  enum_as_string(foot);

  py::class_<Obstacle>(m, "CircleObstacle",
                       "A circle the footsteps keep radius + margin away from (world frame, m).")
      .def(py::init([](double x, double y, double radius, double margin) {
             return Obstacle{x, y, radius, margin};
           }),
           py::arg("x"), py::arg("y"), py::arg("radius"), py::arg("margin") = 0.0)
      .def_readwrite("x", &Obstacle::x)
      .def_readwrite("y", &Obstacle::y)
      .def_readwrite("radius", &Obstacle::radius)
      .def_readwrite("margin", &Obstacle::margin)
      .def("__repr__", &obstacle_repr);

  using Soft = SoftConstraintWeights<double>;
  py::class_<Soft>(m, "SoftConstraintWeights",
                   "Exact-penalty weights per constraint block, 0 = hard: on an infeasible QP "
                   "the generator walks the plan that violates the soft blocks least (status "
                   "'relaxed'; docs/walking.md, 'Soft constraints').")
      .def(py::init<>())
      .def_readwrite("zmp_polygon", &Soft::zmp_polygon)
      .def_readwrite("footstep_feasibility", &Soft::footstep_feasibility)
      .def_readwrite("relative_yaw", &Soft::relative_yaw)
      .def_readwrite("foot_separation", &Soft::foot_separation)
      .def_readwrite("obstacles", &Soft::obstacles)
      .def_readwrite("capture_point", &Soft::capture_point);

  py::class_<Settings> s(m, "WalkingSettings",
                         "The generator's settings (thesis Table 6.1; docs/yaml.md lists the "
                         "fields). WalkingSettings() is the HRP-2 preset.");
  s.def(py::init<>())
      .def_static("hrp2", &hrp2_settings<double>, "The HRP-2 settings of the thesis.")
      .def_static("heicub", &heicub_settings<double>, "The HeiCub settings of the thesis.")
      .def_static(
          "from_yaml",
          [](const std::string& text, const Settings& defaults) {
            return walking_settings_from_yaml<double>(text, defaults);
          },
          py::arg("text"), py::arg("defaults") = hrp2_settings<double>(),
          "Settings from YAML text (keys of configs/*.yaml); unset keys keep `defaults`.")
      .def_static(
          "load",
          [](const std::string& path, const Settings& defaults) {
            return load_walking_settings<double>(path, defaults);
          },
          py::arg("path"), py::arg("defaults") = hrp2_settings<double>(),
          "Settings from a YAML file (e.g. configs/hrp2.yaml).")
      .def(
          "validate", [](const Settings& self) { validate(self); },
          "Raises ValueError naming the first field out of range.")
      .def("copy", [](const Settings& self) { return Settings(self); })
      .def_property_readonly("samples_per_step", &Settings::samples_per_step)
      .def_property_readonly("planned_steps", &Settings::planned_steps);

  // Scalars and integers, in the order of settings.hpp.
  s.def_readwrite("foot_width", &Settings::foot_width)
      .def_readwrite("foot_length", &Settings::foot_length)
      .def_readwrite("foot_distance", &Settings::foot_distance)
      .def_readwrite("min_foot_separation", &Settings::min_foot_separation)
      .def_readwrite("step_height", &Settings::step_height)
      .def_readwrite("com_z", &Settings::com_z)
      .def_readwrite("max_relative_yaw", &Settings::max_relative_yaw)
      .def_readwrite("max_relative_yaw_rate", &Settings::max_relative_yaw_rate)
      .def_readwrite("gravity", &Settings::gravity)
      .def_readwrite("t_step", &Settings::t_step)
      .def_readwrite("t_ds", &Settings::t_ds)
      .def_readwrite("n", &Settings::n)
      .def_readwrite("t", &Settings::t)
      .def_readwrite("t_feedback", &Settings::t_feedback)
      .def_readwrite("command_period", &Settings::command_period)
      .def_readwrite("n_still", &Settings::n_still)
      .def_readwrite("alpha", &Settings::alpha)
      .def_readwrite("beta", &Settings::beta)
      .def_readwrite("gamma", &Settings::gamma)
      .def_readwrite("step_velocity_weight", &Settings::step_velocity_weight)
      .def_readwrite("heading_weight", &Settings::heading_weight)
      .def_readwrite("cpu_time", &Settings::cpu_time)
      .def_readwrite("nwsr", &Settings::nwsr)
      .def_readwrite("footstep_regularization", &Settings::footstep_regularization)
      .def_readwrite("sqp_iterations", &Settings::sqp_iterations)
      .def_readwrite("sqp_corrections", &Settings::sqp_corrections)
      .def_readwrite("sqp_tolerance", &Settings::sqp_tolerance)
      .def_readwrite("soft", &Settings::soft, "SoftConstraintWeights (all 0: hard constraints)")
      .def_readwrite("max_state_distance", &Settings::max_state_distance)
      .def_readwrite("max_com_speed", &Settings::max_com_speed)
      .def_readwrite("max_com_acceleration", &Settings::max_com_acceleration)
      .def_readwrite("support_foot", &Settings::support_foot)
      .def_readwrite("foot_x", &Settings::foot_x)
      .def_readwrite("foot_y", &Settings::foot_y)
      .def_readwrite("foot_q", &Settings::foot_q)
      .def_readwrite("obstacles", &Settings::obstacles,
                     "List of CircleObstacle (assign a new list to change it).");

  vector_property(s, "security_margin", &Settings::security_margin,
                  "(x, y) margins of the ZMP inside the sole [m]");
  vector_property(s, "max_command", &Settings::max_command,
                  "(vx, vy, wz) limits of the velocity command");
  vector_property(s, "com_x", &Settings::com_x, "initial CoM x, ẋ, ẍ");
  vector_property(s, "com_y", &Settings::com_y, "initial CoM y, ẏ, ÿ");
  vector_property(s, "com_q", &Settings::com_q, "initial CoM yaw θ, θ̇, θ̈");
  polygon_property(s, "left_foot_convex_hull", &Settings::left_foot_convex_hull,
                   "(k, 2) vertices where the right foot may land, left support");
  polygon_property(s, "right_foot_convex_hull", &Settings::right_foot_convex_hull,
                   "(k, 2) vertices where the left foot may land, right support");
  polygon_property(s, "zmp_polygon", &Settings::zmp_polygon,
                   "(k, 2) ZMP polygon in the sole frame (empty: the sole less the margins)");
}

}  // namespace walkgen::python
