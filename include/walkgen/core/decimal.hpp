#pragma once
/// @file
/// Decimal integers from text, for the loaders and the examples' command lines: digits only, so
/// that "010" is 10 (not octal 8), "0x10" and "-1" are refused, and no value wraps.

#include <string>

namespace walkgen::detail {

/// Reads `text` as decimal digits (after one optional '+' when allow_plus) whose value is at
/// most `max` into *value. Returns false, leaving *value alone, for anything else.
inline bool parse_decimal(const std::string& text, unsigned long long max,
                          unsigned long long* value, bool allow_plus = false) {
  const std::size_t first = allow_plus && !text.empty() && text[0] == '+' ? 1 : 0;
  if (text.size() <= first) return false;
  unsigned long long v = 0;
  for (std::size_t i = first; i < text.size(); ++i) {
    if (text[i] < '0' || text[i] > '9') return false;
    const unsigned digit = static_cast<unsigned>(text[i] - '0');
    if (v > (max - digit) / 10) return false;  // v * 10 + digit > max, without overflow
    v = v * 10 + digit;
  }
  *value = v;
  return true;
}

}  // namespace walkgen::detail
