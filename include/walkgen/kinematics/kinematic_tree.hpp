#pragma once
/// @file
/// Kinematic tree of a floating-base robot, templated on the scalar (docs/design.md convention 7):
/// forward kinematics of every link (thesis §2.4.1, eq. 2.112), the whole-body centre of mass,
/// frame Jacobians and the centre-of-mass Jacobian (the J of eq. 2.114). Eigen only, so that
/// automatic-differentiation scalars (ceres::Jet) flow through the same code.
///
/// Model / Workspace (convention 3): a KinematicTree is immutable after construction; the poses
/// it computes live in a Workspace made once by make_workspace(). forward_kinematics(),
/// center_of_mass() and the Jacobians never touch the heap.
///
/// Frames and conventions:
/// - Every link has a frame; a joint's frame is its child link's frame (as in URDF). The root
///   link is the floating base; its pose in the world W is an input of forward_kinematics().
/// - Generalised velocity v (size num_velocities() = 6 + num_joints()): the root's linear
///   velocity in W [m/s], its angular velocity in W [rad/s], then the joint rates q̇ [rad/s] in
///   joint_names() order. A Jacobian maps v to a frame's linear velocity in W (rows 0–2) and its
///   angular velocity in W (rows 3–5), the "local world aligned" convention.
/// - q holds one angle [rad] per revolute joint, in the order of the joints in the
///   KinematicDescription (for a URDF: document order), which joint_index() also gives.
///
/// The description is plain data in double (read from URDF by urdf/urdf_loader.hpp, or written by
/// hand); the tree validates it and converts it once to Scalar.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cmath>
#include <cstddef>
#include <limits>
#include <optional>
#include <sstream>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "walkgen/core/exceptions.hpp"
#include "walkgen/core/math.hpp"

namespace walkgen {

/// Joint types of a KinematicTree. A URDF "continuous" joint is a revolute one without limits.
enum class JointType { revolute, fixed };

/// "revolute" or "fixed", e.g. for logs; "unknown" for a value out of range.
constexpr const char* to_string(JointType type) noexcept {
  switch (type) {
    case JointType::revolute:
      return "revolute";
    case JointType::fixed:
      return "fixed";
  }
  return "unknown";
}

/// What KinematicTree accepts in a description beyond finiteness: a link's mass and the length
/// of a joint's axis before it is normalised (the norm of (1e200, 0, 0) overflows to a zero
/// axis; 1e308 kg links sum to an infinite mass). The URDF loader checks the same bounds with
/// line numbers (UrdfBounds).
struct KinematicBounds {
  static constexpr double kMaxMass = 1e6;         ///< [kg]
  static constexpr double kMinAxisLength = 1e-6;  ///< axis length, any unit
  static constexpr double kMaxAxisLength = 1e6;
};

/// One rigid body of a KinematicDescription. Units: kg, m, kg m².
struct LinkDescription {
  std::string name;
  double mass = 0.0;                                  ///< [kg], >= 0
  Eigen::Vector3d com = Eigen::Vector3d::Zero();      ///< centre of mass in the link frame [m]
  Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero();  ///< about the centre of mass, link axes
};

/// One joint: places `child`'s frame in `parent`'s frame, at angle q for a revolute joint:
/// T_parent_child(q) = Trans(xyz) · Rot(rpy) · Rot(axis, q) (`rotation` in place of Rot(rpy)
/// when given).
struct JointDescription {
  std::string name;
  JointType type = JointType::fixed;
  std::string parent;                                       ///< parent link name
  std::string child;                                        ///< child link name
  Eigen::Vector3d xyz = Eigen::Vector3d::Zero();            ///< origin in the parent frame [m]
  Eigen::Vector3d rpy = Eigen::Vector3d::Zero();            ///< URDF roll, pitch, yaw [rad]:
                                                            ///< R = Rz(yaw) Ry(pitch) Rx(roll)
  Eigen::Vector3d axis = Eigen::Vector3d::UnitX();          ///< in the joint frame, any length > 0
  double lower = -std::numeric_limits<double>::infinity();  ///< position limit [rad]
  double upper = std::numeric_limits<double>::infinity();   ///< position limit [rad]
  /// The origin's rotation when given, instead of Rot(rpy): exact at any orientation, where
  /// rpy loses digits near pitch ±π/2 (e.g. an MJCF body's quaternion). Orthonormal, det +1.
  std::optional<Eigen::Matrix3d> rotation = std::nullopt;
};

/// A robot as plain data: links and the joints connecting them into one tree.
struct KinematicDescription {
  std::string name;
  std::vector<LinkDescription> links;
  std::vector<JointDescription> joints;
};

namespace detail {

/// Rotation of URDF roll, pitch, yaw angles: Rz(yaw) Ry(pitch) Rx(roll).
inline Eigen::Matrix3d rotation_from_rpy(const Eigen::Vector3d& rpy) {
  return (Eigen::AngleAxisd(rpy.z(), Eigen::Vector3d::UnitZ()) *
          Eigen::AngleAxisd(rpy.y(), Eigen::Vector3d::UnitY()) *
          Eigen::AngleAxisd(rpy.x(), Eigen::Vector3d::UnitX()))
      .toRotationMatrix();
}

/// "'a', 'b', 'c'" for messages.
inline std::string quoted_list(const std::vector<std::string>& names) {
  std::string out;
  for (const auto& n : names) out += (out.empty() ? "'" : ", '") + n + "'";
  return out;
}

inline std::string quote_name(const std::string& name) { return "'" + name + "'"; }

/// "(x y z)" for messages.
inline std::string vector_text(const Eigen::Vector3d& v) {
  std::ostringstream os;
  os << '(' << v.x() << ' ' << v.y() << ' ' << v.z() << ')';
  return os.str();
}

/// A link of a description in tree order (see ordered_links()).
struct OrderedLink {
  int link;    ///< index in KinematicDescription::links
  int joint;   ///< index of its parent joint in KinematicDescription::joints, -1 for the root
  int parent;  ///< position of its parent link in the order, -1 for the root
};

/// Checks a description and orders its links parents first (depth first from the root, children
/// in joint order).
/// @throws walkgen::invalid_argument naming the offending link or joint.
inline std::vector<OrderedLink> ordered_links(const KinematicDescription& d) {
  const char* where = "KinematicTree";
  const int n_links = static_cast<int>(d.links.size());
  check_argument(n_links > 0, where, "a description with at least one link", "none");

  auto find_link = [&](const std::string& name) {
    for (int i = 0; i < n_links; ++i) {
      if (d.links[std::size_t(i)].name == name) return i;
    }
    return -1;
  };
  for (int i = 0; i < n_links; ++i) {
    const LinkDescription& l = d.links[std::size_t(i)];
    const std::string at = std::string(where) + ": link " + quote_name(l.name);
    check_argument(!l.name.empty(), where, "a name for every link", "an empty name");
    check_argument(find_link(l.name) == i, at.c_str(), "a unique name", "it twice");
    check_argument(std::isfinite(l.mass) && l.mass >= 0.0 && l.mass <= KinematicBounds::kMaxMass,
                   at.c_str(), "a mass in [0, 1e6] kg", l.mass);
    check_argument(l.com.allFinite() && l.inertia.allFinite(), at.c_str(),
                   "a finite centre of mass and inertia", "a non-finite value");
    check_argument(l.inertia.isApprox(l.inertia.transpose(), 1e-12) || l.inertia.isZero(0.0),
                   at.c_str(), "a symmetric inertia", "an asymmetric one");
  }

  std::vector<int> parent_joint(std::size_t(n_links), -1);
  for (std::size_t j = 0; j < d.joints.size(); ++j) {
    const JointDescription& jd = d.joints[j];
    const std::string at = std::string(where) + ": joint " + quote_name(jd.name);
    check_argument(!jd.name.empty(), where, "a name for every joint", "an empty name");
    for (std::size_t k = 0; k < j; ++k) {
      check_argument(d.joints[k].name != jd.name, at.c_str(), "a unique name", "it twice");
    }
    const int parent = find_link(jd.parent), child = find_link(jd.child);
    check_argument(parent >= 0, at.c_str(), "a parent link of the description",
                   quote_name(jd.parent), "every link a joint names must be declared");
    check_argument(child >= 0, at.c_str(), "a child link of the description", quote_name(jd.child),
                   "every link a joint names must be declared");
    const int other = parent_joint[std::size_t(child)];
    check_argument(
        other < 0, at.c_str(), "the only joint whose child is " + quote_name(jd.child),
        "a second one after " + quote_name(d.joints[std::size_t(other < 0 ? 0 : other)].name),
        "a link has one parent joint; kinematic loops are not supported");
    parent_joint[std::size_t(child)] = static_cast<int>(j);
    check_argument(jd.xyz.allFinite() && jd.rpy.allFinite(), at.c_str(),
                   "a finite origin xyz and rpy",
                   vector_text(jd.xyz) + " and " + vector_text(jd.rpy));
    if (jd.rotation) {
      const Eigen::Matrix3d& R = *jd.rotation;
      check_argument(R.allFinite() &&
                         (R.transpose() * R - Eigen::Matrix3d::Identity()).norm() <= 1e-9 &&
                         R.determinant() > 0.0,
                     at.c_str(), "an origin rotation that is orthonormal with determinant +1",
                     "a matrix that is not");
    }
    if (jd.type == JointType::revolute) {
      // The norm of (1e200, 0, 0) overflows and normalises to zero: bound it (issue 21).
      const double length = jd.axis.allFinite() ? jd.axis.norm() : 0.0;
      check_argument(
          length >= KinematicBounds::kMinAxisLength && length <= KinematicBounds::kMaxAxisLength,
          at.c_str(), "a finite axis of length in [1e-6, 1e6]", vector_text(jd.axis));
      check_argument(!std::isnan(jd.lower) && !std::isnan(jd.upper) && jd.lower <= jd.upper,
                     at.c_str(), "limits with lower <= upper",
                     std::to_string(jd.lower) + " > " + std::to_string(jd.upper));
    }
  }

  std::vector<std::string> roots;
  int root = -1;
  for (int i = 0; i < n_links; ++i) {
    if (parent_joint[std::size_t(i)] < 0) {
      roots.push_back(d.links[std::size_t(i)].name);
      root = i;
    }
  }
  check_argument(
      roots.size() == 1, where, "exactly one root link (a link that is no joint's child)",
      roots.empty() ? std::string("none") : detail::quoted_list(roots),
      roots.empty() ? "the joints form a cycle" : "connect the roots by joints into one tree");

  // Depth first from the root; a link not reached hangs on a cycle.
  std::vector<OrderedLink> order;
  std::vector<std::pair<int, int>> stack{{root, -1}};  // (link, position of its parent)
  while (!stack.empty()) {
    const auto [link, parent] = stack.back();
    stack.pop_back();
    order.push_back({link, parent_joint[std::size_t(link)], parent});
    const int position = static_cast<int>(order.size()) - 1;
    for (std::size_t j = d.joints.size(); j-- > 0;) {  // reversed: the first joint pops first
      if (d.joints[j].parent == d.links[std::size_t(link)].name) {
        stack.emplace_back(find_link(d.joints[j].child), position);
      }
    }
  }
  if (order.size() != std::size_t(n_links)) {
    std::vector<std::string> unreached;
    for (int i = 0; i < n_links; ++i) {
      bool reached = false;
      for (const auto& o : order) reached = reached || o.link == i;
      if (!reached) unreached.push_back(d.links[std::size_t(i)].name);
    }
    check_argument(false, where, "every link below the root " + quote_name(roots.front()),
                   "a cycle through " + quoted_list(unreached), "a kinematic tree has no loops");
  }
  return order;
}

}  // namespace detail

/// A floating-base kinematic tree over Scalar (double, or an autodiff scalar such as ceres::Jet).
template <typename Scalar>
class KinematicTree {
 public:
  using Vector3 = Eigen::Matrix<Scalar, 3, 1>;
  using Matrix3 = Eigen::Matrix<Scalar, 3, 3>;
  using Matrix3X = Eigen::Matrix<Scalar, 3, Eigen::Dynamic>;
  using Matrix6X = Eigen::Matrix<Scalar, 6, Eigen::Dynamic>;

  /// One link and the joint that connects it to its parent (none for the root).
  struct Link {
    std::string name;
    std::string joint_name;  ///< empty for the root
    JointType joint_type = JointType::fixed;
    int parent = -1;      ///< index of the parent link (parents come first); -1 for the root
    int q_index = -1;     ///< entry of q for a revolute joint, else -1
    Matrix3 origin_R;     ///< joint frame in the parent frame at q = 0: rotation ...
    Vector3 origin_p;     ///< ... and position [m]
    Vector3 axis;         ///< unit joint axis in this link's frame
    Scalar mass;          ///< [kg]
    Scalar subtree_mass;  ///< this link and all below it [kg]
    Vector3 com;          ///< centre of mass in this link's frame [m]
    Matrix3 inertia;      ///< about the centre of mass, this link's axes [kg m²]
  };

  /// World poses of every link after forward_kinematics(), plus scratch space. Made by
  /// make_workspace(); all of its memory is allocated there.
  class Workspace {
   public:
    /// Orientation of link `link`'s frame in the world W (a rotation matrix).
    const Matrix3& rotation_W(int link) const { return R_W_[checked(link)]; }
    /// Position of link `link`'s frame origin in the world W [m].
    const Vector3& position_W(int link) const { return p_W_[checked(link)]; }

   private:
    friend class KinematicTree;
    explicit Workspace(std::size_t links) : R_W_(links), p_W_(links), moment_W_(links) {}
    std::size_t checked(int link) const {
      check_argument(link >= 0 && std::size_t(link) < R_W_.size(), "KinematicTree::Workspace",
                     "a link index in [0, num_links())", link);
      return std::size_t(link);
    }
    std::vector<Matrix3> R_W_;
    std::vector<Vector3> p_W_;
    std::vector<Vector3> moment_W_;  // Σ m (position of the CoM in W) over each link's subtree
    bool valid_ = false;             // forward_kinematics() has run
  };

  /// Validates `description` and converts it to Scalar.
  /// @throws walkgen::invalid_argument for empty or duplicate names, joints naming unknown
  /// links, a link with two parent joints, no or several roots, cycles, non-finite numbers, a
  /// zero axis, lower > upper or a negative mass; the message names the link or joint.
  explicit KinematicTree(KinematicDescription description) : description_(std::move(description)) {
    const auto order = detail::ordered_links(description_);

    for (const auto& jd : description_.joints) {  // q in description order
      if (jd.type == JointType::revolute) {
        joint_names_.push_back(jd.name);
        lower_.push_back(jd.lower);
        upper_.push_back(jd.upper);
      }
    }
    links_.reserve(order.size());
    double total = 0.0;
    for (const auto& o : order) {
      const LinkDescription& ld = description_.links[std::size_t(o.link)];
      Link l;
      l.name = ld.name;
      l.mass = Scalar(ld.mass);
      l.subtree_mass = Scalar(0);
      l.com = ld.com.cast<Scalar>();
      l.inertia = ld.inertia.cast<Scalar>();
      l.origin_R.setIdentity();
      l.origin_p.setZero();
      l.axis = Vector3::UnitX();
      total += ld.mass;
      l.parent = o.parent;
      if (o.joint >= 0) {
        const JointDescription& jd = description_.joints[std::size_t(o.joint)];
        l.joint_name = jd.name;
        l.joint_type = jd.type;
        l.origin_R = (jd.rotation ? *jd.rotation : detail::rotation_from_rpy(jd.rpy))
                         .template cast<Scalar>();
        l.origin_p = jd.xyz.cast<Scalar>();
        if (jd.type == JointType::revolute) {
          l.axis = jd.axis.normalized().cast<Scalar>();
          l.q_index = joint_index_of(jd.name);
        }
      }
      links_.push_back(std::move(l));
    }
    mass_ = total;
    // Subtree masses, children before parents (in double, then converted).
    std::vector<double> subtree(links_.size(), 0.0);
    for (std::size_t i = links_.size(); i-- > 0;) {
      subtree[i] += description_.links[std::size_t(order[i].link)].mass;
      if (links_[i].parent >= 0) subtree[std::size_t(links_[i].parent)] += subtree[i];
    }
    for (std::size_t i = 0; i < links_.size(); ++i) links_[i].subtree_mass = Scalar(subtree[i]);
  }

  /// The same tree over another scalar (e.g. double -> ceres::Jet for automatic differentiation).
  template <typename NewScalar>
  KinematicTree<NewScalar> cast() const {
    return KinematicTree<NewScalar>(description_);
  }

  /// A workspace for this tree (allocates; do it once, outside the control loop).
  Workspace make_workspace() const { return Workspace(links_.size()); }

  int num_links() const { return static_cast<int>(links_.size()); }
  /// Number of revolute joints, the size of q.
  int num_joints() const { return static_cast<int>(joint_names_.size()); }
  /// 6 + num_joints(): the size of the generalised velocity and the columns of a Jacobian.
  int num_velocities() const { return 6 + num_joints(); }
  /// Total mass [kg].
  double mass() const { return mass_; }
  /// The links, parents first; index 0 is the root.
  const std::vector<Link>& links() const { return links_; }
  const Link& link(int index) const {
    check_argument(index >= 0 && index < num_links(), "KinematicTree::link",
                   "an index in [0, num_links())", index);
    return links_[std::size_t(index)];
  }
  /// Revolute joint names in q order.
  const std::vector<std::string>& joint_names() const { return joint_names_; }
  /// Joint position limits [rad] in q order (±infinity where a joint has none).
  Eigen::VectorXd lower_limits() const { return as_vector(lower_); }
  Eigen::VectorXd upper_limits() const { return as_vector(upper_); }
  /// The validated description this tree was built from.
  const KinematicDescription& description() const { return description_; }

  /// Index of the link called `name` (for the workspace and the Jacobians).
  /// @throws walkgen::invalid_argument for an unknown name, listing the known ones.
  int link_index(const std::string& name) const {
    for (std::size_t i = 0; i < links_.size(); ++i) {
      if (links_[i].name == name) return static_cast<int>(i);
    }
    std::vector<std::string> names;
    for (const auto& l : links_) names.push_back(l.name);
    check_argument(false, "KinematicTree::link_index", "one of " + detail::quoted_list(names),
                   detail::quote_name(name));
    return -1;  // not reached
  }

  /// Entry of q that belongs to the revolute joint called `name`.
  /// @throws walkgen::invalid_argument for an unknown or fixed joint, listing the revolute ones.
  int joint_index(const std::string& name) const {
    const int index = joint_index_of(name);
    check_argument(index >= 0, "KinematicTree::joint_index",
                   "one of the revolute joints " + detail::quoted_list(joint_names_),
                   detail::quote_name(name));
    return index;
  }

  /// Forward kinematics (eq. 2.112): the world pose of every link, stored in `ws`.
  /// @param base_position_W, base_rotation_W  the root link's frame in the world (R orthonormal)
  /// @param q joint angles [rad], num_joints() entries in joint_names() order
  /// @throws walkgen::invalid_argument if q has the wrong size or ws belongs to another tree.
  template <typename Derived>
  void forward_kinematics(const Vector3& base_position_W, const Matrix3& base_rotation_W,
                          const Eigen::MatrixBase<Derived>& q, Workspace& ws) const {
    static_assert(std::is_same<typename Derived::Scalar, Scalar>::value,
                  "walkgen: q must have the tree's Scalar type");
    check_argument(q.size() == num_joints(), "KinematicTree::forward_kinematics: size of q",
                   num_joints(), q.size(), "one angle per revolute joint, see joint_names()");
    check_workspace(ws, false, "KinematicTree::forward_kinematics");
    ws.R_W_[0] = base_rotation_W;
    ws.p_W_[0] = base_position_W;
    for (std::size_t i = 1; i < links_.size(); ++i) {
      const Link& l = links_[i];
      const std::size_t parent = std::size_t(l.parent);
      ws.p_W_[i] = ws.p_W_[parent] + ws.R_W_[parent] * l.origin_p;
      if (l.q_index >= 0) {
        ws.R_W_[i] = ws.R_W_[parent] * (l.origin_R * axis_rotation(l.axis, q(l.q_index)));
      } else {
        ws.R_W_[i] = ws.R_W_[parent] * l.origin_R;
      }
    }
    // Mass moments of every subtree, children before parents (for the CoM and its Jacobian).
    for (std::size_t i = 0; i < links_.size(); ++i) {
      ws.moment_W_[i] = links_[i].mass * (ws.p_W_[i] + ws.R_W_[i] * links_[i].com);
    }
    for (std::size_t i = links_.size(); i-- > 1;) {
      ws.moment_W_[std::size_t(links_[i].parent)] += ws.moment_W_[i];
    }
    ws.valid_ = true;
  }

  /// Whole-body centre of mass in W [m] after forward_kinematics().
  /// @throws walkgen::invalid_argument if the tree has no mass or no FK was run on ws.
  Vector3 center_of_mass(const Workspace& ws) const {
    check_workspace(ws, true, "KinematicTree::center_of_mass");
    check_positive("KinematicTree::center_of_mass: total mass", mass_,
                   "a tree with a total mass > 0 kg");
    return ws.moment_W_[0] / links_[0].subtree_mass;
  }

  /// Jacobian of the whole-body centre of mass, 3 × num_velocities(): ċ_W = J v.
  /// @throws walkgen::invalid_argument if J has the wrong number of columns, the tree has no
  /// mass or no FK was run on ws.
  void center_of_mass_jacobian(const Workspace& ws, Eigen::Ref<Matrix3X> J) const {
    const char* where = "KinematicTree::center_of_mass_jacobian";
    check_columns(J.cols(), where);
    const Vector3 c = center_of_mass(ws);
    const Scalar total = links_[0].subtree_mass;
    J.setZero();
    J.template leftCols<3>().setIdentity();
    J.template middleCols<3>(3) = -skew(c - ws.p_W_[0]);
    for (std::size_t i = 1; i < links_.size(); ++i) {
      const Link& l = links_[i];
      if (l.q_index < 0) continue;
      // The subtree turns about the joint axis a: its CoM moves with a × (c_sub − p) m_sub / M.
      const Vector3 a = ws.R_W_[i] * l.axis;
      J.col(6 + l.q_index) = a.cross(ws.moment_W_[i] - l.subtree_mass * ws.p_W_[i]) / total;
    }
  }

  /// Jacobian of a point fixed in link `link` (point_L in the link frame, default its origin),
  /// 6 × num_velocities(): (ṗ_W, ω_W) = J v.
  /// @throws walkgen::invalid_argument for a bad link index, a J with the wrong number of
  /// columns, or no FK run on ws.
  void frame_jacobian(const Workspace& ws, int link, Eigen::Ref<Matrix6X> J,
                      const Vector3& point_L = Vector3::Zero()) const {
    const char* where = "KinematicTree::frame_jacobian";
    check_columns(J.cols(), where);
    check_workspace(ws, true, where);
    check_argument(link >= 0 && link < num_links(), where, "a link index in [0, num_links())", link,
                   "see link_index()");
    const Vector3 point_W = ws.p_W_[std::size_t(link)] + ws.R_W_[std::size_t(link)] * point_L;
    J.setZero();
    J.template block<3, 3>(0, 0).setIdentity();
    J.template block<3, 3>(0, 3) = -skew(point_W - ws.p_W_[0]);
    J.template block<3, 3>(3, 3).setIdentity();
    for (int i = link; i > 0; i = links_[std::size_t(i)].parent) {
      const Link& l = links_[std::size_t(i)];
      if (l.q_index < 0) continue;
      const Vector3 a = ws.R_W_[std::size_t(i)] * l.axis;
      J.template block<3, 1>(0, 6 + l.q_index) = a.cross(point_W - ws.p_W_[std::size_t(i)]);
      J.template block<3, 1>(3, 6 + l.q_index) = a;
    }
  }

 private:
  /// Rotation by angle q about the unit axis a (Rodrigues): cos q I + sin q [a]× + (1 − cos q) a
  /// aᵀ.
  static Matrix3 axis_rotation(const Vector3& a, const Scalar& q) {
    using std::cos;
    using std::sin;
    const Scalar c = cos(q), s = sin(q);
    const Scalar one_minus_c = Scalar(1) - c;
    Matrix3 R = (one_minus_c * a) * a.transpose();
    R += s * skew(a);
    R.diagonal().array() += c;
    return R;
  }

  int joint_index_of(const std::string& name) const {
    for (std::size_t i = 0; i < joint_names_.size(); ++i) {
      if (joint_names_[i] == name) return static_cast<int>(i);
    }
    return -1;
  }

  void check_workspace(const Workspace& ws, bool need_fk, const char* where) const {
    check_argument(ws.R_W_.size() == links_.size(), where,
                   "a workspace made by this tree's make_workspace()",
                   "one for a tree of another size");
    check_argument(!need_fk || ws.valid_, where, "a workspace after forward_kinematics()",
                   "one without poses", "call forward_kinematics() first");
  }

  void check_columns(Eigen::Index cols, const char* where) const {
    if (cols == num_velocities()) return;
    const std::string at = std::string(where) + ": columns of J";
    check_argument(false, at.c_str(), num_velocities(), cols,
                   "num_velocities() = 6 + num_joints()");
  }

  static Eigen::VectorXd as_vector(const std::vector<double>& v) {
    return Eigen::Map<const Eigen::VectorXd>(v.data(), Eigen::Index(v.size()));
  }

  KinematicDescription description_;
  std::vector<Link> links_;
  std::vector<std::string> joint_names_;
  std::vector<double> lower_, upper_;
  double mass_ = 0.0;
};

}  // namespace walkgen
