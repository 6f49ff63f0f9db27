#pragma once
/// @file
/// Umbrella header of the MuJoCo adapter (target walkgen::mujoco, option WALKGEN_WITH_MUJOCO):
/// the simulated robot behind the robot interface, with headless cameras, and the navigation
/// rooms and their look (docs/simulation.md). Includes this adapter's public headers and the
/// core they need, never another adapter; the core umbrella walkgen/walkgen.hpp never includes
/// it.

#include "walkgen/mujoco/mujoco_kinematics.hpp"
#include "walkgen/mujoco/mujoco_robot.hpp"
#include "walkgen/mujoco/navigation_scene.hpp"
#include "walkgen/mujoco/robot_model.hpp"
#include "walkgen/mujoco/scene_appearance.hpp"
