// The fit's DMT and Maugis-Dugdale points (adhesive_curve.hpp), instantiated here for double and
// the evaluator's Jets, apart from the JKR path of the families.
#include <cmath>
#include <limits>

#include <boost/math/constants/constants.hpp>

#include "adhesion/dmt_formula.hpp"
#include "adhesion/maugis_equations.hpp"
#include "fit/evaluators/adhesive_curve.hpp"
#include "layerjkr/error.hpp"
#include "layerjkr/maugis_dugdale.hpp"

namespace layerjkr::detail {

template <class T>
void dmt_point(const StateOf<T>& h, const T& s, const T& R, T* delta, T* P) {
  *delta = h.delta_H;
  *P = dmt_force(h.P_H, T(s * s), R);
}

template <class T>
void maugis_curve(const T& a, const T& E_star, const T& w, const T& R, const T& sigma0, T* delta, T* P) {
  using std::cbrt;
  constexpr double pi = boost::math::constants::pi<double>();
  const T K = (4.0 / 3.0) * E_star;
  const T length = cbrt(pi * w * R * R / K);  // a = A length
  const T lambda = 2.0 * sigma0 * cbrt(R / (pi * w * K * K));
  const T A = a / length;
  const double lv = value_of(lambda), Av = value_of(A);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  if (!(lv >= 1e-4 && lv <= 1e4) || !(Av > 0.0) || !std::isfinite(Av)) {
    *delta = T(nan);
    *P = T(nan);
    return;
  }
  double sm;
  try {
    const double m = maugis_point(lv, Av).m;
    sm = std::sqrt((m - 1.0) * (m + 1.0));
  } catch (const Error&) {
    *delta = T(nan);
    *P = T(nan);
    return;
  }
  // m - 1 loses digits as lambda grows: polish s_m on the first equation itself.
  using J = ceres::Jet<double, 1>;
  double slope = 0.0;
  for (int it = 0; it < 3; ++it) {
    const J F = maugis_residual(J(lv), maugis_terms(J(Av), J(sm, 0)));
    slope = F.v[0];
    if (!(slope > 0.0)) break;
    const double next = sm - F.a / slope;
    if (!(next > 0.0)) break;
    const bool done = std::abs(next - sm) <= 1e-15 * sm;
    sm = next;
    if (done) break;
  }
  if (!(slope > 0.0)) {
    *delta = T(nan);
    *P = T(nan);
    return;
  }
  const T s_m = T(sm) - maugis_residual(lambda, maugis_terms(A, T(sm))) / slope;
  const MaugisTerms<T> t = maugis_terms(A, s_m);
  *P = maugis_force(lambda, A, t) * (pi * w * R);
  *delta = maugis_approach(lambda, A, t) * (length * length / R);
}

template void dmt_point<double>(const StateOf<double>&, const double&, const double&, double*, double*);
template void dmt_point<Jet1>(const StateOf<Jet1>&, const Jet1&, const Jet1&, Jet1*, Jet1*);
template void dmt_point<Jet2>(const StateOf<Jet2>&, const Jet2&, const Jet2&, Jet2*, Jet2*);
template void dmt_point<Jet4>(const StateOf<Jet4>&, const Jet4&, const Jet4&, Jet4*, Jet4*);
template void dmt_point<Jet8>(const StateOf<Jet8>&, const Jet8&, const Jet8&, Jet8*, Jet8*);
template void maugis_curve<double>(const double&, const double&, const double&, const double&, const double&,
                                   double*, double*);
template void maugis_curve<Jet1>(const Jet1&, const Jet1&, const Jet1&, const Jet1&, const Jet1&, Jet1*, Jet1*);
template void maugis_curve<Jet2>(const Jet2&, const Jet2&, const Jet2&, const Jet2&, const Jet2&, Jet2*, Jet2*);
template void maugis_curve<Jet4>(const Jet4&, const Jet4&, const Jet4&, const Jet4&, const Jet4&, Jet4*, Jet4*);
template void maugis_curve<Jet8>(const Jet8&, const Jet8&, const Jet8&, const Jet8&, const Jet8&, Jet8*, Jet8*);

}  // namespace layerjkr::detail
