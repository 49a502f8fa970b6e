// Internal: K1(x)/K0(x) from GSL's exponentially scaled Bessel functions, finite for
// every x > 0 (the unscaled functions underflow beyond x ~ 700).
#pragma once

namespace layerjkr::detail {
double bessel_k1_over_k0(double x);
}
