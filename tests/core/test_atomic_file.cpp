// walkgen::write_atomically (issue 21, defect 7): a file is written to a temporary file in the
// target's folder and renamed over the target, so that a reader sees the old file or the new
// one, never a partial one; a writer that fails leaves the target as it was and no temporary
// file behind.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <set>
#include <stdexcept>
#include <string>

#include "support/expect_error.hpp"
#include "support/files.hpp"
#include "walkgen/core/atomic_file.hpp"

namespace {

namespace fs = std::filesystem;

using walkgen_test::fresh_folder;
std::string read(const fs::path& path) { return walkgen_test::read_bytes(path); }

void write(const fs::path& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}

std::set<std::string> listing(const fs::path& folder) {
  std::set<std::string> names;
  for (const auto& e : fs::directory_iterator(folder)) names.insert(e.path().filename().string());
  return names;
}

TEST(AtomicFile, WritesANewFileThroughATemporaryFileInTheSameFolder) {
  const fs::path folder = fresh_folder("walkgen_atomic_new");
  const fs::path target = folder / "calibration.yml";
  std::string temp;
  walkgen::write_atomically(target.string(), [&](const std::string& path) {
    temp = path;
    EXPECT_FALSE(fs::exists(target));  // nothing at the target while the writer runs
    write(path, "new\n");
  });
  EXPECT_EQ(read(target), "new\n");
  EXPECT_EQ(fs::path(temp).parent_path(), folder);  // same folder: rename, not a copy
  EXPECT_NE(fs::path(temp).filename(), target.filename());
  EXPECT_EQ(fs::path(temp).extension(), ".yml");  // writers that pick the format by extension
  EXPECT_EQ(listing(folder), (std::set<std::string>{"calibration.yml"}));
}

TEST(AtomicFile, ReplacesAnExistingFileAndUsesAFreshTemporaryNameEachTime) {
  const fs::path folder = fresh_folder("walkgen_atomic_replace");
  const fs::path target = folder / "policy.pt";
  write(target, "old");
  std::set<std::string> temps;
  for (int i = 0; i < 3; ++i) {
    walkgen::write_atomically(target.string(), [&](const std::string& path) {
      temps.insert(path);
      EXPECT_EQ(read(target), i == 0 ? "old" : "new " + std::to_string(i - 1));
      write(path, "new " + std::to_string(i));
    });
  }
  EXPECT_EQ(temps.size(), 3u);
  EXPECT_EQ(read(target), "new 2");
  EXPECT_EQ(listing(folder), (std::set<std::string>{"policy.pt"}));
}

TEST(AtomicFile, AWriterInterruptedHalfWayLeavesTheOldFileAndNoTemporaryFile) {
  const fs::path folder = fresh_folder("walkgen_atomic_interrupted");
  const fs::path target = folder / "calibration.yml";
  write(target, "old and complete\n");
  // A walkgen error is passed on unchanged.
  try {
    walkgen::write_atomically(target.string(), [&](const std::string& path) {
      write(path, "half of the ne");
      throw walkgen::invalid_argument("writer: expected something, got something else");
    });
    ADD_FAILURE() << "expected walkgen::invalid_argument";
  } catch (const walkgen::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()), "writer: expected something, got something else");
  }
  EXPECT_EQ(read(target), "old and complete\n");
  EXPECT_EQ(listing(folder), (std::set<std::string>{"calibration.yml"}));
  // Any other exception becomes a walkgen error naming the target and the cause.
  walkgen_test::expect_invalid_argument(
      [&] {
        walkgen::write_atomically(target.string(), [&](const std::string& path) {
          write(path, "half of the ne");
          throw std::runtime_error("disk full");
        });
      },
      {"walkgen::write_atomically", target.string(), "disk full"});
  EXPECT_EQ(read(target), "old and complete\n");
  EXPECT_EQ(listing(folder), (std::set<std::string>{"calibration.yml"}));
}

TEST(AtomicFile, FailuresAreWalkgenErrorsNamingThePath) {
  const fs::path folder = fresh_folder("walkgen_atomic_failures");
  const fs::path target = folder / "out.csv";
  write(target, "old");
  // A writer that writes nothing.
  walkgen_test::expect_invalid_argument(
      [&] { walkgen::write_atomically(target.string(), [](const std::string&) {}); },
      {target.string(), "no file"});
  EXPECT_EQ(read(target), "old");
  // A missing folder.
  const std::string nowhere = (folder / "no_such_folder" / "out.csv").string();
  walkgen_test::expect_invalid_argument(
      [&] { walkgen::write_atomically(nowhere, [](const std::string& p) { write(p, "x"); }); },
      {"walkgen::write_atomically", (folder / "no_such_folder").string(), "missing"});
  // A target that is a folder: the rename fails, the temporary file is removed.
  fs::create_directories(folder / "a_folder" / "inside");
  walkgen_test::expect_invalid_argument(
      [&] {
        walkgen::write_atomically((folder / "a_folder").string(),
                                  [](const std::string& p) { write(p, "x"); });
      },
      {(folder / "a_folder").string()});
  EXPECT_TRUE(fs::is_directory(folder / "a_folder" / "inside"));
  // An empty path.
  walkgen_test::expect_invalid_argument(
      [&] { walkgen::write_atomically("", [](const std::string& p) { write(p, "x"); }); },
      {"walkgen::write_atomically", "a file path"});
  EXPECT_EQ(listing(folder), (std::set<std::string>{"a_folder", "out.csv"}));
}

}  // namespace
