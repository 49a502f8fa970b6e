// The installed package works when this compiles against the installed headers, links
// the installed library and reproduces the half-space JKR pull-off -3/2 pi w R.
#include <cmath>
#include <cstdio>

#include "layerjkr/layerjkr.hpp"

int main() {
  const double R = 1e-3, w = 0.05;
  const auto model = layerjkr::make_half_space(layerjkr::make_paraboloid(R), 1e6, 0.3);
  const auto pull_off = layerjkr::JkrSolution(model, w).pull_off();
  const double expected = -1.5 * M_PI * w * R;
  if (!pull_off || std::abs(pull_off->P / expected - 1.0) > 1e-8) {
    std::fprintf(stderr, "pull-off differs from -3/2 pi w R = %g\n", expected);
    return 1;
  }
  std::printf("installed layerjkr: pull-off %.9g N (-3/2 pi w R = %.9g N)\n", pull_off->P, expected);
  return 0;
}
