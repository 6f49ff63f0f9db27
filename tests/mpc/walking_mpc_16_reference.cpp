// walking_mpc_16_reference OUTPUT: writes the straight walk of walking_mpc_16_walk.hpp, computed
// by the header-only WalkingMpc<double, 16>, to OUTPUT (one number a line, %.17g: exact for
// double), for test_walking_mpc_16 to compare the precompiled walkgen::walking_mpc_16 with.
#include <cstdio>

#include "mpc/walking_mpc_16_walk.hpp"

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: walking_mpc_16_reference OUTPUT\n");
    return 2;
  }
  std::FILE* file = std::fopen(argv[1], "w");
  if (file == nullptr) {
    std::fprintf(stderr, "walking_mpc_16_reference: cannot write %s\n", argv[1]);
    return 1;
  }
  for (double value : walkgen_test::walk_straight_16()) std::fprintf(file, "%.17g\n", value);
  return std::fclose(file) == 0 ? 0 : 1;
}
