#pragma once
// Helpers of the kinematics tests: random configurations within the joint limits, random
// floating-base poses, and central finite differences of frame and centre-of-mass Jacobians.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <random>
#include <sstream>
#include <string>

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
  walkgen::LinkDescription l;
  l.name = name;
  l.mass = mass;
  l.com = com;
  l.inertia = Eigen::Vector3d(0.01, 0.02, 0.025).asDiagonal();
  return l;
}

inline walkgen::JointDescription make_joint(
    const std::string& name, walkgen::JointType type, const std::string& parent,
    const std::string& child, const Eigen::Vector3d& xyz,
    const Eigen::Vector3d& axis = Eigen::Vector3d::UnitZ()) {
  walkgen::JointDescription j;
  j.name = name;
  j.type = type;
  j.parent = parent;
  j.child = child;
  j.xyz = xyz;
  j.axis = axis;
  return j;
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

/// Position and orientation of a point fixed in a link, for a configuration.
struct PointPose {
  Eigen::Vector3d position;
  Eigen::Matrix3d rotation;
};

/// The configuration moved by h along generalised velocity component k (base translation in W,
/// base rotation in W, joints), evaluated by `f(position, rotation, q)`.
template <typename F>
auto perturbed(const BasePose& base, const Eigen::VectorXd& q, int k, double h, F&& f) {
  BasePose b = base;
  Eigen::VectorXd qk = q;
  if (k < 3) {
    b.position[k] += h;
  } else if (k < 6) {
    b.rotation = Eigen::AngleAxisd(h, Eigen::Vector3d::Unit(k - 3)).toRotationMatrix() * b.rotation;
  } else {
    qk[k - 6] += h;
  }
  return f(b.position, b.rotation, qk);
}

/// Largest entry of |J − J_fd| for the frame Jacobian of `link` at point_L, J_fd by central
/// differences with step h (angular rows from log(R₊ R₋ᵀ) / 2h).
inline double frame_jacobian_fd_error(const Tree& tree, const BasePose& base,
                                      const Eigen::VectorXd& q, int link,
                                      const Eigen::Vector3d& point_L, double h = 1e-6) {
  Tree::Workspace ws = tree.make_workspace();
  auto pose = [&](const Eigen::Vector3d& p, const Eigen::Matrix3d& R, const Eigen::VectorXd& qq) {
    tree.forward_kinematics(p, R, qq, ws);
    return PointPose{ws.position_W(link) + ws.rotation_W(link) * point_L, ws.rotation_W(link)};
  };
  tree.forward_kinematics(base.position, base.rotation, q, ws);
  Eigen::Matrix<double, 6, Eigen::Dynamic> J(6, tree.num_velocities());
  tree.frame_jacobian(ws, link, J, point_L);
  double error = 0.0;
  for (int k = 0; k < tree.num_velocities(); ++k) {
    const PointPose plus = perturbed(base, q, k, h, pose), minus = perturbed(base, q, k, -h, pose);
    const Eigen::AngleAxisd turn(plus.rotation * minus.rotation.transpose());
    Eigen::Matrix<double, 6, 1> column;
    column << (plus.position - minus.position) / (2 * h), turn.angle() * turn.axis() / (2 * h);
    error = std::max(error, (J.col(k) - column).cwiseAbs().maxCoeff());
  }
  return error;
}

/// Largest entry of |J − J_fd| for the centre-of-mass Jacobian, by central differences.
inline double com_jacobian_fd_error(const Tree& tree, const BasePose& base,
                                    const Eigen::VectorXd& q, double h = 1e-6) {
  Tree::Workspace ws = tree.make_workspace();
  auto com = [&](const Eigen::Vector3d& p, const Eigen::Matrix3d& R, const Eigen::VectorXd& qq) {
    tree.forward_kinematics(p, R, qq, ws);
    return Eigen::Vector3d(tree.center_of_mass(ws));
  };
  tree.forward_kinematics(base.position, base.rotation, q, ws);
  Eigen::Matrix<double, 3, Eigen::Dynamic> J(3, tree.num_velocities());
  tree.center_of_mass_jacobian(ws, J);
  double error = 0.0;
  for (int k = 0; k < tree.num_velocities(); ++k) {
    const Eigen::Vector3d column =
        (perturbed(base, q, k, h, com) - perturbed(base, q, k, -h, com)) / (2 * h);
    error = std::max(error, (J.col(k) - column).cwiseAbs().maxCoeff());
  }
  return error;
}

/// Largest central-difference errors of frame Jacobians (every link, at random points) and of the
/// centre-of-mass Jacobian, over the configurations added.
struct JacobianFdErrors {
  double frame = 0.0;
  double com = 0.0;

  /// Adds a random base pose and in-limit configuration of `tree`; the frame Jacobian of each
  /// link is taken at a point uniform in [-point_range, point_range]^3 of its frame.
  void add_random_configuration(const Tree& tree, std::mt19937& rng, double point_range) {
    const auto base = random_base_pose(rng);
    const Eigen::VectorXd q = random_configuration(tree, rng);
    std::uniform_real_distribution<double> u(-point_range, point_range);
    for (int link = 0; link < tree.num_links(); ++link) {
      const Eigen::Vector3d point_L(u(rng), u(rng), u(rng));
      frame = std::max(frame, frame_jacobian_fd_error(tree, base, q, link, point_L));
    }
    com = std::max(com, com_jacobian_fd_error(tree, base, q));
  }
};

}  // namespace walkgen_test
