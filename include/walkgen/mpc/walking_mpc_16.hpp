#pragma once
/// @file
/// Opt-in precompiled `WalkingMpc<double, 16>` (docs/walking.md, "Compile time"). Include this
/// header instead of mpc/walking_mpc.hpp and link the CMake target walkgen::walking_mpc_16: the
/// translation unit then uses the library's instantiation of the generator, its formulation
/// (WalkingModel) and the QP (DenseQp<double>) instead of compiling them: 1.4 s of compile time
/// instead of 16.5 s (-O3). Every other part of walkgen stays header-only, and
/// mpc/walking_mpc.hpp alone still gives the whole generator without the library.
///
/// Every translation unit that includes this header must be linked with walkgen::walking_mpc_16
/// (it declares `extern template` for the three classes, so it also uses the library's
/// DenseQp<double> wherever it uses DenseQp<double> itself). Other sizes, scalars and polygon
/// edges instantiate as usual.
///
/// The library and your code must agree on Eigen's alignment of fixed-size matrices (SIMD flags
/// such as -mavx or -march=native change it, and with it the generator's memory layout): the
/// library defines a symbol named after the alignment it was compiled with, and this header
/// needs the one of the translation unit, so a mismatch fails to link instead of corrupting
/// memory at run time. Build the library with the flags of your code (add_subdirectory does).

#include <Eigen/Core>

#include "walkgen/mpc/walking_model.hpp"
#include "walkgen/mpc/walking_mpc.hpp"
#include "walkgen/qp/dense_qp.hpp"

#define WALKGEN_DETAIL_ALIGNMENT_TAG_(bytes) walking_mpc_16_eigen_alignment_##bytes
#define WALKGEN_DETAIL_ALIGNMENT_TAG(bytes) WALKGEN_DETAIL_ALIGNMENT_TAG_(bytes)

namespace walkgen {

namespace detail {
/// Defined by walkgen::walking_mpc_16 as walking_mpc_16_eigen_alignment_<bytes> for its Eigen
/// static alignment in bytes (EIGEN_MAX_STATIC_ALIGN_BYTES).
extern const int WALKGEN_DETAIL_ALIGNMENT_TAG(EIGEN_MAX_STATIC_ALIGN_BYTES);
#if defined(__GNUC__)
// Kept in every object file that includes this header, so the symbol above is always needed.
[[gnu::used]] static const int* const walking_mpc_16_alignment_check =
    &WALKGEN_DETAIL_ALIGNMENT_TAG(EIGEN_MAX_STATIC_ALIGN_BYTES);
#endif
}  // namespace detail

extern template class DenseQp<double>;
extern template class WalkingModel<double, 16, 4, 5>;
extern template class WalkingMpc<double, 16, 4, 5>;

}  // namespace walkgen
