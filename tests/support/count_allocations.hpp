#pragma once
// A counting replacement of operator new and count_allocations(f), for the no-allocation tests
// (docs/design.md convention 6). Include it in exactly one translation unit of a test binary that
// is built with EIGEN_RUNTIME_NO_MALLOC (Eigen heap allocations then abort) and without NDEBUG.

#include <Eigen/Core>
#include <atomic>
#include <cstdlib>
#include <new>

#ifndef EIGEN_RUNTIME_NO_MALLOC
#error "this test needs EIGEN_RUNTIME_NO_MALLOC"
#endif

namespace walkgen_test {
inline std::atomic<long> g_news{0};

// Runs f with Eigen allocations forbidden and returns how many operator new calls it made.
template <typename F>
long count_allocations(F&& f) {
  const long before = g_news.load();
  Eigen::internal::set_is_malloc_allowed(false);
  f();
  Eigen::internal::set_is_malloc_allowed(true);
  return g_news.load() - before;
}
}  // namespace walkgen_test

void* operator new(std::size_t size) {
  ++walkgen_test::g_news;
  if (void* p = std::malloc(size == 0 ? 1 : size)) return p;
  throw std::bad_alloc();
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
