#pragma once
/// @file
/// The parts of the module walkgen._core, one translation unit each (module.cpp calls them).

#include <pybind11/pybind11.h>

#include <string>

namespace walkgen::python {

namespace py = pybind11;

void bind_qp(py::module_& m);
void bind_settings(py::module_& m);
void bind_mpc(py::module_& m);
void bind_envs(py::module_& m);
void bind_kinematics(py::module_& m);
void bind_ik(py::module_& m);          // with WALKGEN_PYTHON_HAVE_CERES
void bind_simulation(py::module_& m);  // with WALKGEN_PYTHON_HAVE_SIMULATION
void bind_navigation(py::module_& m);  // with WALKGEN_PYTHON_HAVE_NAVIGATION

/// Makes a bound enum print as its name ("solved"), as walkgen's to_string() does, and compare
/// equal to that name, so `result.status == "solved"` reads as it should. The methods replace
/// pybind11's own (py::enum_::def would only add overloads behind them).
template <typename Enum>
void enum_as_string(py::enum_<Enum>& e) {
  const auto equal = [](Enum v, const py::object& other) {
    if (py::isinstance<py::str>(other)) return other.cast<std::string>() == to_string(v);
    if (py::isinstance<Enum>(other)) return other.cast<Enum>() == v;
    return false;
  };
  e.attr("__str__") =
      py::cpp_function([](Enum v) { return std::string(to_string(v)); }, py::is_method(e));
  e.attr("__eq__") = py::cpp_function(equal, py::is_method(e));
  e.attr("__ne__") = py::cpp_function(
      [equal](Enum v, const py::object& other) { return !equal(v, other); }, py::is_method(e));
  e.attr("__hash__") =
      py::cpp_function([](Enum v) { return static_cast<int>(v); }, py::is_method(e));
}

}  // namespace walkgen::python
