#pragma once
/// @file
/// Exceptions thrown at walkgen's API boundaries (docs/design.md convention 10, tier b).
///
/// Bad input that a caller can fix (wrong sizes, malformed files, out-of-range settings)
/// throws walkgen::invalid_argument with a message of the form
/// "<where>: expected <what>, got <what> (hint: <how to fix>)". Numerical outcomes
/// (an infeasible QP, a non-converged solve) are never thrown: they are reported in a
/// Result's status.

#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>

namespace walkgen {

/// Bad input at an API boundary. Derives from std::invalid_argument so generic handlers work.
class invalid_argument : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

namespace detail {

/// Formats "<where>: expected <expected>, got <got>[ (hint: <hint>)]".
template <typename Expected, typename Got>
std::string expected_got(const char* where, const Expected& expected, const Got& got,
                         const char* hint = nullptr) {
  std::ostringstream os;
  os << where << ": expected " << expected << ", got " << got;
  if (hint != nullptr) os << " (hint: " << hint << ")";
  return os.str();
}

}  // namespace detail

/// Throws walkgen::invalid_argument unless `condition` holds.
/// The message is only built when the check fails.
template <typename Expected, typename Got>
void check_argument(bool condition, const char* where, const Expected& expected, const Got& got,
                    const char* hint = nullptr) {
  if (!condition) {
    throw invalid_argument(detail::expected_got(where, expected, got, hint));
  }
}

/// Throws unless value is finite and > 0; `expected` describes it, e.g. "a period > 0 s".
template <typename Scalar>
void check_positive(const char* where, Scalar value, const char* expected = "a finite value > 0") {
  check_argument(std::isfinite(value) && value > Scalar(0), where, expected, value);
}

/// Throws unless value is finite and >= 0.
template <typename Scalar>
void check_non_negative(const char* where, Scalar value,
                        const char* expected = "a finite value >= 0") {
  check_argument(std::isfinite(value) && value >= Scalar(0), where, expected, value);
}

}  // namespace walkgen
