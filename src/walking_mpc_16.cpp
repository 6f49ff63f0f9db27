/// @file
/// walkgen::walking_mpc_16 (CMakeLists.txt, option WALKGEN_BUILD_PRECOMPILED): the one
/// translation unit that compiles WalkingMpc<double, 16> (FootEdges 4, HullEdges 5), its
/// WalkingModel and DenseQp<double>, for the translation units that include
/// walkgen/mpc/walking_mpc_16.hpp and so skip compiling them.
#include "walkgen/mpc/walking_mpc_16.hpp"

namespace walkgen {

namespace detail {
extern const int WALKGEN_DETAIL_ALIGNMENT_TAG(EIGEN_MAX_STATIC_ALIGN_BYTES) =
    EIGEN_MAX_STATIC_ALIGN_BYTES;
}  // namespace detail

template class DenseQp<double>;
template class WalkingModel<double, 16, 4, 5>;
template class WalkingMpc<double, 16, 4, 5>;

}  // namespace walkgen
