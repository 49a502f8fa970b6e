// Residuals of a fit: per-sample contact radii by safeguarded Newton, exact Jacobians by
// implicit differentiation through ceres::Jet.
#include "curve_evaluator.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include <boost/math/tools/roots.hpp>

namespace layerjkr::detail {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();
// The first radius search of a model with no largest radius starts here [m]; every later
// search starts from the previous solution, so this only has to be within the search's
// bracketing range (decades either way), not close.
constexpr double kUnboundedSeedRadius = 1e-6;

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
  }
  return kNaN;
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
    case FitParameter::v_star:
    case FitParameter::n: return value(q, x);
    case FitParameter::beta: return beta_scale;
    case FitParameter::G: return G_log ? value(q, x) : G_scale;
    case FitParameter::w: return 2.0 * s_scale * s_scale * xv;
    case FitParameter::delta0: return L;
    case FitParameter::P0: return F;
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
    case FitParameter::P0: return 0.0;
    case FitParameter::E: return f.E;
    case FitParameter::R: return f.R;
    case FitParameter::sigma0: return f.sigma0;
    case FitParameter::E_inf: return f.E_inf;
    case FitParameter::tau: return f.tau;
    case FitParameter::beta: return f.beta;
    case FitParameter::v_star: return f.v_star;
    case FitParameter::n: return f.n;
  }
  return kNaN;
}

std::string ParameterMap::name_at(std::size_t j) const {
  std::string name = to_string(free[j]);
  if (j < slot_curve.size() && slot_curve[j] >= 0) return name + " of curve " + std::to_string(slot_curve[j] + 1);
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

std::size_t FitData::residuals() const {
  // Samples of weight 0 (excluded, or history only in a fit in time) are not residuals: they
  // would inflate the degrees of freedom and shrink every error bar.
  const auto counts = [&](std::size_t i) { return sqrt_weight.empty() || sqrt_weight[i] > 0.0; };
  std::size_t m = 0;
  for (std::size_t i = 0; i < delta.size(); ++i) m += counts(i) ? 1 : 0;
  if (radius_driven) return m;  // the radius is the given, not a residual
  for (std::size_t i = 0; i < a.size(); ++i) m += !std::isnan(a[i]) && counts(i) ? 1 : 0;
  return m;
}

CurveEvaluator::CurveEvaluator(const CurveModel& model, const ParameterMap& map, const FitData& data,
                               double cantilever_k)
    : model_(model), map_(map), data_(data), n_free_(map.free.size()), cantilever_k_(cantilever_k) {
  const std::size_t n = data.delta.size();
  row_.assign(n + 1, 0);
  for (std::size_t i = 0; i < n; ++i)
    row_[i + 1] = row_[i] + 1 + (data.radius_driven || data.a.empty() || std::isnan(data.a[i]) ? 0 : 1);
  order_.resize(n);
  std::iota(order_.begin(), order_.end(), std::size_t{0});
  std::stable_sort(order_.begin(), order_.end(),
                   [&](std::size_t i, std::size_t j) { return data.delta[i] < data.delta[j]; });
  a_cache_.assign(n, 0.0);
  P_fit_.assign(n, 0.0);
  // A radius where delta ~ the data's span seeds every later search.
  const double seed = std::isfinite(model.max_radius()) ? 0.25 * model.max_radius() : kUnboundedSeedRadius;
  a_typ_ = seed;
  CurveParameters<double> p;
  double d0 = 0.0, P0 = 0.0;
  std::vector<double> x0(n_free_, 0.0);
  map.physical(x0.data(), &p, &d0, &P0);
  p.s = 0.0;
  const double lo = std::max(model.min_radius(), 0.0);
  const double a = solve_radius(p, map.L, lo, seed);
  if (std::isfinite(a) && a > 0.0) a_typ_ = a;
}

void CurveEvaluator::curve(const CurveParameters<double>& p, double a, double* delta, double* P,
                           double* ddelta, double* dP) const {
  const CurveParameters<Jet1> pj{Jet1(p.K), Jet1(p.G), Jet1(p.E), Jet1(p.s), Jet1(p.R), Jet1(p.sigma0)};
  Jet1 d, F;
  model_.evaluate(Jet1(a, 0), pj, &d, &F);
  *delta = d.a;
  *P = F.a;
  if (ddelta) *ddelta = d.v[0];
  if (dP) *dP = F.v[0];
}

double CurveEvaluator::solve_radius(const CurveParameters<double>& p, double target, double lo,
                                    double guess, double* P_out) const {
  double a_closed, P_closed;
  if (model_.invert(p, target, &a_closed, &P_closed) && a_closed >= lo && a_closed < model_.max_radius()) {
    if (P_out) *P_out = P_closed;
    return a_closed;
  }
  const double a_max = model_.max_radius();
  double hi = kInf;
  double x = guess > lo ? guess : (lo > 0.0 ? 2.0 * lo : a_typ_);
  if (!(x < a_max)) x = lo > 0.0 ? 0.5 * (lo + a_max) : 0.5 * a_max;
  for (int it = 0; it < 300; ++it) {
    double d, P, dd, dP;
    curve(p, x, &d, &P, &dd, &dP);
    if (!std::isfinite(d) || !std::isfinite(dd)) return kNaN;
    const double g = d - target;
    if (g == 0.0) {
      if (P_out) *P_out = P;
      return x;
    }
    (g < 0.0 ? lo : hi) = x;
    double next = x - g / dd;
    // Quadratic convergence: once the step is below 1e-8 x the Newton update is exact to
    // ~1e-16, and so is the first-order update of P.
    if (dd > 0.0 && std::abs(next - x) <= 1e-8 * x && next > lo && next < hi) {
      if (P_out) *P_out = P + dP * (next - x);
      return next;
    }
    if (!(dd > 0.0) || !(next > lo && next < hi)) {
      if (std::isfinite(hi))
        next = 0.5 * (lo + hi);
      else
        next = 2.0 * x;
    }
    if (!(next < a_max)) {
      if (a_max - x <= 1e-12 * a_max) return kNaN;  // the target lies beyond the model's domain
      next = 0.5 * (x + a_max);
    }
    if (std::isfinite(hi) && hi - lo <= 4e-16 * hi) {
      if (P_out) curve(p, next, &d, P_out, nullptr, nullptr);
      return next;
    }
    x = next;
  }
  return kNaN;
}

bool CurveEvaluator::branch_start(const CurveParameters<double>& p, StartKind kind,
                                  BranchStart* out) const {
  const double floor = std::max(model_.min_radius(), 1e-9 * a_typ_);
  auto finish = [&](double a) {
    double P;
    out->a = a;
    curve(p, a, &out->delta, &P, nullptr, nullptr);
    return std::isfinite(out->delta);
  };
  if (p.s == 0.0) return finish(floor);
  // P(a) = 0, dP/da = 0 or d delta/da = 0: each is negative below its root.
  auto g = [&](double a) {
    double d, P, dd, dP;
    curve(p, a, &d, &P, &dd, &dP);
    if (kind == StartKind::cantilever) return dP + cantilever_k_ * dd;  // dP/d delta + k, times d delta/da
    return kind == StartKind::zero_load ? P : kind == StartKind::pull_off ? dP : dd;
  };
  double x = start_cache_[static_cast<int>(kind)];
  if (!(x > floor && x < model_.max_radius())) x = a_typ_;
  double lo, hi;
  if (g(x) >= 0.0) {
    hi = x;
    for (;;) {
      x *= 0.5;
      if (x <= floor) return finish(floor);
      if (g(x) < 0.0) break;
      hi = x;
    }
    lo = x;
  } else {
    lo = x;
    for (;;) {
      x *= 2.0;
      if (!(x < model_.max_radius())) return false;
      if (g(x) >= 0.0) break;
      lo = x;
    }
    hi = x;
  }
  std::uintmax_t iters = 100;
  const auto r = boost::math::tools::toms748_solve(
      g, lo, hi, boost::math::tools::eps_tolerance<double>(48), iters);
  return finish(0.5 * (r.first + r.second));
}

bool CurveEvaluator::evaluate(const double* x, bool jacobian) {
  const bool same_point = have_cache_ && std::equal(x_cache_.begin(), x_cache_.end(), x);
  if (same_point && (have_jac_ || !jacobian)) return cache_ok_;
  // Ceres asks for the Jacobian at a point whose residuals it just evaluated: reuse the radii.
  reuse_radii_ = same_point && cache_ok_;
  x_cache_.assign(x, x + n_free_);
  have_cache_ = true;
  have_jac_ = jacobian;
  cache_ok_ = false;

  const std::size_t slots = n_free_ + 1;
  if (slots <= 2) cache_ok_ = sweep<Jet2>(x, jacobian);
  else if (slots <= 4) cache_ok_ = sweep<Jet4>(x, jacobian);
  else cache_ok_ = sweep<Jet8>(x, jacobian);
  return cache_ok_;
}

template <class J>
bool CurveEvaluator::sweep(const double* x, bool jacobian) {
  constexpr int kRadiusSlot = J::DIMENSION - 1;
  CurveParameters<double> p;
  double delta0 = 0.0, P0 = 0.0;
  map_.physical(x, &p, &delta0, &P0);
  if (!(p.K >= 0.0 && p.E >= 0.0 && p.R >= 0.0 && p.sigma0 >= 0.0) || !std::isfinite(p.K) || !std::isfinite(p.E) ||
      !std::isfinite(p.R) || !std::isfinite(p.G) || !std::isfinite(p.s) || !std::isfinite(p.sigma0))
    return false;
  CurveParameters<J> pj;
  J d0j, P0j;
  if (jacobian) {
    std::array<J, J::DIMENSION> xj;
    for (std::size_t j = 0; j < n_free_; ++j) xj[j] = J(x[j], static_cast<int>(j));
    map_.physical(xj.data(), &pj, &d0j, &P0j);
  }
  const std::size_t m = row_.back();
  r_.assign(m, 0.0);
  detached_.assign(data_.delta.size(), 0);
  clamped_.assign(data_.delta.size(), 0);
  if (jacobian) J_.assign(m * n_free_, 0.0);
  contact_count_ = 0;
  const double F = map_.F, A = data_.a_scale;
  if (data_.radius_driven) {  // (P, a) data: the force at each measured radius
    for (std::size_t i = 0; i < data_.P.size(); ++i) {
      const double a = data_.a[i], sw = data_.sqrt_weight[i];
      double P = 0.0, d = 0.0;
      if (jacobian) {
        J dj, Pj;
        model_.evaluate(J(a, kRadiusSlot), pj, &dj, &Pj);
        P = Pj.a;
        for (std::size_t j = 0; j < n_free_; ++j) J_[i * n_free_ + j] = sw * (Pj.v[j] + P0j.v[j]) / F;
      } else {
        curve(p, a, &d, &P, nullptr, nullptr);
      }
      if (!std::isfinite(P)) return false;
      P_fit_[i] = P0 + P;
      r_[i] = sw * (P0 + P - data_.P[i]) / F;
    }
    contact_count_ = data_.P.size();
    return true;
  }

  for (int branch = 0; branch < 2; ++branch) {
    const bool retract = branch == 1;
    bool any = false;
    for (std::size_t i : order_) any = any || data_.retract[i] == retract;
    if (!any) continue;
    bool forced = false;
    for (std::size_t i : order_) forced = forced || (data_.retract[i] == retract && !data_.contact.empty() && data_.contact[i] >= 0);
    const StartKind kind = !retract                       ? (forced ? StartKind::fixed_grips : StartKind::zero_load)
                           : std::isinf(cantilever_k_)     ? StartKind::fixed_grips
                           : cantilever_k_ > 0.0           ? StartKind::cantilever
                           : forced                        ? StartKind::fixed_grips
                                                           : StartKind::pull_off;
    BranchStart start;
    if (!branch_start(p, kind, &start)) return false;
    start_cache_[static_cast<int>(kind)] = start.a;
    double lo = start.a;
    for (std::size_t i : order_) {
      if (data_.retract[i] != retract) continue;
      const double t = data_.delta[i] - delta0;
      const double sw = data_.sqrt_weight[i];
      const std::size_t r0 = row_[i];
      const bool has_a = rows(i) == 2;
      const signed char flag = data_.contact.empty() ? -1 : data_.contact[i];
      // A sample held in contact below the curve's end sits at the end (a smooth penalty).
      const bool clamped = flag == 1 && t < start.delta;
      if (flag == 0 || (flag < 0 && t < start.delta)) {  // not in contact: the baseline only
        detached_[i] = retract ? 1 : 0;
        P_fit_[i] = P0;
        r_[r0] = sw * (P0 - data_.P[i]) / F;
        if (jacobian)
          for (std::size_t j = 0; j < n_free_; ++j) J_[r0 * n_free_ + j] = sw * P0j.v[j] / F;
        if (has_a) r_[r0 + 1] = -sw * data_.a[i] / A;
        continue;
      }
      double P = 0.0;
      double a;
      if (clamped) {
        double d;
        clamped_[i] = 1;
        a = start.a;
        curve(p, a, &d, &P, nullptr, nullptr);
      } else {
        a = reuse_radii_ ? a_cache_[i] : solve_radius(p, t, lo, std::max(a_cache_[i], lo), &P);
      }
      if (!std::isfinite(a)) return false;
      lo = a;
      a_cache_[i] = a;
      ++contact_count_;
      if (jacobian) {
        J dj, Pj;
        model_.evaluate(J(a, kRadiusSlot), pj, &dj, &Pj);
        P = Pj.a;
        const double slope = dj.v[kRadiusSlot];
        if (!(slope > 0.0) && !clamped) return false;
        for (std::size_t j = 0; j < n_free_; ++j) {
          const double da = clamped ? 0.0 : (-d0j.v[j] - dj.v[j]) / slope;
          J_[r0 * n_free_ + j] = sw * (Pj.v[j] + Pj.v[kRadiusSlot] * da + P0j.v[j]) / F;
          if (has_a) J_[(r0 + 1) * n_free_ + j] = sw * da / A;
        }
      }
      if (!std::isfinite(P)) return false;
      P_fit_[i] = P0 + P;
      r_[r0] = sw * (P0 + P - data_.P[i]) / F;
      if (has_a) r_[r0 + 1] = sw * (a - data_.a[i]) / A;
    }
  }
  return true;
}

}  // namespace layerjkr::detail
