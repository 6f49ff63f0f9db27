#pragma once
/// @file
/// Umbrella header of the application component humanoid (target walkgen::humanoid: ceres +
/// urdf): walkgen's humanoid for inverse kinematics (docs/kinematics.md).

#include "walkgen/humanoid/humanoid_ik.hpp"
