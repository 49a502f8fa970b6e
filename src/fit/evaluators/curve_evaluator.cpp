// Residuals of a fit: per-sample contact radii by safeguarded Newton, exact Jacobians by
// implicit differentiation through ceres::Jet.
#include "fit/evaluators/curve_evaluator.hpp"

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

}  // namespace

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
  std::vector<std::size_t> order(n);
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t i, std::size_t j) { return data.delta[i] < data.delta[j]; });
  for (std::size_t i : order) branch_order_[data.retract[i] ? 1 : 0].push_back(i);
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

double CurveEvaluator::nearest_radius(const CurveParameters<double>& p, double target_delta, double target_P,
                                      double kappa, double lo, double guess, double* P_out, double* misfit_out) const {
  const double a_max = model_.max_radius();
  const auto misfit = [&](double a, double* d, double* P, double* dd, double* dP) {
    curve(p, a, d, P, dd, dP);
    const double ud = kappa * (*d - target_delta), uP = *P - target_P;
    return ud * ud + uP * uP;
  };
  double a = std::max(guess, lo), d, P, dd, dP;
  double phi = misfit(a, &d, &P, &dd, &dP);
  const auto found = [&]() {
    *P_out = P;
    if (misfit_out) *misfit_out = phi;
    return a;
  };
  for (int it = 0; it < 100 && std::isfinite(phi); ++it) {
    // Gauss-Newton in a: the curve's tangent (dP, kappa dd) against the offset to the sample.
    const double g = dP * (P - target_P) + kappa * kappa * dd * (d - target_delta);
    const double h = dP * dP + kappa * kappa * dd * dd;
    if (!(h > 0.0)) return kNaN;
    double step = -g / h;
    for (int half = 0; half < 60; ++half, step *= 0.5) {
      const double next = std::clamp(a + step, lo, a_max < kInf ? std::nextafter(a_max, 0.0) : kInf);
      double d1, P1, dd1, dP1;
      const double phi1 = misfit(next, &d1, &P1, &dd1, &dP1);
      if (phi1 <= phi) {
        const bool done = std::abs(next - a) <= 1e-13 * a;
        a = next, d = d1, P = P1, dd = dd1, dP = dP1, phi = phi1;
        if (done) return found();
        break;
      }
    }
    if (!(std::abs(step) > 1e-13 * a)) break;  // no step lowers the misfit: a is the nearest point
  }
  return std::isfinite(phi) ? found() : kNaN;
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

void CurveEvaluator::swap_saved() {
  x_cache_.swap(saved_.x);
  r_.swap(saved_.r);
  J_.swap(saved_.J);
  P_fit_.swap(saved_.P_fit);
  detached_.swap(saved_.detached);
  clamped_.swap(saved_.clamped);
  std::swap(contact_count_, saved_.contact_count);
}

bool CurveEvaluator::evaluate(const double* x, bool jacobian) {
  const bool same_point = have_cache_ && std::equal(x_cache_.begin(), x_cache_.end(), x);
  if (same_point && (have_jac_ || !jacobian)) return cache_ok_;
  if (!same_point && have_saved_ && std::equal(saved_.x.begin(), saved_.x.end(), x)) {
    swap_saved();  // back to the last successful Jacobian evaluation: the current one is dropped
    have_saved_ = false;
    have_jac_ = cache_ok_ = true;
    reuse_radii_ = false;
    return true;
  }
  if (!same_point && have_cache_ && have_jac_ && cache_ok_) {
    swap_saved();  // keep it aside; the sweep below writes into the buffers it leaves here
    have_saved_ = true;
  }
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
bool CurveEvaluator::distance_residual(const CurveParameters<double>& p, const CurveParameters<J>& pj, std::size_t i,
                                       double a, double t, double P0, const J& P0j, const J& d0j, double kappa,
                                       bool jacobian, double* P) {
  constexpr int kRadiusSlot = J::DIMENSION - 1;
  const double sw = data_.sqrt_weight[i], F = map_.F;
  const std::size_t r0 = row_[i];
  double d, dd, dP;
  J dj, Pj;
  if (jacobian) {
    model_.evaluate(J(a, kRadiusSlot), pj, &dj, &Pj);
    d = dj.a, *P = Pj.a, dd = dj.v[kRadiusSlot], dP = Pj.v[kRadiusSlot];
  } else {
    curve(p, a, &d, P, &dd, &dP);
  }
  const double length = std::hypot(kappa * dd, dP);
  if (!(length > 0.0) || !std::isfinite(length) || !std::isfinite(*P)) return false;
  // The unit normal in the metric (P, kappa delta), oriented as the force: it is the force's
  // residual alone when the displacement is exact (kappa -> infinity).
  const double nP = kappa * dd / length, nd = -dP / length;
  r_[r0] = sw * (nP * (P0 + *P - data_.P[i]) + nd * kappa * (d - t)) / F;
  if (jacobian)
    for (std::size_t j = 0; j < n_free_; ++j)
      J_[r0 * n_free_ + j] = sw * (nP * (Pj.v[j] + P0j.v[j]) + nd * kappa * (dj.v[j] + d0j.v[j])) / F;
  return true;
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
  P_fit_.resize(data_.delta.size());  // the buffers may be the ones kept aside (swap_saved)
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
    const std::vector<std::size_t>& samples = branch_order_[branch];
    if (samples.empty()) continue;
    const bool forced = !data_.contact.empty() && std::any_of(samples.begin(), samples.end(), [&](std::size_t i) {
      return data_.contact[i] >= 0;
    });
    const StartKind kind = !retract                       ? (forced ? StartKind::fixed_grips : StartKind::zero_load)
                           : std::isinf(cantilever_k_)     ? StartKind::fixed_grips
                           : cantilever_k_ > 0.0           ? StartKind::cantilever
                           : forced                        ? StartKind::fixed_grips
                                                           : StartKind::pull_off;
    BranchStart start;
    if (!branch_start(p, kind, &start)) return false;
    start_cache_[static_cast<int>(kind)] = start.a;
    double lo = start.a;
    for (std::size_t i : samples) {
      const double t = data_.delta[i] - delta0;
      const double sw = data_.sqrt_weight[i];
      const std::size_t r0 = row_[i];
      const bool has_a = rows(i) == 2;
      const signed char flag = data_.contact.empty() ? -1 : data_.contact[i];
      // Errors in the displacement: a contact sample's residual is its distance to the curve.
      const double kappa = has_a ? 0.0 : data_.displacement_weight;
      // A sample held in contact below the curve's end sits at the end (a smooth penalty); with
      // errors in the displacement its nearest point is searched from there instead.
      const bool clamped = flag == 1 && t < start.delta && !(kappa > 0.0);
      // Below the branch's start the model decides; with errors in the displacement by which of the
      // baseline and the branch lies nearer (a measured delta just short of it is noise). The branch's
      // nearest point found for that serves the sample's residual if it is in contact.
      bool off = flag == 0 || (flag < 0 && t < start.delta);
      double a_near = kNaN, P_near = 0.0;
      if (off && flag < 0 && kappa > 0.0) {
        const double above = data_.P[i] - P0;  // the sample's distance to the baseline [N]
        double misfit = kInf;
        a_near = nearest_radius(p, t, above, kappa, start.a, start.a, &P_near, &misfit);
        off = !(std::isfinite(a_near) && misfit < above * above);
      }
      if (off) {  // not in contact: the baseline only
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
      } else if (reuse_radii_) {
        a = a_cache_[i];
      } else if (kappa > 0.0) {
        // Seeded at the radius of the sample's delta; `lo` keeps following those radii, which grow
        // with delta where the nearest points need not.
        if (std::isfinite(a_near)) {
          a = a_near, P = P_near;
        } else {
          double seed = start.a;
          if (t >= start.delta) seed = lo = solve_radius(p, t, lo, std::max(a_cache_[i], lo));
          if (!std::isfinite(seed)) return false;
          a = nearest_radius(p, t, data_.P[i] - P0, kappa, start.a, seed, &P);
        }
        // Held in contact short of the branch's end and nearest to the end itself: beyond the branch,
        // marked so that the held reading trims it (retract_reading.cpp); its residual stays the
        // distance to the end (a force-only penalty there let a free P0 trade with delta0).
        if (flag == 1 && t < start.delta && !(a > start.a)) clamped_[i] = 1;
      } else {
        a = lo = solve_radius(p, t, lo, std::max(a_cache_[i], lo), &P);
      }
      if (!std::isfinite(a)) return false;
      a_cache_[i] = a;
      ++contact_count_;
      if (kappa > 0.0) {
        if (!distance_residual(p, pj, i, a, t, P0, P0j, d0j, kappa, jacobian, &P)) return false;
        // What the fit minimises, as a force: the sample's force moved by its distance to the curve.
        P_fit_[i] = sw > 0.0 ? data_.P[i] + r_[r0] * F / sw : P0 + P;
        continue;
      }
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
