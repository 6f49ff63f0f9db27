// Fuzz harness: WalkingMpc driven by an operation sequence decoded from bytes
// (tests/fuzz/README.md): settings near a preset, then set_command, set_state, set_obstacles,
// solve and advance in any order.
// Invariants: only walkgen::invalid_argument escapes (and only from the constructor, set_state
// and set_obstacles); set_command answers with a status; "solved" means the plan meets its
// nonlinear constraints within sqp_tolerance; the plan, the state and the result are never NaN
// or inf, whatever the status.
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "fuzz/fuzz_support.hpp"
#include "walkgen/mpc/walking_mpc.hpp"

namespace {

using Mpc = walkgen::WalkingMpc<double, Eigen::Dynamic>;
using walkgen::MpcStatus;
using walkgen_fuzz::ByteReader;

walkgen::WalkingSettings<double> settings_from(ByteReader& in) {
  auto s = in.flag() ? walkgen::heicub_settings<double>() : walkgen::hrp2_settings<double>();
  // A handful of keys perturbed: one byte says which.
  const int changes = in.integer(0, 4);
  for (int k = 0; k < changes; ++k) {
    switch (in.byte() % 12) {
      case 0:
        s.n = in.integer(1, 40);
        break;
      case 1:
        s.alpha = in.around(s.alpha);
        break;
      case 2:
        s.beta = in.around(s.beta);
        break;
      case 3:
        s.gamma = in.around(s.gamma);
        break;
      case 4:
        s.sqp_iterations = in.integer(0, 4);
        break;
      case 5:
        s.sqp_corrections = in.integer(0, 6);
        break;
      case 6:
        s.sqp_tolerance = in.around(s.sqp_tolerance);
        break;
      case 7:
        s.com_y[0] = in.around(s.com_y[0]);
        break;
      case 8:
        s.security_margin[0] = in.around(s.security_margin[0]);
        break;
      case 9:
        s.max_relative_yaw = in.around(s.max_relative_yaw);
        break;
      case 10:
        s.footstep_regularization = in.around(s.footstep_regularization);
        break;
      default:
        s.step_velocity_weight = in.around(s.step_velocity_weight);
        break;
    }
  }
  return s;
}

void check_finite(const Mpc& mpc, const std::string& where) {
  const auto& st = mpc.state();
  WALKGEN_FUZZ_CHECK(mpc.plan().U.allFinite(), where + ": non-finite plan");
  WALKGEN_FUZZ_CHECK(st.com_x.allFinite() && st.com_y.allFinite() && std::isfinite(st.support.x) &&
                         std::isfinite(st.support.y) && std::isfinite(st.swing.x.position) &&
                         std::isfinite(st.swing.y.position),
                     where + ": non-finite state");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  ByteReader in(data, size);
  const auto settings = settings_from(in);
  std::unique_ptr<Mpc> mpc;
  const bool built = walkgen_fuzz::only_walkgen_errors(
      "WalkingMpc constructor", [&] { mpc = std::make_unique<Mpc>(settings, 4); });
  if (!built) return 0;
  const double tol = mpc->settings().sqp_tolerance;
  for (int op = 0; op < 24 && in.remaining() > 0; ++op) {
    const std::string where = "operation " + std::to_string(op);
    switch (in.byte() % 6) {
      case 0: {  // a command, anything: the status answers
        const Eigen::Vector3d c(in.around(0.2), in.around(0.0), in.around(0.0));
        const auto st = mpc->set_command(c);
        WALKGEN_FUZZ_CHECK(st != walkgen::CommandStatus::accepted || c.allFinite(),
                           where + ": a non-finite command accepted");
        break;
      }
      case 1: {  // feedback: a perturbed state
        auto st = mpc->state();
        switch (in.byte() % 4) {
          case 0:
            st.com_x[0] = in.around(st.com_x[0]);
            break;
          case 1:
            st.com_y[0] = st.support.y + in.around(st.com_y[0] - st.support.y);
            break;
          case 2:
            st.com_x[1] = in.around(0.1);
            break;
          default:
            st.com_y[1] = in.around(0.0);
            break;
        }
        walkgen_fuzz::only_walkgen_errors("WalkingMpc::set_state", [&] { mpc->set_state(st); });
        break;
      }
      case 2: {  // obstacles
        std::vector<walkgen::CircleObstacle<double>> obstacles(std::size_t(in.integer(0, 4)));
        for (auto& o : obstacles) {
          o = {mpc->state().com_x[0] + in.around(1.0), in.around(0.1), in.around(0.2),
               in.around(0.1)};
        }
        walkgen_fuzz::only_walkgen_errors("WalkingMpc::set_obstacles",
                                          [&] { mpc->set_obstacles(obstacles); });
        break;
      }
      case 3:
        mpc->advance();
        check_finite(*mpc, where + " (advance)");
        break;
      default: {
        const auto& r = mpc->solve();
        const std::string what = where + " (solve, " + walkgen::to_string(r.status) + ")";
        WALKGEN_FUZZ_CHECK(r.status == MpcStatus::solved || r.status == MpcStatus::qp_failed ||
                               r.status == MpcStatus::not_converged,
                           what);
        if (r.status == MpcStatus::solved) {
          WALKGEN_FUZZ_CHECK(r.constraint_violation <= tol,
                             what + ": violation " + std::to_string(r.constraint_violation) +
                                 " above sqp_tolerance " + std::to_string(tol));
          WALKGEN_FUZZ_CHECK(r.qp_status == walkgen::QpStatus::solved, what + ": QP not solved");
        }
        WALKGEN_FUZZ_CHECK(std::isfinite(r.constraint_violation), what + ": non-finite violation");
        check_finite(*mpc, what);
        break;
      }
    }
  }
  return 0;
}
