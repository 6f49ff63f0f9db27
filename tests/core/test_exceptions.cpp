// Tests of walkgen's boundary checks (docs/design.md convention 10, tier b).

#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

#include "walkgen/core/exceptions.hpp"

namespace {

TEST(Exceptions, CheckArgumentPassesSilently) {
  EXPECT_NO_THROW(walkgen::check_argument(true, "where", "x", 1));
}

TEST(Exceptions, MessageSaysWhereExpectedGotAndHint) {
  try {
    walkgen::check_argument(false, "DenseQp: g", "a vector of size 3", 4, "resize g");
    FAIL() << "expected walkgen::invalid_argument";
  } catch (const walkgen::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()),
              "DenseQp: g: expected a vector of size 3, got 4 (hint: resize g)");
  }
}

TEST(Exceptions, IsAStdInvalidArgument) {
  EXPECT_THROW(walkgen::check_argument(false, "w", 1, 2), std::invalid_argument);
  try {
    walkgen::check_argument(false, "w", 1, 2);
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()), "w: expected 1, got 2");
  }
}

}  // namespace
