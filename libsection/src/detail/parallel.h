// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// A minimal parallel loop over independent items: results are written by index, so the
// output does not depend on the thread count.
#include <algorithm>
#include <atomic>
#include <cstddef>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

namespace section::detail {

/// Starts up to `count` threads running `body`: as many as the system lets start (none under
/// a low `ulimit -v`, where a thread's stack cannot be mapped); the caller does the work of
/// those that did not, and joins the others.
template <class F>
std::vector<std::thread> start_threads(std::size_t count, const F& body) {
  std::vector<std::thread> pool;
  for (std::size_t t = 0; t < count; ++t) {
    try {
      pool.emplace_back(body);
    } catch (const std::exception&) {
      break;  // (std::system_error EAGAIN, or no memory for the list)
    }
  }
  return pool;
}

/// Runs body(i) for i in [0, count) on up to `threads` threads (0 = all cores), fewer when
/// threads cannot start; rethrows the first exception a body threw once all are done.
template <class F>
void parallel_for(std::size_t count, int threads, F&& body) {
  std::size_t workers =
      threads > 0 ? std::size_t(threads) : std::max(1u, std::thread::hardware_concurrency());
  workers = std::min(workers, count);
  if (workers <= 1) {
    for (std::size_t i = 0; i < count; ++i) body(i);
    return;
  }
  std::atomic<std::size_t> next{0};
  std::exception_ptr error;
  std::mutex error_mutex;
  // After an error no further item is started: the call fails anyway (a cancelled call
  // returns sooner).
  std::atomic<bool> failed{false};
  auto run = [&] {
    for (std::size_t i; !failed && (i = next++) < count;) {
      try {
        body(i);
      } catch (...) {
        std::lock_guard<std::mutex> lock(error_mutex);
        if (!error) error = std::current_exception();
        failed = true;
      }
    }
  };
  std::vector<std::thread> pool = start_threads(workers - 1, run);
  run();
  for (auto& t : pool) t.join();
  if (error) std::rethrow_exception(error);
}

}  // namespace section::detail
