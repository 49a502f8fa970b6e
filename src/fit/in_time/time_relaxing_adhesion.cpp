// Adhesion on a relaxing half-space fitted in time (time_evaluators.hpp): the Maugis-Dugdale
// contact stepped in time over the measured indentation (viscoelastic_adhesion.hpp).
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "fit/in_time/time_evaluators.hpp"
#include "layerjkr/error.hpp"
#include "layerjkr/viscoelastic_adhesion.hpp"

namespace layerjkr::detail {
namespace {

// Central differences in the dimensionless parameters (a modulus, a time or sqrt(w) moves by 1e-4
// of itself, delta0 by 1e-4 of the length scale), against a stepping whose grid and step are held.
constexpr double kStep = 1e-4;

// The law at the parameters p, as kernel_at reads them.
RelaxationLaw law_at(const RelaxationLaw& law, const CurveParameters<double>& p) {
  if (law.kind == RelaxationLaw::Kind::prony && law.g.size() == 1)
    return RelaxationLaw::standard_linear_solid(p.E_inf / p.E, p.tau);
  if (law.kind == RelaxationLaw::Kind::prony && law.two_term_form)
    return RelaxationLaw::maxwell2(p.E_inf / p.E, p.tau, p.E_2 / p.E, p.tau_2);
  if (law.kind == RelaxationLaw::Kind::fractional)
    return RelaxationLaw::fractional_sls(p.beta, p.tau, law.plateau_form ? p.E_inf / p.E : 0.0);
  return law;
}

}  // namespace

RelaxingAdhesionEvaluator::RelaxingAdhesionEvaluator(const Profile& profile, double nu, const ParameterMap& map,
                                                     const FitData& data, const RelaxationLaw& law)
    : profile_(profile), nu_(nu), map_(map), data_(data), law_(law) {}

bool RelaxingAdhesionEvaluator::forces_at(const double* x, Forces* out, const RelaxingDugdaleOptions* stepping) {
  const std::size_t n = data_.P.size();
  out->P.assign(n, 0.0);
  out->in_contact.assign(n, 0);
  CurveParameters<double> p;
  double delta0 = 0.0, P0 = 0.0;
  map_.physical(x, &p, &delta0, &P0);
  const double w = p.s * p.s, E_star = p.E / (1.0 - nu_ * nu_);
  if (!(E_star > 0.0 && std::isfinite(E_star)) || !(w > 0.0 && std::isfinite(w)) ||
      !(p.sigma0 > 0.0 && std::isfinite(p.sigma0)) || !std::isfinite(delta0))
    return false;
  try {
    const RelaxationLaw law = law_at(law_, p);
    // The contact snaps in at the instantaneous elastic contact's zero load, as simulate's does.
    // The Jacobian's steps in the law, delta0, P0 and drag leave it unchanged: the last is kept.
    if (!(snap_key_[0] == E_star && snap_key_[1] == w && snap_key_[2] == p.sigma0)) {
      snap_ = dugdale_zero_load_indentation(profile_, E_star, w, p.sigma0);
      snap_key_ = {E_star, w, p.sigma0};
    }
    const double d_snap = snap_;
    std::size_t first = n;
    for (std::size_t i = 0; i < n && first == n; ++i)
      if (!data_.retract[i] && data_.delta[i] - delta0 >= d_snap) first = i;
    if (first == n) return true;  // never in contact
    std::vector<double> t(data_.t.begin() + static_cast<long>(first), data_.t.end()), d;
    for (std::size_t i = first; i < n; ++i) d.push_back(data_.delta[i] - delta0);
    if (!stepping_set_) {
      // The grid and the step are chosen once, at the first parameters, and then held: a choice
      // that moved with them would put steps into the cost. Twice the extent leaves room for the
      // parameters to grow the zone; twice the points keep the spacing.
      // The step is converged to a tenth of the data's noise (within [1e-5, 1e-3] of the largest
      // force), so the model's own error moves no estimate by more than a fraction of its error bar.
      RelaxingDugdaleOptions first_choice;
      double span = 0.0;
      for (double P : data_.P) span = std::max(span, std::abs(P - data_.baseline));
      if (span > 0.0 && data_.noise > 0.0) first_choice.tolerance = std::clamp(0.1 * data_.noise / span, 1e-5, 1e-3);
      const RelaxingDugdaleResponse r = relaxing_dugdale_response(profile_, E_star, law, w, p.sigma0, t, d, first_choice);
      stepping_.extent = 2.0 * r.extent;
      stepping_.grid_points = 2 * r.grid_points - 1;
      stepping_.substeps = std::max(r.substeps, 2);
      stepping_set_ = true;
    }
    const RelaxingDugdaleResponse r =
        relaxing_dugdale_response(profile_, E_star, law, w, p.sigma0, t, d, stepping ? *stepping : stepping_);
    for (std::size_t k = 0; k < r.separated_at; ++k) {
      out->P[first + k] = r.P[k];
      out->in_contact[first + k] = 1;
    }
    out->force_error = r.force_error;
    out->substeps = r.substeps;
    return true;
  } catch (const Error&) {
    return false;
  }
}

bool RelaxingAdhesionEvaluator::evaluate(const double* x, bool jacobian) {
  const std::size_t n_free = map_.free.size(), n = data_.P.size();
  const bool same_point = have_cache_ && std::equal(x_cache_.begin(), x_cache_.end(), x);
  if (same_point && (have_jac_ || !jacobian)) return cache_ok_;
  x_cache_.assign(x, x + n_free);
  have_cache_ = true;
  have_jac_ = jacobian;
  cache_ok_ = false;
  Forces at;
  if (!forces_at(x, &at)) return false;
  CurveParameters<double> p;
  double delta0 = 0.0, P0 = 0.0;
  map_.physical(x, &p, &delta0, &P0);
  const double drag = map_.drag(x), F = map_.F;
  const auto velocity = [&](std::size_t i) { return data_.velocity.empty() ? 0.0 : data_.velocity[i]; };
  r_.assign(n, 0.0);
  P_fit_.assign(n, 0.0);
  detached_.assign(n, 0);
  contact_count_ = 0;
  bool touched = false;
  for (std::size_t i = 0; i < n; ++i) {
    P_fit_[i] = P0 + at.P[i] + drag * velocity(i);
    r_[i] = data_.sqrt_weight[i] * (P_fit_[i] - data_.P[i]) / F;
    touched = touched || at.in_contact[i];
    detached_[i] = data_.retract[i] && touched && !at.in_contact[i] ? 1 : 0;
    contact_count_ += at.in_contact[i] ? 1 : 0;
  }
  if (jacobian) {
    J_.assign(n * n_free, 0.0);
    std::vector<double> xp(x, x + n_free), xm(x, x + n_free);
    for (std::size_t j = 0; j < n_free; ++j) {
      xp[j] = x[j] + kStep;
      xm[j] = x[j] - kStep;
      CurveParameters<double> q;
      double d0 = 0.0, P0p = 0.0, P0m = 0.0;
      map_.physical(xp.data(), &q, &d0, &P0p);
      map_.physical(xm.data(), &q, &d0, &P0m);
      const double drag_p = map_.drag(xp.data()), drag_m = map_.drag(xm.data());
      const FitParameter f = map_.free[j];
      if (f == FitParameter::P0 || f == FitParameter::drag) {  // the force moves alike with or without contact
        for (std::size_t i = 0; i < n; ++i)
          J_[i * n_free + j] = data_.sqrt_weight[i] * (P0p - P0m + (drag_p - drag_m) * velocity(i)) / (2.0 * kStep * F);
      } else {
        Forces plus, minus;
        const bool ok_p = forces_at(xp.data(), &plus), ok_m = forces_at(xm.data(), &minus);
        for (std::size_t i = 0; i < n; ++i) {
          const bool same_p = ok_p && plus.in_contact[i] == at.in_contact[i];
          const bool same_m = ok_m && minus.in_contact[i] == at.in_contact[i];
          const double dP = contact_difference(same_p, same_m, plus.P[i], at.P[i], minus.P[i], kStep);
          J_[i * n_free + j] = data_.sqrt_weight[i] * dP / F;
        }
      }
      xp[j] = xm[j] = x[j];
    }
  }
  cache_ok_ = true;
  return true;
}

std::string RelaxingAdhesionEvaluator::stepping_note(const double* x) {
  // The held step's error by halving it (second order: a third of the change), against the noise.
  Forces held, halved;
  RelaxingDugdaleOptions finer = stepping_;
  finer.substeps = 2 * stepping_.substeps;
  if (!stepping_set_ || !forces_at(x, &held) || !forces_at(x, &halved, &finer)) return std::string();
  double change = 0.0;
  for (std::size_t i = 0; i < held.P.size(); ++i) change = std::max(change, std::abs(held.P[i] - halved.P[i]));
  char text[320];
  std::snprintf(text, sizeof text,
                "adhesion on the relaxing half-space: Maugis-Dugdale stepped in time with %d steps per sample on %d "
                "points over %.3g m, held through the fit; its error at the answer, estimated by halving the step, is "
                "%.2g N (%.2g of the data's noise)",
                stepping_.substeps, stepping_.grid_points, stepping_.extent, change / 3.0,
                data_.noise > 0.0 ? change / 3.0 / data_.noise : 0.0);
  return text;
}

}  // namespace layerjkr::detail
