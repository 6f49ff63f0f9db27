/// @file
/// Robots and their kinematics: walkgen.RobotDescription (models/<robot>/robot.yaml,
/// docs/robots.md) and walkgen.KinematicTree (walkgen/kinematics/kinematic_tree.hpp) read from a
/// URDF (when the package is built with walkgen::urdf) or an MJCF (with walkgen::mujoco), with
/// forward kinematics, the centre of mass and the Jacobians on NumPy arrays.

#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <map>
#include <memory>
#include <string>
#include <vector>

#include "arrays.hpp"
#include "bindings.hpp"
#include "kinematics.hpp"
#include "walkgen/kinematics/kinematic_tree.hpp"
#include "walkgen/robot/robot_description.hpp"
#include "walkgen/yaml/robot_description_loader.hpp"
#ifdef WALKGEN_PYTHON_HAVE_URDF
#include "walkgen/urdf/urdf_loader.hpp"
#endif
#ifdef WALKGEN_PYTHON_HAVE_MUJOCO
#include "walkgen/mujoco/mujoco_kinematics.hpp"
#include "walkgen/mujoco/robot_model.hpp"
#endif

namespace walkgen::python {
namespace {

using Tree = KinematicTree<double>;

/// The poses of one forward-kinematics call: the tree (shared, immutable) and its workspace.
class Kinematics {
 public:
  Kinematics(std::shared_ptr<const Tree> tree, const py::handle& q, const py::handle& position,
             const py::handle& rotation)
      : tree_(std::move(tree)), ws_(tree_->make_workspace()) {
    const VectorArg qa(q, "q", tree_->num_joints());
    const VectorArg p(position, "base_position", 3);
    const MatrixArg R(rotation, "base_rotation", 3, 3);
    const Eigen::Matrix3d Rb = R.map(3, 3);
    check_argument(qa.map().allFinite() && p.map().allFinite() && Rb.allFinite(),
                   "KinematicTree.forward_kinematics", "finite q, base_position and base_rotation",
                   "NaN or inf");
    check_argument(
        (Rb.transpose() * Rb - Eigen::Matrix3d::Identity()).norm() < 1e-6 && Rb.determinant() > 0.0,
        "KinematicTree.forward_kinematics: base_rotation", "a rotation matrix",
        "a matrix that is not orthonormal with determinant 1");
    tree_->forward_kinematics(Eigen::Vector3d(p.map()), Rb, qa.map(), ws_);
  }

  int link(const py::object& link) const {
    if (py::isinstance<py::str>(link)) return tree_->link_index(link.cast<std::string>());
    const long long i = link.cast<long long>();
    check_argument(i >= 0 && i < tree_->num_links(), "KinematicTree: link index",
                   "0 to " + std::to_string(tree_->num_links() - 1), i);
    return static_cast<int>(i);
  }
  py::array_t<double> position(const py::object& l) const {
    return to_numpy(ws_.position_W(link(l)));
  }
  py::array_t<double> rotation(const py::object& l) const {
    return to_numpy(ws_.rotation_W(link(l)));
  }
  py::array_t<double> pose(const py::object& l) const {
    const int i = link(l);
    Eigen::Matrix4d T = Eigen::Matrix4d::Identity();
    T.topLeftCorner<3, 3>() = ws_.rotation_W(i);
    T.topRightCorner<3, 1>() = ws_.position_W(i);
    return to_numpy(T);
  }
  py::array_t<double> positions() const {
    Eigen::MatrixXd out(tree_->num_links(), 3);
    for (int i = 0; i < tree_->num_links(); ++i) out.row(i) = ws_.position_W(i).transpose();
    return to_numpy(out);
  }
  py::array_t<double> center_of_mass() const { return to_numpy(tree_->center_of_mass(ws_)); }
  py::array_t<double> com_jacobian() const {
    Eigen::Matrix<double, 3, Eigen::Dynamic> J(3, tree_->num_velocities());
    tree_->center_of_mass_jacobian(ws_, J);
    return to_numpy(J);
  }
  py::array_t<double> frame_jacobian(const py::object& l, const py::object& point) const {
    Eigen::Matrix<double, 6, Eigen::Dynamic> J(6, tree_->num_velocities());
    const Eigen::Vector3d p = point.is_none() ? Eigen::Vector3d::Zero()
                                              : Eigen::Vector3d(VectorArg(point, "point", 3).map());
    tree_->frame_jacobian(ws_, link(l), J, p);
    return to_numpy(J);
  }

 private:
  std::shared_ptr<const Tree> tree_;
  Tree::Workspace ws_;
};

PyTree make_tree(KinematicTree<double> tree) {
  return PyTree{std::make_shared<const Tree>(std::move(tree))};
}

PyTree tree_of_description(const RobotDescription& robot) {
#ifdef WALKGEN_PYTHON_HAVE_MUJOCO
  if (!robot.mjcf_path.empty()) return make_tree(robot_kinematic_tree_from_mjcf(robot));
#endif
#ifdef WALKGEN_PYTHON_HAVE_URDF
  if (!robot.urdf_path.empty()) return make_tree(kinematic_tree_from_urdf_file(robot.urdf_path));
#endif
  throw invalid_argument(
      detail::expected_got(("KinematicTree.from_description: robot '" + robot.name + "'").c_str(),
                           "a model this package reads (MJCF with MuJoCo, URDF with tinyxml2)",
                           "mjcf '" + robot.mjcf_path + "', urdf '" + robot.urdf_path + "'",
                           "the package was built without the adapter: see walkgen.features"));
}

std::map<std::string, double> stand_pose(const RobotDescription& d) {
  std::map<std::string, double> out;
  for (const JointAngle& a : d.stand_pose) out[a.joint] = a.angle;
  return out;
}

}  // namespace

void bind_kinematics(py::module_& m) {
  py::dict features;
  features["yaml"] = true;
#ifdef WALKGEN_PYTHON_HAVE_URDF
  features["urdf"] = true;
#else
  features["urdf"] = false;
#endif
#ifdef WALKGEN_PYTHON_HAVE_MUJOCO
  features["mujoco"] = true;
#else
  features["mujoco"] = false;
#endif
#ifdef WALKGEN_PYTHON_HAVE_CERES
  features["ik"] = true;
#else
  features["ik"] = false;
#endif
#ifdef WALKGEN_PYTHON_HAVE_SIMULATION
  features["simulation"] = true;
#else
  features["simulation"] = false;
#endif
#ifdef WALKGEN_PYTHON_HAVE_NAVIGATION
  features["navigation"] = true;
#else
  features["navigation"] = false;
#endif
  m.attr("features") = features;

  py::class_<RobotDescription>(m, "RobotDescription",
                               "A robot as data (models/<robot>/robot.yaml; docs/robots.md).")
      .def_static("load", &load_robot_description, py::arg("path"),
                  "Reads a description file; model paths are taken beside it.")
      .def_static("find", &find_robot_description, py::arg("name_or_path"),
                  "NAME (models/NAME/robot.yaml under walkgen's data folder) or a .yaml path.")
      .def_static(
          "from_yaml",
          [](const std::string& text, const std::string& base_dir) {
            return robot_description_from_yaml(text, base_dir);
          },
          py::arg("text"), py::arg("base_dir") = ".")
      .def_static("walkgen_humanoid", &walkgen_humanoid_description,
                  "walkgen's own 15-joint humanoid (the same as find('walkgen_humanoid')).")
      .def_readonly("name", &RobotDescription::name)
      .def_readonly("urdf_path", &RobotDescription::urdf_path)
      .def_readonly("mjcf_path", &RobotDescription::mjcf_path)
      .def_readonly("joint_names", &RobotDescription::joint_names)
      .def_readonly("sole_frames", &RobotDescription::sole_frames)
      .def_readonly("ft_sensor_frames", &RobotDescription::ft_sensor_frames)
      .def_readonly("ft_sensor_height", &RobotDescription::ft_sensor_height)
      .def_readonly("cameras", &RobotDescription::cameras)
      .def_readonly("imu_site", &RobotDescription::imu_site)
      .def_readonly("base_body", &RobotDescription::base_body)
      .def_readonly("torso_body", &RobotDescription::torso_body)
      .def_readonly("stand_keyframe", &RobotDescription::stand_keyframe)
      .def_property_readonly("stand_pose", &stand_pose, "{joint: angle [rad]} of the posture")
      .def_property_readonly(
          "stand_angles",
          [](const RobotDescription& d) {
            const std::vector<double> q = stand_angles(d);
            return to_numpy(
                Eigen::Map<const Eigen::VectorXd>(q.data(), static_cast<Eigen::Index>(q.size())));
          },
          "The standing posture over joint_names.")
      .def_property_readonly(
          "walking", [](const RobotDescription& d) { return d.walking; },
          "A copy of the robot's WalkingSettings.")
      .def("validate", [](const RobotDescription& d) { validate(d); })
      .def("__repr__", [](const RobotDescription& d) {
        return "RobotDescription('" + d.name + "', " + std::to_string(d.joint_names.size()) +
               " joints)";
      });

  py::class_<Kinematics>(m, "Kinematics",
                         "World poses of every link after KinematicTree.forward_kinematics(); "
                         "links by name or index.")
      .def("position", &Kinematics::position, py::arg("link"), "(3,) [m]")
      .def("rotation", &Kinematics::rotation, py::arg("link"), "(3, 3)")
      .def("pose", &Kinematics::pose, py::arg("link"), "(4, 4) homogeneous transform")
      .def("positions", &Kinematics::positions, "(num_links, 3), links in tree order")
      .def("center_of_mass", &Kinematics::center_of_mass, "(3,) whole-body CoM [m]")
      .def("com_jacobian", &Kinematics::com_jacobian,
           "(3, num_velocities): CoM velocity = J v, v = (base linear, base angular, q rates)")
      .def("frame_jacobian", &Kinematics::frame_jacobian, py::arg("link"),
           py::arg("point") = py::none(),
           "(6, num_velocities): (linear, angular) velocity in the world of a point of the link "
           "(default its origin; `point` in the link frame)");

  py::class_<PyTree>(m, "KinematicTree",
                     "A floating-base kinematic tree: FK, CoM and Jacobians (thesis §2.4.1).")
#ifdef WALKGEN_PYTHON_HAVE_URDF
      .def_static(
          "from_urdf",
          [](const std::string& path) { return make_tree(kinematic_tree_from_urdf_file(path)); },
          py::arg("path"), "The tree of a URDF file.")
#endif
#ifdef WALKGEN_PYTHON_HAVE_MUJOCO
      .def_static(
          "from_mjcf",
          [](const std::string& path, const std::string& base_body) {
            return make_tree(kinematic_tree_from_mjcf_file(path, base_body));
          },
          py::arg("path"), py::arg("base_body") = "",
          "The tree of an MJCF file (the subtree of base_body; default the free-floating body).")
#endif
      .def_static("from_description", &tree_of_description, py::arg("robot"),
                  "The tree of a RobotDescription: its MJCF plus its added frames (with MuJoCo), "
                  "else its URDF.")
      .def_property_readonly("num_links", [](const PyTree& t) { return t.tree->num_links(); })
      .def_property_readonly("num_joints", [](const PyTree& t) { return t.tree->num_joints(); })
      .def_property_readonly("num_velocities",
                             [](const PyTree& t) { return t.tree->num_velocities(); })
      .def_property_readonly("mass", [](const PyTree& t) { return t.tree->mass(); })
      .def_property_readonly("joint_names", [](const PyTree& t) { return t.tree->joint_names(); })
      .def_property_readonly("link_names",
                             [](const PyTree& t) {
                               std::vector<std::string> names;
                               for (const auto& l : t.tree->links()) names.push_back(l.name);
                               return names;
                             })
      .def_property_readonly("lower_limits",
                             [](const PyTree& t) { return to_numpy(t.tree->lower_limits()); })
      .def_property_readonly("upper_limits",
                             [](const PyTree& t) { return to_numpy(t.tree->upper_limits()); })
      .def(
          "joint_index",
          [](const PyTree& t, const std::string& n) { return t.tree->joint_index(n); },
          py::arg("name"))
      .def(
          "link_index", [](const PyTree& t, const std::string& n) { return t.tree->link_index(n); },
          py::arg("name"))
      .def(
          "stand_configuration",
          [](const PyTree& t, const RobotDescription& robot) {
            return to_numpy(stand_configuration(*t.tree, robot));
          },
          py::arg("robot"), "The robot's standing posture in this tree's joint order.")
      .def(
          "forward_kinematics",
          [](const PyTree& t, const py::handle& q, const py::handle& base_position,
             const py::handle& base_rotation) {
            return Kinematics(t.tree, q, base_position, base_rotation);
          },
          py::arg("q"), py::arg("base_position") = to_numpy(Eigen::Vector3d::Zero().eval()),
          py::arg("base_rotation") = to_numpy(Eigen::Matrix3d::Identity().eval()),
          "Poses of every link for joint angles q (num_joints,) and the base's pose in the "
          "world; returns a Kinematics.")
      .def("__repr__", [](const PyTree& t) {
        return "KinematicTree(" + std::to_string(t.tree->num_links()) + " links, " +
               std::to_string(t.tree->num_joints()) + " joints, " + std::to_string(t.tree->mass()) +
               " kg)";
      });
}

}  // namespace walkgen::python
