#pragma once
// A straight walk of WalkingMpc<double, 16> (tests/mpc/walking_mpc_16_walk.cpp), compiled twice:
// header-only into the program walking_mpc_16_reference, and through the extern header
// walkgen/mpc/walking_mpc_16.hpp into test_walking_mpc_16, which links walkgen::walking_mpc_16.

#include <vector>

namespace walkgen_test {

/// Ticks of the walk: 0.1 m/s straight ahead from standing, three landings (HRP-2: 8 ticks per
/// step).
constexpr int kWalkingMpc16Ticks = 30;

/// Per tick (solve, then advance): status, SQP and QP iterations, constraint violation, the plan
/// U and the state after advance() (CoM x, y: position, velocity, acceleration; support foot x,
/// y, yaw), in that order.
std::vector<double> walk_straight_16();

}  // namespace walkgen_test
