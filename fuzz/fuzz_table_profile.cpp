// libFuzzer target: the tabulated profile. The input is read as pairs of doubles (r, z);
// a table must be rejected with layerjkr::Error or give finite f, f', f'', moment and
// Sneddon integrals at radii inside it.
#include <cmath>
#include <cstdint>
#include <cstring>
#include <vector>

#include "layerjkr/error.hpp"
#include "layerjkr/profile.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::vector<double> r, z;
  for (std::size_t k = 0; k + 16 <= size && r.size() < 64; k += 16) {
    double a, b;
    std::memcpy(&a, data + k, 8);
    std::memcpy(&b, data + k + 8, 8);
    r.push_back(a);
    z.push_back(b);
  }
  try {
    const layerjkr::ProfilePtr p = layerjkr::make_table_profile(r, z);
    const double top = r.back();
    for (double t : {0.1, 0.37, 0.5, 0.99, 1.0}) {
      const double a = t * top;
      if (!(a > 0.0)) continue;
      const layerjkr::ProfileDerivatives d = p->derivatives(a);
      const double M = p->moment(a);
      if (!std::isfinite(d.f) || !std::isfinite(d.df) || !std::isfinite(d.d2f) || !std::isfinite(M))
        __builtin_trap();
      if (d.f < 0.0 || d.df < -1e-9 * std::abs(d.f / a) - 1e-300) __builtin_trap();  // monotone
      const layerjkr::SneddonIntegrals I = p->sneddon(a);
      if (!std::isfinite(I.I0) || !std::isfinite(I.I2)) __builtin_trap();
    }
  } catch (const layerjkr::Error&) {
  }
  return 0;
}
