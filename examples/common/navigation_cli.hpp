// Command-line options over walkgen's navigation rooms (thesis §11.1), shared by the programs that
// record, evaluate or teleoperate in them.
#pragma once

#include <string>
#include <vector>

#include "common/cli.hpp"
#include "walkgen/mujoco/navigation_scene.hpp"

namespace walkgen_examples {

/// "straight", "curved", ...: every walkgen::NavigationTask's name.
inline std::vector<std::string> navigation_task_names() {
  std::vector<std::string> names;
  for (walkgen::NavigationTask t : walkgen::all_navigation_tasks()) {
    names.emplace_back(walkgen::to_string(t));
  }
  return names;
}

/// `--tasks a,b,...` (comma-separated, each name checked) into `tasks`, default: every task.
/// Read tasks() after parsing; CLI11 writes into this object, which therefore stays in place.
class NavigationTasksOption {
 public:
  NavigationTasksOption(const NavigationTasksOption&) = delete;
  NavigationTasksOption& operator=(const NavigationTasksOption&) = delete;

  explicit NavigationTasksOption(CLI::App& app) : names_(navigation_task_names()) {
    const std::vector<std::string> all = names_;
    app.add_option("--tasks", names_, "comma-separated room tasks")
        ->delimiter(',')
        ->allow_extra_args(false)
        ->check(CLI::IsMember(all))
        ->default_str(CLI::detail::join(all, ","));
  }

  /// The chosen tasks, in the order given.
  std::vector<walkgen::NavigationTask> tasks() const {
    std::vector<walkgen::NavigationTask> tasks;
    for (const std::string& name : names_) {
      tasks.push_back(walkgen::navigation_task_from_string(name));
    }
    return tasks;
  }

 private:
  std::vector<std::string> names_;
};

}  // namespace walkgen_examples
