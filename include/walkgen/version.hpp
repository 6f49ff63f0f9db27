#pragma once
/// @file
/// walkgen's version. CMakeLists.txt reads these numbers, so they are the single source.

#define WALKGEN_VERSION_MAJOR 0
#define WALKGEN_VERSION_MINOR 1
#define WALKGEN_VERSION_PATCH 0

namespace walkgen {
/// "major.minor.patch"
inline constexpr const char* kVersion = "0.1.0";
}  // namespace walkgen
