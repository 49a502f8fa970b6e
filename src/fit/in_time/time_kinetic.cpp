// Crack kinetics fitted in time: equilibrium on approach and dwell, the retract by the crack's ODE
// (time_evaluators.hpp).
#include <algorithm>
#include <cmath>

#include "time/crack_kinetics.hpp"
#include "fit/in_time/time_evaluators.hpp"

namespace layerjkr::detail {
namespace {

constexpr double kPi = 3.14159265358979323846;
// Central differences of the retract's forces, in the dimensionless parameters: ~1e-4 relative in
// a modulus or a rate, 1e-4 of the data's length and force scales in delta0 and P0, against the
// integrator's 1e-10.
constexpr double kStep = 1e-4;

}  // namespace

struct KineticEvaluator::Retract {
  std::vector<double> P;         // at each retract sample
  std::vector<char> in_contact;  // not yet separated
};

KineticEvaluator::KineticEvaluator(const CurveModel& model, const ParameterMap& map, const FitData& data)
    : model_(model), map_(map), data_(data) {
  for (std::size_t i = 0; i < data.P.size(); ++i) (data.retract[i] ? retract_ : equilibrium_).push_back(i);
  turn_ = retract_.empty() ? data.P.size() - 1 : (retract_.front() > 0 ? retract_.front() - 1 : 0);
  FitData& e = equilibrium_data_;
  for (std::size_t i : equilibrium_) {
    e.delta.push_back(data.delta[i]);
    e.P.push_back(data.P[i]);
    e.sqrt_weight.push_back(data.sqrt_weight[i]);
    e.retract.push_back(false);
  }
  e.baseline = data.baseline;
  e.noise = data.noise;
  equilibrium_ev_ = std::make_unique<CurveEvaluator>(model, map, equilibrium_data_, 0.0);
}

KineticEvaluator::~KineticEvaluator() = default;

void KineticEvaluator::invalidate() {
  for (std::size_t k = 0; k < equilibrium_.size(); ++k) equilibrium_data_.sqrt_weight[k] = data_.sqrt_weight[equilibrium_[k]];
  equilibrium_ev_->invalidate();
  have_cache_ = false;
}

bool KineticEvaluator::retract_at(const double* x, Retract* out) const {
  out->P.assign(retract_.size(), 0.0);
  out->in_contact.assign(retract_.size(), 0);
  if (retract_.empty()) return true;
  CurveParameters<double> p;
  double delta0 = 0.0, P0 = 0.0;
  map_.physical(x, &p, &delta0, &P0);
  const double w0 = p.s * p.s;
  if (!(w0 > 0.0) || !(p.v_star > 0.0) || !(p.n > 0.0) || !std::isfinite(p.v_star) || !std::isfinite(p.n)) return false;
  // The medium's non-adhesive state from its JKR curve at w = 0 and w = 1 J/m^2: the transform's
  // adhesive shifts give S = dP/d delta and S' (P_H - P_1 = sqrt(4 pi a S^2/S'), delta_H - delta_1 =
  // sqrt(4 pi a / S')).
  CurveParameters<Jet1> pj{Jet1(p.K), Jet1(p.G), Jet1(p.E), Jet1(0.0), Jet1(p.R), Jet1(p.sigma0)};
  CurveParameters<Jet1> p1 = pj;
  p1.s = Jet1(1.0);
  const StateAt state = [&](double a) {
    Jet1 d, P, d1, P1;
    model_.evaluate(Jet1(a, 0), pj, &d, &P);
    model_.evaluate(Jet1(a, 0), p1, &d1, &P1);
    NonAdhesiveState s;
    s.a = a;
    s.P_H = P.a;
    s.delta_H = d.a;
    const double gap = d.a - d1.a;
    s.S = (P.a - P1.a) / gap;
    s.dS_da = 4.0 * kPi * a / (gap * gap);
    return s;
  };
  // The equilibrium contact at the turn, on the branch stable under fixed grips.
  const double d_turn = data_.delta[turn_] - delta0;
  BranchStart grips;
  if (!equilibrium_ev_->branch_start(p, StartKind::fixed_grips, &grips)) return false;
  if (!(d_turn > grips.delta)) return true;  // no contact at the turn: the retract is free
  const double a_turn = equilibrium_ev_->solve_radius(p, d_turn, grips.a, grips.a);
  if (!(std::isfinite(a_turn) && a_turn > 0.0)) return false;
  KineticStepper stepper(state, w0, CrackKinetics{p.v_star, p.n}, RetractControl::fixed_grips, 0.0);
  stepper.start(data_.t[turn_], a_turn, d_turn);
  for (std::size_t k = 0; k < retract_.size(); ++k) {
    const std::size_t i = retract_[k];
    if (!stepper.advance(data_.t[i], data_.delta[i] - delta0)) return false;
    out->P[k] = stepper.point().P;
    out->in_contact[k] = stepper.separated() ? 0 : 1;
    if (!std::isfinite(out->P[k])) return false;
  }
  return true;
}

bool KineticEvaluator::evaluate(const double* x, bool jacobian) {
  const std::size_t n_free = map_.free.size(), n = data_.P.size();
  const bool same_point = have_cache_ && std::equal(x_cache_.begin(), x_cache_.end(), x);
  if (same_point && (have_jac_ || !jacobian)) return cache_ok_;
  x_cache_.assign(x, x + n_free);
  have_cache_ = true;
  have_jac_ = jacobian;
  cache_ok_ = false;
  if (!equilibrium_ev_->evaluate(x, jacobian)) return false;
  Retract at;
  if (!retract_at(x, &at)) return false;
  CurveParameters<double> p;
  double delta0 = 0.0, P0 = 0.0;
  map_.physical(x, &p, &delta0, &P0);
  r_.assign(n, 0.0);
  P_fit_.assign(n, 0.0);
  detached_.assign(n, 0);
  if (jacobian) J_.assign(n * n_free, 0.0);
  contact_count_ = equilibrium_ev_->in_contact();
  const double F = map_.F;
  for (std::size_t k = 0; k < equilibrium_.size(); ++k) {
    const std::size_t i = equilibrium_[k];
    r_[i] = equilibrium_ev_->residuals()[k];
    P_fit_[i] = equilibrium_ev_->predicted()[k];
    if (jacobian)
      std::copy_n(equilibrium_ev_->jacobian().begin() + static_cast<long>(k * n_free), n_free, J_.begin() + static_cast<long>(i * n_free));
  }
  for (std::size_t k = 0; k < retract_.size(); ++k) {
    const std::size_t i = retract_[k];
    P_fit_[i] = P0 + at.P[k];
    r_[i] = data_.sqrt_weight[i] * (P_fit_[i] - data_.P[i]) / F;
    detached_[i] = at.in_contact[k] ? 0 : 1;
    contact_count_ += at.in_contact[k] ? 1 : 0;
  }
  if (jacobian && !retract_.empty()) {
    // contact_difference: central where the contact holds or has let go on both sides.
    std::vector<double> xp(x, x + n_free), xm(x, x + n_free);
    for (std::size_t j = 0; j < n_free; ++j) {
      if (map_.free[j] == FitParameter::P0) {  // the baseline moves every force alike: no ODE to solve again
        for (std::size_t i : retract_) J_[i * n_free + j] = data_.sqrt_weight[i] * map_.F / F;
        continue;
      }
      xp[j] = x[j] + kStep;
      xm[j] = x[j] - kStep;
      Retract plus, minus;
      const bool ok_p = retract_at(xp.data(), &plus), ok_m = retract_at(xm.data(), &minus);
      double dP0p = 0.0, dP0m = 0.0;
      {
        CurveParameters<double> q;
        double d0 = 0.0;
        map_.physical(xp.data(), &q, &d0, &dP0p);
        map_.physical(xm.data(), &q, &d0, &dP0m);
      }
      for (std::size_t k = 0; k < retract_.size(); ++k) {
        const std::size_t i = retract_[k];
        const bool same_p = ok_p && plus.in_contact[k] == at.in_contact[k];
        const bool same_m = ok_m && minus.in_contact[k] == at.in_contact[k];
        const double dP = contact_difference(same_p, same_m, plus.P[k] + dP0p, at.P[k] + P0, minus.P[k] + dP0m, kStep);
        J_[i * n_free + j] = data_.sqrt_weight[i] * dP / F;
      }
      xp[j] = xm[j] = x[j];
    }
  }
  cache_ok_ = true;
  return true;
}

}  // namespace layerjkr::detail
