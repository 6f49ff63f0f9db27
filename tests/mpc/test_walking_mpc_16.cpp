// The precompiled WalkingMpc<double, 16> (include/walkgen/mpc/walking_mpc_16.hpp, the library
// walkgen::walking_mpc_16) plans exactly what the header-only generator plans: the straight walk
// of walking_mpc_16_walk.hpp, run here through the library, against the same walk written by the
// header-only program walking_mpc_16_reference (the ctest fixture of the same name).

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <string>
#include <vector>

#include "mpc/walking_mpc_16_walk.hpp"
#include "walkgen/mpc/walking_mpc_16.hpp"  // MpcStatus; and checked by walking_mpc_16_extern

namespace {

std::vector<double> read_reference() {
  std::ifstream in(WALKGEN_WALKING_MPC_16_REFERENCE);
  std::vector<double> values;
  for (std::string line; std::getline(in, line);)
    values.push_back(std::strtod(line.c_str(), nullptr));
  return values;
}

TEST(WalkingMpc16, PlansWhatTheHeaderOnlyGeneratorPlans) {
  const std::vector<double> reference = read_reference();
  ASSERT_FALSE(reference.empty()) << "no reference walk in " << WALKGEN_WALKING_MPC_16_REFERENCE
                                  << " (the ctest walking_mpc_16_reference writes it)";
  const std::vector<double> precompiled = walkgen_test::walk_straight_16();
  ASSERT_EQ(precompiled.size(), reference.size());
  // Every tick solved (the first number of each tick is its status).
  const std::size_t per_tick = reference.size() / walkgen_test::kWalkingMpc16Ticks;
  for (std::size_t i = 0; i < reference.size(); i += per_tick) {
    EXPECT_EQ(reference[i], double(walkgen::MpcStatus::solved)) << "tick " << i / per_tick;
  }
  // The same compiler and flags on the same code: the same numbers (bitwise on x86-64; 1e-12
  // leaves room for a compiler that contracts differently where it inlines differently).
  for (std::size_t i = 0; i < reference.size(); ++i) {
    ASSERT_NEAR(precompiled[i], reference[i], 1e-12 * (1.0 + std::abs(reference[i])))
        << "number " << i << " (tick " << i / per_tick << ")";
  }
}

}  // namespace
