#pragma once
// Shared pieces of the fuzz harnesses (tests/fuzz/README.md). A harness defines
// LLVMFuzzerTestOneInput; it is linked either with libFuzzer (clang, -fsanitize=fuzzer) or with
// replay_main.cpp, which feeds it the files of a corpus (any compiler; ctest label "fuzz").
//
// A harness asserts walkgen's invariants with WALKGEN_FUZZ_CHECK: a failure prints the
// condition and the harness's message and aborts, which both libFuzzer and the replay report as
// a crash with the input that caused it.

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <limits>
#include <string>

#include "walkgen/core/exceptions.hpp"

#define WALKGEN_FUZZ_CHECK(condition, message)                                         \
  do {                                                                                 \
    if (!(condition)) ::walkgen_fuzz::fail(__FILE__, __LINE__, #condition, (message)); \
  } while (false)

namespace walkgen_fuzz {

[[noreturn]] inline void fail(const char* file, int line, const char* condition,
                              const std::string& message) {
  std::fprintf(stderr, "%s:%d: fuzz invariant violated: %s\n  %s\n", file, line, condition,
               message.c_str());
  std::fflush(stderr);
  std::abort();
}

/// Runs `f`; walkgen::invalid_argument is the one exception a loader or solver may throw on
/// bad input (a clear error). Anything else escaping (cv::Exception, std::bad_alloc,
/// std::out_of_range, ...) violates the invariant. Returns whether f completed without throwing.
template <typename F>
bool only_walkgen_errors(const char* what, F&& f) {
  try {
    f();
    return true;
  } catch (const walkgen::invalid_argument& e) {
    WALKGEN_FUZZ_CHECK(std::strlen(e.what()) > 0, std::string(what) + ": empty error message");
    return false;
  } catch (const std::exception& e) {
    fail(__FILE__, __LINE__, "only walkgen::invalid_argument escapes",
         std::string(what) + " let a foreign exception escape: " + e.what());
  } catch (...) {
    fail(__FILE__, __LINE__, "only walkgen::invalid_argument escapes",
         std::string(what) + " let a non-std exception escape");
  }
}

/// Decodes the fuzzer's bytes into values; past the end every read returns zeros.
class ByteReader {
 public:
  ByteReader(const std::uint8_t* data, std::size_t size) : data_(data), size_(size) {}

  std::size_t remaining() const { return size_ - pos_; }
  std::uint8_t byte() { return pos_ < size_ ? data_[pos_++] : 0; }
  /// An integer in [lo, hi] (hi - lo < 2^16).
  int integer(int lo, int hi) {
    const unsigned v = static_cast<unsigned>(byte()) | (static_cast<unsigned>(byte()) << 8);
    return lo + static_cast<int>(v % static_cast<unsigned>(hi - lo + 1));
  }
  bool flag() { return (byte() & 1u) != 0; }
  /// A double built to reach the values that break numerical code: one byte chooses a class
  /// (0, ±1, small integers, tiny, huge, NaN, ±inf, denormal) or reads 8 raw bytes.
  double number() {
    const std::uint8_t kind = byte();
    const double sign = (kind & 0x80u) ? -1.0 : 1.0;
    switch (kind & 0x0fu) {
      case 0:
        return 0.0;
      case 1:
        return sign;
      case 2:
        return sign * static_cast<double>(byte());
      case 3:
        return sign * static_cast<double>(byte()) / 64.0;
      case 4:
        return sign * std::pow(10.0, -static_cast<double>(byte() % 200));
      case 5:
        return sign * std::pow(10.0, static_cast<double>(byte() % 200));
      case 6:
        return std::numeric_limits<double>::quiet_NaN();
      case 7:
        return sign * std::numeric_limits<double>::infinity();
      case 8:
        return sign * std::numeric_limits<double>::denorm_min() * (1 + byte());
      default: {
        std::uint64_t bits = 0;
        for (int i = 0; i < 8; ++i) bits |= static_cast<std::uint64_t>(byte()) << (8 * i);
        double v;
        std::memcpy(&v, &bits, sizeof v);
        return v;
      }
    }
  }
  /// A double near `typical`: mostly small perturbations, sometimes number().
  double around(double typical) {
    const std::uint8_t kind = byte();
    if (kind < 200) return typical * (1.0 + (static_cast<double>(kind) - 100.0) / 200.0);
    return number();
  }

 private:
  const std::uint8_t* data_;
  std::size_t size_;
  std::size_t pos_ = 0;
};

}  // namespace walkgen_fuzz
