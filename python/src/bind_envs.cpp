/// @file
/// The learning environments (walkgen/learning/): the benchmarking environment of thesis
/// §11.2.1 (PointGoalEnv) and the NMPC goal environment of §11.2.2 with obstacles
/// (NmpcGoalEnv<Eigen::Dynamic>, any horizon), one at a time and vectorised: N of them stepped
/// in C++ threads (walkgen/learning/step_pool.hpp) with the GIL released. The Gymnasium-shaped
/// classes users meet are in python/walkgen/envs.py; these are their engines (_core.*).

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "arrays.hpp"
#include "bindings.hpp"
#include "walkgen/learning/environment.hpp"
#include "walkgen/learning/nmpc_environment.hpp"
#include "walkgen/learning/step_pool.hpp"

namespace walkgen::python {
namespace {

using NmpcEnv = NmpcGoalEnv<Eigen::Dynamic>;
using FloatArray = py::array_t<float, py::array::c_style>;

/// The action of one environment: `size` finite or non-finite floats (the environments clip
/// them to [−1, 1] and read a non-finite entry as 0).
std::vector<float> action_of(const py::handle& action, int size) {
  const VectorArg a(action, "action", size);
  std::vector<float> out(static_cast<std::size_t>(size));
  for (int i = 0; i < size; ++i) out[static_cast<std::size_t>(i)] = static_cast<float>(a.map()[i]);
  return out;
}

template <typename Env>
FloatArray observe(const Env& env) {
  FloatArray out(env.observation_size());
  env.observe(out.mutable_data());
  return out;
}

/// One step's outcome as a Python tuple (reward, end, message).
py::tuple step_tuple(const EnvStep& r) {
  return py::make_tuple(r.reward, r.end, std::string(r.message));
}

/// N environments of one kind, seeded seed, seed + 1, ... (reset() must follow construction);
/// step() steps all of them on a StepPool (the GIL released) and resets those whose episode ended
/// (same-step auto-reset: the observation returned for such an environment is the first of its new
/// episode, the last one of the old is in the final observations).
template <typename Env, typename Settings>
class VectorEnvCore {
 public:
  VectorEnvCore(const Settings& settings, long long num_envs, std::uint64_t seed,
                long long threads) {
    check_argument(num_envs >= 1 && num_envs <= 4096, "VectorEnv: num_envs", "1 to 4096", num_envs);
    check_argument(threads >= 0 && threads <= 256, "VectorEnv: threads", "0 (one per core) to 256",
                   threads);
    int t = static_cast<int>(threads);
    if (t == 0) t = static_cast<int>(std::max(1U, std::thread::hardware_concurrency()));
    t = std::min<int>(t, static_cast<int>(num_envs));
    for (long long i = 0; i < num_envs; ++i) {
      envs_.push_back(std::make_unique<Env>(settings));
      // Seeded after the constructor's reset(), so that the first reset() draws the seed's
      // first task, as NmpcGoalEnv(seed=s).reset() and reset(seed=s) do in envs.py.
      envs_.back()->seed(seed + static_cast<std::uint64_t>(i));
    }
    pool_ = std::make_unique<StepPool>(t);
    const auto n = static_cast<std::size_t>(num_envs);
    obs_size_ = envs_.front()->observation_size();
    act_size_ = envs_.front()->action_size();
    steps_.resize(n);
    actions_.resize(n * static_cast<std::size_t>(act_size_));
  }

  long long num_envs() const { return static_cast<long long>(envs_.size()); }
  int threads() const { return pool_->threads(); }
  int observation_size() const { return obs_size_; }
  int action_size() const { return act_size_; }
  Env& env(long long i) {
    check_argument(i >= 0 && i < num_envs(), "VectorEnv.env: index",
                   "0 to " + std::to_string(num_envs() - 1), i);
    return *envs_[static_cast<std::size_t>(i)];
  }

  /// Reseeds environment i with seed + i, then resets all; the first observations (N, obs).
  FloatArray reset(const std::optional<std::uint64_t>& seed) {
    FloatArray obs(std::vector<py::ssize_t>{num_envs(), obs_size_});
    float* out = obs.mutable_data();
    {
      py::gil_scoped_release release;
      pool_->run(static_cast<int>(envs_.size()), [&](int i) {
        Env& e = *envs_[static_cast<std::size_t>(i)];
        if (seed) e.seed(*seed + static_cast<std::uint64_t>(i));
        e.reset();
        e.observe(out + static_cast<std::ptrdiff_t>(i) * obs_size_);
      });
    }
    return obs;
  }

  /// Steps every environment with its row of `actions` (N, act).
  /// @returns (observations (N, obs), rewards (N,), ends (list), messages (list),
  ///           final observations (N, obs): the last one of each episode that ended, else 0)
  py::tuple step(const py::handle& actions) {
    const auto n = static_cast<Eigen::Index>(envs_.size());
    const MatrixArg a(actions, "actions", n, act_size_);
    const auto map = a.map(n, act_size_);
    for (Eigen::Index i = 0; i < n; ++i) {
      for (int j = 0; j < act_size_; ++j) {
        actions_[static_cast<std::size_t>(i * act_size_ + j)] = static_cast<float>(map(i, j));
      }
    }
    FloatArray obs(std::vector<py::ssize_t>{n, obs_size_});
    FloatArray final_obs(std::vector<py::ssize_t>{n, obs_size_});
    float* out = obs.mutable_data();
    float* final_out = final_obs.mutable_data();
    {
      py::gil_scoped_release release;
      pool_->run(static_cast<int>(n), [&](int i) {
        const auto k = static_cast<std::size_t>(i);
        Env& e = *envs_[k];
        const std::ptrdiff_t row = static_cast<std::ptrdiff_t>(i) * obs_size_;
        steps_[k] = e.step(actions_.data() + static_cast<std::ptrdiff_t>(i) * act_size_);
        std::fill(final_out + row, final_out + row + obs_size_, 0.0F);
        if (steps_[k].done()) {
          e.observe(final_out + row);
          e.reset();
        }
        e.observe(out + row);
      });
    }
    py::array_t<double> rewards(n);
    py::list ends, messages;
    for (std::size_t k = 0; k < envs_.size(); ++k) {
      rewards.mutable_data()[k] = steps_[k].reward;
      ends.append(steps_[k].end);
      messages.append(std::string(steps_[k].message));
    }
    return py::make_tuple(obs, rewards, ends, messages, final_obs);
  }

 private:
  std::vector<std::unique_ptr<Env>> envs_;
  std::unique_ptr<StepPool> pool_;
  int obs_size_ = 0, act_size_ = 0;
  std::vector<EnvStep> steps_;
  std::vector<float> actions_;
};

/// The methods both single environments share.
template <typename Env, typename Class>
void single_env_methods(Class& c) {
  c.def("seed", &Env::seed, py::arg("seed"),
        "Restarts the task generator; the next reset() draws the seed's first task.")
      .def("reset", py::overload_cast<>(&Env::reset), "A new random task.")
      .def("observe", &observe<Env>, "The observation (float32).")
      .def(
          "step",
          [](Env& env, const py::handle& action) {
            const std::vector<float> a = action_of(action, env.action_size());
            EnvStep r;
            {
              py::gil_scoped_release release;
              r = env.step(a.data());
            }
            return step_tuple(r);
          },
          py::arg("action"), "One step: (reward, end, message).")
      .def_property_readonly("observation_size", &Env::observation_size)
      .def_property_readonly("action_size", &Env::action_size)
      // copies: a reference would let Python change (or outlive) the environment's own
      .def_property_readonly("settings", [](const Env& env) { return env.settings(); });
}

template <typename Core>
void vector_env_methods(py::class_<Core>& c) {
  c.def_property_readonly("num_envs", &Core::num_envs)
      .def_property_readonly("threads", &Core::threads)
      .def_property_readonly("observation_size", &Core::observation_size)
      .def_property_readonly("action_size", &Core::action_size)
      .def("reset", &Core::reset, py::arg("seed") = py::none(),
           "Reseeds environment i with seed + i (when given), resets all: (N, obs) float32.")
      .def("step", &Core::step, py::arg("actions"),
           "(obs, rewards, ends, messages, final_obs); ended environments are reset.")
      .def("env", &Core::env, py::arg("index"), py::return_value_policy::reference_internal,
           "Environment `index` (for inspection).");
}

}  // namespace

void bind_envs(py::module_& m) {
  py::enum_<EpisodeEnd> end(m, "EpisodeEnd", "How an episode ended at a step.");
  end.value("none", EpisodeEnd::none)
      .value("success", EpisodeEnd::success)
      .value("failure", EpisodeEnd::failure)
      .value("truncated", EpisodeEnd::truncated);
  enum_as_string(end);

  py::class_<PointGoalSettings>(m, "PointGoalSettings",
                                "Settings of the benchmarking environment (thesis §11.2.1).")
      .def(py::init<>())
      .def_readwrite("step_size", &PointGoalSettings::step_size)
      .def_readwrite("win_radius", &PointGoalSettings::win_radius)
      .def_readwrite("lose_radius", &PointGoalSettings::lose_radius)
      .def_readwrite("goal_range", &PointGoalSettings::goal_range)
      .def_readwrite("integer_goals", &PointGoalSettings::integer_goals)
      .def_readwrite("max_steps", &PointGoalSettings::max_steps)
      .def_readwrite("win_reward", &PointGoalSettings::win_reward)
      .def_readwrite("lose_reward", &PointGoalSettings::lose_reward)
      .def("validate", [](const PointGoalSettings& s) { validate(s); })
      .def("copy", [](const PointGoalSettings& s) { return PointGoalSettings(s); });

  py::class_<NmpcGoalSettings>(m, "NmpcGoalSettings",
                               "Settings of the NMPC goal environment (thesis §11.2.2, with "
                               "obstacles).")
      .def(py::init<>())
      .def_readwrite("walking", &NmpcGoalSettings::walking)
      .def_readwrite("ticks_per_step", &NmpcGoalSettings::ticks_per_step)
      .def_readwrite("max_steps", &NmpcGoalSettings::max_steps)
      .def_readwrite("goal_min_distance", &NmpcGoalSettings::goal_min_distance)
      .def_readwrite("goal_max_distance", &NmpcGoalSettings::goal_max_distance)
      .def_readwrite("success_radius", &NmpcGoalSettings::success_radius)
      .def_readwrite("command_fraction", &NmpcGoalSettings::command_fraction)
      .def_readwrite("frontal_weight", &NmpcGoalSettings::frontal_weight)
      .def_readwrite("goal_weight", &NmpcGoalSettings::goal_weight)
      .def_readwrite("time_weight", &NmpcGoalSettings::time_weight)
      .def_readwrite("success_reward", &NmpcGoalSettings::success_reward)
      .def_readwrite("failure_reward", &NmpcGoalSettings::failure_reward)
      .def_readwrite("obstacles", &NmpcGoalSettings::obstacles)
      .def_readwrite("obstacle_min_radius", &NmpcGoalSettings::obstacle_min_radius)
      .def_readwrite("obstacle_max_radius", &NmpcGoalSettings::obstacle_max_radius)
      .def_readwrite("obstacle_margin", &NmpcGoalSettings::obstacle_margin)
      .def_readwrite("obstacle_lateral", &NmpcGoalSettings::obstacle_lateral)
      .def_readwrite("obstacle_clearance", &NmpcGoalSettings::obstacle_clearance)
      .def_readwrite("observe_motion", &NmpcGoalSettings::observe_motion)
      .def_readwrite("obstacle_weight", &NmpcGoalSettings::obstacle_weight)
      .def_readwrite("obstacle_shaping_distance", &NmpcGoalSettings::obstacle_shaping_distance)
      .def("validate", [](const NmpcGoalSettings& s) { validate(s); })
      .def("copy", [](const NmpcGoalSettings& s) { return NmpcGoalSettings(s); });

  py::class_<PointGoalEnv> point(m, "_PointGoalCore");
  point.def(py::init<const PointGoalSettings&, std::uint64_t>(), py::arg("settings"),
            py::arg("seed") = 0);
  single_env_methods<PointGoalEnv>(point);
  point
      .def(
          "reset_to",
          [](PointGoalEnv& env, const py::handle& goal) {
            env.reset(Eigen::Vector2d(VectorArg(goal, "goal", 2).map()));
          },
          py::arg("goal"))
      .def_property_readonly("agent", [](const PointGoalEnv& e) { return to_numpy(e.agent()); })
      .def_property_readonly("goal", [](const PointGoalEnv& e) { return to_numpy(e.goal()); });

  py::class_<NmpcEnv> nmpc(m, "_NmpcGoalCore");
  nmpc.def(py::init<const NmpcGoalSettings&, std::uint64_t>(), py::arg("settings"),
           py::arg("seed") = 0);
  single_env_methods<NmpcEnv>(nmpc);
  nmpc.def(
          "reset_to",
          [](NmpcEnv& env, const py::handle& goal, const std::vector<CircleObstacle<double>>& obs) {
            NmpcGoalTask task;
            task.goal = VectorArg(goal, "goal", 2).map();
            task.obstacles = obs;
            env.reset(task);
          },
          py::arg("goal"), py::arg("obstacles") = std::vector<CircleObstacle<double>>{})
      .def_property_readonly("position", [](const NmpcEnv& e) { return to_numpy(e.position()); })
      .def_property_readonly("heading", &NmpcEnv::heading)
      .def_property_readonly("distance", &NmpcEnv::distance)
      .def_property_readonly("goal", [](const NmpcEnv& e) { return to_numpy(e.goal()); })
      .def_property_readonly(
          "obstacles",
          [](const NmpcEnv& e) { return std::vector<CircleObstacle<double>>(e.obstacles()); })
      .def_property_readonly("min_obstacle_clearance", &NmpcEnv::min_obstacle_clearance)
      .def_property_readonly("steps", &NmpcEnv::steps)
      .def_property_readonly("ticks", &NmpcEnv::ticks)
      .def_property_readonly("time", [](const NmpcEnv& e) { return e.mpc().state().time; })
      .def("command_of",
           [](const NmpcEnv& env, const py::handle& action) {
             const std::vector<float> a = action_of(action, env.action_size());
             return to_numpy(env.command_of(a.data()));
           })
      .def_property_readonly("mpc", &NmpcEnv::mpc, py::return_value_policy::reference_internal,
                             "The environment's WalkingMpc (read it, do not step it).");

  using PointVector = VectorEnvCore<PointGoalEnv, PointGoalSettings>;
  py::class_<PointVector> pv(m, "_PointGoalVectorCore");
  pv.def(py::init<const PointGoalSettings&, long long, std::uint64_t, long long>(),
         py::arg("settings"), py::arg("num_envs"), py::arg("seed") = 0, py::arg("threads") = 0);
  vector_env_methods(pv);

  using NmpcVector = VectorEnvCore<NmpcEnv, NmpcGoalSettings>;
  py::class_<NmpcVector> nv(m, "_NmpcGoalVectorCore");
  nv.def(py::init<const NmpcGoalSettings&, long long, std::uint64_t, long long>(),
         py::arg("settings"), py::arg("num_envs"), py::arg("seed") = 0, py::arg("threads") = 0);
  vector_env_methods(nv);
}

}  // namespace walkgen::python
