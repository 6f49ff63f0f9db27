#pragma once
/// @file
/// The vector kernels of DenseQp (walkgen/qp/dense_qp.hpp): its product-form Q and its
/// triangular solves with the Cholesky factor L.
///
/// A group of G Householder reflections in compact WY form (Schreiber and Van Loan 1989),
///
///   P_0 P_1 ⋯ P_{G−1} = I − V T Vᵀ      (P_j = I − β_j v_j v_jᵀ),
///
/// with V (rows × G) holding the v_j as columns and T (G × G) upper triangular, is applied to a
/// vector in one pass over V for s = Vᵀy and one for y −= V (T s): 4·rows·G flops, as the G
/// reflections one by one, but y is read twice instead of 2G times and the G dot products run
/// side by side. The substitutions with L work alike on panels of G columns. The passes use
/// Eigen's packet primitives (the SIMD layer of Eigen's own kernels): neither Eigen's product
/// dispatch nor the compiler produces these loops for small G without overhead, and the
/// overhead dominates at the sizes of walking QPs. Any Scalar works (a packet of one where Eigen
/// does not vectorise it).

#include <Eigen/Core>
#include <algorithm>

namespace walkgen {
namespace detail {

/// The SIMD packet of the kernels: Eigen's widest for Scalar, but at most 32 bytes wide (with
/// AVX-512, half of Eigen's 64): the vectors here are a few dozen entries long, and the wider the
/// packet, the more of them is left to the scalar remainder loop. (Selected by a bool, not by
/// std::conditional on packet types, whose vector attributes GCC would drop with a warning.)
template <typename Scalar,
          bool Halve = (Eigen::internal::packet_traits<Scalar>::size * sizeof(Scalar) > 32)>
struct KernelPacketOf {
  using type = typename Eigen::internal::packet_traits<Scalar>::type;
  static constexpr Eigen::Index size = Eigen::internal::packet_traits<Scalar>::size;
};
template <typename Scalar>
struct KernelPacketOf<Scalar, true> {
  using type = typename Eigen::internal::packet_traits<Scalar>::half;
  static constexpr Eigen::Index size = Eigen::internal::packet_traits<Scalar>::size / 2;
};
template <typename Scalar>
using KernelPacket = typename KernelPacketOf<Scalar>::type;

/// s = Vᵀ y: G dot products in one pass over y. V: rows × G, column-major with column stride
/// ld (a pointer to V(0, 0)); y: rows entries.
template <int G, typename Scalar>
Eigen::Matrix<Scalar, G, 1> block_dot(const Scalar* V, Eigen::Index ld, const Scalar* y,
                                      Eigen::Index rows) {
  namespace ei = Eigen::internal;
  using Packet = KernelPacket<Scalar>;
  constexpr Eigen::Index kSize = KernelPacketOf<Scalar>::size;
  Packet acc[G];
  for (int c = 0; c < G; ++c) acc[c] = ei::pset1<Packet>(Scalar(0));
  Eigen::Index i = 0;
  for (; i + kSize <= rows; i += kSize) {
    const Packet yi = ei::ploadu<Packet>(y + i);
    for (int c = 0; c < G; ++c) acc[c] = ei::pmadd(ei::ploadu<Packet>(V + c * ld + i), yi, acc[c]);
  }
  Eigen::Matrix<Scalar, G, 1> s;
  for (int c = 0; c < G; ++c) s[c] = ei::predux(acc[c]);
  for (; i < rows; ++i) {
    for (int c = 0; c < G; ++c) s[c] += V[c * ld + i] * y[i];
  }
  return s;
}

/// y −= V s: one pass over y. V as in block_dot(); s: G entries.
template <int G, typename Scalar>
void subtract_block(const Scalar* V, Eigen::Index ld, const Eigen::Matrix<Scalar, G, 1>& s,
                    Scalar* y, Eigen::Index rows) {
  namespace ei = Eigen::internal;
  using Packet = KernelPacket<Scalar>;
  constexpr Eigen::Index kSize = KernelPacketOf<Scalar>::size;
  Packet sp[G];
  for (int c = 0; c < G; ++c) sp[c] = ei::pset1<Packet>(s[c]);
  Eigen::Index i = 0;
  for (; i + kSize <= rows; i += kSize) {
    Packet yi = ei::ploadu<Packet>(y + i);
    for (int c = 0; c < G; ++c)
      yi = ei::psub(yi, ei::pmul(ei::ploadu<Packet>(V + c * ld + i), sp[c]));
    ei::pstoreu(y + i, yi);
  }
  for (; i < rows; ++i) {
    for (int c = 0; c < G; ++c) y[i] -= V[c * ld + i] * s[c];
  }
}

/// s ← T s (or Tᵀ s when Transposed) for the upper triangle of the G × G matrix T, in place
/// (unrolled: Eigen's triangular product kernel costs more than the product at this size).
template <bool Transposed, int G, typename Scalar, typename TDerived>
void upper_times(const Eigen::MatrixBase<TDerived>& T, Eigen::Matrix<Scalar, G, 1>& s) {
  if (Transposed) {
    for (int i = G - 1; i >= 0; --i) {  // (Tᵀs)_i = Σ_{j≤i} T_ji s_j
      Scalar t = Scalar(0);
      for (int j = 0; j <= i; ++j) t += T(j, i) * s[j];
      s[i] = t;
    }
  } else {
    for (int i = 0; i < G; ++i) {  // (Ts)_i = Σ_{j≥i} T_ij s_j
      Scalar t = Scalar(0);
      for (int j = i; j < G; ++j) t += T(i, j) * s[j];
      s[i] = t;
    }
  }
}

/// y ← (I − V Tᵀ Vᵀ) y when Transposed (the group's (P_0 ⋯ P_{G−1})ᵀ), else y ← (I − V T Vᵀ) y.
/// V as in block_dot(); T: G × G, read as upper triangular.
template <int G, bool Transposed, typename Scalar, typename TDerived>
void apply_block_reflector(const Scalar* V, Eigen::Index ld, const Eigen::MatrixBase<TDerived>& T,
                           Scalar* y, Eigen::Index rows) {
  Eigen::Matrix<Scalar, G, 1> s = block_dot<G>(V, ld, y, rows);
  upper_times<Transposed>(T, s);
  subtract_block<G>(V, ld, s, y, rows);
}

/// v ← L⁻¹ v for a lower-triangular L (size × size, column-major with column stride ld, the
/// reciprocals of its diagonal in inv_diag): forward substitution by panels of G columns, each
/// solved in its G × G triangle and then subtracted from the rows below in one pass. Panels
/// where v is zero (leading zeros of a sparse constraint row) are skipped.
template <int G, typename Scalar>
void lower_solve(const Scalar* L, Eigen::Index ld, const Scalar* inv_diag, Scalar* v,
                 Eigen::Index size) {
  for (Eigen::Index k0 = 0; k0 < size; k0 += G) {
    const Eigen::Index g = std::min<Eigen::Index>(G, size - k0);
    Eigen::Matrix<Scalar, G, 1> x = Eigen::Matrix<Scalar, G, 1>::Zero();
    bool zero = true;
    for (Eigen::Index c = 0; c < g; ++c) {
      const Eigen::Index k = k0 + c;
      Scalar t = v[k];
      for (Eigen::Index j = 0; j < c; ++j) t -= L[(k0 + j) * ld + k] * x[j];
      x[c] = t * inv_diag[k];
      v[k] = x[c];
      zero = zero && x[c] == Scalar(0);
    }
    if (g == G && !zero) subtract_block<G>(L + k0 * ld + k0 + G, ld, x, v + k0 + G, size - k0 - G);
  }
}

/// v ← L⁻ᵀ v for L as in lower_solve(): back substitution by panels of G rows (aligned as in
/// lower_solve(), taken from the bottom up), each taking its dot products with the solved part
/// below in one pass. Trailing zeros of v stay zero and are skipped.
template <int G, typename Scalar>
void upper_solve(const Scalar* L, Eigen::Index ld, const Scalar* inv_diag, Scalar* v,
                 Eigen::Index size) {
  Eigen::Index end = size;  // v[end..size) is zero and stays zero
  while (end > 0 && v[end - 1] == Scalar(0)) --end;
  if (end == 0) return;
  for (Eigen::Index k0 = (end - 1) / G * G; k0 >= 0; k0 -= G) {
    const Eigen::Index k1 = std::min<Eigen::Index>(k0 + G, end);  // the panel [k0, k1)
    Eigen::Matrix<Scalar, G, 1> s = Eigen::Matrix<Scalar, G, 1>::Zero();
    if (k1 < end) s = block_dot<G>(L + k0 * ld + k1, ld, v + k1, end - k1);  // full panel
    for (Eigen::Index k = k1 - 1; k >= k0; --k) {
      Scalar t = v[k] - s[k - k0];
      for (Eigen::Index j = k + 1; j < k1; ++j) t -= L[k * ld + j] * v[j];
      v[k] = t * inv_diag[k];
    }
  }
}

}  // namespace detail
}  // namespace walkgen
