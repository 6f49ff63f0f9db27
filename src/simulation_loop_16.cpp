/// @file
/// walkgen_simulation_loop_16 (CMakeLists.txt; walkgen's own tests and examples only): the one
/// translation unit that compiles KinematicTree<double>, HumanoidIk and SimLoop for the programs
/// that get src/simulation_loop_16.hpp force-included. The archive also holds
/// src/walking_mpc_16.cpp (WalkingMpc<double, 16>): one walkgen archive ahead of Debian's static
/// libceres.a on the link line (CMakeLists.txt says why).
#include "simulation_loop_16.hpp"

namespace walkgen {

template class KinematicTree<double>;
template class CeresInverseKinematics<kHumanoidJoints>;
template class WalkingLoop<16, HumanoidIk>;
template class CeresInverseKinematics<Eigen::Dynamic>;
template class WalkingLoop<16, CeresInverseKinematics<Eigen::Dynamic>>;  // RobotLoop

}  // namespace walkgen
