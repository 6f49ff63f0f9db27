#pragma once
/// @file
/// Internal invariant checks (docs/design.md convention 10, tier a).
///
/// WALKGEN_ASSERT(cond) guards invariants of walkgen's own code. It is compiled out when
/// NDEBUG is defined (release builds) unless WALKGEN_ENABLE_ASSERTS is defined. A failed
/// assertion calls std::abort() after no output: a broken invariant is a walkgen bug, and
/// the debugger's stack trace is the report.

#include <cstdlib>

#if !defined(NDEBUG) || defined(WALKGEN_ENABLE_ASSERTS)
#define WALKGEN_ASSERT(cond)   \
  do {                         \
    if (!(cond)) std::abort(); \
  } while (false)
#else
#define WALKGEN_ASSERT(cond) \
  do {                       \
  } while (false)
#endif
