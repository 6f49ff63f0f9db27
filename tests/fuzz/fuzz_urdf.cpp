// Fuzz harness of the URDF adapter (tests/fuzz/README.md): the bytes are URDF text. Whatever
// they are, kinematic_tree_from_urdf() either throws walkgen::invalid_argument or returns a tree
// whose numbers are sound: a finite total mass >= 0 (massless robots are allowed), unit joint
// axes, finite limits with lower <= upper or none, and finite forward kinematics, rotations,
// centre of mass and Jacobians at the zero configuration and at configurations within the
// limits. Seeds: tests/fuzz/corpus/urdf (small robots of every joint type, the humanoid) and the
// reproducers in tests/data/reliability/urdf.

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <exception>
#include <optional>
#include <string>

#include "fuzz/fuzz_support.hpp"
#include "walkgen/urdf/urdf_loader.hpp"

namespace {

using Tree = walkgen::KinematicTree<double>;

// FK at q, then every pose, the CoM and the Jacobians must be finite, the rotations orthonormal.
void check_configuration(const Tree& tree, Tree::Workspace& ws, const Eigen::VectorXd& q,
                         const char* which) {
  const std::string at = std::string(" at the ") + which + " configuration";
  tree.forward_kinematics(Eigen::Vector3d::Zero(), Eigen::Matrix3d::Identity(), q, ws);
  for (int i = 0; i < tree.num_links(); ++i) {
    const std::string link = "link '" + tree.link(i).name + "'";
    WALKGEN_FUZZ_CHECK(ws.position_W(i).allFinite(), link + ": a non-finite position" + at);
    const Eigen::Matrix3d& R = ws.rotation_W(i);
    WALKGEN_FUZZ_CHECK(R.allFinite(), link + ": a non-finite rotation" + at);
    // Each joint adds ~1e-16 of rounding; 1e-9 leaves room for thousands of links.
    WALKGEN_FUZZ_CHECK(
        (R.transpose() * R - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff() < 1e-9,
        link + ": a rotation that is not orthonormal" + at);
  }
  Eigen::Matrix<double, 6, Eigen::Dynamic> J(6, tree.num_velocities());
  tree.frame_jacobian(ws, tree.num_links() - 1, J);
  WALKGEN_FUZZ_CHECK(J.allFinite(), "a non-finite frame Jacobian" + at);
  if (tree.mass() > 0.0) {
    const Eigen::Vector3d com = tree.center_of_mass(ws);
    WALKGEN_FUZZ_CHECK(com.allFinite(), "a non-finite centre of mass" + at);
    Eigen::Matrix<double, 3, Eigen::Dynamic> Jc(3, tree.num_velocities());
    tree.center_of_mass_jacobian(ws, Jc);
    WALKGEN_FUZZ_CHECK(Jc.allFinite(), "a non-finite CoM Jacobian" + at);
  }
}

void check_tree(const Tree& tree) {
  WALKGEN_FUZZ_CHECK(std::isfinite(tree.mass()) && tree.mass() >= 0.0,
                     "total mass " + std::to_string(tree.mass()) + " kg");
  WALKGEN_FUZZ_CHECK(tree.num_links() >= 1, "a tree without links");
  for (const auto& link : tree.links()) {
    WALKGEN_FUZZ_CHECK(std::isfinite(link.mass) && link.mass >= 0.0,
                       "link '" + link.name + "': mass " + std::to_string(link.mass));
    WALKGEN_FUZZ_CHECK(link.com.allFinite() && link.inertia.allFinite(),
                       "link '" + link.name + "': a non-finite CoM or inertia");
    if (link.q_index >= 0) {
      WALKGEN_FUZZ_CHECK(std::abs(link.axis.norm() - 1.0) < 1e-12,
                         "joint '" + link.joint_name + "': axis of length " +
                             std::to_string(link.axis.norm()) + " after normalising");
    }
  }
  const Eigen::VectorXd lower = tree.lower_limits(), upper = tree.upper_limits();
  for (int j = 0; j < tree.num_joints(); ++j) {
    const bool unlimited = std::isinf(lower[j]) && lower[j] < 0 && std::isinf(upper[j]) &&
                           upper[j] > 0;  // a continuous joint
    WALKGEN_FUZZ_CHECK(
        unlimited || (std::isfinite(lower[j]) && std::isfinite(upper[j]) && lower[j] <= upper[j]),
        "joint '" + tree.joint_names()[std::size_t(j)] + "': limits [" + std::to_string(lower[j]) +
            ", " + std::to_string(upper[j]) + "]");
  }

  // The zero configuration, both ends of the limits and their middle (continuous joints at
  // -1, 1 and 0 rad).
  auto ws = tree.make_workspace();
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(tree.num_joints());
  Eigen::VectorXd at_lower = zero, at_upper = zero, middle = zero;
  for (int j = 0; j < tree.num_joints(); ++j) {
    const bool limited = std::isfinite(lower[j]);
    at_lower[j] = limited ? lower[j] : -1.0;
    at_upper[j] = limited ? upper[j] : 1.0;
    middle[j] = limited ? 0.5 * (lower[j] + upper[j]) : 0.0;
  }
  check_configuration(tree, ws, zero, "zero");
  check_configuration(tree, ws, at_lower, "lower-limit");
  check_configuration(tree, ws, at_upper, "upper-limit");
  check_configuration(tree, ws, middle, "mid-range");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string urdf(reinterpret_cast<const char*>(data), size);
  std::optional<Tree> tree;
  if (!walkgen_fuzz::only_walkgen_errors("kinematic_tree_from_urdf", [&] {
        tree.emplace(walkgen::kinematic_tree_from_urdf(urdf, "fuzz.urdf"));
      })) {
    return 0;  // rejected with a clear error
  }
  // A tree that loaded must not throw later (e.g. center_of_mass() on an infinite mass).
  try {
    check_tree(*tree);
  } catch (const std::exception& e) {
    walkgen_fuzz::fail(__FILE__, __LINE__, "a loaded tree is usable",
                       std::string("it threw: ") + e.what());
  }
  return 0;
}
