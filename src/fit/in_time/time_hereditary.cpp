// A relaxing medium fitted in time: the hereditary response at every sample, with exact Jacobians
// (time_evaluators.hpp).
#include <algorithm>
#include <cmath>
#include <numeric>

#include "fit/in_time/time_evaluators.hpp"
#include "time/hereditary.hpp"

namespace layerjkr::detail {

template <class T>
RelaxationKernel<T> kernel_at(const RelaxationLaw& law, const CurveParameters<T>& p, double t_lo, double t_hi) {
  switch (law.kind) {
    case RelaxationLaw::Kind::prony:
      if (law.g.size() == 1) {
        const T ratio = p.E_inf / p.E;  // E_inf/E: psi = ratio + (1 - ratio) exp(-t/tau)
        return prony_kernel<T>(ratio, {T(1.0) - ratio}, {p.tau});
      } else if (law.two_term_form) {  // E(t) = E_inf + (E - E_inf - E_2) exp(-t/tau) + E_2 exp(-t/tau_2)
        const T r_inf = p.E_inf / p.E, r_2 = p.E_2 / p.E;
        return prony_kernel<T>(r_inf, {T(1.0) - r_inf - r_2, r_2}, {p.tau, p.tau_2});
      } else {
        std::vector<T> g, tau;
        for (std::size_t i = 0; i < law.g.size(); ++i) {
          g.push_back(T(law.g[i]));
          tau.push_back(T(law.tau[i]));
        }
        return prony_kernel<T>(T(1.0 - std::accumulate(law.g.begin(), law.g.end(), 0.0)), g, tau);
      }
    case RelaxationLaw::Kind::power_law:
      // The plateau law holds E_inf in Pa (free or the scene's): its ratio moves with E.
      return power_law_kernel<T>(p.beta, law.t0, t_lo, t_hi, law.plateau_form ? T(p.E_inf / p.E) : T(0.0));
    case RelaxationLaw::Kind::fractional:
      return fractional_kernel<T>(p.beta, p.tau, t_lo, t_hi, law.plateau_form ? T(p.E_inf / p.E) : T(0.0));
    case RelaxationLaw::Kind::elastic:
      break;
  }
  return prony_kernel<T>(T(1.0), {}, {});
}

template RelaxationKernel<double> kernel_at(const RelaxationLaw&, const CurveParameters<double>&, double, double);

HereditaryEvaluator::HereditaryEvaluator(const CurveModel& model, const ParameterMap& map, const FitData& data,
                                         const RelaxationLaw& law)
    : model_(model), map_(map), data_(data), law_(law), radii_(model, map, data) {
  time_scales(data.t, &t_lo_, &t_hi_);
  a_cache_.assign(data.P.size(), 0.0);
}

bool HereditaryEvaluator::evaluate(const double* x, bool jacobian) {
  const std::size_t n_free = map_.free.size();
  const bool same_point = have_cache_ && std::equal(x_cache_.begin(), x_cache_.end(), x);
  if (same_point && (have_jac_ || !jacobian)) return cache_ok_;
  x_cache_.assign(x, x + n_free);
  have_cache_ = true;
  have_jac_ = jacobian;
  if (!jacobian) cache_ok_ = sweep<double>(x, false);
  else if (n_free + 1 <= 2) cache_ok_ = sweep<Jet2>(x, true);
  else if (n_free + 1 <= 4) cache_ok_ = sweep<Jet4>(x, true);
  else cache_ok_ = sweep<Jet8>(x, true);
  return cache_ok_;
}

template <class J>
bool HereditaryEvaluator::sweep(const double* x, bool jacobian) {
  constexpr bool kJet = !std::is_same_v<J, double>;
  const std::size_t n_free = map_.free.size(), n = data_.P.size();
  CurveParameters<double> p;
  double delta0 = 0.0, P0 = 0.0;
  map_.physical(x, &p, &delta0, &P0);
  const bool prony1 = law_.kind == RelaxationLaw::Kind::prony && law_.g.size() == 1;
  if (!(p.E > 0.0 && std::isfinite(p.E)) || !std::isfinite(delta0) || !std::isfinite(P0)) return false;
  if (prony1 && !(p.E_inf >= 0.0 && std::isfinite(p.E_inf) && p.tau > 0.0 && std::isfinite(p.tau))) return false;
  if (law_.kind == RelaxationLaw::Kind::power_law && !(p.beta >= 0.0 && p.beta < 1.0)) return false;
  if (law_.kind == RelaxationLaw::Kind::fractional &&
      !(p.beta >= fractional::kBetaMin && p.beta <= fractional::kBetaMax && p.tau > 0.0 && std::isfinite(p.tau)))
    return false;
  if (law_.plateau_form && !(p.E_inf >= 0.0 && p.E_inf < p.E)) return false;
  if (law_.two_term_form && !(p.E_inf >= 0.0 && p.E_2 >= 0.0 && p.E_inf + p.E_2 <= p.E && p.tau > 0.0 &&
                              p.tau_2 > 0.0 && std::isfinite(p.tau) && std::isfinite(p.tau_2)))
    return false;
  p.s = 0.0;  // the elastic force: no adhesion
  CurveParameters<J> pj;
  J d0j(delta0), P0j(P0), dragj(map_.drag(x));
  if constexpr (kJet) {
    std::array<J, J::DIMENSION> xj;
    for (std::size_t j = 0; j < n_free; ++j) xj[j] = J(x[j], static_cast<int>(j));
    map_.physical(xj.data(), &pj, &d0j, &P0j);
    dragj = map_.drag(xj.data());
    pj.s = J(0.0);
  } else {
    pj = p;
  }
  std::vector<J> d(n), PH(n, J(0.0));
  const double lo = std::max(model_.min_radius(), 0.0);
  for (std::size_t i = 0; i < n; ++i) {
    d[i] = J(data_.delta[i]) - d0j;
    const double di = data_.delta[i] - delta0;
    if (!(di > 0.0)) continue;
    double P = 0.0;
    const double a = radii_.solve_radius(p, di, lo, a_cache_[i] > lo ? a_cache_[i] : 0.0, &P);
    if (!(std::isfinite(a) && a > 0.0)) return false;
    a_cache_[i] = a;
    if constexpr (kJet) {
      // P_H at the radius where delta_H(a) = delta_i - delta0, a moving with the parameters.
      constexpr int kA = J::DIMENSION - 1;
      J dj, Pj;
      model_.evaluate(J(a, kA), pj, &dj, &Pj);
      const double slope = dj.v[kA];
      if (!(slope > 0.0)) return false;
      J out(Pj.a);
      for (std::size_t j = 0; j < n_free; ++j) out.v[j] = Pj.v[j] + Pj.v[kA] * (-d0j.v[j] - dj.v[j]) / slope;
      PH[i] = out;
    } else {
      PH[i] = P;
    }
  }
  HereditaryResult<J> h;
  if (!hereditary_response(data_.t, d, PH, kernel_at(law_, pj, t_lo_, t_hi_), &h)) return false;
  r_.assign(n, 0.0);
  P_fit_.assign(n, 0.0);
  detached_.assign(n, 0);
  if (jacobian) J_.assign(n * n_free, 0.0);
  contact_count_ = 0;
  const double F = map_.F;
  for (std::size_t i = 0; i < n; ++i) {
    const J Pi = data_.velocity.empty() ? h.P[i] + P0j : h.P[i] + P0j + dragj * data_.velocity[i];
    const double value = value_of(Pi);
    if (!std::isfinite(value)) return false;
    const double sw = data_.sqrt_weight[i];
    P_fit_[i] = value;
    r_[i] = sw * (value - data_.P[i]) / F;
    if constexpr (kJet)
      for (std::size_t j = 0; j < n_free; ++j) J_[i * n_free + j] = sw * Pi.v[j] / F;
    const ContactPhase phase = h.phase[i];
    if (phase == ContactPhase::loading || phase == ContactPhase::holding || phase == ContactPhase::receding)
      ++contact_count_;
    detached_[i] = phase == ContactPhase::separated && data_.retract[i] ? 1 : 0;
  }
  return true;
}

}  // namespace layerjkr::detail
