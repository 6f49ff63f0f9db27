// Behavioural cloning in the loop (thesis §11.1.2, figures 11.5–11.13): the trained U-Net-LSTM
// (python/bc_train.py → model.pt, walkgen::VelocityNetwork) drives the humanoid in MuJoCo from
// its chest cameras (left RGB + WLS disparity, one frame per NMPC tick), in held-out random rooms
// of each task; or, with --expert, the scripted expert that recorded the demonstrations.
//
//   bc_evaluate (--model FILE | --expert) [--tasks LIST] [--layouts N] [--seed S]
//               [--time-limit T] [--handover T] [--dagger DIR] [--out DIR] [--require-reached]
//               [--shift LIST] [--randomize]
//     --model FILE    the TorchScript network (an existing file)
//     --expert        the scripted expert instead (excludes --model)
//     --tasks LIST    comma-separated (default: straight,curved,obstacle,scan,dynamic,distractor)
//     --layouts N     rooms per task, >= 1 (default 20), seeds S, S+1, ...
//     --seed S        the first room's seed (default 900000: not recorded)
//     --time-limit T  simulated seconds per episode [s], >= 0 (default 0: from the room)
//     --handover T    the network (with --expert: a blind walk straight ahead, into the chair of
//                     an obstacle room) drives for T simulated seconds [s], then the expert (does
//                     the expert, which DAgger asks for labels there, recover from such states?)
//     --dagger DIR    with --model: record what the robot sees while the network drives, labelled
//                     with the expert's commands (DAgger, against the drift of plain cloning)
//     --out DIR       where the CSV files go, created if missing (default .)
//     --require-reached  exit status 1 when an episode did not reach its target (always so
//                     with --expert: the expert is the baseline every room must be solvable by)
//     --shift LIST    held-out looks, comma-separated, each applied to every room in turn
//                     (walkgen::SceneShift: none, dim, side_light, blue_target, small_target,
//                     new_floor; default none: the rooms' default look)
//     --randomize     each room's look drawn from its seed within the training ranges
//                     (walkgen::random_scene_appearance, as record_demonstrations --randomize;
//                     in-distribution), before the shift
// The command line is parsed by CLI11 (examples/common/cli.hpp): --help prints every option with
// its default.
// Writes DIR/bc_evaluation.csv (one line per episode: the look (shift: the shift's name, with
// --randomize "randomized" or "randomized_<shift>"), task, seed, reached, collided, fell, time,
// final distance, NMPC vs measured ZMP mean, command entropy (eq. 9.1), inference ms per frame,
// the target's and the chair's place), DIR/bc_paths.csv (one line per tick: shift, task, seed,
// time, the generator's planar pose, the command; python/plot_bc_evaluation.py --paths draws
// them in their rooms), DIR/appearance.csv (shift, task, seed and each room's look) and
// DIR/bc_shifts.csv (shift, episodes, success_rate: one line per look), and prints the
// success rate per task and look. Exit status: 2 for a bad command line (one line on stderr), a
// model that does not load or a DAgger episode the folder already holds; 1 with --require-reached
// (or --expert) when an episode did not reach its target; else 0.
#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <memory>
#include <sstream>
#include <string>
#include <type_traits>
#include <vector>

#include "common/cli.hpp"
#include "common/navigation_cli.hpp"
#include "walkgen/navigation/scripted_expert.hpp"
#include "walkgen/robot/robot_description.hpp"
#include "walkgen/torch/velocity_network.hpp"

namespace {

/// Eq. 9.1: entropy [nats] of the commands' histogram (bins 0.005 m/s × 0.015 rad/s).
double command_entropy(const std::vector<Eigen::Vector3d>& commands) {
  std::map<std::pair<int, int>, int> bins;
  for (const auto& c : commands) {
    ++bins[{int(std::floor(c.x() / 0.005)), int(std::floor(c.z() / 0.015))}];
  }
  double h = 0.0;
  for (const auto& [bin, n] : bins) {
    const double p = double(n) / double(commands.size());
    h -= p * std::log(p);
  }
  return h;
}

/// What every room of a run shares: who drives, the limits, the DAgger folder and the CSVs.
struct Evaluation {
  walkgen::VelocityNetwork* network = nullptr;  ///< null: the scripted expert drives
  double handover = -1.0;                       ///< [s] < 0: the network drives throughout
  double time_limit = 0.0;                      ///< [s] 0: the room's own
  std::string dagger;                           ///< DAgger folder, empty: none
  std::ofstream& csv;
  std::ofstream& paths;
};

/// The name of a look in the CSVs: the shift's, "randomized" or "randomized_<shift>".
std::string look_name(walkgen::SceneShift shift, bool randomize) {
  if (!randomize) return walkgen::to_string(shift);
  if (shift == walkgen::SceneShift::none) return "randomized";
  return std::string("randomized_") + walkgen::to_string(shift);
}

/// Runs one room (`look` names its look in the CSVs), writes its CSV lines and prints one line.
/// @returns whether the target was reached.
/// @throws walkgen::invalid_argument when the DAgger folder already holds the episode.
bool evaluate_room(Evaluation& ev, const walkgen::NavigationScene& scene, const std::string& look) {
  const Eigen::Vector3d max_command = walkgen::walkgen_humanoid_description().walking.max_command;
  const char* task = walkgen::to_string(scene.task);
  walkgen::ScriptedExpert scripted(scene, max_command);
  walkgen::VelocityNetwork* network = ev.network;
  const double handover = ev.handover;
  std::unique_ptr<walkgen::DemonstrationRecorder> recorder;
  if (!ev.dagger.empty() && network) {  // refuses an episode the folder already holds
    recorder = std::make_unique<walkgen::DemonstrationRecorder>(
        ev.dagger, std::string("dagger_") + task + "_" + std::to_string(scene.seed) +
                       (look == "none" ? "" : "_" + look));
  }
  double inference_s = 0.0;
  long frames = 0;
  if (network) network->reset();
  walkgen::NavigationOptions options;
  options.time_limit = ev.time_limit;
  if (recorder) {
    options.recorder = recorder.get();
    options.label = [&](const walkgen::NavigationObservation& o) { return scripted(o); };
  }
  const auto r = walkgen::run_navigation_episode(
      scene,
      [&](const walkgen::NavigationObservation& o) -> Eigen::Vector3d {
        Eigen::Vector3d c;
        // The expert follows the episode from its start, also before it takes over.
        if (!network || handover >= 0.0) c = scripted(o);
        if (network && (handover < 0.0 || o.time < handover)) {
          const auto t0 = std::chrono::steady_clock::now();
          c = network->step(o.images->left, o.disparity->ptr<float>());
          inference_s +=
              std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
          ++frames;
        } else if (!network && o.time < handover) {
          c = Eigen::Vector3d(0.95 * max_command.x(), 0.0, 0.0);  // blind, straight ahead
        }
        ev.paths << look << ',' << task << ',' << scene.seed << ',' << o.time << ',' << o.pose.x
                 << ',' << o.pose.y << ',' << o.pose.yaw << ',' << c.x() << ',' << c.z() << '\n';
        return c;
      },
      options);
  double zmp = 0.0;
  for (double d : r.zmp_distance) zmp += d;
  zmp /= double(std::max<std::size_t>(1, r.zmp_distance.size()));
  const double ms = frames > 0 ? 1e3 * inference_s / double(frames) : 0.0;
  ev.csv << look << ',' << task << ',' << scene.seed << ',' << int(r.reached) << ','
         << int(r.collided) << ',' << int(r.fell) << ',' << r.time << ',' << r.final_distance << ','
         << zmp << ',' << command_entropy(r.commands) << ',' << ms << ',' << scene.target.x() << ','
         << scene.target.y();
  if (scene.chairs.empty()) {
    ev.csv << ",,,\n";
  } else {
    ev.csv << ',' << scene.chairs[0].x << ',' << scene.chairs[0].y << ',' << scene.chairs[0].radius
           << '\n';
  }
  std::printf("%s%-10s seed %u: %s after %5.1f s, %.2f m from the target%s%s\n",
              look == "none" ? "" : (look + ": ").c_str(), task, scene.seed,
              r.reached ? "reached" : "FAILED ", r.time, r.final_distance,
              r.message.empty() ? "" : ": ", r.message.c_str());
  std::fflush(stdout);
  ev.csv.flush();  // an interrupted run keeps the episodes it finished
  ev.paths.flush();
  return r.reached;
}

}  // namespace

int main(int argc, char** argv) {
  std::string model, out = ".";
  bool expert = false;
  bool require_reached = false;  // exit status 1 when an episode misses (implied by --expert)
  double time_limit = 0.0;       // 0: from the scene
  double handover = -1.0;        // < 0: the network drives the whole episode
  std::string dagger;            // record the expert's labels of the network's states here
  int layouts = 20;
  std::uint32_t seed = 900000;
  CLI::App app{
      "Behavioural cloning in the loop: the trained network (or the scripted expert) "
      "walks the humanoid through held-out random rooms (thesis §11.1.2)",
      "bc_evaluate"};
  walkgen_examples::cli_defaults(app);
  CLI::Option* model_option =
      app.add_option("--model", model,
                     "the network that drives (bc_train.py's model.pt); or --expert")
          ->check(CLI::ExistingFile);
  CLI::Option* expert_option =
      app.add_flag("--expert", expert, "the scripted expert drives instead (the baseline)");
  model_option->excludes(expert_option);
  const walkgen_examples::NavigationTasksOption task_option(app);
  const walkgen_examples::EnumListOption<walkgen::SceneShift> shift_option(
      app, "--shift",
      "held-out looks, comma-separated, each applied to every room in turn (none: the "
      "default look)",
      walkgen::all_scene_shifts(), {walkgen::SceneShift::none});
  bool randomize = false;
  app.add_flag("--randomize", randomize,
               "each room's look drawn from its seed in the training ranges (in-distribution, "
               "as record_demonstrations --randomize), before the shift");
  app.add_option("--layouts", layouts, "rooms per task, >= 1: seeds --seed, --seed + 1, ...")
      ->transform(walkgen_examples::decimal_at_least<int>(1));
  app.add_option("--seed", seed, "the first room's seed; room r uses seed + r")
      ->transform(walkgen_examples::decimal_at_least<std::uint32_t>(0));
  app.add_option("--time-limit", time_limit,
                 "simulated time per episode [s], >= 0; 0: the room's own")
      ->check(walkgen_examples::non_negative);
  app.add_option("--handover", handover,
                 "the expert takes over after this time [s], >= 0 (default: none)")
      ->check(walkgen_examples::non_negative)
      ->default_str("");
  app.add_option("--dagger", dagger,
                 "DAgger: record the network's states with the expert's commands into this "
                 "folder (default: none)")
      ->needs(model_option);
  app.add_option("--out", out,
                 "folder of bc_evaluation.csv, bc_paths.csv, bc_shifts.csv and appearance.csv");
  app.add_flag("--require-reached", require_reached,
               "exit status 1 when a room's target is not reached (as --expert)");
  // Here rather than an option group that requires one: an unknown option is reported first
  // (CLI11 checks required options before the unknown ones).
  app.callback([&] {
    if (model.empty() && !expert) throw CLI::RequiredError("--model FILE or --expert");
  });
  WALKGEN_CLI_PARSE(app, argc, argv);
  const std::vector<walkgen::NavigationTask> tasks = task_option.tasks();
  const std::vector<walkgen::SceneShift> shifts = shift_option.values();
  std::unique_ptr<walkgen::VelocityNetwork> network;
  if (!expert) {
    try {
      network = std::make_unique<walkgen::VelocityNetwork>(model);
    } catch (const walkgen::invalid_argument& e) {
      std::fprintf(stderr, "bc_evaluate: %s\n", e.what());
      return 2;
    }
  }
  std::error_code ec;
  std::filesystem::create_directories(out, ec);
  std::ofstream csv(out + "/bc_evaluation.csv");
  std::ofstream paths(out + "/bc_paths.csv");
  std::ofstream summary(out + "/bc_shifts.csv");
  std::filesystem::remove(out + "/appearance.csv", ec);  // this run's looks only
  walkgen_examples::AppearanceLog looks;
  if (!csv.good() || !paths.good() || !summary.good() || !looks.open(out, "shift,task,seed")) {
    std::fprintf(stderr,
                 "bc_evaluate: cannot write %s/bc_evaluation.csv, bc_paths.csv, bc_shifts.csv "
                 "and appearance.csv\n",
                 out.c_str());
    return 2;
  }
  csv << "shift,task,seed,reached,collided,fell,time,final_distance,zmp_distance_mean,"
         "command_entropy,inference_ms,target_x,target_y,chair_x,chair_y,chair_radius\n";
  paths << "shift,task,seed,time,x,y,yaw,v_x,omega_z\n";
  summary << "shift,episodes,success_rate\n";
  Evaluation evaluation{network.get(), handover, time_limit, dagger, csv, paths};
  int total_reached = 0, total = 0;
  try {
    for (walkgen::SceneShift shift : shifts) {
      const std::string look = look_name(shift, randomize);
      const std::string prefix = look == "none" ? "" : look + ": ";
      int look_reached = 0, look_total = 0;
      for (walkgen::NavigationTask task : tasks) {
        int reached = 0;
        for (int l = 0; l < layouts; ++l) {
          auto scene = walkgen::make_navigation_scene(task, seed + std::uint32_t(l));
          if (randomize) scene.appearance = walkgen::random_scene_appearance(scene.seed);
          scene.appearance = walkgen::apply_scene_shift(scene.appearance, shift);
          looks.add(look + ',' + walkgen::to_string(task) + ',' + std::to_string(scene.seed),
                    scene.appearance);
          reached += evaluate_room(evaluation, scene, look);
        }
        std::printf("bc_evaluate: %s%s: %d / %d reached\n", prefix.c_str(),
                    walkgen::to_string(task), reached, layouts);
        look_reached += reached;
        look_total += layouts;
      }
      summary << look << ',' << look_total << ',' << double(look_reached) / double(look_total)
              << '\n';
      summary.flush();
      if (shifts.size() > 1 || look != "none") {
        std::printf("bc_evaluate: look %s: %d / %d reached\n", look.c_str(), look_reached,
                    look_total);
      }
      total_reached += look_reached;
      total += look_total;
    }
  } catch (const walkgen::invalid_argument& e) {  // a DAgger episode the folder already holds
    std::fprintf(stderr, "bc_evaluate: %s\n", e.what());
    return 2;
  }
  std::printf("bc_evaluate: %d / %d episodes reached the target (%s); %s/bc_evaluation.csv\n",
              total_reached, total, expert ? "scripted expert" : model.c_str(), out.c_str());
  return (expert || require_reached) && total_reached < total ? 1 : 0;
}
