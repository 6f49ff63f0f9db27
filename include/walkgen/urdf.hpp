#pragma once
/// @file
/// Umbrella header of the URDF adapter (target walkgen::urdf, option WALKGEN_WITH_URDF,
/// tinyxml2): robot descriptions read into a KinematicDescription / KinematicTree
/// (docs/kinematics.md). Includes this adapter's public headers and the core they need, never
/// another adapter; the core umbrella walkgen/walkgen.hpp never includes it.

#include "walkgen/urdf/urdf_loader.hpp"
