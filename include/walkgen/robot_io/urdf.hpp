#pragma once
/// @file
/// URDF adapter (docs/design.md conventions 10-12): reads a robot description (URDF) into a
/// KinematicDescription / KinematicTree. Target walkgen::urdf (tinyxml2, Debian:
/// libtinyxml2-dev); the core never includes this header.
///
/// Read: <robot> with its <link>s (name; <inertial> with <origin xyz rpy>, <mass value> and
/// <inertia ixx ixy ixz iyy iyz izz>) and <joint>s (name, type, <parent link>, <child link>,
/// <origin xyz rpy>, <axis xyz>, <limit lower upper>). Joint types: revolute (needs <limit>),
/// continuous (a revolute joint without limits) and fixed; prismatic, floating and planar joints
/// are rejected. Ignored: visuals, collisions, materials, <mimic> (a mimic joint is read as an
/// independent joint), <dynamics>, and every other element (gazebo, transmission, sensor, ...).
///
/// Every problem throws walkgen::invalid_argument naming the source, the line and the element,
/// e.g. "robot.urdf:12: <joint name='l_knee'> <origin> xyz: expected 3 finite numbers separated
/// by spaces, got '0 0'". Problems of the tree's shape (unknown links, cycles, several roots)
/// are found by KinematicTree and reported with the source prepended.

#include <tinyxml2.h>

#include <cmath>
#include <fstream>
#include <locale>
#include <sstream>
#include <string>

#include "walkgen/core/exceptions.hpp"
#include "walkgen/kinematics/kinematic_tree.hpp"

namespace walkgen {

namespace detail {

/// An element of the document being read. Messages start with where():
/// "<source>:<line>: <joint name='x'> <origin> xyz".
struct UrdfElement {
  const std::string& source;
  const tinyxml2::XMLElement* element;  ///< nullptr for an optional child that is absent
  std::string owner;  ///< label() of the enclosing link or joint, "" for those themselves

  /// "<link name='x'>" for a link or joint, "<link name='x'> <mass>" for an element inside one.
  std::string label() const {
    const std::string tag = "<" + std::string(element->Name());
    if (!owner.empty()) return owner + " " + tag + ">";
    const char* name = element->Attribute("name");
    return tag + (name != nullptr ? std::string(" name='") + name + "'" : std::string()) + ">";
  }
  std::string where(const char* attribute = nullptr) const {
    return source + ":" + std::to_string(element->GetLineNum()) + ": " + label() +
           (attribute != nullptr ? std::string(" ") + attribute : std::string());
  }

  /// The first child element `tag`; absent (element == nullptr) unless `is_required`.
  UrdfElement child(const char* tag, bool is_required) const {
    const tinyxml2::XMLElement* c = element->FirstChildElement(tag);
    if (c == nullptr && is_required) {
      check_argument(false, where().c_str(), std::string("a <") + tag + "> element", "none");
    }
    return {source, c, owner.empty() ? label() : owner};
  }

  /// The attribute's text. @throws if it is missing.
  std::string text(const char* attribute) const {
    const char* value = element->Attribute(attribute);
    if (value == nullptr) check_argument(false, where(attribute).c_str(), "the attribute", "none");
    return value;
  }

  /// Count finite numbers separated by spaces; `fallback` is used when the attribute is missing
  /// (none: the attribute is required).
  template <int Count>
  Eigen::Matrix<double, Count, 1> numbers(const char* attribute,
                                          const char* fallback = nullptr) const {
    const char* value = element->Attribute(attribute);
    const std::string input = value != nullptr      ? value
                              : fallback != nullptr ? fallback
                                                    : text(attribute);
    std::istringstream in(input);
    in.imbue(std::locale::classic());
    Eigen::Matrix<double, Count, 1> out;
    bool ok = true;
    for (int i = 0; i < Count && ok; ++i) ok = (in >> out[i]) && std::isfinite(out[i]);
    std::string rest;
    if (!ok || (in >> rest)) {
      const std::string what =
          Count == 1 ? std::string("a finite number") : std::to_string(Count) + " finite numbers";
      check_argument(false, where(attribute).c_str(), what, "'" + input + "'");
    }
    return out;
  }
  double number(const char* attribute, const char* fallback = nullptr) const {
    return numbers<1>(attribute, fallback)[0];
  }
};

/// <origin xyz rpy> of `e` (each defaults to zero, as does a missing <origin>).
inline void read_urdf_origin(const UrdfElement& e, Eigen::Vector3d& xyz, Eigen::Vector3d& rpy) {
  const UrdfElement origin = e.child("origin", false);
  xyz.setZero();
  rpy.setZero();
  if (origin.element == nullptr) return;
  xyz = origin.numbers<3>("xyz", "0 0 0");
  rpy = origin.numbers<3>("rpy", "0 0 0");
}

inline LinkDescription read_urdf_link(const UrdfElement& e) {
  LinkDescription link;
  link.name = e.text("name");
  const UrdfElement inertial = e.child("inertial", false);
  if (inertial.element == nullptr) return link;  // massless
  Eigen::Vector3d xyz, rpy;
  read_urdf_origin(inertial, xyz, rpy);
  const UrdfElement mass = inertial.child("mass", true);
  link.mass = mass.number("value");
  check_argument(link.mass >= 0.0, mass.where("value").c_str(), "a mass >= 0 kg", link.mass);
  const UrdfElement inertia = inertial.child("inertia", true);
  const double ixy = inertia.number("ixy"), ixz = inertia.number("ixz"),
               iyz = inertia.number("iyz");
  Eigen::Matrix3d I;
  I << inertia.number("ixx"), ixy, ixz, ixy, inertia.number("iyy"), iyz, ixz, iyz,
      inertia.number("izz");
  const Eigen::Matrix3d R = rotation_from_rpy(rpy);  // inertia frame -> link frame
  link.com = xyz;
  link.inertia = R * I * R.transpose();
  link.inertia = (link.inertia + link.inertia.transpose()) / 2.0;  // exactly symmetric
  return link;
}

inline JointDescription read_urdf_joint(const UrdfElement& e) {
  JointDescription joint;
  joint.name = e.text("name");
  const std::string type = e.text("type");
  const bool revolute = type == "revolute", continuous = type == "continuous";
  check_argument(revolute || continuous || type == "fixed", e.where("type").c_str(),
                 "revolute, continuous or fixed", "'" + type + "'",
                 "walkgen's kinematic tree has rotary and fixed joints only");
  joint.type = revolute || continuous ? JointType::revolute : JointType::fixed;
  joint.parent = e.child("parent", true).text("link");
  joint.child = e.child("child", true).text("link");
  read_urdf_origin(e, joint.xyz, joint.rpy);
  if (joint.type == JointType::fixed) return joint;
  const UrdfElement axis = e.child("axis", false);
  if (axis.element != nullptr) {
    joint.axis = axis.numbers<3>("xyz", "1 0 0");
    check_argument(joint.axis.norm() > 0.0, axis.where("xyz").c_str(), "a non-zero axis", "0 0 0");
  }
  if (revolute) {  // URDF: lower and upper default to 0
    const UrdfElement limit = e.child("limit", true);
    joint.lower = limit.number("lower", "0");
    joint.upper = limit.number("upper", "0");
    check_argument(joint.lower <= joint.upper, limit.where().c_str(), "lower <= upper",
                   std::to_string(joint.lower) + " > " + std::to_string(joint.upper));
  }
  return joint;
}

/// The whole file as text. @throws walkgen::invalid_argument if it cannot be read.
inline std::string read_urdf_file(const std::string& path, const char* where) {
  std::ifstream file(path, std::ios::binary);
  check_argument(static_cast<bool>(file), where, "a readable URDF file", "'" + path + "'",
                 "check the path");
  std::ostringstream text;
  text << file.rdbuf();
  return text.str();
}

}  // namespace detail

/// Reads URDF text into a KinematicDescription.
/// @param source the document's name in messages (a path, or "URDF text")
/// @throws walkgen::invalid_argument for malformed XML, a missing <robot>, missing or malformed
/// attributes and unsupported joint types, naming the line and element.
[[nodiscard]] inline KinematicDescription kinematic_description_from_urdf(
    const std::string& urdf, const std::string& source = "URDF text") {
  tinyxml2::XMLDocument doc;
  if (doc.Parse(urdf.c_str(), urdf.size()) != tinyxml2::XML_SUCCESS) {
    const std::string where = source + ":" + std::to_string(doc.ErrorLineNum());
    const char* error = doc.ErrorStr();
    check_argument(false, where.c_str(), "well-formed XML",
                   std::string(error != nullptr ? error : "a parse error"));
  }
  const tinyxml2::XMLElement* robot = doc.RootElement();
  check_argument(robot != nullptr && std::string(robot->Name()) == "robot", source.c_str(),
                 "a <robot> root element",
                 robot == nullptr ? std::string("none") : "<" + std::string(robot->Name()) + ">");
  KinematicDescription d;
  const char* name = robot->Attribute("name");
  d.name = name != nullptr ? name : "";
  for (const tinyxml2::XMLElement* e = robot->FirstChildElement(); e != nullptr;
       e = e->NextSiblingElement()) {
    const std::string tag = e->Name();
    if (tag == "link") d.links.push_back(detail::read_urdf_link({source, e, ""}));
    if (tag == "joint") d.joints.push_back(detail::read_urdf_joint({source, e, ""}));
  }
  check_argument(!d.links.empty(), source.c_str(), "a <robot> with at least one <link>", "none");
  return d;
}

/// Reads a URDF file into a KinematicDescription.
/// @throws walkgen::invalid_argument if the file cannot be read, and as
/// kinematic_description_from_urdf().
[[nodiscard]] inline KinematicDescription kinematic_description_from_urdf_file(
    const std::string& path) {
  return kinematic_description_from_urdf(
      detail::read_urdf_file(path, "kinematic_description_from_urdf_file"), path);
}

/// Reads URDF text into a KinematicTree<Scalar>.
/// @throws walkgen::invalid_argument as kinematic_description_from_urdf() and as the
/// KinematicTree constructor (unknown links, cycles, ...), with `source` prepended.
template <typename Scalar = double>
[[nodiscard]] KinematicTree<Scalar> kinematic_tree_from_urdf(
    const std::string& urdf, const std::string& source = "URDF text") {
  KinematicDescription d = kinematic_description_from_urdf(urdf, source);
  try {
    return KinematicTree<Scalar>(std::move(d));
  } catch (const invalid_argument& e) {
    throw invalid_argument(source + ": " + e.what());
  }
}

/// Reads a URDF file into a KinematicTree<Scalar>; see kinematic_tree_from_urdf().
template <typename Scalar = double>
[[nodiscard]] KinematicTree<Scalar> kinematic_tree_from_urdf_file(const std::string& path) {
  return kinematic_tree_from_urdf<Scalar>(
      detail::read_urdf_file(path, "kinematic_tree_from_urdf_file"), path);
}

}  // namespace walkgen
