// Solves the walking-like QP sequence of thesis §2.2 with walkgen's dense QP solver and plots the
// walk: CoM, ZMP and footsteps, plus the solve time of each tick.
//
// Each tick builds the linearised NMPC QP (68 variables, 106 rows: LIPM preview eq. 2.36–2.42,
// ZMP-in-foot rows 2.68, footstep feasibility 2.71, relative yaw limits 2.75–2.77; built by
// walkgen::WalkingQpSequence, walkgen/scenarios/walking_qp_sequence.hpp), solves it warm-started
// from the previous active set, applies the first jerks and advances. The command changes every few
// seconds (Seq::demo_command): straight, curved, sideways, turn on the spot. The full NMPC
// (walkgen::WalkingMpc) is walking_scenarios'.
//
//   qp_walking_sequence [--ticks N] [--csv FILE] [--png FILE] [--no-plot] [--quiet]
//
//   --ticks N    ticks of T = 0.1 s to walk, 1..100000 (default 240: 24 s)
//   --csv FILE   one row per tick (default qp_walking_sequence.csv)
//   --png FILE   the plot, when /usr/bin/python3 has matplotlib (default qp_walking_sequence.png)
//   --no-plot    write the CSV only
//   --quiet      print only the summary, not a line every 40 ticks
//
// --help lists the options. Exits 0; 1 on a failed QP or an unwritable CSV; 2 on a bad command
// line (one line on stderr). A failed plot is only a warning.

#include <Eigen/Dense>
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

#include "common/cli.hpp"
#include "walkgen/qp/dense_qp.hpp"
#include "walkgen/scenarios/walking_qp_sequence.hpp"

namespace {

using Seq = walkgen::WalkingQpSequence;

struct Options {
  int ticks = 240;
  std::string csv = "qp_walking_sequence.csv";
  std::string png = "qp_walking_sequence.png";
  bool plot = true;
  bool quiet = false;
};

}  // namespace

int main(int argc, char** argv) {
  Options opt;
  CLI::App app{
      "Solves the walking QP sequence of thesis §2.2 with walkgen's dense QP solver and "
      "plots the walk",
      "qp_walking_sequence"};
  walkgen_examples::cli_defaults(app);
  app.add_option("--ticks", opt.ticks, "ticks to walk, one QP each [ticks of 0.1 s]")
      ->type_name("N")
      ->transform(walkgen_examples::decimal_at_least<int>(1))
      ->check(CLI::Range(1, 100000));
  app.add_option("--csv", opt.csv, "output CSV file, one row per tick")->type_name("FILE");
  app.add_option("--png", opt.png, "output plot (needs /usr/bin/python3 with matplotlib)")
      ->type_name("FILE");
  bool no_plot = false;
  app.add_flag("--no-plot", no_plot, "write the CSV only");
  app.add_flag("--quiet", opt.quiet, "print only the summary, not a line every 40 ticks");
  WALKGEN_CLI_PARSE(app, argc, argv);
  opt.plot = !no_plot;

  Seq seq;
  walkgen::DenseQp<double> qp(Seq::kVars, Seq::kRows);
  const double T = seq.lipm().T, h_over_g = seq.lipm().com_height / seq.lipm().gravity;

  std::ofstream csv(opt.csv);
  if (!csv) {
    std::cerr << "error: cannot write " << opt.csv << "\n";
    return 1;
  }
  csv << "t,cmd_vx,cmd_vy,cmd_wz,com_x,com_y,zmp_x,zmp_y,support_x,support_y,support_yaw,"
         "left_support,next_step_x,next_step_y,status,iterations,active_set,warm_started,solve_"
         "us\n";
  csv.precision(9);

  std::vector<double> solve_us;
  solve_us.reserve(static_cast<std::size_t>(opt.ticks));
  if (!opt.quiet) {
    std::cout << "walkgen QP walking sequence: " << Seq::kVars << " variables, " << Seq::kRows
              << " constraint rows, " << opt.ticks << " ticks of " << T << " s\n";
  }
  for (int tick = 0; tick < opt.ticks; ++tick) {
    const Seq::Command cmd = Seq::demo_command(tick);
    const walkgen::WalkingQp w = seq.build(cmd);
    // init() factorises H and validates the data; solve() starts from the last active set.
    const auto start = std::chrono::steady_clock::now();
    qp.init(w.H, w.g, w.A, w.lb, w.ub);
    const auto& r = qp.solve();
    const double us =
        std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - start).count();
    if (r.status != walkgen::QpStatus::solved) {
      std::cerr << "error: tick " << tick << ": QP " << walkgen::to_string(r.status) << ": "
                << r.message << "\n";
      return 1;
    }
    solve_us.push_back(us);

    // ZMP of the current state (eq. 2.23: z = c − c_z/g c̈), then apply the first jerks.
    const double zx = seq.com_x()[0] - h_over_g * seq.com_x()[2];
    const double zy = seq.com_y()[0] - h_over_g * seq.com_y()[2];
    csv << tick * T << ',' << cmd.vx << ',' << cmd.vy << ',' << cmd.wz << ',' << seq.com_x()[0]
        << ',' << seq.com_y()[0] << ',' << zx << ',' << zy << ',' << seq.support()[0] << ','
        << seq.support()[1] << ',' << seq.support()[2] << ',' << seq.left_support() << ','
        << r.x[Seq::kN] << ',' << r.x[2 * Seq::kN + Seq::kSteps] << ','
        << walkgen::to_string(r.status) << ',' << r.iterations << ',' << r.active_set_size << ','
        << r.warm_started << ',' << us << '\n';
    if (!opt.quiet && (tick + 1) % 40 == 0) {
      std::printf(
          "  t = %5.1f s  cmd (%.2f, %.2f, %.2f)  CoM (%6.3f, %6.3f)  %2d active, %2d "
          "iterations, %.1f us\n",
          (tick + 1) * T, cmd.vx, cmd.vy, cmd.wz, seq.com_x()[0], seq.com_y()[0], r.active_set_size,
          r.iterations, us);
    }
    seq.advance(r.x);
  }
  csv.close();

  std::vector<double> sorted = solve_us;
  std::sort(sorted.begin(), sorted.end());
  const double median = sorted[sorted.size() / 2], worst = sorted.back();
  std::printf(
      "solved %d QPs: init + warm solve median %.1f us, max %.1f us (wall clock of this "
      "run; see benchmarks/bench_qp for measurements)\n",
      opt.ticks, median, worst);
  std::printf("final CoM (%.3f, %.3f) m; wrote %s\n", seq.com_x()[0], seq.com_y()[0],
              opt.csv.c_str());

  if (opt.plot) {
    const std::string script = std::string(WALKGEN_SOURCE_DIR) + "/python/plot_walking_qp.py";
    const std::string cmd = "/usr/bin/python3 " + walkgen_examples::shell_quote(script) + " " +
                            walkgen_examples::shell_quote(opt.csv) + " " +
                            walkgen_examples::shell_quote(opt.png);
    if (std::system(cmd.c_str()) == 0) {
      std::printf("wrote %s\n", opt.png.c_str());
    } else {
      std::fprintf(stderr,
                   "warning: plotting failed (needs /usr/bin/python3 with matplotlib: "
                   "apt-get install python3-matplotlib); the CSV is complete\n");
    }
  }
  return 0;
}
