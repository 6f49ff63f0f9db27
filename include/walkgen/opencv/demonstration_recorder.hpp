#pragma once
/// @file
/// Recording demonstrations for behavioural cloning (thesis §7.1.2, figure 7.2): per sample the
/// left camera's RGB image, the confidence-weighted WLS disparity of the stereo pair (§3.1) and
/// the velocity command, stored in a folder with an index text file that lists the image files
/// and the commands. OpenCV adapter (walkgen::opencv): images are written as PNG.
///
/// Folder layout:
///
///     <folder>/index.txt            one line per sample, see below
///     <folder>/rgb/<name>.png       8-bit RGB, as the camera delivered it
///     <folder>/disparity/<name>.png 16-bit grey: disparity [px] × 16, 0 where unknown
///
/// index.txt starts with a comment line (#) naming the columns, then per sample, separated by
/// single spaces: rgb path, disparity path (both relative to the folder), episode name, time [s],
/// v_x [m/s], v_y [m/s], ω_z [rad/s]. Several recorders (episodes) may append to one folder, each
/// under its own episode name: a name that the folder already holds (in index.txt or as image
/// files) is refused, since recording it again would overwrite its images and list them twice.

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <Eigen/Core>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "walkgen/core/exceptions.hpp"
#include "walkgen/robot/robot.hpp"

namespace walkgen {

/// One line of a demonstration index.
struct DemonstrationEntry {
  std::string rgb, disparity;  ///< paths relative to the folder
  std::string episode;
  double time = 0.0;                                  ///< [s] within the episode
  Eigen::Vector3d command = Eigen::Vector3d::Zero();  ///< v_x, v_y, ω_z
};

/// Writes samples of one episode into a demonstration folder.
class DemonstrationRecorder {
 public:
  /// Creates <folder>, its rgb/ and disparity/ subfolders and index.txt when missing, and
  /// appends to index.txt.
  /// @throws walkgen::invalid_argument when the episode name is empty or has characters other
  ///   than letters, digits, '_' and '-', when the folder already holds the episode (index.txt
  ///   lists it, or rgb/ or disparity/ holds an image <episode>_<digits>.png; nothing is then
  ///   changed), or when the folder cannot be written.
  DemonstrationRecorder(const std::string& folder, const std::string& episode)
      : folder_(folder), episode_(episode) {
    bool ok = !episode.empty();
    for (char c : episode) {
      ok = ok && (std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-');
    }
    check_argument(ok, "DemonstrationRecorder: episode", "letters, digits, '_' or '-'",
                   "'" + episode + "'");
    check_episode_is_new();
    std::error_code ec;
    std::filesystem::create_directories(folder_ + "/rgb", ec);
    std::filesystem::create_directories(folder_ + "/disparity", ec);
    const std::string index = folder_ + "/index.txt";
    const bool fresh = !std::filesystem::exists(index);
    index_.open(index, std::ios::app);
    check_argument(index_.good() && std::filesystem::is_directory(folder_ + "/rgb"),
                   "DemonstrationRecorder: folder", "a writable folder", "'" + folder_ + "'");
    if (fresh) index_ << "# rgb disparity episode time v_x v_y omega" << std::endl;
    index_.precision(9);
  }

  /// Adds one sample: `left` is the left camera's RGB image (CameraImage::rgb), `disparity`
  /// the WLS disparity [px] of the pair (CV_32F, ≤ 0 unknown, the image's size).
  /// @throws walkgen::invalid_argument for an empty image, mismatched sizes, a non-finite time or
  ///   command, or a file that cannot be written.
  void record(double time, const CameraImage& left, const cv::Mat& disparity,
              const Eigen::Vector3d& command) {
    check_argument(left.width > 0 && left.height > 0 &&
                       left.rgb.size() == std::size_t(left.width) * std::size_t(left.height) * 3,
                   "DemonstrationRecorder::record: left image", "a non-empty RGB image",
                   "an empty or inconsistent one");
    check_argument(
        disparity.type() == CV_32F && disparity.cols == left.width && disparity.rows == left.height,
        "DemonstrationRecorder::record: disparity",
        "CV_32F of the image's size " + std::to_string(left.width) + "x" +
            std::to_string(left.height),
        std::to_string(disparity.cols) + "x" + std::to_string(disparity.rows));
    check_argument(std::isfinite(time) && command.allFinite(), "DemonstrationRecorder::record",
                   "a finite time and command", "NaN or inf");
    char name[64];
    std::snprintf(name, sizeof(name), "%06ld", count_);
    const std::string stem = episode_ + "_" + name + ".png";
    const cv::Mat rgb(left.height, left.width, CV_8UC3, const_cast<std::uint8_t*>(left.rgb.data()));
    cv::cvtColor(rgb, bgr_, cv::COLOR_RGB2BGR);  // imwrite expects BGR
    disparity.convertTo(fixed_, CV_16U, 16.0);   // negative (unknown) saturates to 0
    const std::string rgb_path = "rgb/" + stem, disparity_path = "disparity/" + stem;
    check_argument(cv::imwrite(folder_ + "/" + rgb_path, bgr_) &&
                       cv::imwrite(folder_ + "/" + disparity_path, fixed_),
                   "DemonstrationRecorder::record", "writable image files",
                   "'" + folder_ + "/" + rgb_path + "'");
    index_ << rgb_path << ' ' << disparity_path << ' ' << episode_ << ' ' << time << ' '
           << command.x() << ' ' << command.y() << ' ' << command.z() << '\n';
    index_.flush();
    ++count_;
  }

  long samples() const { return count_; }
  const std::string& folder() const { return folder_; }

 private:
  /// Throws when index.txt lists the episode or an image of it exists (before anything is
  /// created or opened, so that a refused recorder changes nothing).
  void check_episode_is_new() const {
    const std::string where = "DemonstrationRecorder: episode '" + episode_ + "'";
    const std::string expected = "an episode name not yet in '" + folder_ + "'";
    const char* hint =
        "choose another episode name (e.g. another seed) or folder; to record the episode "
        "again, first delete its lines from index.txt and its images";
    std::ifstream index(folder_ + "/index.txt");
    std::string line;
    for (int number = 1; std::getline(index, line); ++number) {
      if (line.empty() || line[0] == '#') continue;
      std::istringstream fields(line);
      std::string rgb, disparity, episode;
      fields >> rgb >> disparity >> episode;
      check_argument(episode != episode_, where.c_str(), expected,
                     "index.txt line " + std::to_string(number) + " listing it", hint);
    }
    for (const char* sub : {"rgb", "disparity"}) {
      std::string first;  // the lowest name: the message does not depend on the listing order
      std::error_code ec;
      for (std::filesystem::directory_iterator it(folder_ + "/" + sub, ec), end; !ec && it != end;
           it.increment(ec)) {
        const std::string name = it->path().filename().string();
        if (is_episode_image(name) && (first.empty() || name < first)) first = name;
      }
      check_argument(first.empty(), where.c_str(), expected,
                     std::string("its image ") + sub + "/" + first, hint);
    }
  }
  /// <episode>_<digits>.png, the names record() writes.
  bool is_episode_image(const std::string& name) const {
    const std::string prefix = episode_ + "_", suffix = ".png";
    if (name.size() <= prefix.size() + suffix.size() ||
        name.compare(0, prefix.size(), prefix) != 0 ||
        name.compare(name.size() - suffix.size(), suffix.size(), suffix) != 0) {
      return false;
    }
    for (std::size_t i = prefix.size(); i < name.size() - suffix.size(); ++i) {
      if (!std::isdigit(static_cast<unsigned char>(name[i]))) return false;
    }
    return true;
  }

  std::string folder_, episode_;
  std::ofstream index_;
  long count_ = 0;
  cv::Mat bgr_, fixed_;
};

/// Reads <folder>/index.txt.
/// @throws walkgen::invalid_argument when the file is missing or a line is malformed (naming
///   the line).
[[nodiscard]] inline std::vector<DemonstrationEntry> read_demonstration_index(
    const std::string& folder) {
  const std::string path = folder + "/index.txt";
  std::ifstream in(path);
  check_argument(in.good(), "read_demonstration_index", "a readable index.txt",
                 "'" + path + "' (missing)");
  std::vector<DemonstrationEntry> entries;
  std::string line;
  int number = 0;
  while (std::getline(in, line)) {
    ++number;
    if (line.empty() || line[0] == '#') continue;
    std::istringstream fields(line);
    DemonstrationEntry e;
    fields >> e.rgb >> e.disparity >> e.episode >> e.time >> e.command.x() >> e.command.y() >>
        e.command.z();
    std::string extra;
    const bool ok =
        !fields.fail() && !(fields >> extra) && std::isfinite(e.time) && e.command.allFinite();
    check_argument(ok, ("read_demonstration_index: " + path + ":" + std::to_string(number)).c_str(),
                   "rgb disparity episode time v_x v_y omega", "'" + line + "'");
    entries.push_back(e);
  }
  return entries;
}

}  // namespace walkgen
