#pragma once
/// @file
/// Umbrella header of the application component simulation (target walkgen::simulation:
/// humanoid + mujoco): the closed loop of figure 6.1 in MuJoCo and the tasks of §9.2
/// (docs/simulation.md).

#include "walkgen/simulation/humanoid_loop.hpp"
#include "walkgen/simulation/simulated_tasks.hpp"
