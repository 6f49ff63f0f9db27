// Measures what the generator's main settings do to the HRP-2 walks of thesis §9.1 and prints
// the tables of docs/tuning.md (markdown, on stdout):
//   1. step_velocity_weight: steady-state velocity (robot frame) of the straight, sideways,
//      curved and turning walks;
//   2. the horizon N: failed ticks, correction iterations and the obstacle pass for every
//      scenario;
//   3. beta: ZMP distance from the support foot's centre against velocity tracking.
//
//   walking_tuning            (no options besides --help and --version)
//
// Each run is 200 ticks of WalkingMpc (walkgen/scenarios/walking_scenarios.hpp); the velocity is
// walkgen::mean_velocity over ticks 88–200, as in tests/mpc/test_walking_mpc.cpp. --help
// prints the usage; any other argument exits 2 with one line on stderr.

#include <cmath>
#include <cstdio>
#include <initializer_list>
#include <string>
#include <vector>

#include "common/cli.hpp"
#include "walkgen/mpc/settings.hpp"
#include "walkgen/scenarios/walking_scenarios.hpp"

namespace {

using walkgen::ScenarioRun;
using Settings = walkgen::WalkingSettings<double>;

Eigen::Vector3d velocity(const ScenarioRun& run, const Settings& s) {
  return walkgen::mean_velocity(run, 88, 6, 2 * s.samples_per_step(), s.t);
}

int failed_ticks(const ScenarioRun& run) {
  int failed = 0;
  for (const auto& r : run.results) failed += r.status != walkgen::MpcStatus::solved;
  return failed;
}

// Prints a markdown table: the header, then one row per value of a setting; `apply` sets the
// value on the HRP-2 preset, `cells` prints the row's cells for those settings.
template <typename Apply, typename Cells>
void table(const char* header, std::initializer_list<double> values, Apply apply, Cells cells) {
  std::printf("%s", header);
  for (double value : values) {
    Settings s = walkgen::hrp2_settings();
    apply(s, value);
    cells(s);
    std::printf("\n");
  }
}

void step_velocity_table() {
  table(
      "| step_velocity_weight | straight (0.1, 0, 0) | sideways (0, 0.1, 0) | "
      "curved (0.1, 0, 0.1) | turn (0, 0, 0.2) |\n|---|---|---|---|---|\n",
      {0.0, 1.0, 10.0, 30.0, 100.0, 300.0},
      [](Settings& s, double w) { s.step_velocity_weight = w; },
      [](const Settings& s) {
        std::printf("| %g |", s.step_velocity_weight);
        for (const char* name : {"straight", "sideways", "curved", "turn"}) {
          const ScenarioRun run = walkgen::run_scenario(walkgen::scenario(name), s);
          const Eigen::Vector3d v = velocity(run, s);
          std::printf(" %.4f, %.4f, %.4f%s |", v[0], v[1], v[2],
                      failed_ticks(run) ? " (failed)" : "");
        }
      });
}

void horizon_table() {
  table(
      "\n| N (preview) | straight | sideways | curved | turn | sequence | obstacle |\n"
      "|---|---|---|---|---|---|---|\n",
      {8, 12, 16, 24, 32}, [](Settings& s, double n) { s.n = int(n); },
      [](const Settings& s) {
        std::printf("| %d (%.1f s) |", s.n, s.n * s.t);
        for (const auto& sc : walkgen::walking_scenarios()) {
          const ScenarioRun run = walkgen::run_scenario(sc, s);
          int corrections = 0;
          for (const auto& r : run.results) corrections += r.sqp_iterations - s.sqp_iterations;
          std::printf(" %d failed, %d corr.", failed_ticks(run), corrections);
          if (!sc.obstacles.empty()) {
            const auto& o = sc.obstacles.front();
            const bool passed =
                failed_ticks(run) == 0 && run.states.back().com_x[0] > o.x + o.radius + o.margin;
            std::printf(passed ? ", passed" : ", not passed");
          }
          std::printf(" |");
        }
      });
}

// Mean distance of the ZMP from the support foot's centre in single support [m].
double mean_zmp_offset(const ScenarioRun& run) {
  double sum = 0;
  int count = 0;
  for (const auto& o : run.samples) {
    if (o.double_support) continue;
    const auto p = o.foot(o.support_foot).motion.pose();
    sum += std::hypot(o.zmp_x - p.x, o.zmp_y - p.y);
    ++count;
  }
  return count > 0 ? sum / count : 0.0;
}

void beta_table() {
  table(
      "\n| beta | straight: velocity x | mean ZMP offset in single support [mm] | "
      "QP active-set changes per tick |\n|---|---|---|---|\n",
      {1e-6, 1e-3, 1e-1, 1.0}, [](Settings& s, double beta) { s.beta = beta; },
      [](const Settings& s) {
        const ScenarioRun run = walkgen::run_scenario(walkgen::scenario("straight"), s);
        double changes = 0;
        for (const auto& r : run.results) changes += r.qp_iterations;
        std::printf("| %g | %.4f%s | %.1f | %.1f |", s.beta, velocity(run, s)[0],
                    failed_ticks(run) ? " (failed)" : "", 1e3 * mean_zmp_offset(run),
                    changes / double(run.results.size()));
      });
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "Prints the tables of docs/tuning.md: what step_velocity_weight, the horizon N and "
      "beta do to the HRP-2 walks of thesis §9.1",
      "walking_tuning"};
  walkgen_examples::cli_defaults(app);
  WALKGEN_CLI_PARSE(app, argc, argv);  // no options: --help, --version, unknown ones rejected

  std::printf("HRP-2 preset, 200 ticks per run; velocity = (v_x [m/s], v_y [m/s], w [rad/s])\n\n");
  step_velocity_table();
  horizon_table();
  beta_table();
  return 0;
}
