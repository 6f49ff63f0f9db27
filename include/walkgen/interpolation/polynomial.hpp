#pragma once
/// @file
/// Polynomial foot trajectories of thesis §2.3.1: p(t) = Σ aᵢ tⁱ with its first two derivatives
/// (eq. 2.90–2.92), a 5th-order polynomial meeting position, velocity and acceleration at both
/// ends (eq. 2.102–2.111: feet x, y and yaw) and a 4th-order one meeting height and vertical
/// velocity at both ends plus the apex height at mid-time (eq. 2.93–2.101: foot lift).
///
/// The coefficients use the closed-form inverses of eq. 2.101 and 2.111 (checked against the
/// boundary conditions by tests/interpolation/test_polynomial.cpp). Scalar-generic; no allocation.

#include <Eigen/Core>
#include <algorithm>

#include "walkgen/core/exceptions.hpp"

namespace walkgen {

/// Position, velocity and acceleration of a trajectory at one instant.
template <typename Scalar>
struct Sample3 {
  Scalar position, velocity, acceleration;
};

/// p(t) = Σ_{i=0..Degree} aᵢ tⁱ on [0, duration].
template <typename Scalar, int Degree>
struct Polynomial {
  static_assert(Degree >= 0, "walkgen: Polynomial's Degree must be >= 0");
  Eigen::Matrix<Scalar, Degree + 1, 1> a = Eigen::Matrix<Scalar, Degree + 1, 1>::Zero();
  Scalar duration = Scalar(0);  ///< [s]

  /// p, ṗ, p̈ at time t (eq. 2.90–2.92), by Horner's scheme. t is clamped to [0, duration], so
  /// sampling a little past the end holds the end state instead of extrapolating.
  Sample3<Scalar> evaluate(Scalar t) const {
    using std::max;
    using std::min;
    t = min(max(t, Scalar(0)), duration);
    Scalar p = a[Degree], v = Scalar(0), acc = Scalar(0);
    for (int i = Degree - 1; i >= 0; --i) {
      acc = acc * t + Scalar(2) * v;
      v = v * t + p;
      p = p * t + a[i];
    }
    return {p, v, acc};
  }
};

/// The 5th-order polynomial from (p0, v0, a0) at t = 0 to (p1, v1, a1) at t = duration
/// (eq. 2.108–2.111). Used for the feet's x, y and yaw during single support.
/// @throws walkgen::invalid_argument if duration is not finite and > 0.
template <typename Scalar>
Polynomial<Scalar, 5> quintic(Scalar duration, const Sample3<Scalar>& start,
                              const Sample3<Scalar>& end) {
  check_positive("quintic: duration", duration, "a duration > 0 s");
  const Scalar T = duration, T2 = T * T, T3 = T2 * T, T4 = T3 * T, T5 = T4 * T;
  const Scalar p0 = start.position, v0 = start.velocity, a0 = start.acceleration;
  const Scalar p1 = end.position, v1 = end.velocity, a1 = end.acceleration;
  Polynomial<Scalar, 5> poly;
  poly.duration = T;
  // Rows of M_x⁻¹ in eq. 2.111 (with its factor ½ applied).
  poly.a[0] = p0;
  poly.a[1] = v0;
  poly.a[2] = a0 / Scalar(2);
  poly.a[3] = (Scalar(20) * (p1 - p0) - (Scalar(12) * v0 + Scalar(8) * v1) * T -
               (Scalar(3) * a0 - a1) * T2) /
              (Scalar(2) * T3);
  poly.a[4] = (Scalar(30) * (p0 - p1) + (Scalar(16) * v0 + Scalar(14) * v1) * T +
               (Scalar(3) * a0 - Scalar(2) * a1) * T2) /
              (Scalar(2) * T4);
  poly.a[5] =
      (Scalar(12) * (p1 - p0) - Scalar(6) * (v0 + v1) * T - (a0 - a1) * T2) / (Scalar(2) * T5);
  return poly;
}

/// The 4th-order lift profile of eq. 2.93–2.101: height z0 and vertical velocity v0 at t = 0,
/// apex height z_mid at t = duration/2, height z1 and vertical velocity v1 at t = duration.
/// A foot step uses quartic_lift(T, 0, 0, step_height, 0, 0).
/// @throws walkgen::invalid_argument if duration is not finite and > 0.
template <typename Scalar>
Polynomial<Scalar, 4> quartic_lift(Scalar duration, Scalar z0, Scalar v0, Scalar z_mid, Scalar z1,
                                   Scalar v1) {
  check_positive("quartic_lift: duration", duration, "a duration > 0 s");
  const Scalar T = duration, T2 = T * T, T3 = T2 * T, T4 = T3 * T;
  Polynomial<Scalar, 4> poly;
  poly.duration = T;
  // Rows of M_z⁻¹ in eq. 2.101.
  poly.a[0] = z0;
  poly.a[1] = v0;
  poly.a[2] =
      (-Scalar(11) * z0 + Scalar(16) * z_mid - Scalar(5) * z1) / T2 + (v1 - Scalar(4) * v0) / T;
  poly.a[3] = (Scalar(18) * z0 - Scalar(32) * z_mid + Scalar(14) * z1) / T3 +
              (Scalar(5) * v0 - Scalar(3) * v1) / T2;
  poly.a[4] =
      (-Scalar(8) * z0 + Scalar(16) * z_mid - Scalar(8) * z1) / T4 + (Scalar(2) * (v1 - v0)) / T3;
  return poly;
}

}  // namespace walkgen
