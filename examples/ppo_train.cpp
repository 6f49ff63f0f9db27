// Thesis §11.2 (figures 11.16–11.19): trains and evaluates PPO agents (walkgen::TorchPpo).
//
//   ppo_train benchmark [options]   the benchmarking environment of §11.2.1
//   ppo_train nmpc [options]        the NMPC environment of §11.2.2 (--obstacles K: beyond it)
//
// Training prints one line per epoch (epoch, mean reward, wins/losses, σ), writes
// <out>/learning_<env>.csv, saves the policy as TorchScript (<out>/ppo_<env>.pt; each better
// epoch replaces it atomically, so a run stopped during a save leaves the last good one), then
// tests it: benchmark: 10 runs of 10 000 steps of the policy mean (wins, losses); nmpc: 100
// held-out goals all around the robot (reached, failed, footsteps inside obstacles) and the
// trajectories of four goals (figure 11.19) in <out>/trajectories_<env>.csv.
// --policy FILE skips the training and tests a saved policy. --plot draws the PNGs through
// python/plot_learning.py.
//
// Options (CLI11, examples/common/cli.hpp; --help lists them with their defaults):
//   --config FILE   PPO hyper-parameters and the run's schedule from YAML (walkgen::PpoConfig,
//                   keys in docs/learning.md); the options below override the file
//   --epochs E      training epochs, >= 1 (default 50 for benchmark, 30 for nmpc, 200 with
//                   obstacles)
//   --steps S       environment steps per epoch, all processes, >= 1 (default 10000 benchmark,
//                   8192 nmpc), rounded up to whole updates
//   --seed N        seed of the weights, environments, noise and minibatch order (default 1)
//   --out DIR       output folder, created if missing (default .)
//   --envs K        environments, all processes (default 8)
//   --threads T     threads that step a process's environments (default 2; benchmark 1)
//   --obstacles K   nmpc: circular obstacles per episode, >= 0 (default 0); with obstacles the
//                   defaults are --observe-motion, --success-reward 10000, --epochs 200 and
//                   ppo.anneal_learning_rate
//   --observe-motion, --no-observe-motion   nmpc: the robot's motion in the state (7 numbers)
//   --success-reward R   nmpc: reward for reaching the goal (default 100, the thesis's)
//   --obstacle-weight W  nmpc: shaping near obstacles (NmpcGoalSettings::obstacle_weight, 0)
//   --soft-obstacles W   nmpc: the NMPC's obstacle rows soft at this exact-penalty weight
//                   (WalkingSettings::soft.obstacles; 0: hard; default 0, with obstacles 1e4)
//   --checkpoint-every K   epochs between checkpoints (<out>/checkpoint_<env>.pt; 0: none)
//   --resume        continue from <out>/checkpoint_<env>.pt: the result equals an uninterrupted run
//   --stop-after E  stop after E epochs of this invocation, as an interruption would (for tests)
//   --world-size W, --rank R, --master-addr A, --master-port P
//                   data-parallel training over W processes (c10d Gloo); default from torchrun's
//                   WORLD_SIZE, RANK, MASTER_ADDR, MASTER_PORT; rank 0 logs, saves and tests
//   --policy FILE   test this saved policy (an existing file) instead of training
//   --test-runs R   benchmark: test runs of 10 000 steps, >= 1 (default 10)
//   --test-goals G  nmpc: held-out test goals, >= 1 (default 100)
//   --plot          draw the PNGs (python/plot_learning.py)
//   --quiet         no progress output
// Progress: a bar with the ETA on a terminal, else one line per epoch. <out>/config_<env>.yaml
// records the settings in effect. A bad command line exits 2 with one line on stderr.
#include <torch/torch.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <limits>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <type_traits>
#include <vector>

#include "common/cli.hpp"
#include "walkgen/core/atomic_file.hpp"
#include "walkgen/learning/environment.hpp"
#include "walkgen/learning/nmpc_environment.hpp"
#include "walkgen/learning/step_pool.hpp"
#include "walkgen/torch/ppo.hpp"
#include "walkgen/torch/training.hpp"
#include "walkgen/yaml/ppo_settings_loader.hpp"
#if WALKGEN_HAS_DISTRIBUTED
#include "walkgen/torch/distributed.hpp"
#endif

namespace {

constexpr int kObstacleEpochs = 200;    // nmpc's default training epochs with obstacles
constexpr double kSoftObstacles = 1e4;  // nmpc's default --soft-obstacles with obstacles

struct Options {
  std::string env;
  std::string config;
  walkgen::PpoConfig cfg;  // the settings in effect: defaults, then --config, then options
  std::string out = ".";
  int obstacles = 0;
  // The environment's settings beyond the thesis's; the defaults with obstacles are in
  // apply_obstacle_defaults().
  bool observe_motion = false;
  double obstacle_weight = 0.0;
  double soft_obstacles = 0.0;
  double success_reward = walkgen::NmpcGoalSettings{}.success_reward;
  bool resume = false;
  int stop_after = 0;
  int world_size = 1, rank = 0, master_port = 29500;
  std::string master_addr = "127.0.0.1";
  std::string policy;
  int test_runs = 10;
  int test_goals = 100;
  bool plot = false;
  bool quiet = false;
  walkgen::PpoCommunicator* communicator = nullptr;
  /// text_hash of the settings a resumed run must share with its checkpoint (all but the
  /// epochs to run, the threads and the checkpoint interval)
  std::uint64_t settings_hash = 0;
  bool lead() const { return rank == 0; }
};

std::string env_name(const Options& o) {
  return o.env == "nmpc" && o.obstacles > 0 ? "nmpc_obstacles" : o.env;
}

// The environment's settings that the PPO config does not hold, as the command line that gives
// them: part of the settings hashes, and a comment atop <out>/config_<env>.yaml.
std::string env_key(const Options& o) {
  std::ostringstream k;
  k << o.env;
  if (o.env == "nmpc") {
    k << " --obstacles " << o.obstacles
      << (o.observe_motion ? " --observe-motion" : " --no-observe-motion") << " --success-reward "
      << o.success_reward << " --obstacle-weight " << o.obstacle_weight;
    // only when set: the runs before the option keep their settings hash (and --resume)
    if (o.soft_obstacles != 0.0) k << " --soft-obstacles " << o.soft_obstacles;
  }
  return k.str() + "\n";
}

// "1m05s", "42s": the time left, for the progress bar.
std::string duration_text(double seconds) {
  const long s = std::lround(std::max(0.0, seconds));
  char buf[32];
  if (s >= 60)
    std::snprintf(buf, sizeof buf, "%ldm%02lds", s / 60, s % 60);
  else
    std::snprintf(buf, sizeof buf, "%lds", s);
  return buf;
}

// `text` to `path` atomically; a failed write throws (the old file stays).
void write_text(const std::string& path, const std::string& text) {
  walkgen::write_atomically(path, [&](const std::string& temp) {
    std::ofstream out(temp);
    out << text;
    out.close();
    walkgen::check_argument(!out.fail(), "ppo_train", "'" + path + "' written", "a write error",
                            "is the disk full, the folder writable?");
  });
}

// The CSV log's complete rows of epochs <= `epochs` (a resumed run continues the log of its
// checkpoint; a row cut short by an interruption is dropped).
void truncate_log(const std::string& csv, int epochs) {
  std::ifstream in(csv);
  if (!in) return;
  std::string line, header, kept;
  if (!std::getline(in, header)) return;
  const auto fields = [](const std::string& l) { return std::count(l.begin(), l.end(), ',') + 1; };
  kept = header + '\n';
  while (std::getline(in, line))
    if (fields(line) == fields(header) && std::atoi(line.c_str()) <= epochs) kept += line + '\n';
  in.close();
  write_text(csv, kept);
}

constexpr const char* kLogHeader =
    "epoch,steps,mean_reward,mean_return,episodes,wins,losses,truncations,std,seconds,"
    "policy_loss,value_loss,entropy,approx_kl,clip_fraction,total_steps,success_rate,elapsed,"
    "updates\n";

// Trains o.cfg.run.epochs epochs; writes the CSV log (rank 0). With a `validate(epoch)` score
// (higher is better, e.g. test-mode wins on validation goals; nullopt: this epoch is not
// validated), the policy of the best validated epoch is kept (the thesis also kept its best
// network); otherwise the last one. Saves it
// (TorchPpo::save replaces the file atomically: a crash mid-save leaves the previous policy).
// Every checkpoint_every epochs a checkpoint (TorchPpo::save_checkpoint) lets --resume continue.
// Returns false when --stop-after ended the run early.
template <class Env>
bool train(walkgen::TorchPpo& ppo, std::vector<Env>& envs, walkgen::StepPool& pool,
           const Options& o, const std::string& policy_path,
           const std::function<std::optional<double>(int epoch)>& validate = nullptr) {
  const walkgen::PpoRunSettings& run = o.cfg.run;
  walkgen::PpoTrainer<Env> trainer(ppo, envs, run.rollout_steps, &pool);
  ppo.set_total_updates(run.epochs * trainer.updates_per_epoch(run.steps));
  const std::string csv = o.out + "/learning_" + env_name(o) + ".csv";
  const std::string checkpoint = o.out + "/checkpoint_" + env_name(o) + ".pt";
  double best = -1e300, elapsed = 0.0, total_steps = 0.0;
  int best_epoch = 0;
  const std::vector<std::string> counters = {
      "epoch", "best_score", "best_epoch",    "elapsed",          "total_steps",
      "envs",  "world_size", "rollout_steps", "settings_hash_hi", "settings_hash_lo"};
  const double hash_hi = static_cast<double>(o.settings_hash >> 32);
  const double hash_lo = static_cast<double>(o.settings_hash & 0xFFFFFFFFull);
  if (o.resume) {
    const auto c = ppo.resume_checkpoint(checkpoint, counters);
    const auto check_same = [&](double saved, double now, const char* what) {
      walkgen::check_argument(
          saved == now, "--resume", std::string("the checkpoint's ") + what,
          std::to_string(now) + " (the checkpoint has " + std::to_string(saved) + ")");
    };
    check_same(c[5], run.envs, "envs");
    check_same(c[6], o.world_size, "world size");
    check_same(c[7], run.rollout_steps, "rollout_steps");
    walkgen::check_argument(c[8] == hash_hi && c[9] == hash_lo, "--resume",
                            "the settings of the checkpoint's run (seed, steps, PPO's "
                            "hyper-parameters, environment; compare " +
                                o.out + "/config_" + env_name(o) + ".yaml)",
                            "other settings", "resume with the run's command line and --config");
    if (o.communicator != nullptr) {  // every rank resumed the same state
      std::uint64_t h =
          walkgen::text_hash(reinterpret_cast<const char*>(c.data()), sizeof(double) * c.size());
      for (const auto& p : ppo.model()->parameters()) {
        const torch::Tensor t = p.detach().contiguous();
        h ^= walkgen::text_hash(static_cast<const char*>(t.data_ptr()), t.nbytes()) +
             0x9E3779B97F4A7C15ull + (h << 6) + (h >> 2);
      }
      walkgen::check_same_on_all_processes(*o.communicator,
                                           h ^ static_cast<std::uint64_t>(ppo.updates()),
                                           "checkpoint (epoch, counters and weights)");
    }
    trainer.set_epoch(static_cast<int>(c[0]));
    best = c[1];
    best_epoch = static_cast<int>(c[2]);
    elapsed = c[3];
    total_steps = c[4];
    if (o.lead()) {
      truncate_log(csv, trainer.epochs());
      std::printf("resumed %s from %s after epoch %d (%.0f steps)\n", env_name(o).c_str(),
                  checkpoint.c_str(), trainer.epochs(), total_steps);
    }
  }
  std::ofstream log;
  if (o.lead()) {
    const bool append = o.resume && std::filesystem::exists(csv);
    log.open(csv, append ? std::ios::app : std::ios::trunc);
    if (!append) log << kLogHeader;
  }
  const bool bar = o.lead() && !o.quiet && isatty(fileno(stdout));
  int done_here = 0, last_checkpoint = o.resume ? trainer.epochs() : 0;
  double here_seconds = 0.0;  // this invocation's epochs: the ETA's rate
  while (trainer.epochs() < run.epochs) {
    if (o.stop_after > 0 && done_here == o.stop_after) {
      if (bar) std::printf("\n");
      if (last_checkpoint > 0)
        std::printf(
            "stopped after epoch %d (--stop-after %d); --resume continues from the "
            "checkpoint of epoch %d\n",
            trainer.epochs(), o.stop_after, last_checkpoint);
      else
        std::printf(
            "stopped after epoch %d (--stop-after %d); no checkpoint was written "
            "(--checkpoint-every 0 or none due yet)\n",
            trainer.epochs(), o.stop_after);
      return false;
    }
    const walkgen::PpoEpoch ep = trainer.run_epoch(run.steps);
    ++done_here;
    elapsed += ep.seconds;
    total_steps += static_cast<double>(ep.steps);
    if (o.lead()) {
      const std::optional<double> score =
          validate ? validate(ep.epoch) : std::optional<double>(0.0);
      if (score && *score >= best) {
        best = *score;
        best_epoch = ep.epoch;
        ppo.save(policy_path);
      }
      log << ep.epoch << ',' << ep.steps << ',' << ep.mean_reward << ',' << ep.mean_return << ','
          << ep.episodes << ',' << ep.wins << ',' << ep.losses << ',' << ep.truncations << ','
          << ep.std << ',' << ep.seconds << ',' << ep.update.policy_loss << ','
          << ep.update.value_loss << ',' << ep.update.entropy << ',' << ep.update.approx_kl << ','
          << ep.update.clip_fraction << ',' << static_cast<long long>(total_steps) << ','
          << ep.success_rate() << ',' << elapsed << ',' << ppo.updates() << '\n';
      log.flush();
      walkgen::check_argument(!log.fail(), "ppo_train", "'" + csv + "' written", "a write error",
                              "is the disk full?");
    }
    const bool due = run.checkpoint_every > 0 &&
                     (ep.epoch % run.checkpoint_every == 0 || ep.epoch == run.epochs);
    if (due) last_checkpoint = ep.epoch;
    if (due && o.lead())
      ppo.save_checkpoint(checkpoint, {{"epoch", ep.epoch},
                                       {"best_score", best},
                                       {"best_epoch", best_epoch},
                                       {"elapsed", elapsed},
                                       {"total_steps", total_steps},
                                       {"envs", run.envs},
                                       {"world_size", o.world_size},
                                       {"rollout_steps", run.rollout_steps},
                                       {"settings_hash_hi", hash_hi},
                                       {"settings_hash_lo", hash_lo}});
    if (o.quiet || !o.lead()) continue;
    const double eta = (here_seconds += ep.seconds) / done_here * (run.epochs - ep.epoch);
    if (bar) {
      const int width = 24, filled = width * ep.epoch / run.epochs;
      std::printf("\r%s [%s%s] %3d/%d  reward %8.4f  success %5.1f %%  std %.3f  ETA %-8s",
                  env_name(o).c_str(), std::string(static_cast<std::size_t>(filled), '#').c_str(),
                  std::string(static_cast<std::size_t>(width - filled), '.').c_str(), ep.epoch,
                  run.epochs, ep.mean_reward, 100.0 * ep.success_rate(), ep.std,
                  duration_text(eta).c_str());
      std::fflush(stdout);
    } else {
      std::printf(
          "epoch %3d/%d  mean reward %9.4f  return %9.2f  wins %4d  losses %3d  "
          "timeouts %3d  std %.3f  %.1f s  ETA %s\n",
          ep.epoch, run.epochs, ep.mean_reward, ep.mean_return, ep.wins, ep.losses, ep.truncations,
          ep.std, ep.seconds, duration_text(eta).c_str());
    }
  }
  if (bar) std::printf("\n");
  // The last epoch's weights of every process (they are the same: the test of the distributed
  // run compares them); the best epoch's policy is policy_path.
  ppo.save(o.out + "/ppo_" + env_name(o) + "_last" +
           (o.lead() ? std::string() : ".rank" + std::to_string(o.rank)) + ".pt");
  if (o.lead()) {
    std::printf(
        "trained %s: %d epochs, %.0f steps in %.1f s (%.0f environment steps/s, %d process%s), "
        "log %s, policy of epoch %d (validation score %g) saved to %s\n",
        env_name(o).c_str(), run.epochs, total_steps, elapsed,
        total_steps / std::max(1e-9, elapsed), o.world_size, o.world_size > 1 ? "es" : "",
        csv.c_str(), best_epoch, validate ? best : 0.0, policy_path.c_str());
    ppo.load_parameters(policy_path);
  }
  return true;
}

// The environments of this process: its share of the run's, as consecutive global indices.
int local_envs(const Options& o) {
  walkgen::check_argument(o.cfg.run.envs % o.world_size == 0, "--envs",
                          "a multiple of the world size " + std::to_string(o.world_size),
                          o.cfg.run.envs);
  return o.cfg.run.envs / o.world_size;
}

int run_benchmark(const Options& o) {
  walkgen::PointGoalSettings env_settings;  // test mode: no step budget (the thesis)
  walkgen::PointGoalSettings train_settings = env_settings;
  train_settings.max_steps = 200;
  const int E = local_envs(o);
  walkgen::PpoSettings s = o.cfg.ppo;
  s.seed = o.cfg.run.seed;
  walkgen::TorchPpo ppo =
      o.policy.empty() ? walkgen::TorchPpo(4, 2, s) : walkgen::TorchPpo::load(o.policy, s);
  if (o.policy.empty()) {
    ppo.set_communicator(o.communicator);
    std::vector<walkgen::PointGoalEnv> envs;
    for (int e = 0; e < E; ++e) envs.emplace_back(train_settings, 0);  // seeded by the trainer
    walkgen::StepPool pool(o.cfg.run.threads);
    // Validation: test mode (policy mean) for 2000 steps on goals apart from the test's.
    walkgen::PointGoalSettings validation_settings = env_settings;
    validation_settings.max_steps = 200;
    const auto validate = [&](int) -> std::optional<double> {
      walkgen::PointGoalEnv env(validation_settings, o.cfg.run.validation_seed);
      const auto t = walkgen::evaluate_steps(ppo, env, 2000);
      return double(t.wins) - 10.0 * t.losses - t.truncations;
    };
    if (!train(ppo, envs, pool, o, o.out + "/ppo_benchmark.pt", validate)) return 0;
  }
  if (!o.lead()) return 0;
  // Test mode: the policy mean, R runs of 10 000 steps.
  std::ofstream test(o.out + "/test_benchmark.csv");
  test << "run,steps,wins,losses,mean_reward\n";
  double wins = 0, wins_sq = 0;
  int losses = 0;
  for (int r = 0; r < o.test_runs; ++r) {
    walkgen::PointGoalEnv env(env_settings, o.cfg.run.evaluation_seed + r);
    const auto t = walkgen::evaluate_steps(ppo, env, 10000);
    test << r << ',' << t.steps << ',' << t.wins << ',' << t.losses << ',' << t.mean_reward << '\n';
    wins += t.wins;
    wins_sq += double(t.wins) * t.wins;
    losses += t.losses;
  }
  const double mean = wins / o.test_runs;
  const double sd = std::sqrt(std::max(0.0, wins_sq / o.test_runs - mean * mean));
  std::printf("test mode (policy mean), %d runs of 10000 steps: %.1f +- %.1f wins, %d losses\n",
              o.test_runs, mean, sd, losses);
  // Trajectories of the test mode (figure 11.18): 300 steps.
  std::ofstream traj(o.out + "/trajectories_benchmark.csv");
  traj << "episode,step,agent_x,agent_y,goal_x,goal_y,end\n";
  walkgen::PointGoalEnv env(env_settings, 4242);
  int episode = 0;
  float obs[4], act[2];
  for (int k = 0; k < 300; ++k) {
    env.observe(obs);
    ppo.act(obs, 1, true, act);
    const auto r = env.step(act);
    traj << episode << ',' << k << ',' << env.agent().x() << ',' << env.agent().y() << ','
         << env.goal().x() << ',' << env.goal().y() << ',' << walkgen::to_string(r.end) << '\n';
    if (r.done()) {
      env.reset();
      ++episode;
    }
  }
  return 0;
}

constexpr int kValidationGoals = 50;  // nmpc: goals of each validation ...
constexpr int kValidationEvery = 5;   // ... every this many epochs and after the last

// How the policy mean did on a goal set (NmpcGoalEnv), goal by goal.
struct GoalOutcomes {
  std::vector<walkgen::PpoTaskResult> results;
  std::vector<double> clearance;      // smallest footstep-circle distance (inf: no obstacle)
  std::vector<double> end_clearance;  // the CoM's distance to the nearest R + m at the end
  std::vector<double> end_speed;      // the CoM's speed at the end [m/s]
  std::vector<char> reached_goal;     // success with no footstep inside an obstacle
  std::vector<std::string> conflict;  // an infeasible QP's conflicting blocks ("" if none)
  int reached = 0;
};

// The policy mean on `tasks` (NmpcGoalTask), the environments stepped on the pool.
template <class Env, class Task>
GoalOutcomes reached_goals(walkgen::TorchPpo& ppo, std::vector<Env>& envs,
                           const std::vector<Task>& tasks, walkgen::StepPool& pool) {
  GoalOutcomes g;
  const std::size_t n = tasks.size();
  g.clearance.assign(n, 0.0);
  g.end_clearance.assign(n, std::numeric_limits<double>::infinity());
  g.end_speed.assign(n, 0.0);
  g.conflict.assign(n, "");
  g.results = walkgen::evaluate_tasks<Env, Task>(
      ppo, envs, tasks, &pool, [&](std::size_t i, const Env& env) {
        g.clearance[i] = env.min_obstacle_clearance();
        // where the episode ended: a failed QP at a circle's edge at speed came too late to turn
        for (const auto& ob : env.obstacles())
          g.end_clearance[i] =
              std::min(g.end_clearance[i], (env.position() - Eigen::Vector2d(ob.x, ob.y)).norm() -
                                               ob.radius - ob.margin);
        const auto& st = env.mpc().state();
        g.end_speed[i] = std::hypot(st.com_x[1], st.com_y[1]);
        g.conflict[i] = env.mpc().block_names(env.failure_conflicts());
      });
  g.reached_goal.assign(n, 0);
  for (std::size_t i = 0; i < n; ++i) {
    g.reached_goal[i] = g.results[i].end == walkgen::EpisodeEnd::success && g.clearance[i] >= 0.0;
    g.reached += g.reached_goal[i];
  }
  return g;
}

int run_nmpc(const Options& o) {
  walkgen::NmpcGoalSettings env_settings;
  env_settings.obstacles = o.obstacles;
  env_settings.observe_motion = o.observe_motion;
  env_settings.obstacle_weight = o.obstacle_weight;
  env_settings.walking.soft.obstacles = o.soft_obstacles;
  env_settings.success_reward = o.success_reward;
  if (o.obstacles > 0) {
    env_settings.goal_min_distance = 1.0;
    env_settings.goal_max_distance = 2.0;
  }
  const int E = local_envs(o);
  using Env = walkgen::NmpcGoalEnv<16>;
  walkgen::StepPool pool(o.cfg.run.threads);
  const int obs_size = Env(env_settings, 0).observation_size();
  walkgen::PpoSettings s = o.cfg.ppo;
  s.seed = o.cfg.run.seed;
  walkgen::TorchPpo ppo =
      o.policy.empty() ? walkgen::TorchPpo(obs_size, 2, s) : walkgen::TorchPpo::load(o.policy, s);
  if (o.policy.empty()) {
    ppo.set_communicator(o.communicator);
    std::vector<Env> envs;
    envs.reserve(E);
    for (int e = 0; e < E; ++e) envs.emplace_back(env_settings, 0);  // seeded by the trainer
    // Validation every kValidationEvery epochs and after the last: the policy mean on
    // kValidationGoals goals of run.validation_seed (apart from training's and the test's);
    // the best of these epochs is kept (the later one on a tie).
    std::vector<walkgen::NmpcGoalTask> validation_goals;
    Env drawer(env_settings, o.cfg.run.validation_seed);
    for (int g = 0; g < kValidationGoals; ++g) validation_goals.push_back(drawer.sample_task());
    const auto validate = [&](int epoch) -> std::optional<double> {
      if (epoch % kValidationEvery != 0 && epoch != o.cfg.run.epochs) return std::nullopt;
      std::vector<Env> venvs;
      venvs.reserve(static_cast<std::size_t>(std::max(1, o.cfg.run.envs)));
      for (int e = 0; e < std::max(1, o.cfg.run.envs); ++e) venvs.emplace_back(env_settings, 0);
      return double(reached_goals(ppo, venvs, validation_goals, pool).reached);
    };
    if (!train(ppo, envs, pool, o, o.out + "/ppo_" + env_name(o) + ".pt", validate)) return 0;
  }
  if (!o.lead()) return 0;
  const int test_envs = std::max(1, o.cfg.run.envs);
  // Held-out goals: drawn by an environment seeded apart from the training ones.
  std::vector<Env> envs;
  envs.reserve(test_envs);
  for (int e = 0; e < test_envs; ++e)
    envs.emplace_back(env_settings, o.cfg.run.evaluation_seed + e);
  std::vector<walkgen::NmpcGoalTask> tasks;
  for (int g = 0; g < o.test_goals; ++g) tasks.push_back(envs[0].sample_task());
  const GoalOutcomes out = reached_goals(ppo, envs, tasks, pool);
  int failed = 0, inside = 0, behind = 0, behind_reached = 0;  // failed: failed QPs
  std::ofstream test(o.out + "/test_" + env_name(o) + ".csv");
  test << "goal,goal_x,goal_y,end,steps,reward,min_clearance,end_clearance,end_speed,conflict\n";
  for (std::size_t i = 0; i < tasks.size(); ++i) {
    const auto& r = out.results[i];
    const bool in = out.clearance[i] < 0.0;
    const bool ok = out.reached_goal[i] != 0;
    failed += r.end == walkgen::EpisodeEnd::failure && !in;  // else a collision ended it
    inside += in;
    if (tasks[i].goal.x() < 0.0) {
      ++behind;
      behind_reached += ok;
    }
    test << i << ',' << tasks[i].goal.x() << ',' << tasks[i].goal.y() << ','
         << walkgen::to_string(r.end) << ',' << r.steps << ',' << r.reward << ','
         << (o.obstacles > 0 ? out.clearance[i] : 0.0) << ','
         << (o.obstacles > 0 ? out.end_clearance[i] : 0.0) << ',' << out.end_speed[i] << ','
         << out.conflict[i] << '\n';
  }
  std::printf(
      "test mode (policy mean) on %d held-out goals: %d reached (%d of %d behind the "
      "robot), %d QP failures, %d with a footstep inside an obstacle (a collision)\n",
      o.test_goals, out.reached, behind_reached, behind, failed, inside);
  // Figure 11.19: four goals, CoM paths and footsteps.
  std::ofstream traj(o.out + "/trajectories_" + env_name(o) + ".csv");
  traj << "case,tick,com_x,com_y,heading,foot_x,foot_y,foot_q,goal_x,goal_y,v_x,omega\n";
  std::ofstream obst(o.out + "/obstacles_" + env_name(o) + ".csv");
  obst << "case,x,y,radius,margin\n";
  const double goals[4][2] = {{1.5, 0.0}, {0.5, 1.2}, {-1.2, 0.6}, {-1.0, -1.0}};
  Env env(env_settings, 31337);
  for (int c = 0; c < 4; ++c) {
    walkgen::NmpcGoalTask task = env.sample_task();
    task.goal = Eigen::Vector2d(goals[c][0], goals[c][1]);
    for (auto& ob : task.obstacles) {  // in the way, halfway
      ob.x = 0.5 * task.goal.x() + (c % 2 == 0 ? 0.05 : -0.05);
      ob.y = 0.5 * task.goal.y();
      ob.radius = 0.15;
      obst << c << ',' << ob.x << ',' << ob.y << ',' << ob.radius << ',' << ob.margin << '\n';
    }
    env.reset(task);
    std::vector<float> obs(static_cast<std::size_t>(obs_size));
    float act[2];
    for (;;) {
      env.observe(obs.data());
      ppo.act(obs.data(), 1, true, act);
      const Eigen::Vector3d cmd = env.command_of(act);
      const auto r = env.step(act);
      const auto& st = env.mpc().state();
      traj << c << ',' << env.mpc().state().time << ',' << st.com_x[0] << ',' << st.com_y[0] << ','
           << st.heading() << ',' << st.support.x << ',' << st.support.y << ',' << st.support.q
           << ',' << task.goal.x() << ',' << task.goal.y() << ',' << cmd[0] << ',' << cmd[2]
           << '\n';
      if (r.done()) {
        std::printf("  trajectory %d: goal (%.1f, %.1f) %s after %.1f s\n", c, task.goal.x(),
                    task.goal.y(), walkgen::to_string(r.end), st.time);
        break;
      }
    }
  }
  return 0;
}

// With obstacles (beyond the thesis, docs/learning.md "With obstacles"): the robot's motion in
// the state, a success reward as large as the failure penalty (with the thesis's 100 a policy
// that stalls at an obstacle's edge or circles 0.25 m from the goal earned nearly as much as
// one that arrives), a step size annealed to 0 and longer training. Options given on the
// command line and in --config win.
void apply_obstacle_defaults(Options& o, const CLI::App& app) {
  if (o.env != "nmpc" || o.obstacles == 0) return;
  if (app.count("--observe-motion") == 0 && app.count("--no-observe-motion") == 0)
    o.observe_motion = true;
  if (app.count("--success-reward") == 0) o.success_reward = 1e4;
  if (app.count("--soft-obstacles") == 0) o.soft_obstacles = kSoftObstacles;
  o.cfg.ppo.anneal_learning_rate = true;  // before --config
  o.cfg.run.epochs = kObstacleEpochs;     // before --config and --epochs
}

// The thesis's settings of each environment (docs/learning.md), before --config and options.
walkgen::PpoConfig defaults_for(const std::string& env) {
  walkgen::PpoConfig c;
  if (env == "benchmark") {
    // §11.2.1: 16-32 ReLU, ε = 0.2, c1 = 0.5, minibatch 512, 8 epochs; an update every 4096
    // actions (8 × 512); 10 000 steps per epoch, rounded up to whole updates: 3, 12 288 steps.
    c.ppo = walkgen::point_goal_ppo_settings();
    c.run.epochs = 50;
    c.run.steps = 10000;
    c.run.rollout_steps = 512;
    c.run.threads = 1;  // the benchmark's step is cheaper than a thread hand-off
    c.run.evaluation_seed = 7777;
  } else {
    // §11.2.2: 64-64 tanh, ε = 0.2, c1 = 0.5, Adam; 8 × 256 steps per update, 4 per epoch.
    c.ppo = walkgen::nmpc_goal_ppo_settings();
    c.run.epochs = 30;
    c.run.steps = 8192;
    c.run.rollout_steps = 256;
    c.run.threads = 2;
    c.run.evaluation_seed = 900000;
  }
  return c;
}

std::string config_yaml(const walkgen::PpoConfig& c) {
  std::ostringstream y;
  const auto list = [](const std::vector<std::int64_t>& v) {
    std::string s = "[";
    for (std::size_t i = 0; i < v.size(); ++i) s += (i ? ", " : "") + std::to_string(v[i]);
    return s + "]";
  };
  y.precision(17);
  y << "# the settings of this run (examples/ppo_train --config reads this file back)\nppo:\n"
    << "  actor_hidden: " << list(c.ppo.actor_hidden)
    << "\n  critic_hidden: " << list(c.ppo.critic_hidden)
    << "\n  activation: " << walkgen::to_string(c.ppo.activation)
    << "\n  initial_std: " << c.ppo.initial_std << "\n  learning_rate: " << c.ppo.learning_rate
    << "\n  gamma: " << c.ppo.gamma << "\n  lambda: " << c.ppo.lambda << "\n  clip: " << c.ppo.clip
    << "\n  value_coef: " << c.ppo.value_coef << "\n  entropy_coef: " << c.ppo.entropy_coef
    << "\n  epochs: " << c.ppo.epochs << "\n  minibatch: " << c.ppo.minibatch
    << "\n  max_grad_norm: " << c.ppo.max_grad_norm << "\n  target_kl: " << c.ppo.target_kl
    << "\n  reward_scale: " << c.ppo.reward_scale
    << "\n  normalize_advantages: " << (c.ppo.normalize_advantages ? "true" : "false")
    << "\n  anneal_learning_rate: " << (c.ppo.anneal_learning_rate ? "true" : "false")
    << "\nrun:\n  epochs: " << c.run.epochs << "\n  steps: " << c.run.steps
    << "\n  envs: " << c.run.envs << "\n  rollout_steps: " << c.run.rollout_steps
    << "\n  threads: " << c.run.threads << "\n  seed: " << c.run.seed
    << "\n  validation_seed: " << c.run.validation_seed
    << "\n  evaluation_seed: " << c.run.evaluation_seed
    << "\n  checkpoint_every: " << c.run.checkpoint_every << "\n";
  return y.str();
}

}  // namespace

int main(int argc, char** argv) {
  Options o;
  walkgen::PpoRunSettings cli;  // values of the run options given on the command line
  CLI::App app{
      "Trains and tests PPO agents (walkgen::TorchPpo) in the benchmarking or the NMPC "
      "environment (thesis §11.2), on one process or data-parallel over several (c10d Gloo)",
      "ppo_train"};
  walkgen_examples::cli_defaults(app);
  app.add_option("env", o.env, "benchmark (§11.2.1) or nmpc (§11.2.2)")
      ->required()
      ->check(CLI::IsMember({"benchmark", "nmpc"}));
  app.add_option("--config", o.config,
                 "YAML file of PPO settings (ppo:) and the run (run:), see docs/learning.md; "
                 "options given here override it")
      ->check(CLI::ExistingFile);
  // The run's options: given on the command line, they override the defaults and --config.
  std::vector<std::function<void()>> overrides;
  const auto run_option = [&](const char* name, auto& cli_field, auto min, const std::string& help,
                              auto apply) {
    using T = std::decay_t<decltype(cli_field)>;
    CLI::Option* option =
        app.add_option(name, cli_field, help)
            ->transform(walkgen_examples::decimal_at_least<T>(static_cast<T>(min)))
            ->default_str("");
    overrides.push_back([option, apply] {
      if (option->count() > 0) apply();
    });
  };
  run_option("--epochs", cli.epochs, 1,
             "training epochs, >= 1 (default: benchmark 50, nmpc 30, "
             "with obstacles 200)",
             [&] { o.cfg.run.epochs = cli.epochs; });
  run_option("--steps", cli.steps, 1,
             "steps per epoch over all processes, >= 1, rounded up to whole updates (default: "
             "benchmark 10000, nmpc 8192)",
             [&] { o.cfg.run.steps = cli.steps; });
  run_option("--seed", cli.seed, 0,
             "seed of the weights, the environments, the exploration noise and the minibatch "
             "order (default 1)",
             [&] { o.cfg.run.seed = cli.seed; });
  app.add_option("--out", o.out, "folder of the CSV files, the policy and the checkpoint");
  run_option("--envs", cli.envs, 1,
             "environments over all processes, a multiple of --world-size (default 8)",
             [&] { o.cfg.run.envs = cli.envs; });
  run_option("--threads", cli.threads, 1,
             "threads that step a process's environments (default: benchmark 1, nmpc 2)",
             [&] { o.cfg.run.threads = cli.threads; });
  app.add_option("--obstacles", o.obstacles, "nmpc: circular obstacles per episode, >= 0")
      ->transform(walkgen_examples::decimal_at_least<int>(0));
  app.add_flag("--observe-motion,!--no-observe-motion", o.observe_motion,
               "nmpc: the state adds the robot's motion (CoM velocity, command, support foot, "
               "step phase; NmpcGoalSettings::observe_motion; default: on with obstacles)");
  app.add_option("--obstacle-weight", o.obstacle_weight,
                 "nmpc: weight of the shaping term near obstacles, >= 0 "
                 "(NmpcGoalSettings::obstacle_weight; default 0)")
      ->check(CLI::NonNegativeNumber);
  app.add_option("--soft-obstacles", o.soft_obstacles,
                 "nmpc: exact-penalty weight of the NMPC's soft obstacle rows, >= 0 "
                 "(WalkingSettings::soft.obstacles; 0: hard, an infeasible QP fails; default 0, "
                 "with obstacles 1e4)")
      ->check(CLI::NonNegativeNumber);
  app.add_option("--success-reward", o.success_reward,
                 "nmpc: reward for reaching the goal (NmpcGoalSettings::success_reward; "
                 "default: 100 as the thesis, 10000 with obstacles)")
      ->check(CLI::NonNegativeNumber);
  run_option("--checkpoint-every", cli.checkpoint_every, 0,
             "epochs between checkpoints, 0: none (default 1)",
             [&] { o.cfg.run.checkpoint_every = cli.checkpoint_every; });
  app.add_flag("--resume", o.resume,
               "continue from <out>/checkpoint_<env>.pt (same settings): the result equals the "
               "uninterrupted run's");
  app.add_option("--stop-after", o.stop_after,
                 "stop after this many epochs of this invocation, as an interruption would "
                 "(0: run to the end)")
      ->transform(walkgen_examples::decimal_at_least<int>(0));
#if WALKGEN_HAS_DISTRIBUTED
  try {  // torchrun's variables give the defaults
    const walkgen::DistributedSettings d = walkgen::distributed_settings_from_environment();
    o.world_size = d.world_size;
    o.rank = d.rank;
    o.master_addr = d.master_addr;
    o.master_port = d.master_port;
  } catch (const std::exception& e) {
    std::cerr << "ppo_train: " << e.what() << '\n';
    return 2;
  }
  app.add_option("--world-size", o.world_size,
                 "processes of a data-parallel run (c10d Gloo; default: $WORLD_SIZE, else 1)")
      ->transform(walkgen_examples::decimal_at_least<int>(1));
  app.add_option("--rank", o.rank, "this process, 0 ... world size - 1 (default: $RANK, else 0)")
      ->transform(walkgen_examples::decimal_at_least<int>(0));
  app.add_option("--master-addr", o.master_addr,
                 "where the processes meet: rank 0's address (default: $MASTER_ADDR, else "
                 "127.0.0.1)");
  app.add_option("--master-port", o.master_port,
                 "rank 0's TCP port for the meeting, 1 ... 65535 (default: $MASTER_PORT, else "
                 "29500); rank 0 listens on it on every interface")
      ->transform(walkgen_examples::decimal_at_least<int>(1))
      ->check(CLI::Range(1, 65535));
#else
  if (const char* world = std::getenv("WORLD_SIZE"); world != nullptr && std::atoi(world) > 1) {
    std::cerr << "ppo_train: WORLD_SIZE=" << world
              << " asks for a distributed run, but this build has no c10d Gloo (install "
                 "libgloo-dev and configure again)\n";
    return 2;
  }
#endif
  app.add_option("--policy", o.policy,
                 "test this saved policy instead of training one (default: none)")
      ->check(CLI::ExistingFile);
  app.add_option("--test-runs", o.test_runs, "benchmark: test runs of 10000 steps, >= 1")
      ->transform(walkgen_examples::decimal_at_least<int>(1));
  app.add_option("--test-goals", o.test_goals, "nmpc: held-out test goals, >= 1")
      ->transform(walkgen_examples::decimal_at_least<int>(1));
  app.add_flag("--plot", o.plot, "draw the PNGs (python/plot_learning.py)");
  app.add_flag("--quiet", o.quiet, "no progress output");
  WALKGEN_CLI_PARSE(app, argc, argv);
  std::setvbuf(stdout, nullptr, _IOLBF, 0);  // progress lines also when piped to a file
  torch::set_num_threads(1);  // small networks: intra-op threads cost more than they give
  int rc = 0;
  try {
    o.cfg = defaults_for(o.env);
    apply_obstacle_defaults(o, app);
    if (!o.config.empty()) o.cfg = walkgen::load_ppo_config(o.config, o.cfg);
    for (const auto& apply : overrides) apply();
    walkgen::validate(o.cfg.run);
    walkgen::check_argument(o.rank < o.world_size, "--rank",
                            "a rank below the world size " + std::to_string(o.world_size), o.rank);
    (void)local_envs(o);  // --envs splits over the processes: checked before they meet
    std::filesystem::create_directories(o.out);
#if WALKGEN_HAS_DISTRIBUTED
    std::unique_ptr<walkgen::TorchGlooCommunicator> group;
    if (o.world_size > 1 && o.policy.empty()) {
      walkgen::DistributedSettings d;
      d.rank = o.rank;
      d.world_size = o.world_size;
      d.master_addr = o.master_addr;
      d.master_port = o.master_port;
      group = std::make_unique<walkgen::TorchGlooCommunicator>(d);
      o.communicator = group.get();
    }
#endif
    {
      walkgen::PpoConfig resumable = o.cfg;  // what a resumed run must share with its checkpoint
      resumable.run.epochs = 1;
      resumable.run.threads = 1;
      resumable.run.checkpoint_every = 0;
      const std::string key = env_key(o) + config_yaml(resumable);
      o.settings_hash = walkgen::text_hash(key.data(), key.size());
    }
#if WALKGEN_HAS_DISTRIBUTED
    if (o.communicator != nullptr) {  // the same settings everywhere, or every rank stops here
      const std::string all = env_key(o) + config_yaml(o.cfg) + (o.resume ? "resume" : "") +
                              std::to_string(o.stop_after);
      walkgen::check_same_on_all_processes(*o.communicator,
                                           walkgen::text_hash(all.data(), all.size()),
                                           "settings (command line and --config)");
    }
#endif
    if (o.lead() && o.policy.empty()) {
      const std::string path = o.out + "/config_" + env_name(o) + ".yaml";
      write_text(path, "# environment: ppo_train " + env_key(o) + config_yaml(o.cfg));
    }
    rc = o.env == "benchmark" ? run_benchmark(o) : run_nmpc(o);
  } catch (const std::exception& e) {
    std::cerr << "ppo_train: " << e.what() << '\n';
    return 1;
  }
  if (o.plot && o.lead()) {
    const std::string cmd =
        "/usr/bin/python3 " +
        walkgen_examples::shell_quote(WALKGEN_SOURCE_DIR "/python/plot_learning.py") + " " +
        walkgen_examples::shell_quote(o.out) + " " + env_name(o);
    if (std::system(cmd.c_str()) != 0) {
      std::cerr << "ppo_train: plotting failed: " << cmd << '\n';
      return 1;
    }
  }
  return rc;
}
