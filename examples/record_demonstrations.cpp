// Demonstrations for behavioural cloning without a person (thesis §7.1, §11.1.1, figure 7.2):
// the scripted expert (walkgen::GoToTarget with knowledge of the scene) walks the humanoid in
// MuJoCo through random rooms of every task (walkgen::NavigationScene); each NMPC tick (0.4 s)
// the left RGB image, the WLS disparity of the chest stereo pair and the command are recorded
// (walkgen::DemonstrationRecorder: PNG files and index.txt).
//
//   record_demonstrations --out DIR [--episodes N] [--seed S] [--tasks LIST] [--noise W]
//                         [--randomize]
//     --out DIR     the dataset folder (required; episodes are added to its index.txt; an
//                   episode the folder already holds is refused, exit status 2)
//     --episodes N  episodes, >= 1, cycling through the tasks (default 6)
//     --seed S      seed of the first layout; episode e uses S + e (default 1000)
//     --tasks LIST  comma-separated: straight,curved,obstacle,scan,dynamic,distractor (default all)
//     --noise W     in every other episode, the robot executes the expert's command plus a
//                   random turn rate (normal, W rad/s, a new one every 2 s) while the expert's
//                   own command is recorded: states off the expert's path, labelled with the way
//                   back (DART, Laskey et al. 2017; against the drift of plain cloning).
//                   In [0, 1) rad/s; default 0.
//     --randomize   domain randomisation: each room's look (light intensity and direction,
//                   floor texture and colours, target colour, size and shape, wall colour,
//                   camera pose offsets, pixel noise) drawn from its seed within the training
//                   ranges (walkgen::random_scene_appearance, walkgen::AppearanceRanges);
//                   without it, the rooms' default look
// Each episode's look is added to DIR/appearance.csv (episode, then
// walkgen::appearance_csv_header()'s columns).
// The command line is parsed by CLI11 (examples/common/cli.hpp): --help prints every option with
// its default; an unknown option or a bad value exits 2 with one line on stderr.
// Prints one line per episode and a summary; exit status 0 when every episode reached its target.
#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <optional>
#include <random>
#include <sstream>
#include <string>
#include <type_traits>
#include <vector>

#include "common/cli.hpp"
#include "common/navigation_cli.hpp"
#include "walkgen/navigation/scripted_expert.hpp"
#include "walkgen/robot/robot_description.hpp"

int main(int argc, char** argv) {
  std::string out;
  int episodes = 6;
  std::uint32_t seed = 1000;
  double noise = 0.0;
  bool randomize = false;
  CLI::App app{
      "Demonstrations for behavioural cloning: the scripted expert walks the humanoid "
      "through random rooms, recorded per NMPC tick (thesis §7.1, §11.1.1)",
      "record_demonstrations"};
  walkgen_examples::cli_defaults(app);
  app.add_option("--out", out, "the dataset folder (episodes are added to it)")->required();
  app.add_option("--episodes", episodes, "episodes, >= 1, cycling through the tasks")
      ->transform(walkgen_examples::decimal_at_least<int>(1));
  app.add_option("--seed", seed, "the first room's seed; episode e uses seed + e")
      ->transform(walkgen_examples::decimal_at_least<std::uint32_t>(0));
  const walkgen_examples::NavigationTasksOption task_option(app);
  app.add_option("--noise", noise,
                 "DART: every other episode adds a random turn rate, sigma [rad/s] in [0, 1)")
      ->check(walkgen_examples::number_where("in [0, 1) [rad/s]",
                                             [](double v) { return v >= 0.0 && v < 1.0; }));
  app.add_flag("--randomize", randomize,
               "domain randomisation: each room's look (light, floor, target colour, size and "
               "shape, walls, camera pose, pixel noise) drawn from its seed in the training "
               "ranges; every episode's look goes to OUT/appearance.csv");
  WALKGEN_CLI_PARSE(app, argc, argv);
  const std::vector<walkgen::NavigationTask> tasks = task_option.tasks();
  int reached = 0;
  long frames = 0;
  double simulated = 0.0;
  walkgen_examples::AppearanceLog looks;
  for (int e = 0; e < episodes; ++e) {
    const walkgen::NavigationTask task = tasks[std::size_t(e) % tasks.size()];
    walkgen::NavigationScene scene = walkgen::make_navigation_scene(task, seed + std::uint32_t(e));
    if (randomize) scene.appearance = walkgen::random_scene_appearance(scene.seed);
    const std::string episode =
        std::string(walkgen::to_string(task)) + "_" + std::to_string(scene.seed);
    std::optional<walkgen::DemonstrationRecorder> recorder_slot;
    try {  // refuses an episode the folder already holds
      recorder_slot.emplace(out, episode);
    } catch (const walkgen::invalid_argument& e) {
      std::fprintf(stderr, "record_demonstrations: %s\n", e.what());
      return 2;
    }
    walkgen::DemonstrationRecorder& recorder = *recorder_slot;
    if (!looks.is_open() && !looks.open(out, "episode")) {
      std::fprintf(stderr, "record_demonstrations: cannot write %s/appearance.csv\n", out.c_str());
      return 2;
    }
    looks.add(episode, scene.appearance);
    walkgen::ScriptedExpert expert(scene,
                                   walkgen::walkgen_humanoid_description().walking.max_command);
    walkgen::NavigationOptions options;
    options.recorder = &recorder;
    const bool perturbed = noise > 0.0 && e % 2 == 1;
    std::mt19937 rng(scene.seed);
    std::normal_distribution<double> turn(0.0, noise);
    double offset = 0.0, offset_until = -1.0;
    if (perturbed) {
      options.label = [&](const walkgen::NavigationObservation& o) { return expert(o); };
    }
    const auto r = walkgen::run_navigation_episode(
        scene,
        [&](const walkgen::NavigationObservation& o) -> Eigen::Vector3d {
          Eigen::Vector3d c = expert(o);
          if (perturbed) {
            if (o.time >= offset_until) {
              offset = turn(rng);
              offset_until = o.time + 2.0;
            }
            c.z() += offset;
          }
          return c;
        },
        options);
    reached += r.reached;
    frames += recorder.samples();
    simulated += r.time;
    std::printf(
        "episode %3d %-10s seed %u%s: %s after %5.1f s, %.2f m from the target, %ld frames, %d "
        "restart(s) after QP failures%s%s\n",
        e + 1, walkgen::to_string(task), scene.seed, perturbed ? " (perturbed)" : "",
        r.reached ? "reached" : "FAILED ", r.time, r.final_distance, recorder.samples(), r.restarts,
        r.message.empty() ? "" : ": ", r.message.c_str());
    std::fflush(stdout);
  }
  std::printf(
      "record_demonstrations: %d / %d episodes reached the target; %ld frames (%.1f min "
      "simulated) in %s/index.txt\n",
      reached, episodes, frames, simulated / 60.0, out.c_str());
  return reached == episodes ? 0 : 1;
}
