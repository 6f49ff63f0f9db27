// Packaging check of the YAML adapter: a program built against walkgen::yaml must compile, link
// against yaml-cpp and read settings.
#include <cstdio>

#include <walkgen/version.hpp>
#include <walkgen/yaml/settings_loader.hpp>

int main() {
  const auto s = walkgen::walking_settings_from_yaml("optimization: {n: 20}\nt_step: 1.6\n");
  std::printf("walkgen %s: n = %d, t_step = %g\n", walkgen::kVersion, s.n, s.t_step);
  if (s.n != 20 || s.t_step != 1.6) {
    std::fprintf(stderr, "wrong answer: expected n = 20 and t_step = 1.6\n");
    return 1;
  }
  try {
    (void)walkgen::walking_settings_from_yaml("t_stpe: 1.6\n");  // only the error is wanted
  } catch (const walkgen::invalid_argument& e) {
    std::printf("unknown key rejected: %s\n", e.what());
    return 0;
  }
  std::fprintf(stderr, "an unknown key was accepted\n");
  return 1;
}
