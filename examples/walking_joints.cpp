// Pattern to joints (thesis §2.4.2, §6.3): a Heicub walk of the NMPC generator, interpolated at
// the command period, turned into joint trajectories of walkgen's humanoid (models/) by the
// Ceres whole-body inverse kinematics, one warm-started solve per sample.
//
//   walking_joints [--ticks N] [--out FILE]
//     --ticks N   NMPC ticks of 0.4 s to walk, N >= 1 (default 32: two gait cycles of 6.4 s)
//     --out FILE  the CSV (default walking_joints.csv): time [s], then one column per joint named
//                 as in the URDF (q [rad]), then the root link's position (base_x, base_y,
//                 base_z [m])
// The command line is parsed by CLI11 (examples/common/cli.hpp): --help lists every option with
// its default and exits 0; an unknown option or a bad value exits 2 with one line on stderr.
// Exits 1 when the walk failed (a rejected command or an NMPC that did not solve), an IK solve
// did not converge or the CSV could not be written.
#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

#include "common/cli.hpp"
#include "walkgen/control/pattern_targets.hpp"
#include "walkgen/humanoid/humanoid_ik.hpp"
#include "walkgen/scenarios/walking_scenarios.hpp"

int main(int argc, char** argv) {
  int ticks = 32;  // two gait cycles of 6.4 s
  std::string out = "walking_joints.csv";
  CLI::App app{
      "Turns an NMPC walk into joint trajectories of walkgen's humanoid by the Ceres IK "
      "(thesis §2.4.2, §6.3)",
      "walking_joints"};
  walkgen_examples::cli_defaults(app);
  app.add_option("--ticks", ticks,
                 "NMPC ticks of 0.4 s to walk, >= 1 (32: two gait cycles of 6.4 s)")
      ->transform(walkgen_examples::decimal_at_least<int>(1))
      ->check(CLI::Range(1, 100000));
  app.add_option("--out", out,
                 "CSV: time [s], one column per URDF joint (q [rad]), base_x, base_y, base_z [m]");
  WALKGEN_CLI_PARSE(app, argc, argv);
  const Eigen::Vector3d command(0.02, 0.0, 0.05);  // within heicub_settings().max_command
  std::printf("walking_joints: NMPC walk of %d ticks, command (%.3f, %.3f, %.3f)\n", ticks,
              command.x(), command.y(), command.z());
  const walkgen::PatternWalk walk = walkgen::heicub_walk(command, ticks);
  if (!walk.ok()) {
    std::fprintf(stderr, "walking_joints: %s\n", walk.message.c_str());
    return 1;
  }
  const std::vector<walkgen::TrajectorySample<double>>& samples = walk.samples;

  const walkgen::KinematicTree<double> tree = walkgen::humanoid_tree();
  walkgen::HumanoidIk ik(tree);
  walkgen::start_walk(ik, samples.front());

  std::ofstream csv(out);
  csv << "time";
  for (const auto& name : tree.joint_names()) csv << ',' << name;
  csv << ",base_x,base_y,base_z\n";
  csv.precision(10);
  int failures = 0, iterations = 0;
  for (std::size_t k = 0; k < samples.size(); ++k) {
    const walkgen::IkResult r = ik.solve(walkgen::ik_target(samples[k]));
    failures += r.status != walkgen::IkStatus::converged;  // the previous q is kept and written
    iterations += r.iterations;
    csv << samples[k].time;
    for (Eigen::Index j = 0; j < ik.q().size(); ++j) csv << ',' << ik.q()[j];
    const Eigen::Vector3d& p = ik.base_position_W();
    csv << ',' << p.x() << ',' << p.y() << ',' << p.z() << '\n';
    if ((k + 1) % 200 == 0 || k + 1 == samples.size()) {
      std::printf("  t = %6.2f s: %zu / %zu samples, %d not converged\n", samples[k].time, k + 1,
                  samples.size(), failures);
    }
  }
  std::printf(
      "walking_joints: wrote %s (%zu rows, %d joints), %.1f LM iterations per sample, "
      "%d not converged\n",
      out.c_str(), samples.size(), tree.num_joints(), double(iterations) / double(samples.size()),
      failures);
  return failures == 0 && csv.good() ? 0 : 1;
}
