#pragma once
/// @file
/// Mathematical constants: walkgen's one spelling of π.

namespace walkgen {

/// π to double precision (std::numbers::pi is C++20; M_PI is POSIX, not standard C++).
/// In scalar-generic code write Scalar(kPi), so that no double leaks into a Scalar expression
/// (docs/design.md convention 7: Ceres Jets flow through the kinematics).
inline constexpr double kPi = 3.14159265358979323846;

}  // namespace walkgen
