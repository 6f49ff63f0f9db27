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
//   --epochs E      training epochs, >= 1 (default 50 for benchmark, 30 for nmpc)
//   --steps S       environment steps per epoch, >= 1 (default 10000 benchmark, 8192 nmpc)
//   --seed N        seed of the policy and the training environments (default 1)
//   --out DIR       output folder, created if missing (default .)
//   --envs K        environments stepped at once, >= 1 (default 8)
//   --threads T     nmpc: threads that step them, >= 1 (default 2)
//   --obstacles K   nmpc: circular obstacles per episode, >= 0 (default 0)
//   --policy FILE   test this saved policy (an existing file) instead of training
//   --test-runs R   benchmark: test runs of 10 000 steps, >= 1 (default 10)
//   --test-goals G  nmpc: held-out test goals, >= 1 (default 100)
//   --plot          draw the PNGs (python/plot_learning.py)
//   --quiet         no line per epoch
// A bad command line exits 2 with one line on stderr.
#include <torch/torch.h>

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
#include <string>
#include <type_traits>
#include <vector>

#include "common/cli.hpp"
#include "walkgen/learning/environment.hpp"
#include "walkgen/learning/nmpc_environment.hpp"
#include "walkgen/learning/step_pool.hpp"
#include "walkgen/torch/ppo.hpp"
#include "walkgen/torch/training.hpp"

namespace {

struct Options {
  std::string env;
  int epochs = -1;
  long steps = -1;
  std::uint64_t seed = 1;
  std::string out = ".";
  int envs = 8;
  int threads = 2;
  int obstacles = 0;
  std::string policy;
  int test_runs = 10;
  int test_goals = 100;
  bool plot = false;
  bool quiet = false;
};

std::string env_name(const Options& o) {
  return o.env == "nmpc" && o.obstacles > 0 ? "nmpc_obstacles" : o.env;
}

// Trains for o.epochs epochs of o.steps steps; writes the CSV log. With a `validate` score
// (higher is better, e.g. test-mode wins on a validation environment), the policy of the best
// epoch is kept (the thesis also kept its best network); otherwise the last one. Saves it
// (TorchPpo::save replaces the file atomically: a crash mid-save leaves the previous policy).
template <class Env>
void train(walkgen::TorchPpo& ppo, std::vector<Env>& envs, int rollout_steps,
           walkgen::StepPool& pool, const Options& o, const std::string& policy_path,
           const std::function<double()>& validate = nullptr) {
  walkgen::PpoTrainer<Env> trainer(ppo, envs, rollout_steps, &pool);
  const std::string csv = o.out + "/learning_" + env_name(o) + ".csv";
  std::ofstream log(csv);
  log << "epoch,steps,mean_reward,mean_return,episodes,wins,losses,truncations,std,seconds,"
         "policy_loss,value_loss,entropy,approx_kl,clip_fraction\n";
  double total = 0.0, best = -1e300;
  int best_epoch = 0;
  for (int e = 0; e < o.epochs; ++e) {
    const walkgen::PpoEpoch ep = trainer.run_epoch(o.steps);
    total += ep.seconds;
    const double score = validate ? validate() : 0.0;
    if (!validate || score >= best) {
      best = score;
      best_epoch = ep.epoch;
      ppo.save(policy_path);
    }
    log << ep.epoch << ',' << ep.steps << ',' << ep.mean_reward << ',' << ep.mean_return << ','
        << ep.episodes << ',' << ep.wins << ',' << ep.losses << ',' << ep.truncations << ','
        << ep.std << ',' << ep.seconds << ',' << ep.update.policy_loss << ','
        << ep.update.value_loss << ',' << ep.update.entropy << ',' << ep.update.approx_kl << ','
        << ep.update.clip_fraction << '\n';
    log.flush();
    if (!o.quiet)
      std::printf(
          "epoch %3d/%d  mean reward %9.4f  return %9.2f  wins %4d  losses %3d  "
          "timeouts %3d  std %.3f  %.1f s\n",
          ep.epoch, o.epochs, ep.mean_reward, ep.mean_return, ep.wins, ep.losses, ep.truncations,
          ep.std, ep.seconds);
  }
  std::printf("trained %s: %d epochs in %.1f s, log %s, policy of epoch %d saved to %s\n",
              env_name(o).c_str(), o.epochs, total, csv.c_str(), best_epoch, policy_path.c_str());
  ppo.load_parameters(policy_path);
}

int run_benchmark(const Options& o) {
  // Thesis §11.2.1: actor and critic 16-32 ReLU, tanh mean, ε = 0.2, c1 = 0.5; 10 000 steps per
  // epoch, an update every 4096 actions, minibatch 512, 8 epochs; Adam.
  walkgen::PpoSettings s = walkgen::point_goal_ppo_settings();
  s.seed = o.seed;
  walkgen::PointGoalSettings env_settings;  // test mode: no step budget (the thesis)
  walkgen::PointGoalSettings train_settings = env_settings;
  train_settings.max_steps = 200;
  const int epochs = o.epochs > 0 ? o.epochs : 50;
  Options opt = o;
  opt.epochs = epochs;
  opt.steps = o.steps > 0 ? o.steps : 10000;
  const int E = std::max(1, o.envs);
  walkgen::TorchPpo ppo =
      o.policy.empty() ? walkgen::TorchPpo(4, 2, s) : walkgen::TorchPpo::load(o.policy, s);
  if (o.policy.empty()) {
    std::vector<walkgen::PointGoalEnv> envs;
    for (int e = 0; e < E; ++e) envs.emplace_back(train_settings, o.seed * 1000 + e);
    walkgen::StepPool pool(1);  // the benchmark's step is cheaper than a thread hand-off
    // Validation: test mode (policy mean) for 2000 steps on goals apart from the test's.
    walkgen::PointGoalSettings validation_settings = env_settings;
    validation_settings.max_steps = 200;
    const auto validate = [&]() {
      walkgen::PointGoalEnv env(validation_settings, 555);
      const auto t = walkgen::evaluate_steps(ppo, env, 2000);
      return double(t.wins) - 10.0 * t.losses - t.truncations;
    };
    train(ppo, envs, std::max(1, 4096 / E), pool, opt, o.out + "/ppo_benchmark.pt", validate);
  }
  // Test mode: the policy mean, R runs of 10 000 steps.
  std::ofstream test(o.out + "/test_benchmark.csv");
  test << "run,steps,wins,losses,mean_reward\n";
  double wins = 0, wins_sq = 0;
  int losses = 0;
  for (int r = 0; r < o.test_runs; ++r) {
    walkgen::PointGoalEnv env(env_settings, 7777 + r);
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

int run_nmpc(const Options& o) {
  // Thesis §11.2.2: 64-64 tanh networks, ε = 0.2, c1 = 0.5, Adam; minibatches over a rollout.
  walkgen::PpoSettings s = walkgen::nmpc_goal_ppo_settings();
  s.seed = o.seed;
  walkgen::NmpcGoalSettings env_settings;
  env_settings.obstacles = o.obstacles;
  if (o.obstacles > 0) {
    env_settings.goal_min_distance = 1.0;
    env_settings.goal_max_distance = 2.0;
  }
  Options opt = o;
  opt.epochs = o.epochs > 0 ? o.epochs : 30;
  opt.steps = o.steps > 0 ? o.steps : 8192;
  const int E = std::max(1, o.envs);
  using Env = walkgen::NmpcGoalEnv<16>;
  walkgen::StepPool pool(std::max(1, o.threads));
  const int obs_size = 2 + 3 * o.obstacles;
  walkgen::TorchPpo ppo =
      o.policy.empty() ? walkgen::TorchPpo(obs_size, 2, s) : walkgen::TorchPpo::load(o.policy, s);
  if (o.policy.empty()) {
    std::vector<Env> envs;
    envs.reserve(E);
    for (int e = 0; e < E; ++e) envs.emplace_back(env_settings, o.seed * 1000 + e);
    train(ppo, envs, 256, pool, opt, o.out + "/ppo_" + env_name(o) + ".pt");
  }
  // Held-out goals: drawn by an environment seeded apart from the training ones.
  std::vector<Env> envs;
  envs.reserve(E);
  for (int e = 0; e < E; ++e) envs.emplace_back(env_settings, 900000 + e);
  std::vector<walkgen::NmpcGoalTask> tasks;
  for (int g = 0; g < o.test_goals; ++g) tasks.push_back(envs[0].sample_task());
  std::vector<double> clearance(tasks.size(), 0.0);
  const auto results = walkgen::evaluate_tasks<Env, walkgen::NmpcGoalTask>(
      ppo, envs, tasks, &pool,
      [&](std::size_t i, const Env& env) { clearance[i] = env.min_obstacle_clearance(); });
  int reached = 0, failed = 0, inside = 0, behind = 0, behind_reached = 0;
  std::ofstream test(o.out + "/test_" + env_name(o) + ".csv");
  test << "goal,goal_x,goal_y,end,steps,reward,min_clearance\n";
  for (std::size_t i = 0; i < tasks.size(); ++i) {
    const auto& r = results[i];
    const bool in = o.obstacles > 0 && clearance[i] < 0.0;
    const bool ok = r.end == walkgen::EpisodeEnd::success && !in;
    reached += ok;
    failed += r.end == walkgen::EpisodeEnd::failure;
    inside += in;
    if (tasks[i].goal.x() < 0.0) {
      ++behind;
      behind_reached += ok;
    }
    test << i << ',' << tasks[i].goal.x() << ',' << tasks[i].goal.y() << ','
         << walkgen::to_string(r.end) << ',' << r.steps << ',' << r.reward << ','
         << (o.obstacles > 0 ? clearance[i] : 0.0) << '\n';
  }
  std::printf(
      "test mode (policy mean) on %d held-out goals: %d reached (%d of %d behind the "
      "robot), %d QP failures, %d with a footstep inside an obstacle\n",
      o.test_goals, reached, behind_reached, behind, failed, inside);
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
    std::vector<float> obs(static_cast<std::size_t>(obs_size));  // 2 + 3 per obstacle
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

}  // namespace

int main(int argc, char** argv) {
  Options o;
  CLI::App app{
      "Trains and tests PPO agents (walkgen::TorchPpo) in the benchmarking or the NMPC "
      "environment (thesis §11.2)",
      "ppo_train"};
  walkgen_examples::cli_defaults(app);
  app.add_option("env", o.env, "benchmark (§11.2.1) or nmpc (§11.2.2)")
      ->required()
      ->check(CLI::IsMember({"benchmark", "nmpc"}));
  app.add_option("--epochs", o.epochs, "training epochs, >= 1 (default: benchmark 50, nmpc 30)")
      ->transform(walkgen_examples::decimal_at_least<int>(1))
      ->default_str("");
  app.add_option("--steps", o.steps, "steps per epoch, >= 1 (default: benchmark 10000, nmpc 8192)")
      ->transform(walkgen_examples::decimal_at_least<long>(1))
      ->default_str("");
  app.add_option("--seed", o.seed, "seed of the policy and the training environments")
      ->transform(walkgen_examples::decimal_at_least<std::uint64_t>(0));
  app.add_option("--out", o.out, "folder of the CSV files and the policy (ppo_<env>.pt)");
  app.add_option("--envs", o.envs, "environments stepped at once, >= 1")
      ->transform(walkgen_examples::decimal_at_least<int>(1));
  app.add_option("--threads", o.threads, "nmpc: threads that step the environments, >= 1")
      ->transform(walkgen_examples::decimal_at_least<int>(1));
  app.add_option("--obstacles", o.obstacles, "nmpc: circular obstacles per episode, >= 0")
      ->transform(walkgen_examples::decimal_at_least<int>(0));
  app.add_option("--policy", o.policy,
                 "test this saved policy instead of training one (default: none)")
      ->check(CLI::ExistingFile);
  app.add_option("--test-runs", o.test_runs, "benchmark: test runs of 10000 steps, >= 1")
      ->transform(walkgen_examples::decimal_at_least<int>(1));
  app.add_option("--test-goals", o.test_goals, "nmpc: held-out test goals, >= 1")
      ->transform(walkgen_examples::decimal_at_least<int>(1));
  app.add_flag("--plot", o.plot, "draw the PNGs (python/plot_learning.py)");
  app.add_flag("--quiet", o.quiet, "no line per epoch");
  WALKGEN_CLI_PARSE(app, argc, argv);
  std::setvbuf(stdout, nullptr, _IOLBF, 0);  // progress lines also when piped to a file
  torch::set_num_threads(1);  // small networks: intra-op threads cost more than they give
  int rc = 0;
  try {
    std::filesystem::create_directories(o.out);
    rc = o.env == "benchmark" ? run_benchmark(o) : run_nmpc(o);
  } catch (const std::exception& e) {
    std::cerr << "ppo_train: " << e.what() << '\n';
    return 1;
  }
  if (o.plot) {
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
