// Demonstrations for behavioural cloning without a person (thesis §7.1, §11.1.1, figure 7.2):
// the scripted expert (walkgen::GoToTarget with knowledge of the scene) walks the humanoid in
// MuJoCo through random rooms of every task (walkgen::NavigationScene); each NMPC tick (0.4 s)
// the left RGB image, the WLS disparity of the chest stereo pair and the command are recorded
// (walkgen::DemonstrationRecorder: PNG files and index.txt).
//
//   record_demonstrations --out DIR [--episodes N] [--seed S] [--tasks LIST]
//     --episodes N  episodes, cycling through the tasks (default 6)
//     --seed S      seed of the first layout; episode e uses S + e (default 1000)
//     --tasks LIST  comma-separated: straight,curved,obstacle,scan,dynamic,distractor (default all)
//     --noise W     in every other episode, the robot executes the expert's command plus a
//                   random turn rate (normal, W rad/s, a new one every 2 s) while the expert's
//                   own command is recorded: states off the expert's path, labelled with the way
//                   back (DART, Laskey et al. 2017; against the drift of plain cloning). Default 0.
// Prints one line per episode and a summary; exit status 0 when every episode reached its target.
#include <cstdio>
#include <cstdlib>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "support/navigation_episode.hpp"

int main(int argc, char** argv) {
  std::string out;
  int episodes = 6;
  std::uint32_t seed = 1000;
  double noise = 0.0;
  std::vector<walkgen::NavigationTask> tasks = walkgen::all_navigation_tasks();
  try {
    for (int i = 1; i < argc; ++i) {
      const std::string a = argv[i];
      if (a == "--out" && i + 1 < argc) {
        out = argv[++i];
      } else if (a == "--episodes" && i + 1 < argc) {
        episodes = std::atoi(argv[++i]);
      } else if (a == "--seed" && i + 1 < argc) {
        seed = std::uint32_t(std::strtoul(argv[++i], nullptr, 10));
      } else if (a == "--noise" && i + 1 < argc) {
        noise = std::atof(argv[++i]);
      } else if (a == "--tasks" && i + 1 < argc) {
        tasks = walkgen::navigation_tasks_from_list(argv[++i]);
      } else {
        throw walkgen::invalid_argument("unknown argument '" + a + "'");
      }
    }
  } catch (const walkgen::invalid_argument& e) {
    std::fprintf(stderr,
                 "record_demonstrations: %s\nusage: record_demonstrations --out DIR [--episodes N] "
                 "[--seed S] [--tasks straight,curved,...]\n",
                 e.what());
    return 2;
  }
  if (out.empty() || episodes < 1 || tasks.empty() || !(noise >= 0.0 && noise < 1.0)) {
    std::fprintf(stderr,
                 "record_demonstrations: --out DIR, --episodes >= 1 and 0 <= --noise < 1 "
                 "rad/s are required\n");
    return 2;
  }
  int reached = 0;
  long frames = 0;
  double simulated = 0.0;
  for (int e = 0; e < episodes; ++e) {
    const walkgen::NavigationTask task = tasks[std::size_t(e) % tasks.size()];
    const walkgen::NavigationScene scene =
        walkgen::make_navigation_scene(task, seed + std::uint32_t(e));
    walkgen::DemonstrationRecorder recorder(
        out, std::string(walkgen::to_string(task)) + "_" + std::to_string(scene.seed));
    walkgen_test::ScriptedExpert expert(scene, walkgen::heicub_settings().max_command);
    walkgen_test::NavigationOptions options;
    options.recorder = &recorder;
    const bool perturbed = noise > 0.0 && e % 2 == 1;
    std::mt19937 rng(scene.seed);
    std::normal_distribution<double> turn(0.0, noise);
    double offset = 0.0, offset_until = -1.0;
    if (perturbed) {
      options.label = [&](const walkgen_test::NavigationObservation& o) { return expert(o); };
    }
    const auto r = walkgen_test::run_navigation_episode(
        scene,
        [&](const walkgen_test::NavigationObservation& o) -> Eigen::Vector3d {
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
        "episode %3d %-10s seed %u%s: %s after %5.1f s, %.2f m from the target, %ld frames%s%s\n",
        e + 1, walkgen::to_string(task), scene.seed, perturbed ? " (perturbed)" : "",
        r.reached ? "reached" : "FAILED ", r.time, r.final_distance, recorder.samples(),
        r.message.empty() ? "" : ": ", r.message.c_str());
    std::fflush(stdout);
  }
  std::printf(
      "record_demonstrations: %d / %d episodes reached the target; %ld frames (%.1f min "
      "simulated) in %s/index.txt\n",
      reached, episodes, frames, simulated / 60.0, out.c_str());
  return reached == episodes ? 0 : 1;
}
