#pragma once
// Expects walkgen::invalid_argument from a call, with every given part in its message.

#include <gtest/gtest.h>

#include <functional>
#include <string>
#include <utility>
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

/// validate() (by ADL) accepts `good`, rejects each case's copy naming field, range and value.
template <typename S>
void expect_rejected(
    const S& good,
    const std::vector<std::pair<std::function<void(S&)>, std::vector<std::string>>>& cases) {
  EXPECT_NO_THROW(validate(good));
  for (const auto& [set, parts] : cases) {
    S s = good;
    set(s);
    expect_invalid_argument([&] { validate(s); }, parts);
  }
}

}  // namespace walkgen_test
