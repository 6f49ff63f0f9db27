#pragma once
/// @file
/// Which foot: a discrete choice, so an enum class (never the string "left").

#include <cstdint>

namespace walkgen {

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

}  // namespace walkgen
