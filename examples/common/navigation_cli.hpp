// Command-line options over walkgen's navigation rooms (thesis §11.1), shared by the programs that
// record, evaluate or teleoperate in them.
#pragma once

#include <filesystem>
#include <fstream>
#include <string>
#include <utility>
#include <vector>

#include "common/cli.hpp"
#include "walkgen/mujoco/navigation_scene.hpp"
#include "walkgen/mujoco/scene_appearance.hpp"

namespace walkgen_examples {

/// The to_string() names of `values`.
template <class Enum>
std::vector<std::string> enum_names(const std::vector<Enum>& values) {
  std::vector<std::string> names;
  for (Enum v : values) names.emplace_back(to_string(v));
  return names;
}

/// "straight", "curved", ...: every walkgen::NavigationTask's name.
inline std::vector<std::string> navigation_task_names() {
  return enum_names(walkgen::all_navigation_tasks());
}

/// `FLAG a,b,...`: comma-separated names of enumerators of `all` (each checked), default
/// `defaults`. Read values() after parsing; CLI11 writes into this object, which therefore stays
/// in place.
template <class Enum>
class EnumListOption {
 public:
  EnumListOption(const EnumListOption&) = delete;
  EnumListOption& operator=(const EnumListOption&) = delete;

  EnumListOption(CLI::App& app, const std::string& flag, const std::string& description,
                 std::vector<Enum> all, const std::vector<Enum>& defaults)
      : all_(std::move(all)), names_(enum_names(defaults)) {
    app.add_option(flag, names_, description)
        ->delimiter(',')
        ->allow_extra_args(false)
        ->check(CLI::IsMember(enum_names(all_)))
        ->default_str(CLI::detail::join(names_, ","));
  }

  /// The chosen values, in the order given.
  std::vector<Enum> values() const {
    std::vector<Enum> values;
    for (const std::string& name : names_) {
      for (Enum v : all_) {
        if (name == to_string(v)) values.push_back(v);
      }
    }
    return values;
  }

 private:
  std::vector<Enum> all_;
  std::vector<std::string> names_;
};

/// `--tasks a,b,...` (comma-separated, each name checked), default: every task.
class NavigationTasksOption : public EnumListOption<walkgen::NavigationTask> {
 public:
  explicit NavigationTasksOption(CLI::App& app)
      : EnumListOption(app, "--tasks", "comma-separated room tasks",
                       walkgen::all_navigation_tasks(), walkgen::all_navigation_tasks()) {}

  /// The chosen tasks, in the order given.
  std::vector<walkgen::NavigationTask> tasks() const { return values(); }
};

/// FOLDER/appearance.csv: one row per room, its look (walkgen::appearance_csv_row()) after
/// the columns that name the room; appended to, the header written when the file is new.
class AppearanceLog {
 public:
  /// `columns`: the leading columns' names, comma-separated ("episode").
  /// @returns false (nothing opened) when the file cannot be written.
  bool open(const std::string& folder, const std::string& columns) {
    const std::string path = folder + "/appearance.csv";
    const bool fresh = !std::filesystem::exists(path);
    file_.open(path, std::ios::app);
    if (file_.good() && fresh) file_ << columns << ',' << walkgen::appearance_csv_header() << '\n';
    return file_.good();
  }
  bool is_open() const { return file_.is_open(); }

  /// A row: `leading` (the leading columns' values, comma-separated) and the look.
  void add(const std::string& leading, const walkgen::SceneAppearance& appearance) {
    file_ << leading << ',' << walkgen::appearance_csv_row(appearance) << '\n';
    file_.flush();
  }

 private:
  std::ofstream file_;
};

}  // namespace walkgen_examples
