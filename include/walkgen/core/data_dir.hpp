// Where walkgen's run-time data lives: the robot models (models/) and walking settings (configs/).
#pragma once

#include <cstdlib>
#include <string>

namespace walkgen {

/// The folder holding walkgen's `models/` and `configs/`, in this order of precedence:
///  1. the environment variable `WALKGEN_DATA_DIR`, when set and not empty (for a moved or
///     unusual installation);
///  2. the folder the CMake target told the compiler: the source tree when built against it
///     (add_subdirectory or a build tree), `<prefix>/share/walkgen` when found through an
///     installed package (computed from where walkgenConfig.cmake lies, so a moved prefix works
///     after the consumer is configured again);
///  3. empty, when compiled without walkgen's CMake target (then pass paths explicitly).
/// Never throws; reads the environment on every call (not in the control loop).
inline std::string data_dir() {
  if (const char* env = std::getenv("WALKGEN_DATA_DIR"); env != nullptr && *env != '\0') {
    return env;
  }
#ifdef WALKGEN_DEFAULT_DATA_DIR
  return WALKGEN_DEFAULT_DATA_DIR;
#else
  return {};
#endif
}

/// `data_dir()/<relative>`, or empty when data_dir() is empty.
inline std::string data_path(const std::string& relative) {
  const std::string dir = data_dir();
  return dir.empty() ? std::string() : dir + "/" + relative;
}

/// walkgen's humanoid: the MJCF (MuJoCo) and the URDF (kinematics), under data_dir()/models.
inline std::string humanoid_mjcf_path() { return data_path("models/walkgen_humanoid.xml"); }
inline std::string humanoid_urdf_path() { return data_path("models/walkgen_humanoid.urdf"); }

}  // namespace walkgen
