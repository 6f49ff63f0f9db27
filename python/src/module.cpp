/// @file
/// walkgen._core: the compiled part of the Python package walkgen (python/walkgen/__init__.py
/// re-exports it). docs/python.md is the guide.

#include <pybind11/pybind11.h>

#include "bindings.hpp"
#include "walkgen/version.hpp"

PYBIND11_MODULE(_core, m) {
  m.doc() = "walkgen: NMPC walking pattern generation (C++ core, see docs/python.md)";
  m.attr("__version__") = walkgen::kVersion;
  walkgen::python::bind_qp(m);
  walkgen::python::bind_settings(m);
  walkgen::python::bind_mpc(m);
  walkgen::python::bind_envs(m);
  walkgen::python::bind_kinematics(m);
#ifdef WALKGEN_PYTHON_HAVE_CERES
  walkgen::python::bind_ik(m);
#endif
#ifdef WALKGEN_PYTHON_HAVE_SIMULATION
  walkgen::python::bind_simulation(m);
#endif
#ifdef WALKGEN_PYTHON_HAVE_NAVIGATION
  walkgen::python::bind_navigation(m);
#endif
}
