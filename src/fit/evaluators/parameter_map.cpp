// ParameterMap (curve_evaluator.hpp): the fit's dimensionless vector x to physical parameters -
// moduli and R on a log scale, sqrt(w), delta0 and P0 in units of the curve's spans.
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include <boost/math/tools/toms748_solve.hpp>

#include "fit/evaluators/curve_evaluator.hpp"
#include "layerjkr/error.hpp"

namespace layerjkr::detail {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

int idx(FitParameter p) { return static_cast<int>(p); }

}  // namespace

template <class T>
void ParameterMap::physical(const T* x, CurveParameters<T>* p, T* delta0, T* P0) const {
  using std::exp;
  auto get = [&](FitParameter q) -> const T* { return is_free(q) ? &x[index(q)] : nullptr; };
  const CurveParameters<double>& f = fixed.values;
  p->R = get(FitParameter::R) ? ref[idx(FitParameter::R)] * exp(*get(FitParameter::R)) : T(f.R);
  p->s = get(FitParameter::w) ? s_scale * *get(FitParameter::w) : T(f.s);
  p->E = get(FitParameter::E) ? ref[idx(FitParameter::E)] * exp(*get(FitParameter::E)) : T(f.E);
  // A Dugdale stress from a spacing z0 follows w (sigma0 = 16 w / (9 sqrt 3 z0)) unless freed.
  if (get(FitParameter::sigma0))
    p->sigma0 = ref[idx(FitParameter::sigma0)] * exp(*get(FitParameter::sigma0));
  else
    p->sigma0 = fixed.sigma0_per_w > 0.0 ? fixed.sigma0_per_w * p->s * p->s : T(f.sigma0);
  if (fixed.layer_foundation && get(FitParameter::E)) {
    p->K = fixed.k_per_E * p->E;
    p->G = fixed.g_per_E * p->E;
  } else {
    p->K = get(FitParameter::K) ? ref[idx(FitParameter::K)] * exp(*get(FitParameter::K)) : T(f.K);
    if (!get(FitParameter::G))
      p->G = T(f.G);
    else if (G_log)
      p->G = ref[idx(FitParameter::G)] * exp(*get(FitParameter::G));
    else
      p->G = G_scale * *get(FitParameter::G);
  }
  const auto logarithmic = [&](FitParameter q, double fixed_value) {
    return get(q) ? ref[idx(q)] * exp(*get(q)) : T(fixed_value);
  };
  p->E_inf = logarithmic(FitParameter::E_inf, f.E_inf);
  p->tau = logarithmic(FitParameter::tau, f.tau);
  p->E_2 = logarithmic(FitParameter::E_2, f.E_2);
  p->tau_2 = logarithmic(FitParameter::tau_2, f.tau_2);
  p->v_star = logarithmic(FitParameter::v_star, f.v_star);
  p->n = logarithmic(FitParameter::n, f.n);
  p->beta = get(FitParameter::beta) ? ref[idx(FitParameter::beta)] + beta_scale * *get(FitParameter::beta) : T(f.beta);
  *delta0 = get(FitParameter::delta0) ? ref[idx(FitParameter::delta0)] + L * *get(FitParameter::delta0)
                                      : T(0.0);
  *P0 = get(FitParameter::P0) ? ref[idx(FitParameter::P0)] + F * *get(FitParameter::P0) : T(0.0);
}

template void ParameterMap::physical<double>(const double*, CurveParameters<double>*, double*,
                                             double*) const;
template void ParameterMap::physical<Jet1>(const Jet1*, CurveParameters<Jet1>*, Jet1*, Jet1*) const;
template void ParameterMap::physical<Jet2>(const Jet2*, CurveParameters<Jet2>*, Jet2*, Jet2*) const;
template void ParameterMap::physical<Jet4>(const Jet4*, CurveParameters<Jet4>*, Jet4*, Jet4*) const;
template void ParameterMap::physical<Jet8>(const Jet8*, CurveParameters<Jet8>*, Jet8*, Jet8*) const;

template <class T>
T ParameterMap::drag(const T* x) const {
  return is_free(FitParameter::drag) ? T(drag_scale) * x[index(FitParameter::drag)] : T(0.0);
}

template double ParameterMap::drag<double>(const double*) const;
template Jet1 ParameterMap::drag<Jet1>(const Jet1*) const;
template Jet2 ParameterMap::drag<Jet2>(const Jet2*) const;
template Jet4 ParameterMap::drag<Jet4>(const Jet4*) const;
template Jet8 ParameterMap::drag<Jet8>(const Jet8*) const;

double ParameterMap::value(FitParameter q, const double* x) const {
  CurveParameters<double> p;
  double d0 = 0.0, P0 = 0.0;
  physical(x, &p, &d0, &P0);
  switch (q) {
    case FitParameter::K: return p.K;
    case FitParameter::G: return p.G;
    case FitParameter::w: return p.s * p.s;
    case FitParameter::delta0: return d0;
    case FitParameter::P0: return P0;
    case FitParameter::E: return p.E;
    case FitParameter::R: return p.R;
    case FitParameter::sigma0: return p.sigma0;
    case FitParameter::E_inf: return p.E_inf;
    case FitParameter::tau: return p.tau;
    case FitParameter::beta: return p.beta;
    case FitParameter::v_star: return p.v_star;
    case FitParameter::n: return p.n;
    case FitParameter::drag: return drag(x);
    case FitParameter::E_2: return p.E_2;
    case FitParameter::tau_2: return p.tau_2;
  }
  return kNaN;
}

double ParameterMap::coordinate(FitParameter q, double v, const double* x) const {
  // Wide enough for every map and finite in all: e^300 on the log scales, 300 spans on the linear.
  constexpr double kSpan = 300.0;
  const auto j = static_cast<std::size_t>(index(q));
  std::vector<double> y(x, x + free.size());
  const auto at = [&](double t) {
    y[j] = t;
    return value(q, y.data());
  };
  const double lo = q == FitParameter::w ? 0.0 : -kSpan, hi = kSpan;
  const double f_lo = at(lo), f_hi = at(hi);
  if (!std::isfinite(f_lo) || !std::isfinite(f_hi) || !(f_lo < f_hi))
    throw NumericalError("ParameterMap::coordinate: the map of " + std::string(to_string(q)) +
                         " is not increasing in its coordinate");
  if (v <= f_lo) return q == FitParameter::w && v >= 0.0 ? 0.0 : -std::numeric_limits<double>::infinity();
  if (v >= f_hi) return std::numeric_limits<double>::infinity();
  std::uintmax_t iterations = 200;
  const auto r = boost::math::tools::toms748_solve([&](double t) { return at(t) - v; }, lo, hi, f_lo - v, f_hi - v,
                                                   boost::math::tools::eps_tolerance<double>(52), iterations);
  return 0.5 * (r.first + r.second);
}

double ParameterMap::derivative(FitParameter q, const double* x) const {
  const double xv = x[index(q)];
  switch (q) {
    case FitParameter::K:
    case FitParameter::E:
    case FitParameter::R:
    case FitParameter::sigma0:
    case FitParameter::E_inf:
    case FitParameter::tau:
    case FitParameter::E_2:
    case FitParameter::tau_2:
    case FitParameter::v_star:
    case FitParameter::n: return value(q, x);
    case FitParameter::beta: return beta_scale;
    case FitParameter::G: return G_log ? value(q, x) : G_scale;
    case FitParameter::w: return 2.0 * s_scale * s_scale * xv;
    case FitParameter::delta0: return L;
    case FitParameter::P0: return F;
    case FitParameter::drag: return drag_scale;
  }
  return kNaN;
}

double ParameterMap::fixed_value(FitParameter q) const {
  const CurveParameters<double>& f = fixed.values;
  switch (q) {
    case FitParameter::K: return f.K;
    case FitParameter::G: return f.G;
    case FitParameter::w: return f.s * f.s;
    case FitParameter::delta0:
    case FitParameter::P0:
    case FitParameter::drag: return 0.0;
    case FitParameter::E: return f.E;
    case FitParameter::R: return f.R;
    case FitParameter::sigma0: return f.sigma0;
    case FitParameter::E_inf: return f.E_inf;
    case FitParameter::tau: return f.tau;
    case FitParameter::beta: return f.beta;
    case FitParameter::v_star: return f.v_star;
    case FitParameter::n: return f.n;
    case FitParameter::E_2: return f.E_2;
    case FitParameter::tau_2: return f.tau_2;
  }
  return kNaN;
}

std::string ParameterMap::name_at(std::size_t j) const {
  std::string name = to_string(free[j]);
  if (j < slot_curve.size() && slot_curve[j] >= 0) {
    const auto k = static_cast<std::size_t>(slot_curve[j]);
    return name + " of " + (k < curve_names.size() ? curve_names[k] : "curve " + std::to_string(k + 1));
  }
  return name;
}

double ParameterMap::value_at(std::size_t j, const double* x) const {
  if (j < slot_curve.size() && slot_curve[j] >= 0)
    return slot_ref[j] + (free[j] == FitParameter::delta0 ? L : F) * x[j];
  return value(free[j], x);
}

double ParameterMap::derivative_at(std::size_t j, const double* x) const {
  if (j < slot_curve.size() && slot_curve[j] >= 0) return free[j] == FitParameter::delta0 ? L : F;
  return derivative(free[j], x);
}

}  // namespace layerjkr::detail
