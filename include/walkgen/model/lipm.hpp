#pragma once
/// @file
/// Linear inverted pendulum with piecewise-constant jerk: one-step dynamics (thesis eq. 2.25–2.29)
/// and the preview matrices over a horizon of N samples (eq. 2.30–2.42, with the errata of
/// docs/design.md §5: eq. 2.30 misses a '+', P_pu has (1+3j+3j²)T³/6 and P_vu (1+2j)T²/2, j = row −
/// col).
///
/// State of one axis: c = (position, velocity, acceleration); input: jerk, constant over T.

#include <Eigen/Core>

#include "walkgen/core/exceptions.hpp"

namespace walkgen {

/// One-step LIPM dynamics c_{k+1} = A c_k + B jerk_k (eq. 2.28–2.29) for sampling period T [s].
template <typename Scalar>
struct LipmStep {
  Eigen::Matrix<Scalar, 3, 3> A;
  Eigen::Matrix<Scalar, 3, 1> B;

  explicit LipmStep(Scalar T) {
    check_positive("LipmStep: T", T, "a period > 0 s");
    A << Scalar(1), T, T * T / Scalar(2),  //
        Scalar(0), Scalar(1), T,           //
        Scalar(0), Scalar(0), Scalar(1);
    B << T * T * T / Scalar(6), T * T / Scalar(2), T;
  }

  /// c_{k+1} for state c = (pos, vel, acc) and constant jerk over one period.
  Eigen::Matrix<Scalar, 3, 1> advance(const Eigen::Matrix<Scalar, 3, 1>& c, Scalar jerk) const {
    return A * c + B * jerk;
  }
};

/// Preview matrices over N samples of period T (eq. 2.33–2.42):
///   C_{k+1} = P_ps c_k + P_pu U,  Ċ_{k+1} = P_vs c_k + P_vu U,  C̈_{k+1} = P_as c_k + P_au U,
///   Z_{k+1} = P_zs c_k + P_zu U   (ZMP, Z = C − c_z/g C̈),
/// where U = (jerk_k … jerk_{k+N−1}) and row i of each matrix is sample k+1+i.
/// @tparam N horizon length, or Eigen::Dynamic (then pass it to the constructor).
template <typename Scalar, int N = Eigen::Dynamic>
struct LipmPreview {
  static_assert(N > 0 || N == Eigen::Dynamic,
                "walkgen: LipmPreview's horizon N must be positive or Eigen::Dynamic");
  using StateMatrix = Eigen::Matrix<Scalar, N, 3>;
  using InputMatrix = Eigen::Matrix<Scalar, N, N>;

  StateMatrix P_ps, P_vs, P_as, P_zs;
  InputMatrix P_pu, P_vu, P_au, P_zu;
  Scalar T;           ///< sampling period [s]
  Scalar com_height;  ///< c_z [m]
  Scalar gravity;     ///< g [m/s²]

  /// @param T sampling period [s] (> 0); @param com_height c_z [m] (> 0);
  /// @param gravity g [m/s²] (> 0); @param horizon N (must equal the template N when fixed).
  /// @throws walkgen::invalid_argument on non-positive or non-finite arguments.
  LipmPreview(Scalar T_, Scalar com_height_, Scalar gravity_ = Scalar(9.81),
              Eigen::Index horizon = N)
      : T(T_), com_height(com_height_), gravity(gravity_) {
    check_positive("LipmPreview: T", T, "a period > 0 s");
    check_positive("LipmPreview: com_height", com_height, "a height > 0 m");
    check_positive("LipmPreview: gravity", gravity, "g > 0 m/s^2");
    check_argument(horizon > 0 && (N == Eigen::Dynamic || horizon == N), "LipmPreview: horizon",
                   "N > 0 (equal to the template N when fixed)", horizon);
    const Eigen::Index n = horizon;
    P_ps.resize(n, 3);
    P_vs.resize(n, 3);
    P_as.resize(n, 3);
    P_zs.resize(n, 3);
    P_pu.setZero(n, n);
    P_vu.setZero(n, n);
    P_au.setZero(n, n);
    const Scalar h = com_height / gravity;
    const Scalar T2 = T * T;
    const Scalar T3 = T2 * T;
    for (Eigen::Index i = 0; i < n; ++i) {
      const Scalar s = Scalar(i + 1);  // samples ahead
      P_ps.row(i) << Scalar(1), s * T, s * s * T2 / Scalar(2);
      P_vs.row(i) << Scalar(0), Scalar(1), s * T;
      P_as.row(i) << Scalar(0), Scalar(0), Scalar(1);
      for (Eigen::Index col = 0; col <= i; ++col) {
        const Scalar j = Scalar(i - col);
        P_pu(i, col) = (Scalar(1) + Scalar(3) * j + Scalar(3) * j * j) * T3 / Scalar(6);
        P_vu(i, col) = (Scalar(1) + Scalar(2) * j) * T2 / Scalar(2);
        P_au(i, col) = T;
      }
    }
    P_zs = P_ps - h * P_as;
    P_zu = P_pu - h * P_au;
  }

  Eigen::Index horizon() const { return P_pu.rows(); }
};

}  // namespace walkgen
