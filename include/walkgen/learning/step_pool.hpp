#pragma once
/// @file
/// A fixed pool of threads that runs one function over an index range and waits: the vectorised
/// environment step of the trainers (several NMPC environments stepped at once). The pool is
/// the application's object (docs/design.md convention 13): it is created, sized and owned by the
/// program, which hands it to the trainer; environments never start threads. Standard library
/// only: a program that uses it links Threads::Threads (CMake's FindThreads), as for any
/// std::thread.

#include <condition_variable>
#include <exception>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

#include "walkgen/core/exceptions.hpp"

namespace walkgen {

/// Runs f(i) for i in [0, n) on `threads` threads (the caller's thread is one of them) and
/// returns when all are done. Index i goes to thread i mod threads, so a run is deterministic
/// when f(i) touches only item i. The first exception thrown by f is rethrown by run().
class StepPool {
 public:
  /// @throws walkgen::invalid_argument unless threads ≥ 1.
  explicit StepPool(int threads = 1) : threads_(threads) {
    check_argument(threads >= 1, "StepPool", "at least 1 thread", threads);
    for (int t = 1; t < threads_; ++t) workers_.emplace_back([this, t] { work(t); });
  }
  StepPool(const StepPool&) = delete;
  StepPool& operator=(const StepPool&) = delete;
  ~StepPool() {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      stop_ = true;
    }
    wake_.notify_all();
    for (auto& w : workers_) w.join();
  }

  int threads() const { return threads_; }

  void run(int n, const std::function<void(int)>& f) {
    if (threads_ == 1 || n <= 1) {
      for (int i = 0; i < n; ++i) f(i);
      return;
    }
    {
      std::lock_guard<std::mutex> lock(mutex_);
      job_ = &f;
      n_ = n;
      pending_ = threads_ - 1;
      error_ = nullptr;
      ++generation_;
    }
    wake_.notify_all();
    run_share(0);
    std::unique_lock<std::mutex> lock(mutex_);
    done_.wait(lock, [this] { return pending_ == 0; });
    job_ = nullptr;
    if (error_) std::rethrow_exception(error_);
  }

 private:
  void run_share(int t) {
    try {
      for (int i = t; i < n_; i += threads_) (*job_)(i);
    } catch (...) {
      std::lock_guard<std::mutex> lock(mutex_);
      if (!error_) error_ = std::current_exception();
    }
  }
  void work(int t) {
    long seen = 0;
    for (;;) {
      {
        std::unique_lock<std::mutex> lock(mutex_);
        wake_.wait(lock, [&] { return stop_ || generation_ != seen; });
        if (stop_) return;
        seen = generation_;
      }
      run_share(t);
      {
        std::lock_guard<std::mutex> lock(mutex_);
        --pending_;
      }
      done_.notify_one();
    }
  }

  int threads_;
  std::vector<std::thread> workers_;
  std::mutex mutex_;
  std::condition_variable wake_, done_;
  const std::function<void(int)>* job_ = nullptr;
  int n_ = 0, pending_ = 0;
  long generation_ = 0;
  bool stop_ = false;
  std::exception_ptr error_;
};

}  // namespace walkgen
