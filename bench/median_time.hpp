// The benchmark programs' timer: the median wall time of `runs` calls of f [s], robust to the
// shared machine's occasional stalls where a mean is not.
#pragma once

#include <algorithm>
#include <chrono>
#include <vector>

namespace layerjkr::bench {

template <class F>
double median_seconds(F f, int runs) {
  std::vector<double> t;
  for (int r = 0; r < runs; ++r) {
    const auto t0 = std::chrono::steady_clock::now();
    f();
    t.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  }
  std::sort(t.begin(), t.end());
  return t[t.size() / 2];
}

}  // namespace layerjkr::bench
