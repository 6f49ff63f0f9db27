// Walks the scenarios of thesis §9.1 (figures 9.1–9.3) with the HRP-2 preset
// (walkgen::hrp2_settings): straight, sideways, curved, turn on the spot, a changing command
// sequence and obstacle avoidance, each for 200 ticks of WalkingMpc<double, 16>
// (walkgen/scenarios/walking_scenarios.hpp), and plots each walk from above.
//
//   walking_scenarios [SCENARIO] [--out DIR] [--no-plot]
//
//   SCENARIO    straight, sideways, curved, turn, sequence, obstacle or all (default: all)
//   --out DIR   output folder, created if missing (default: the working directory)
//   --no-plot   write the CSV files only
//
// For each scenario NAME it writes DIR/NAME.csv (the interpolated trajectory, thesis column
// order), DIR/NAME_footsteps.csv (time,foot,x,y,q of every landing, initial feet first),
// DIR/NAME_meta.csv (key,value: foot and margin sizes, command period, obstacles) and, unless
// --no-plot, DIR/NAME.png through python/plot_walking.py (needs /usr/bin/python3 with
// matplotlib). --help lists the options. Exits 0; 1 on a failed QP, file or plot; 2 on a bad
// command line (one line on stderr).

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

#include "common/cli.hpp"
#include "walkgen/interpolation/trajectory.hpp"
#include "walkgen/mpc/settings.hpp"
#include "walkgen/scenarios/walking_scenarios.hpp"

namespace {

struct Options {
  std::string scenario = "all";
  std::string out = ".";
  bool plot = true;
};

bool open(const std::string& path, std::ofstream* os) {
  os->open(path);
  if (!*os) std::cerr << "error: cannot write " << path << "\n";
  return bool(*os);
}

/// Runs, writes and plots one scenario; false on a failed QP, file or plot.
bool walk(const walkgen::Scenario& sc, const Options& opt) {
  const auto settings = walkgen::hrp2_settings<double>();
  const walkgen::ScenarioRun run = walkgen::run_scenario<16>(sc, settings);

  int failures = 0;
  double active_changes = 0.0;
  for (const auto& r : run.results) {
    if (r.status != walkgen::MpcStatus::solved) ++failures;
    active_changes += r.qp_iterations;
  }
  // Distance walked: CoM start to end (net), and the length of its swaying path.
  double path = 0.0;
  for (std::size_t i = 1; i < run.samples.size(); ++i) {
    path += std::hypot(run.samples[i].com_x[0] - run.samples[i - 1].com_x[0],
                       run.samples[i].com_y[0] - run.samples[i - 1].com_y[0]);
  }
  const auto &first = run.samples.front(), &last = run.samples.back();
  const double net = std::hypot(last.com_x[0] - first.com_x[0], last.com_y[0] - first.com_y[0]);
  std::printf(
      "%-9s %3d ticks, %d QP failures, CoM walked %.3f m (path %.3f m), final yaw %.2f "
      "rad, %zu steps, %.2f mean QP active-set changes per tick\n",
      sc.name.c_str(), int(run.results.size()), failures, net, path, last.com_q[0],
      run.landings.size() - 2, active_changes / double(run.results.size()));

  const std::string base = opt.out + "/" + sc.name;
  std::ofstream traj, steps, meta;
  if (!open(base + ".csv", &traj) || !open(base + "_footsteps.csv", &steps) ||
      !open(base + "_meta.csv", &meta)) {
    return false;
  }
  walkgen::write_trajectory_csv(traj, run.samples);
  steps.precision(10);
  steps << "time,foot,x,y,q\n";
  for (const auto& l : run.landings) {
    steps << l.time << ',' << walkgen::to_string(l.foot) << ',' << l.pose.x << ',' << l.pose.y
          << ',' << l.pose.q << '\n';
  }
  meta.precision(10);
  meta << "key,value\nfoot_length," << settings.foot_length << "\nfoot_width,"
       << settings.foot_width << "\nsecurity_margin_x," << settings.security_margin[0]
       << "\nsecurity_margin_y," << settings.security_margin[1] << "\ncommand_period,"
       << settings.command_period << '\n';
  for (const auto& o : sc.obstacles) {
    meta << "obstacle_x," << o.x << "\nobstacle_y," << o.y << "\nobstacle_radius," << o.radius
         << "\nobstacle_margin," << o.margin << '\n';
  }
  traj.close();
  steps.close();
  meta.close();
  if (!traj || !steps || !meta) {
    std::cerr << "error: writing " << base << "*.csv failed\n";
    return false;
  }

  if (failures > 0) {
    for (std::size_t k = 0; k < run.results.size(); ++k) {
      const auto& r = run.results[k];
      if (r.status == walkgen::MpcStatus::solved) continue;
      std::cerr << "error: " << sc.name << " tick " << k << ": QP "
                << walkgen::to_string(r.qp_status) << ": " << r.message << "\n";
      break;
    }
  }
  if (opt.plot) {
    const std::string script = std::string(WALKGEN_SOURCE_DIR) + "/python/plot_walking.py";
    const std::string cmd = "/usr/bin/python3 " + walkgen_examples::shell_quote(script) + " " +
                            walkgen_examples::shell_quote(base);
    if (std::system(cmd.c_str()) != 0) {
      std::cerr << "error: plotting " << base << ".png failed (needs /usr/bin/python3 with "
                << "matplotlib: apt-get install python3-matplotlib, or pass --no-plot); the CSV "
                << "files are complete\n";
      return false;
    }
    std::printf("          wrote %s.png\n", base.c_str());
  }
  return failures == 0;
}

}  // namespace

int main(int argc, char** argv) {
  Options opt;
  std::vector<std::string> names;
  for (const auto& sc : walkgen::walking_scenarios()) names.push_back(sc.name);
  names.push_back("all");

  CLI::App app{"Walks the HRP-2 scenarios of thesis §9.1 (figures 9.1-9.3): CSV files and plots",
               "walking_scenarios"};
  walkgen_examples::cli_defaults(app);
  app.add_option("SCENARIO", opt.scenario, "the scenario to walk (200 ticks of 0.1 s), or all")
      ->check(CLI::IsMember(names));
  app.add_option("--out", opt.out,
                 "output folder for NAME.csv, NAME_footsteps.csv, NAME_meta.csv and NAME.png "
                 "(created if missing)")
      ->type_name("DIR");
  bool no_plot = false;
  app.add_flag("--no-plot", no_plot,
               "write the CSV files only (plotting needs /usr/bin/python3 with matplotlib)");
  WALKGEN_CLI_PARSE(app, argc, argv);
  opt.plot = !no_plot;

  std::error_code ec;
  std::filesystem::create_directories(opt.out, ec);  // a failure shows when a file is opened
  bool ok = true;
  for (const auto& sc : walkgen::walking_scenarios()) {
    if (opt.scenario == "all" || opt.scenario == sc.name) ok = walk(sc, opt) && ok;
  }
  std::printf("output files are in %s\n", opt.out.c_str());
  return ok ? 0 : 1;
}
