#pragma once
// Expects walkgen::invalid_argument from a call, with every given part in its message.

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "walkgen/core/exceptions.hpp"

namespace walkgen_test {

template <typename F>
void expect_invalid_argument(F f, const std::vector<std::string>& parts) {
  try {
    f();
    ADD_FAILURE() << "expected walkgen::invalid_argument";
  } catch (const walkgen::invalid_argument& e) {
    for (const std::string& p : parts) {
      EXPECT_NE(std::string(e.what()).find(p), std::string::npos)
          << "message '" << e.what() << "' lacks '" << p << "'";
    }
  }
}

}  // namespace walkgen_test
