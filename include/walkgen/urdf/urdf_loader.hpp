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
/// Every number must be finite and within the bounds below (UrdfBounds: masses, lengths, angles,
/// inertias, axis lengths), so that a loaded robot has a finite total mass, centre of mass and
/// forward kinematics. Names must be non-empty and unique among the links and among the joints.
///
/// Every problem throws walkgen::invalid_argument naming the source, the line and the element,
/// e.g. "robot.urdf:12: <joint name='l_knee'> <origin> xyz: expected 3 finite numbers separated
/// by spaces, got '0 0'". Problems of the tree's shape (unknown links, a link with two parents,
/// cycles, several roots) are found by KinematicTree's checks and reported with the source
/// prepended, e.g. "robot.urdf: KinematicTree: joint 'l_knee': expected a parent link ...".

#include <tinyxml2.h>

#include <Eigen/Eigenvalues>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <locale>
#include <map>
#include <sstream>
#include <string>

#include "walkgen/core/exceptions.hpp"
#include "walkgen/kinematics/kinematic_tree.hpp"

namespace walkgen {

/// What the URDF loader accepts (docs/kinematics.md, "URDF limits"): bounds far beyond any
/// walking robot that keep the total mass, the centre of mass and the forward kinematics finite.
struct UrdfBounds {
  /// A link's mass [kg]: 0 (massless) or in [kMinMass, kMaxMass].
  static constexpr double kMinMass = 1e-9;
  static constexpr double kMaxMass = KinematicBounds::kMaxMass;
  /// |ixx| ... |izz| [kg m²]; the inertia must also be positive semidefinite: its smallest
  /// eigenvalue >= -kInertiaTolerance times its largest (rounding in the file).
  static constexpr double kMaxInertia = 1e12;
  static constexpr double kInertiaTolerance = 1e-3;
  /// |x|, |y|, |z| of every <origin xyz> [m].
  static constexpr double kMaxLength = 1e3;
  /// |roll|, |pitch|, |yaw| of every <origin rpy> and |lower|, |upper| of a <limit> [rad].
  static constexpr double kMaxAngle = 1e3;
  /// The length of a joint's <axis xyz> before it is normalised.
  static constexpr double kMinAxisLength = KinematicBounds::kMinAxisLength;
  static constexpr double kMaxAxisLength = KinematicBounds::kMaxAxisLength;
};

namespace detail {

/// A bound for messages: 1e6 as "1e6", 1000 as "1000", 1e-9 as "1e-9".
inline std::string urdf_bound_text(double bound) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%g", bound);
  std::string text = buffer;
  const auto e = text.find('e');
  if (e == std::string::npos) return text;
  std::string exponent = text.substr(e + 1);
  const bool negative = exponent[0] == '-';
  if (exponent[0] == '+' || exponent[0] == '-') exponent.erase(0, 1);
  while (exponent.size() > 1 && exponent[0] == '0') exponent.erase(0, 1);
  return text.substr(0, e + 1) + (negative ? "-" : "") + exponent;
}

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

  /// numbers(), each within [-bound, bound]; `what` names them, e.g. "coordinates", `unit` "m".
  template <int Count>
  Eigen::Matrix<double, Count, 1> bounded_numbers(const char* attribute, double bound,
                                                  const char* what, const char* unit,
                                                  const char* fallback = nullptr) const {
    const Eigen::Matrix<double, Count, 1> out = numbers<Count>(attribute, fallback);
    if (out.cwiseAbs().maxCoeff() > bound) {
      const char* value = element->Attribute(attribute);
      check_argument(false, where(attribute).c_str(),
                     std::string(what) + " in [-" + urdf_bound_text(bound) + ", " +
                         urdf_bound_text(bound) + "] " + unit,
                     "'" + std::string(value != nullptr ? value : fallback) + "'");
    }
    return out;
  }
  double bounded_number(const char* attribute, double bound, const char* what, const char* unit,
                        const char* fallback = nullptr) const {
    return bounded_numbers<1>(attribute, bound, what, unit, fallback)[0];
  }

  /// A name attribute (of the element, or "link" of <parent>/<child>): present and non-empty.
  std::string name(const char* attribute) const {
    std::string value = text(attribute);
    check_argument(!value.empty(), where(attribute).c_str(), "a non-empty name", "''");
    return value;
  }
};

/// <origin xyz rpy> of `e` (each defaults to zero, as does a missing <origin>).
inline void read_urdf_origin(const UrdfElement& e, Eigen::Vector3d& xyz, Eigen::Vector3d& rpy) {
  const UrdfElement origin = e.child("origin", false);
  xyz.setZero();
  rpy.setZero();
  if (origin.element == nullptr) return;
  xyz = origin.bounded_numbers<3>("xyz", UrdfBounds::kMaxLength, "3 coordinates", "m", "0 0 0");
  rpy = origin.bounded_numbers<3>("rpy", UrdfBounds::kMaxAngle, "3 angles", "rad", "0 0 0");
}

inline LinkDescription read_urdf_link(const UrdfElement& e) {
  LinkDescription link;
  link.name = e.name("name");
  const UrdfElement inertial = e.child("inertial", false);
  if (inertial.element == nullptr) return link;  // massless
  Eigen::Vector3d xyz, rpy;
  read_urdf_origin(inertial, xyz, rpy);
  const UrdfElement mass = inertial.child("mass", true);
  link.mass = mass.number("value");
  check_argument(
      link.mass == 0.0 || (link.mass >= UrdfBounds::kMinMass && link.mass <= UrdfBounds::kMaxMass),
      mass.where("value").c_str(),
      "a mass of 0 kg or in [" + urdf_bound_text(UrdfBounds::kMinMass) + ", " +
          urdf_bound_text(UrdfBounds::kMaxMass) + "] kg",
      link.mass);
  // Every attribute is read before the matrix is filled: a throw in the middle of Eigen's comma
  // initializer would trip its "too few coefficients" assertion in a Debug build.
  const UrdfElement inertia = inertial.child("inertia", true);
  const auto moment = [&](const char* attribute) {
    return inertia.bounded_number(attribute, UrdfBounds::kMaxInertia, "an inertia entry", "kg m^2");
  };
  const double ixx = moment("ixx"), ixy = moment("ixy"), ixz = moment("ixz"), iyy = moment("iyy"),
               iyz = moment("iyz"), izz = moment("izz");
  Eigen::Matrix3d I;
  I << ixx, ixy, ixz, ixy, iyy, iyz, ixz, iyz, izz;
  const Eigen::Vector3d eigenvalues =
      Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(I, Eigen::EigenvaluesOnly).eigenvalues();
  check_argument(
      eigenvalues.minCoeff() >= -UrdfBounds::kInertiaTolerance * eigenvalues.cwiseAbs().maxCoeff(),
      inertia.where().c_str(),
      "a positive semidefinite inertia (principal moments >= 0, up to " +
          urdf_bound_text(UrdfBounds::kInertiaTolerance) + " of the largest)",
      "principal moments " + vector_text(eigenvalues) + " kg m^2");
  const Eigen::Matrix3d R = rotation_from_rpy(rpy);  // inertia frame -> link frame
  link.com = xyz;
  link.inertia = R * I * R.transpose();
  link.inertia = (link.inertia + link.inertia.transpose()) / 2.0;  // exactly symmetric
  return link;
}

inline JointDescription read_urdf_joint(const UrdfElement& e) {
  JointDescription joint;
  joint.name = e.name("name");
  const std::string type = e.text("type");
  const bool revolute = type == "revolute", continuous = type == "continuous";
  check_argument(revolute || continuous || type == "fixed", e.where("type").c_str(),
                 "revolute, continuous or fixed", "'" + type + "'",
                 "walkgen's kinematic tree has rotary and fixed joints only");
  joint.type = revolute || continuous ? JointType::revolute : JointType::fixed;
  joint.parent = e.child("parent", true).name("link");
  joint.child = e.child("child", true).name("link");
  read_urdf_origin(e, joint.xyz, joint.rpy);
  if (joint.type == JointType::fixed) return joint;
  const UrdfElement axis = e.child("axis", false);
  if (axis.element != nullptr) {
    joint.axis = axis.numbers<3>("xyz", "1 0 0");
    // Bounded before the norm: the squares of (1e200, 0, 0) overflow, and it normalises to 0.
    const double length = joint.axis.cwiseAbs().maxCoeff() <= UrdfBounds::kMaxAxisLength
                              ? joint.axis.norm()
                              : std::numeric_limits<double>::infinity();
    const char* text = axis.element->Attribute("xyz");
    check_argument(length >= UrdfBounds::kMinAxisLength && length <= UrdfBounds::kMaxAxisLength,
                   axis.where("xyz").c_str(),
                   "a non-zero axis of length in [" + urdf_bound_text(UrdfBounds::kMinAxisLength) +
                       ", " + urdf_bound_text(UrdfBounds::kMaxAxisLength) + "]",
                   "'" + std::string(text != nullptr ? text : "1 0 0") + "'", "it is normalised");
  }
  if (revolute) {  // URDF: lower and upper default to 0
    const UrdfElement limit = e.child("limit", true);
    joint.lower = limit.bounded_number("lower", UrdfBounds::kMaxAngle, "a limit", "rad", "0");
    joint.upper = limit.bounded_number("upper", UrdfBounds::kMaxAngle, "a limit", "rad", "0");
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

/// URDF text as a KinematicDescription, every element checked but not the tree's shape (that
/// is KinematicTree's, see kinematic_description_from_urdf()).
inline KinematicDescription read_urdf_description(const std::string& urdf,
                                                  const std::string& source) {
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
  std::map<std::string, int> link_lines, joint_lines;  // first line of each name
  const auto unique = [&](std::map<std::string, int>& lines, const UrdfElement& e,
                          const std::string& element_name, const char* kind) {
    const auto [it, inserted] = lines.emplace(element_name, e.element->GetLineNum());
    check_argument(inserted, e.where("name").c_str(), std::string("a unique ") + kind + " name",
                   std::string(kind) + " '" + element_name + "' again after line " +
                       std::to_string(it->second));
  };
  for (const tinyxml2::XMLElement* e = robot->FirstChildElement(); e != nullptr;
       e = e->NextSiblingElement()) {
    const std::string tag = e->Name();
    const UrdfElement element{source, e, ""};
    if (tag == "link") {
      d.links.push_back(read_urdf_link(element));
      unique(link_lines, element, d.links.back().name, "link");
    }
    if (tag == "joint") {
      d.joints.push_back(read_urdf_joint(element));
      unique(joint_lines, element, d.joints.back().name, "joint");
    }
  }
  check_argument(!d.links.empty(), source.c_str(), "a <robot> with at least one <link>", "none");
  // Each mass is at most UrdfBounds::kMaxMass: the total overflows only for ~1e302 links.
  double total = 0.0;
  for (const auto& link : d.links) total += link.mass;
  check_argument(std::isfinite(total), source.c_str(), "a finite total mass", total);
  return d;
}

/// Runs `f` (KinematicTree's checks), prepending `source` to its message.
template <typename F>
auto with_urdf_source(const std::string& source, F&& f) -> decltype(f()) {
  try {
    return f();
  } catch (const invalid_argument& e) {
    throw invalid_argument(source + ": " + e.what());
  }
}

}  // namespace detail

/// Reads URDF text into a KinematicDescription and checks it as KinematicTree would.
/// @param source the document's name in messages (a path, or "URDF text")
/// @throws walkgen::invalid_argument for malformed XML, a missing <robot>, missing, malformed or
/// out-of-bounds attributes (UrdfBounds), empty or repeated link or joint names and unsupported
/// joint types, naming the line and element; and for a description that is no tree (see
/// KinematicTree's constructor), naming the link or joint, with `source` prepended.
[[nodiscard]] inline KinematicDescription kinematic_description_from_urdf(
    const std::string& urdf, const std::string& source = "URDF text") {
  KinematicDescription d = detail::read_urdf_description(urdf, source);
  // One root, every link reached, no cycles: the checks of KinematicTree's constructor.
  (void)detail::with_urdf_source(source, [&] { return detail::ordered_links(d); });
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
  KinematicDescription d = detail::read_urdf_description(urdf, source);
  return detail::with_urdf_source(source, [&] { return KinematicTree<Scalar>(std::move(d)); });
}

/// Reads a URDF file into a KinematicTree<Scalar>; see kinematic_tree_from_urdf().
template <typename Scalar = double>
[[nodiscard]] KinematicTree<Scalar> kinematic_tree_from_urdf_file(const std::string& path) {
  return kinematic_tree_from_urdf<Scalar>(
      detail::read_urdf_file(path, "kinematic_tree_from_urdf_file"), path);
}

}  // namespace walkgen
