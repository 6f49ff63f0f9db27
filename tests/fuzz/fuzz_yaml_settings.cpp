// Fuzz harness of the YAML settings adapter (tests/fuzz/README.md): the bytes are YAML text read
// over the HRP-2 defaults. Whatever they are, walking_settings_from_yaml() either throws
// walkgen::invalid_argument (never a yaml-cpp exception) or returns settings that pass
// validate() and whose derived sizes are sound: t_step a whole number of samples of t, at least
// one planned step. Seeds: tests/fuzz/corpus/yaml_settings (the configs in configs/ and small
// documents).

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <exception>
#include <optional>
#include <string>

#include "fuzz/fuzz_support.hpp"
#include "walkgen/yaml/settings_loader.hpp"

namespace {

using Settings = walkgen::WalkingSettings<double>;

void check_settings(const Settings& s) {
  try {
    walkgen::validate(s);
  } catch (const std::exception& e) {
    walkgen_fuzz::fail(__FILE__, __LINE__, "loaded settings pass validate()", e.what());
  }
  const int S = s.samples_per_step();
  WALKGEN_FUZZ_CHECK(S >= 1, "samples_per_step() = " + std::to_string(S));
  WALKGEN_FUZZ_CHECK(std::abs(S * s.t - s.t_step) <= 1e-6 * s.t_step,
                     "samples_per_step() * t = " + std::to_string(S * s.t) +
                         " s, t_step = " + std::to_string(s.t_step) + " s");
  WALKGEN_FUZZ_CHECK(s.planned_steps() >= 1,
                     "planned_steps() = " + std::to_string(s.planned_steps()));
  WALKGEN_FUZZ_CHECK(
      s.n >= 1 && s.nwsr >= 1 && s.sqp_iterations >= 1 && s.sqp_corrections >= 0 && s.n_still >= 0,
      "a negative or zero count");
  WALKGEN_FUZZ_CHECK(std::isfinite(s.cpu_time), "cpu_time " + std::to_string(s.cpu_time));
  for (const auto& o : s.obstacles) {
    WALKGEN_FUZZ_CHECK(std::isfinite(o.x) && std::isfinite(o.y) && o.radius > 0 && o.margin >= 0,
                       "an obstacle with a non-finite centre or a bad radius");
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  std::optional<Settings> settings;
  if (walkgen_fuzz::only_walkgen_errors("walking_settings_from_yaml", [&] {
        settings.emplace(walkgen::walking_settings_from_yaml(text, walkgen::hrp2_settings()));
      })) {
    check_settings(*settings);
  }
  return 0;
}
