#pragma once
// Helpers of the kinematics tests: random trees, configurations within the joint limits and base
// poses; frame and centre-of-mass Jacobians against central differences (support/derivatives.hpp).

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <random>
#include <sstream>
#include <string>
#include <utility>

#include "support/derivatives.hpp"
#include "walkgen/core/math.hpp"
#include "walkgen/kinematics/kinematic_tree.hpp"

namespace walkgen_test {

using Tree = walkgen::KinematicTree<double>;

/// "1.23e-10", for RecordProperty.
inline std::string scientific(double value) {
  std::ostringstream os;
  os.precision(3);
  os << std::scientific << value;
  return os.str();
}

/// A link with a diagonal inertia (0.01, 0.02, 0.025) kg m².
inline walkgen::LinkDescription make_link(const std::string& name, double mass = 0.0,
                                          const Eigen::Vector3d& com = Eigen::Vector3d::Zero()) {
  return {name, mass, com, Eigen::Vector3d(0.01, 0.02, 0.025).asDiagonal()};
}

inline walkgen::JointDescription make_joint(
    const std::string& name, walkgen::JointType type, const std::string& parent,
    const std::string& child, const Eigen::Vector3d& xyz,
    const Eigen::Vector3d& axis = Eigen::Vector3d::UnitZ()) {
  return {name, type, parent, child, xyz, Eigen::Vector3d::Zero(), axis};
}

// A random tree: random parents, origins, rpy, axes (not normalised), masses and CoMs, a quarter
// of the joints fixed, and links and joints listed in shuffled order.
inline walkgen::KinematicDescription random_tree(std::mt19937& rng, int n_links) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  auto vec = [&] { return Eigen::Vector3d(u(rng), u(rng), u(rng)); };
  walkgen::KinematicDescription d;
  for (int i = 0; i < n_links; ++i) {
    d.links.push_back(make_link("link" + std::to_string(i), 0.5 + u(rng) * 0.4, vec() * 0.2));
  }
  for (int i = 1; i < n_links; ++i) {
    const int parent = std::uniform_int_distribution<int>(0, i - 1)(rng);
    const walkgen::JointType type =
        i % 4 == 3 ? walkgen::JointType::fixed : walkgen::JointType::revolute;
    walkgen::JointDescription j =
        make_joint("joint" + std::to_string(i), type, "link" + std::to_string(parent),
                   "link" + std::to_string(i), vec() * 0.3, vec() * 2.0);
    j.rpy = vec() * 3.0;
    if (i % 5 == 0) {  // a limited joint
      j.lower = -1.0;
      j.upper = 1.5;
    }
    d.joints.push_back(j);
  }
  std::shuffle(d.links.begin(), d.links.end(), rng);
  std::shuffle(d.joints.begin(), d.joints.end(), rng);
  return d;
}

/// A pose of the root link in the world.
struct BasePose {
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
};

/// Position uniform in [-range, range]^3, orientation uniform over the rotations.
inline BasePose random_base_pose(std::mt19937& rng, double range = 1.0) {
  std::uniform_real_distribution<double> u(-range, range);
  std::normal_distribution<double> n(0.0, 1.0);
  BasePose pose;
  pose.position = Eigen::Vector3d(u(rng), u(rng), u(rng));
  pose.rotation =
      Eigen::Quaterniond(n(rng), n(rng), n(rng), n(rng)).normalized().toRotationMatrix();
  return pose;
}

/// Joint angles uniform within the limits ([-pi, pi] where a joint has none).
inline Eigen::VectorXd random_configuration(const Tree& tree, std::mt19937& rng) {
  const Eigen::VectorXd lower = tree.lower_limits(), upper = tree.upper_limits();
  Eigen::VectorXd q(tree.num_joints());
  for (Eigen::Index i = 0; i < q.size(); ++i) {
    const double lo = std::isfinite(lower[i]) ? lower[i] : -walkgen::kPi;
    const double hi = std::isfinite(upper[i]) ? upper[i] : walkgen::kPi;
    q[i] = std::uniform_real_distribution<double>(lo, hi)(rng);
  }
  return q;
}

/// The generalised velocity's blocks: base position, base rotation, "joint r_knee", ...
inline Blocks velocity_blocks(const Tree& tree) {
  Blocks b = {{"base position", 3}, {"base rotation", 3}};
  for (const auto& name : tree.joint_names()) b.push_back({"joint " + name, 1});
  return b;
}

/// The frame Jacobian of `link` at point_L (rows ṗ, ω), or for link −1 the centre-of-mass
/// Jacobian, against central differences (step 1e-6) in the generalised velocity's coordinates
/// (the base rotation vector in W applied on the left; angular rows from log(R₊ R₋ᵀ) / 2h).
inline JacobianCheck check_tree_jacobian(const Tree& tree, const BasePose& base,
                                         const Eigen::VectorXd& q, int link,
                                         const Eigen::Vector3d& point_L, Tolerance tolerance) {
  const bool com = link < 0;
  Tree::Workspace ws = tree.make_workspace();
  tree.forward_kinematics(base.position, base.rotation, q, ws);
  Eigen::Matrix<double, 6, Eigen::Dynamic> J(6, tree.num_velocities());
  if (com) tree.center_of_mass_jacobian(ws, J.topRows<3>());
  if (!com) tree.frame_jacobian(ws, link, J, point_L);
  using Pose = std::pair<Eigen::Vector3d, Eigen::Matrix3d>;  // the point (or CoM), its rotation
  auto at = [&](const Eigen::VectorXd& dx) {
    const Eigen::Vector3d w = dx.segment<3>(3);
    const Eigen::Matrix3d turn =
        w.norm() > 0.0 ? Eigen::AngleAxisd(w.norm(), w.normalized()).toRotationMatrix()
                       : Eigen::Matrix3d::Identity();
    tree.forward_kinematics(base.position + dx.head<3>(), turn * base.rotation,
                            q + dx.tail(q.size()), ws);
    if (com) return Pose(tree.center_of_mass(ws), Eigen::Matrix3d::Identity());
    return Pose(ws.position_W(link) + ws.rotation_W(link) * point_L, ws.rotation_W(link));
  };
  auto minus = [](const Pose& a, const Pose& b) {
    const Eigen::AngleAxisd turn(a.second * b.second.transpose());
    Eigen::VectorXd d(6);
    d << a.first - b.first, turn.angle() * turn.axis();
    return d;
  };
  const Eigen::Index rows = com ? 3 : 6;
  return compare_jacobians(
      com ? "centre-of-mass Jacobian" : "frame Jacobian of link '" + tree.link(link).name + "'",
      J.topRows(rows), central_differences(tree.num_velocities(), 1e-6, at, minus).topRows(rows),
      tolerance,
      com ? Blocks{{"CoM", 3}} : Blocks{{"point linear velocity", 3}, {"angular velocity", 3}},
      velocity_blocks(tree));
}

/// Non-default body points and weights of the IK residual (IkResidualSettings or CeresIkSettings),
/// so that every term of its Jacobian counts.
template <typename Settings>
Settings offset_ik_settings(Settings s = Settings()) {
  s.com_body_point = Eigen::Vector3d(0.01, -0.02, 0.03);
  s.lf_body_point = Eigen::Vector3d(0.05, 0.01, 0.0);
  s.rf_body_point = Eigen::Vector3d(-0.03, -0.02, 0.01);
  s.foot_orientation_weight = 2.0;
  s.com_weight = 0.5;
  return s;
}

/// Frame Jacobians (every link, at random points) and the centre-of-mass Jacobian against
/// central differences over the configurations added: the worst of each.
struct TreeJacobianChecks {
  JacobianCheck frame, com;

  /// Adds a random base pose and in-limit configuration of `tree`; the frame Jacobian of each
  /// link is taken at a point uniform in [-point_range, point_range]^3 of its frame.
  void add_random_configuration(const Tree& tree, std::mt19937& rng, double point_range,
                                Tolerance tolerance) {
    const auto base = random_base_pose(rng);
    const Eigen::VectorXd q = random_configuration(tree, rng);
    std::uniform_real_distribution<double> u(-point_range, point_range);
    for (int link = 0; link < tree.num_links(); ++link) {
      const Eigen::Vector3d point_L(u(rng), u(rng), u(rng));
      frame.merge(check_tree_jacobian(tree, base, q, link, point_L, tolerance));
    }
    com.merge(check_tree_jacobian(tree, base, q, -1, Eigen::Vector3d::Zero(), tolerance));
  }
};

}  // namespace walkgen_test
