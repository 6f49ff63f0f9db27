#pragma once
/// @file
/// walkgen's one spelling of the small pieces of geometry every floor needs: π, the cross-product
/// matrix, the yaw of a rotation and angle wrapping. Scalar-generic where Ceres Jets flow through
/// (skew, yaw_of: docs/design.md convention 7); the wrapping functions are for plain floating
/// point (std::remainder has no Jet overload).

#include <Eigen/Core>
#include <cmath>
#include <type_traits>

namespace walkgen {

/// π to double precision (std::numbers::pi is C++20; M_PI is POSIX, not standard C++).
/// In scalar-generic code write Scalar(kPi), so that no double leaks into a Scalar expression
/// (docs/design.md convention 7: Ceres Jets flow through the kinematics).
inline constexpr double kPi = 3.14159265358979323846;

/// [v]×, the matrix of the cross product: skew(v) w = v × w.
template <typename Derived>
Eigen::Matrix<typename Derived::Scalar, 3, 3> skew(const Eigen::MatrixBase<Derived>& v) {
  using Scalar = typename Derived::Scalar;
  Eigen::Matrix<Scalar, 3, 3> S;
  S << Scalar(0), -v[2], v[1],  //
      v[2], Scalar(0), -v[0],   //
      -v[1], v[0], Scalar(0);
  return S;
}

/// Yaw [rad] of a rotation matrix R (world from body): the heading of its x axis projected on
/// the ground, atan2(R₁₀, R₀₀), in (−π, π].
template <typename Derived>
typename Derived::Scalar yaw_of(const Eigen::MatrixBase<Derived>& R) {
  using std::atan2;
  return atan2(R(1, 0), R(0, 0));
}

/// The angle a [rad] wrapped to [−π, π] (the representative closest to 0).
template <typename Scalar>
Scalar wrap_angle(Scalar a) {
  static_assert(std::is_floating_point<Scalar>::value, "walkgen: wrap_angle needs a float type");
  return std::remainder(a, Scalar(2 * kPi));
}

/// |a − b| wrapped to [0, π] [rad]: how far apart two headings are.
template <typename Scalar>
Scalar angle_distance(Scalar a, Scalar b) {
  return std::abs(wrap_angle(a - b));
}

}  // namespace walkgen
