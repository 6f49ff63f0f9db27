#pragma once
/// @file
/// Kinematics of any robot MuJoCo loads: a KinematicDescription (and so a KinematicTree, its FK,
/// CoM, Jacobians and the Ceres IK) from an mjModel or an MJCF file, so that a robot described
/// only by its MJCF needs no URDF. Part of walkgen::mujoco.
///
/// What is read: the subtree of the base body (by default the one body below the world with a
/// free joint). Each body becomes a link named as the body (mass, centre of mass, inertia
/// rotated from its principal axes into the body frame); each hinge joint a revolute joint named
/// as the joint, with its axis, its range when limited, its anchor (`pos`) and its reference
/// angle (`ref`, qpos0) taken into account exactly as MuJoCo's kinematics does:
///   T_body = T_parent · Trans(pos) · Rot(quat) · Π_j [Trans(p_j) · Rot(a_j, q_j − ref_j) ·
///   Trans(−p_j)]
/// (a body with several hinges gets massless links "<body>/<joint>" in between; a body without
/// a joint is welded). Each site becomes a massless link named as the site, welded to its body
/// (a site at its body's origin with the body's orientation and the body's name is the body's
/// own link). q follows the order of the joints in the model. Bodies outside the base's subtree
/// (MuJoCo children of the world such as the G1's phantom bodies) are left out.
///
/// Not supported, with an error naming the joint: slide and ball joints, a free joint below the
/// base, joints on a base without a free joint.

#include <mujoco/mujoco.h>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "walkgen/core/exceptions.hpp"
#include "walkgen/kinematics/kinematic_tree.hpp"

namespace walkgen {

namespace detail {

inline Eigen::Matrix3d rotation_from_mj_quat(const mjtNum* q) {
  return Eigen::Quaterniond(q[0], q[1], q[2], q[3]).normalized().toRotationMatrix();
}

inline std::string mj_name(const mjModel& m, mjtObj type, int id, const char* fallback) {
  const char* name = mj_id2name(&m, type, id);
  return name != nullptr && *name != '\0' ? std::string(name)
                                          : std::string(fallback) + std::to_string(id);
}

/// A model MuJoCo loaded, deleted with it.
struct LoadedModel {
  std::unique_ptr<mjModel, void (*)(mjModel*)> m{nullptr, mj_deleteModel};
};

/// Loads an MJCF file. @throws walkgen::invalid_argument "<where>: '<path>': expected an MJCF
/// file MuJoCo loads, got <MuJoCo's message>".
inline LoadedModel load_mjcf(const std::string& path, const char* where) {
  LoadedModel l;
  char error[1000] = "";
  l.m.reset(mj_loadXML(path.c_str(), nullptr, error, sizeof error));
  check_argument(l.m != nullptr, (std::string(where) + ": '" + path + "'").c_str(),
                 "an MJCF file MuJoCo loads", std::string(error));
  return l;
}

}  // namespace detail

/// The kinematic description of the subtree of `base_body` (empty: the one body below the world
/// with a free joint) of a loaded MuJoCo model; see the file comment.
/// @throws walkgen::invalid_argument for an unknown base body (listing the bodies), none or
///   several free-floating bodies, or a joint this reader does not support (naming it).
inline KinematicDescription kinematic_description_from_mujoco(const mjModel& m,
                                                              const std::string& base_body = "") {
  const char* where = "kinematic_description_from_mujoco";
  int base = -1;
  if (!base_body.empty()) {
    base = mj_name2id(&m, mjOBJ_BODY, base_body.c_str());
    if (base <= 0) {
      std::vector<std::string> names;
      for (int b = 1; b < m.nbody; ++b) names.push_back(detail::mj_name(m, mjOBJ_BODY, b, "body"));
      check_argument(false, where, "a body of the model: " + detail::quoted_list(names),
                     "'" + base_body + "'");
    }
  } else {
    std::vector<std::string> floating;
    for (int b = 1; b < m.nbody; ++b) {
      if (m.body_parentid[b] == 0 && m.body_jntnum[b] >= 1 &&
          m.jnt_type[m.body_jntadr[b]] == mjJNT_FREE) {
        base = b;
        floating.push_back(detail::mj_name(m, mjOBJ_BODY, b, "body"));
      }
    }
    check_argument(floating.size() == 1, where,
                   "one body below the world with a free joint (or name the base body)",
                   floating.empty() ? std::string("none") : detail::quoted_list(floating));
  }
  // The base: its free joint (if any) is the tree's base pose; other joints are not supported.
  for (int j = m.body_jntadr[base]; j < m.body_jntadr[base] + m.body_jntnum[base]; ++j) {
    check_argument(m.jnt_type[j] == mjJNT_FREE && m.body_jntnum[base] == 1, where,
                   "a base body with a free joint or none",
                   "joint '" + detail::mj_name(m, mjOBJ_JOINT, j, "joint") + "'");
  }

  const auto massless_link = [](const std::string& name) {
    return LinkDescription{name, 0.0, Eigen::Vector3d::Zero(), Eigen::Matrix3d::Zero()};
  };
  KinematicDescription d;
  d.name = m.names != nullptr ? std::string(m.names) : std::string("mujoco_model");
  std::vector<std::string> link_of(static_cast<std::size_t>(m.nbody));
  std::vector<bool> in_tree(static_cast<std::size_t>(m.nbody), false);
  // Bodies are stored parents first, so one pass sees every parent before its children.
  for (int b = base; b < m.nbody; ++b) {
    const bool is_base = b == base;
    if (!is_base && !in_tree[static_cast<std::size_t>(m.body_parentid[b])]) continue;
    in_tree[static_cast<std::size_t>(b)] = true;
    const std::string name = detail::mj_name(m, mjOBJ_BODY, b, "body");
    link_of[static_cast<std::size_t>(b)] = name;
    LinkDescription link;
    link.name = name;
    link.mass = m.body_mass[b];
    link.com = Eigen::Vector3d(m.body_ipos[3 * b], m.body_ipos[3 * b + 1], m.body_ipos[3 * b + 2]);
    const Eigen::Matrix3d Ri = detail::rotation_from_mj_quat(m.body_iquat + 4 * b);
    link.inertia = Ri * Eigen::Map<const Eigen::Vector3d>(m.body_inertia + 3 * b).asDiagonal() *
                   Ri.transpose();
    link.inertia = (link.inertia + link.inertia.transpose()) / 2.0;
    if (is_base) {
      d.links.push_back(link);
      continue;
    }
    // The chain parent -> [joint links] -> body (file comment).
    std::string parent = link_of[static_cast<std::size_t>(m.body_parentid[b])];
    Eigen::Vector3d xyz(m.body_pos[3 * b], m.body_pos[3 * b + 1], m.body_pos[3 * b + 2]);
    Eigen::Matrix3d R = detail::rotation_from_mj_quat(m.body_quat + 4 * b);
    const int first = m.body_jntadr[b], count = m.body_jntnum[b];
    for (int j = first; j < first + count; ++j) {
      const std::string joint = detail::mj_name(m, mjOBJ_JOINT, j, "joint");
      check_argument(m.jnt_type[j] == mjJNT_HINGE, where,
                     "hinge joints below the base (slide, ball and free joints are not read)",
                     "joint '" + joint + "' of body '" + name + "'");
      const Eigen::Vector3d p(m.jnt_pos[3 * j], m.jnt_pos[3 * j + 1], m.jnt_pos[3 * j + 2]);
      const Eigen::Vector3d axis(m.jnt_axis[3 * j], m.jnt_axis[3 * j + 1], m.jnt_axis[3 * j + 2]);
      const double ref = m.qpos0[m.jnt_qposadr[j]];
      JointDescription jd;
      jd.name = joint;
      jd.type = JointType::revolute;
      jd.parent = parent;
      jd.child = j + 1 < first + count || p.squaredNorm() > 0.0 ? name + "/" + joint : name;
      jd.xyz = xyz + R * p;
      // Rot(a, q − ref) = Rot(a, −ref) Rot(a, q): the reference angle joins the origin.
      jd.rotation = R * Eigen::AngleAxisd(-ref, axis.normalized()).toRotationMatrix();
      jd.axis = axis;
      if (m.jnt_limited[j]) {
        jd.lower = m.jnt_range[2 * j];
        jd.upper = m.jnt_range[2 * j + 1];
      }
      d.joints.push_back(jd);
      if (jd.child != name) d.links.push_back(massless_link(jd.child));
      parent = jd.child;
      xyz = -p;  // the next joint's anchor (or the body) relative to this joint's frame
      R.setIdentity();
    }
    if (parent != name) {  // weld the body to its last joint frame (or to its parent)
      JointDescription weld;
      weld.name = name + "_fixed";
      weld.type = JointType::fixed;
      weld.parent = parent;
      weld.child = name;
      weld.xyz = xyz;
      weld.rotation = R;
      d.joints.push_back(weld);
    }
    d.links.push_back(link);
  }
  for (int s = 0; s < m.nsite; ++s) {
    const int b = m.site_bodyid[s];
    if (!in_tree[static_cast<std::size_t>(b)]) continue;
    const std::string name = detail::mj_name(m, mjOBJ_SITE, s, "site");
    const Eigen::Vector3d xyz(m.site_pos[3 * s], m.site_pos[3 * s + 1], m.site_pos[3 * s + 2]);
    const Eigen::Matrix3d R = detail::rotation_from_mj_quat(m.site_quat + 4 * s);
    const bool at_origin = xyz.squaredNorm() == 0.0 && R.isIdentity(0.0);
    if (name == link_of[static_cast<std::size_t>(b)] && at_origin) continue;  // the body itself
    d.links.push_back(massless_link(name));
    JointDescription weld;
    weld.name = name + "_fixed";
    weld.type = JointType::fixed;
    weld.parent = link_of[static_cast<std::size_t>(b)];
    weld.child = name;
    weld.xyz = xyz;
    weld.rotation = R;
    d.joints.push_back(weld);
  }
  return d;
}

/// The kinematic tree of an MJCF file (loaded with MuJoCo, then read as
/// kinematic_description_from_mujoco()).
/// @throws walkgen::invalid_argument when MuJoCo cannot load the file (with MuJoCo's message)
///   or the model is not read (see kinematic_description_from_mujoco()).
template <typename Scalar = double>
[[nodiscard]] KinematicTree<Scalar> kinematic_tree_from_mjcf_file(
    const std::string& path, const std::string& base_body = "") {
  const detail::LoadedModel l = detail::load_mjcf(path, "kinematic_tree_from_mjcf_file");
  return KinematicTree<Scalar>(kinematic_description_from_mujoco(*l.m, base_body));
}

}  // namespace walkgen
