#pragma once
/// @file
/// Replacing a file so that a reader finds the old file or the new one, never a partial one
/// (issue 21): the new content goes to a temporary file in the target's folder, which is then
/// renamed over the target. Used wherever walkgen writes a file that a later run reads (stereo
/// calibrations, policies). Standard library only (C++17 std::filesystem).
///
/// @code
///   walkgen::write_atomically("stereo.yml", [&](const std::string& temp) {
///     std::ofstream out(temp);   // write everything to `temp`, close it, throw on failure
///     ...
///   });
/// @endcode
///
/// Guarantees and limits:
/// - A writer that throws, or a process that stops before the rename (a crash, a kill, a full
///   disk the writer reports), leaves the target as it was. std::filesystem::rename is POSIX
///   rename(2): it replaces the target in one step, within one file system (hence the same
///   folder).
/// - A crash during the writer can leave its temporary file, `<stem>.tmp-<token><extension>`
///   next to the target (e.g. `stereo.tmp-3f9a0c2e-0.yml`); such files may be deleted. The
///   extension is kept for writers that choose the format by it (cv::imwrite).
/// - Not durable against a power failure: the standard library cannot flush a file to the disk
///   (fsync). The new file gets the default permissions, not the old file's, and a symbolic
///   link at the target is replaced by the file, not followed.

#include <atomic>
#include <chrono>
#include <exception>
#include <filesystem>
#include <random>
#include <sstream>
#include <string>
#include <system_error>
#include <utility>

#include "walkgen/core/exceptions.hpp"

namespace walkgen {

namespace detail {

/// A token that differs between processes (random_device and clock) and between calls (a
/// counter): temporary names of concurrent writers do not collide.
inline std::string atomic_file_token() {
  static const unsigned long long process = [] {
    std::random_device device;
    const auto now = static_cast<unsigned long long>(
        std::chrono::steady_clock::now().time_since_epoch().count());
    return (static_cast<unsigned long long>(device()) << 32) ^ device() ^ now;
  }();
  static std::atomic<unsigned long long> counter{0};
  std::ostringstream token;
  token << std::hex << (process & 0xffffffffffull) << '-' << counter.fetch_add(1);
  return token.str();
}

}  // namespace detail

/// Writes the file `path` through a temporary file: calls `write_to(temp)`, which must write the
/// whole content to the file `temp` (in the same folder) and close it, then renames `temp` over
/// `path`. On any failure the temporary file is removed and `path` is left as it was.
/// @param write_to callable as `write_to(const std::string& temp_path)`; reports a failure by
///   throwing (walkgen::invalid_argument is passed on unchanged).
/// @throws walkgen::invalid_argument naming `path` when the path is empty or names a folder,
///   its folder is missing, the writer throws anything else (its message is kept), the writer
///   creates no file, or the rename fails (e.g. `path` is a folder).
template <typename Writer>
void write_atomically(const std::string& path, Writer&& write_to) {
  namespace fs = std::filesystem;
  constexpr const char* where = "walkgen::write_atomically";
  check_argument(!path.empty(), where, "a file path", "an empty string");
  const fs::path target(path);
  check_argument(target.has_filename() && target.filename() != "." && target.filename() != "..",
                 where, "a file path", "'" + path + "' (a folder)");
  const fs::path folder = target.parent_path();
  std::error_code ec;
  check_argument(folder.empty() || fs::is_directory(folder, ec), where,
                 "a file in an existing folder",
                 "'" + path + "' ('" + folder.string() + "' missing)");
  fs::path temp;
  for (int attempt = 0; attempt < 16; ++attempt) {  // another file of that name: unlikely
    temp = folder / (target.stem().string() + ".tmp-" + detail::atomic_file_token() +
                     target.extension().string());
    if (!fs::exists(fs::symlink_status(temp, ec))) break;
  }
  const std::string temp_path = temp.string();
  const auto discard = [&temp] {
    std::error_code ignored;
    fs::remove(temp, ignored);
  };
  try {
    std::forward<Writer>(write_to)(temp_path);
  } catch (const invalid_argument&) {
    discard();
    throw;
  } catch (const std::exception& e) {
    discard();
    throw invalid_argument(detail::expected_got(where, "'" + path + "' written",
                                                std::string("an error: ") + e.what(),
                                                "the previous file, if any, is unchanged"));
  } catch (...) {
    discard();
    throw;
  }
  if (!fs::is_regular_file(temp, ec)) {
    discard();
    throw invalid_argument(detail::expected_got(
        where, "the writer of '" + path + "' to create '" + temp_path + "'", "no file"));
  }
  fs::rename(temp, target, ec);
  if (ec) {
    discard();
    throw invalid_argument(detail::expected_got(
        where, "'" + temp_path + "' renamed over '" + path + "'", "an error: " + ec.message(),
        "the previous file, if any, is unchanged"));
  }
}

}  // namespace walkgen
