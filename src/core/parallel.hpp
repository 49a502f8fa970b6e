// Internal: a parallel loop for one-off builds (kernel tables, Dugdale tables) whose first use
// waits for them, so the machine's cores are worth spending there.
#pragma once

#include <algorithm>
#include <atomic>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

namespace layerjkr::detail {

/// Runs body(i) for every i in [0, n) on up to `max_threads` threads (the calling thread
/// included); the first exception a body throws is rethrown after all have finished.
template <class Body>
void parallel_for(int n, const Body& body, int max_threads = 4) {
  const int threads = std::clamp(std::min(n, static_cast<int>(std::thread::hardware_concurrency())), 1, max_threads);
  std::atomic<int> next{0};
  std::exception_ptr failure;
  std::mutex failure_mutex;
  auto work = [&] {
    for (int i = next++; i < n; i = next++) try {
        body(i);
      } catch (...) {
        const std::lock_guard<std::mutex> lock(failure_mutex);
        if (!failure) failure = std::current_exception();
      }
  };
  std::vector<std::thread> pool;
  for (int t = 1; t < threads; ++t) pool.emplace_back(work);
  work();
  for (std::thread& t : pool) t.join();
  if (failure) std::rethrow_exception(failure);
}

}  // namespace layerjkr::detail
