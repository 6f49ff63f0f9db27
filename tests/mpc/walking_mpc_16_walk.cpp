// The straight walk of walking_mpc_16_walk.hpp. WALKGEN_TEST_PRECOMPILED (test_walking_mpc_16)
// includes the extern header, so the generator runs in walkgen::walking_mpc_16; without it
// (walking_mpc_16_reference) this file instantiates the generator itself, header-only.
#include "mpc/walking_mpc_16_walk.hpp"

#ifdef WALKGEN_TEST_PRECOMPILED
#include "walkgen/mpc/walking_mpc_16.hpp"
#else
#include "walkgen/mpc/walking_mpc.hpp"
#endif

namespace walkgen_test {

std::vector<double> walk_straight_16() {
  walkgen::WalkingMpc<double, 16> mpc(walkgen::hrp2_settings());
  std::vector<double> out;
  if (mpc.set_command({0.1, 0.0, 0.0}) != walkgen::CommandStatus::accepted) return out;
  for (int tick = 0; tick < kWalkingMpc16Ticks; ++tick) {
    const auto& r = mpc.solve();
    out.push_back(double(r.status));
    out.push_back(r.sqp_iterations);
    out.push_back(r.qp_iterations);
    out.push_back(r.constraint_violation);
    out.insert(out.end(), mpc.plan().U.data(), mpc.plan().U.data() + mpc.plan().U.size());
    mpc.advance();
    const auto& s = mpc.state();
    out.insert(out.end(), s.com_x.data(), s.com_x.data() + 3);
    out.insert(out.end(), s.com_y.data(), s.com_y.data() + 3);
    out.insert(out.end(), {s.support.x, s.support.y, s.support.q});
  }
  return out;
}

}  // namespace walkgen_test
