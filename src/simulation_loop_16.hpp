#pragma once
/// @file
/// walkgen's own tests and examples only (not installed): the closed loop of our humanoid,
/// SimLoop (WalkingLoop<16, HumanoidIk>), its Ceres IK and KinematicTree<double> declared
/// `extern template`, on top of the precompiled WalkingMpc<double, 16> of
/// walkgen/mpc/walking_mpc_16.hpp. CMakeLists.txt ("The project's programs compile the heavy
/// templates once") force-includes this header into every test and example that links
/// walkgen::simulation and links them to walkgen_simulation_loop_16 (src/simulation_loop_16.cpp,
/// with its own copy of src/walking_mpc_16.cpp), which instantiates the three once: a closed-loop
/// test then compiles in a third of the time (test_balance.cpp under the sanitizers: 161 s -> 53 s
/// of CPU). The code is the library's headers, unchanged; only where it is compiled moves. Users
/// compile walkgen header-only, or opt into walkgen::walking_mpc_16 (docs/walking.md, "Compile
/// time").

#include "walkgen/mpc/walking_mpc_16.hpp"
#include "walkgen/simulation/humanoid_loop.hpp"

namespace walkgen {

extern template class KinematicTree<double>;
extern template class CeresInverseKinematics<kHumanoidJoints>;
extern template class WalkingLoop<16, HumanoidIk>;
extern template class CeresInverseKinematics<Eigen::Dynamic>;
extern template class WalkingLoop<16, CeresInverseKinematics<Eigen::Dynamic>>;  // RobotLoop

}  // namespace walkgen
