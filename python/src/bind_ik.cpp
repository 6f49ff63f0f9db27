/// @file
/// walkgen.InverseKinematics: the whole-body Levenberg–Marquardt IK in Ceres
/// (walkgen/ceres/inverse_kinematics.hpp, thesis §2.4.2) on any KinematicTree, with a robot's
/// settings and standing posture from its description. Built when the package has walkgen::ceres
/// and walkgen::urdf (WALKGEN_PYTHON_HAVE_CERES); walkgen.features["ik"] says so.

#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <memory>
#include <optional>
#include <string>

#include "arrays.hpp"
#include "bindings.hpp"
#include "kinematics.hpp"
#include "walkgen/ceres/inverse_kinematics.hpp"
#include "walkgen/humanoid/humanoid_ik.hpp"

namespace walkgen::python {
namespace {

using Ik = CeresInverseKinematics<Eigen::Dynamic>;

/// The solver with the tree it was built on (kept alive with it).
class PyIk {
 public:
  PyIk(const PyTree& tree, const std::optional<RobotDescription>& robot)
      : tree_(tree.tree),
        ik_(std::make_unique<Ik>(*tree_, robot ? ceres_ik_settings(*robot) : CeresIkSettings())),
        robot_(robot) {
    if (robot_) start_standing(*ik_, Eigen::Vector3d::Zero(), 0.0, *robot_);
  }

  void stand(const py::handle& left_sole, double yaw) {
    check_argument(robot_.has_value(), "InverseKinematics.stand", "a solver made with a robot",
                   "none", "pass robot= to InverseKinematics, or use set_initial_guess()");
    const Eigen::Vector3d p = VectorArg(left_sole, "left_sole", 3).map();
    check_argument(p.allFinite() && std::isfinite(yaw), "InverseKinematics.stand",
                   "a finite sole position and yaw", "NaN or inf");
    start_standing(*ik_, p, yaw, *robot_);
  }

  void set_initial_guess(const py::handle& position, const py::handle& rotation,
                         const py::handle& q) {
    ik_->set_initial_guess(VectorArg(position, "base_position", 3).map(),
                           MatrixArg(rotation, "base_rotation", 3, 3).map(3, 3),
                           VectorArg(q, "q", ik_->num_joints()).map());
  }

  IkResult solve(const py::handle& com, const py::handle& left_foot, const py::handle& right_foot,
                 double left_yaw, double right_yaw, const std::optional<double>& yaw) {
    IkTarget t;
    t.com_W = VectorArg(com, "com", 3).map();
    t.left_foot = {VectorArg(left_foot, "left_foot", 3).map(), left_yaw};
    t.right_foot = {VectorArg(right_foot, "right_foot", 3).map(), right_yaw};
    t.hold_upright(yaw ? *yaw : 0.5 * (left_yaw + right_yaw));
    check_argument(t.all_finite(), "InverseKinematics.solve", "finite targets", "NaN or inf");
    py::gil_scoped_release release;
    return ik_->solve(t);
  }

  py::array_t<double> q() const { return to_numpy(ik_->q()); }
  py::array_t<double> base_position() const { return to_numpy(ik_->base_position_W()); }
  py::array_t<double> base_rotation() const { return to_numpy(ik_->base_rotation_W()); }
  int num_joints() const { return ik_->num_joints(); }

 private:
  std::shared_ptr<const KinematicTree<double>> tree_;
  std::unique_ptr<Ik> ik_;
  std::optional<RobotDescription> robot_;
};

}  // namespace

void bind_ik(py::module_& m) {
  py::enum_<IkStatus> status(m, "IkStatus", "Outcome of an IK solve.");
  status.value("converged", IkStatus::converged)
      .value("not_converged", IkStatus::not_converged)
      .value("invalid_input", IkStatus::invalid_input);
  enum_as_string(status);

  py::class_<IkResult>(m, "IkResult", "Status, work and the errors of the final iterate.")
      .def_readonly("status", &IkResult::status)
      .def_property_readonly("message", [](const IkResult& r) { return std::string(r.message); })
      .def_property_readonly("ok",
                             [](const IkResult& r) { return r.status == IkStatus::converged; })
      .def_readonly("applied", &IkResult::applied)
      .def_readonly("iterations", &IkResult::iterations)
      .def_readonly("runs", &IkResult::runs)
      .def_readonly("com_error", &IkResult::com_error)
      .def_readonly("foot_position_error", &IkResult::foot_position_error)
      .def_readonly("foot_yaw_error", &IkResult::foot_yaw_error)
      .def_readonly("foot_tilt_error", &IkResult::foot_tilt_error)
      .def_readonly("base_orientation_error", &IkResult::base_orientation_error)
      .def_readonly("torso_orientation_error", &IkResult::torso_orientation_error)
      .def_readonly("cost", &IkResult::cost)
      .def("__repr__", [](const IkResult& r) {
        return std::string("IkResult(") + to_string(r.status) +
               ", com_error=" + std::to_string(r.com_error) +
               ", iterations=" + std::to_string(r.iterations) + ")";
      });

  py::class_<PyIk>(m, "InverseKinematics",
                   "Whole-body LM inverse kinematics (Ceres): CoM, both soles flat at their "
                   "positions and yaws, pelvis and torso upright. Holds its solution, the warm "
                   "start of the next solve.")
      .def(py::init<const PyTree&, const std::optional<RobotDescription>&>(), py::arg("tree"),
           py::arg("robot") = py::none(),
           "With a robot: its sole frames, torso and held joints, started standing.")
      .def("stand", &PyIk::stand, py::arg("left_sole") = to_numpy(Eigen::Vector3d::Zero().eval()),
           py::arg("yaw") = 0.0,
           "Initial guess: the robot's standing posture with its left sole at left_sole.")
      .def("set_initial_guess", &PyIk::set_initial_guess, py::arg("base_position"),
           py::arg("base_rotation"), py::arg("q"))
      .def("solve", &PyIk::solve, py::arg("com"), py::arg("left_foot"), py::arg("right_foot"),
           py::arg("left_yaw") = 0.0, py::arg("right_yaw") = 0.0, py::arg("yaw") = py::none(),
           "Solves for the targets (world frame; yaw of pelvis and torso defaults to the feet's "
           "mean). Returns an IkResult; the solution changes only when it converged.")
      .def_property_readonly("q", &PyIk::q, "Joint angles of the solution (tree order).")
      .def_property_readonly("base_position", &PyIk::base_position)
      .def_property_readonly("base_rotation", &PyIk::base_rotation)
      .def_property_readonly("num_joints", &PyIk::num_joints);
}

}  // namespace walkgen::python
