#pragma once
/// @file
/// walkgen.KinematicTree's C++ side, shared by the kinematics and IK bindings.

#include <memory>

#include "walkgen/kinematics/kinematic_tree.hpp"

namespace walkgen::python {

/// A KinematicTree shared with what is made from it (Kinematics, InverseKinematics), which keep
/// it alive.
struct PyTree {
  std::shared_ptr<const KinematicTree<double>> tree;
};

}  // namespace walkgen::python
