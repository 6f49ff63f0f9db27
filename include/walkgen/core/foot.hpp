#pragma once
/// @file
/// The feet's vocabulary, shared by every floor: which foot (a discrete choice, so an enum class,
/// never the string "left"), a foot's pose on the ground and the timing of a step.

#include <cstdint>

namespace walkgen {

/// Which foot.
enum class Foot : std::uint8_t { left, right };

/// The other foot.
constexpr Foot other(Foot foot) { return foot == Foot::left ? Foot::right : Foot::left; }

/// "left" or "right", e.g. for logs and configuration files; "unknown" for a value out of range.
constexpr const char* to_string(Foot foot) noexcept {
  switch (foot) {
    case Foot::left:
      return "left";
    case Foot::right:
      return "right";
  }
  return "unknown";
}

/// A planar foot pose on the ground: position [m] and yaw [rad], world frame.
template <typename Scalar>
struct FootPose {
  Scalar x = Scalar(0), y = Scalar(0), q = Scalar(0);
};

/// Timing of a step (all in seconds since the step began).
template <typename Scalar>
struct StepTiming {
  Scalar t_ds;         ///< double-support duration at the start of the step
  Scalar t_step;       ///< step duration
  Scalar step_height;  ///< apex height of the swing foot [m]
};

}  // namespace walkgen
