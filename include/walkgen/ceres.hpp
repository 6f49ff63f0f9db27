#pragma once
/// @file
/// Umbrella header of the Ceres adapter (target walkgen::ceres, option WALKGEN_WITH_CERES):
/// whole-body inverse kinematics by Levenberg–Marquardt over the core's kinematic tree
/// (docs/kinematics.md). Includes this adapter's public headers and the core they need, never
/// another adapter; the core umbrella walkgen/walkgen.hpp never includes it.

#include "walkgen/ceres/inverse_kinematics.hpp"
