// Packaging check of walkgen::walking_mpc_16: a program that includes the extern header links
// the library's WalkingMpc<double, 16> (it defines none of its members itself) and walks with it.
#include <cstdio>

#include <walkgen/mpc/walking_mpc_16.hpp>
#include <walkgen/version.hpp>

int main() {
  walkgen::WalkingMpc<double, 16> mpc(walkgen::hrp2_settings());
  if (mpc.set_command({0.1, 0.0, 0.0}) != walkgen::CommandStatus::accepted) return 1;
  for (int tick = 0; tick < 20; ++tick) {
    const auto& r = mpc.solve();
    if (r.status != walkgen::MpcStatus::solved) {
      std::fprintf(stderr, "tick %d: %s (%s)\n", tick, walkgen::to_string(r.status), r.message);
      return 1;
    }
    mpc.advance();
  }
  std::printf("walkgen %s, precompiled WalkingMpc<double, 16>: CoM x %.3f m after 2 s\n",
              walkgen::kVersion, mpc.state().com_x[0]);
  return mpc.state().com_x[0] > 0.05 ? 0 : 1;
}
