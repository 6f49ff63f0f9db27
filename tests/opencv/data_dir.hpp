#pragma once
// Where the OpenCV tests find the shared data (tests/opencv/CMakeLists.txt sets
// WALKGEN_TEST_DATA_DIR).
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

namespace walkgen::test {

/// WALKGEN_TEST_DATA_DIR/<sub>; fails the current test (it does not skip) when it does not exist.
inline std::string data_path(const std::string& sub) {
  const std::string path = std::string(WALKGEN_TEST_DATA_DIR) + "/" + sub;
  EXPECT_TRUE(std::filesystem::exists(path))
      << "walkgen: test data '" << path
      << "' not found; the stereo data ships in tests/data (or give another folder with "
         "-DWALKGEN_TEST_DATA_DIR=<folder>)";
  return path;
}

}  // namespace walkgen::test
