#pragma once
// Checks the to_string() convention of walkgen's enums (status enums above all): every
// enumerator has its own snake_case name, and a value out of range gives "unknown".

#include <gtest/gtest.h>

#include <array>
#include <cstddef>
#include <limits>
#include <set>
#include <string>
#include <type_traits>

namespace walkgen_test {

/// True for a non-empty snake_case name: [a-z][a-z0-9_]*.
inline bool is_snake_case(const std::string& s) {
  if (s.empty() || !(s[0] >= 'a' && s[0] <= 'z')) return false;
  for (char c : s) {
    if (!((c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_')) return false;
  }
  return true;
}

/// `all` lists every enumerator of Enum in declaration order; the enumerators must be 0, 1, ...
/// (no explicit values), so that the value all.size() is the first one out of range: a new
/// enumerator that the list lacks then makes to_string(all.size()) a name, not "unknown".
template <typename Enum, std::size_t Count>
void expect_enum_strings(const std::array<Enum, Count>& all) {
  static_assert(std::is_enum<Enum>::value, "walkgen: expect_enum_strings needs an enum");
  static_assert(noexcept(to_string(all[0])), "walkgen: to_string must be noexcept");
  using Underlying = std::underlying_type_t<Enum>;
  std::set<std::string> names;
  for (std::size_t i = 0; i < Count; ++i) {
    EXPECT_EQ(static_cast<std::size_t>(static_cast<Underlying>(all[i])), i)
        << "the list must hold the enumerators in declaration order";
    const char* name = to_string(all[i]);
    ASSERT_NE(name, nullptr);
    EXPECT_NE(std::string(name), "unknown") << "enumerator " << i;
    EXPECT_TRUE(is_snake_case(name)) << "'" << name << "'";
    EXPECT_TRUE(names.insert(name).second) << "'" << name << "' twice";
  }
  EXPECT_STREQ(to_string(static_cast<Enum>(Count)), "unknown") << "the first value out of range";
  EXPECT_STREQ(to_string(static_cast<Enum>(std::numeric_limits<Underlying>::max())), "unknown");
}

}  // namespace walkgen_test
