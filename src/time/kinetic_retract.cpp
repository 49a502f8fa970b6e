// A retract with rate-dependent adhesion, from equilibrium to the loss of contact (kinetics.hpp).
#include "layerjkr/kinetics.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <boost/math/tools/roots.hpp>

#include "time/crack_kinetics.hpp"
#include "layerjkr/error.hpp"

namespace layerjkr {
namespace {

// Below this kinetic correction (rho^n, rho the drive's crack speed over v_star) the retract is at
// equilibrium to within it: answered by the JKR limit instead of integrated (v_star = 1e50 failed
// at once, a retract at 1e-300 m/s reported +1e-19 N, at 1e-20 m/s - rho^n = 1.6e-8 - and n = 10
// at rho = 0.14 - rho^n = 3e-9 - the integrator crawled 2 million steps and failed).
constexpr double kEquilibriumCorrection = 1e-6;
// Beyond this many times v_star the pull-off grows without bound and the stiff ODE takes more
// steps than any retract is worth (rho = 1.4e15 failed after 60 s; 1.4e12 takes seconds).
constexpr double kMaxRateRatio = 1e12;

// The equilibrium contact's control value: the force, the approach, or the base's position.
double control_value(const RetractDrive& d, const AdhesiveState& s) {
  switch (d.control) {
    case RetractControl::load: return s.P;
    case RetractControl::cantilever: return s.delta + s.P / d.stiffness;
    default: return s.delta;
  }
}

CriticalPoint point_of(const AdhesiveState& s) { return {s.a, s.P, s.delta}; }

// Where a cantilever of stiffness k lets go of the JKR curve: dP/d delta = -k, between the
// pull-off (dP/d delta = 0) and the fixed-grips point (infinite), or the smallest radius.
CriticalPoint cantilever_release(const AdhesiveSolution& sol, double k, double a_pull_off, double a_floor) {
  const auto slope_plus_k = [&](double a) {
    const double h = 1e-6 * a;
    const AdhesiveState lo = sol.at(a - h), hi = sol.at(a + h);
    const double dd = hi.delta - lo.delta, dP = hi.P - lo.P;
    return dP + k * dd;  // (dP/d delta + k) d delta, negative below the release on the grips-stable side
  };
  double lo = a_floor;
  if (const auto grips = sol.fixed_grips_critical()) lo = grips->a * (1.0 + 1e-9);
  const double hi = a_pull_off;
  if (!(slope_plus_k(lo) < 0.0 && slope_plus_k(hi) > 0.0)) return point_of(sol.at(lo));
  std::uintmax_t it = 200;
  const auto r = boost::math::tools::toms748_solve(slope_plus_k, lo, hi, boost::math::tools::eps_tolerance<double>(45), it);
  return point_of(sol.at(0.5 * (r.first + r.second)));
}

// The lowest force over the steps, refined by the parabola through its neighbours.
void lowest_force(KineticRetract& r, const AdhesiveSolution& sol, RetractControl control) {
  const std::size_t n = r.P.size();
  std::size_t i = static_cast<std::size_t>(std::min_element(r.P.begin(), r.P.end()) - r.P.begin());
  r.pull_off = {r.a[i], r.P[i], r.delta[i]};
  r.pull_off_time = r.t[i];
  if (control == RetractControl::load || i == 0 || i + 1 >= n) return;
  const double t0 = r.t[i - 1], t1 = r.t[i], t2 = r.t[i + 1];
  const double P0 = r.P[i - 1], P1 = r.P[i], P2 = r.P[i + 1];
  const double d01 = (P1 - P0) / (t1 - t0), d12 = (P2 - P1) / (t2 - t1), curvature = (d12 - d01) / (t2 - t0);
  if (!(curvature > 0.0)) return;
  const double tv = 0.5 * (t0 + t1) - d01 / (2.0 * curvature);  // where the parabola's slope vanishes
  if (!(tv > t0 && tv < t2)) return;
  const double Pv = P1 + d01 * (tv - t1) + curvature * (tv - t0) * (tv - t1);
  const double f = (tv - t1) / ((tv > t1 ? t2 : t0) - t1);
  const std::size_t j = tv > t1 ? i + 1 : i - 1;
  r.pull_off = {r.a[i] + f * (r.a[j] - r.a[i]), Pv, r.delta[i] + f * (r.delta[j] - r.delta[i])};
  r.pull_off_time = tv;
  (void)sol;
}

// The retract at equilibrium (G = w0 throughout): the JKR curve from a0 to the separation, each
// state at the time the control reaches it.
void equilibrium_retract(KineticRetract& r, const AdhesiveSolution& sol, const RetractDrive& drive, double a0,
                         double c0) {
  r.at_equilibrium = true;
  const double a_end = r.equilibrium_separation.a;
  constexpr int kSamples = 400;
  for (int k = 0; k <= kSamples; ++k) {
    const double a = a0 + (a_end - a0) * k / kSamples;
    const AdhesiveState s = sol.at(a);
    r.t.push_back(std::max(0.0, (c0 - control_value(drive, s)) / drive.rate));
    r.a.push_back(a);
    r.P.push_back(s.P);
    r.delta.push_back(s.delta);
    r.G.push_back(sol.w());
  }
  for (std::size_t k = 0; k < r.a.size(); ++k) {
    const std::size_t i = k == 0 ? 0 : k - 1, j = k + 1 < r.a.size() ? k + 1 : k;
    r.speed.push_back(r.t[j] > r.t[i] ? -(r.a[j] - r.a[i]) / (r.t[j] - r.t[i]) : 0.0);
  }
  r.pull_off = r.equilibrium_pull_off;
  const AdhesiveState po = sol.at(r.pull_off.a);
  r.separation_time = r.t.back();
  // The lowest force comes no later than the release (under a lever of 1e-300 N/m the two points
  // coincide and P/k's rounding could order them either way).
  r.pull_off_time = std::min(std::max(0.0, (c0 - control_value(drive, po)) / drive.rate), r.separation_time);
}

}  // namespace

void RetractDrive::validate() const {
  if (control == RetractControl::automatic)
    throw DomainError("RetractDrive", "control (automatic)", 0.0, "load, fixed_grips or cantilever");
  if (!(rate > 0.0 && std::isfinite(rate)))
    throw DomainError("RetractDrive", "rate", rate, control == RetractControl::load ? "finite and > 0 [N/s]" : "finite and > 0 [m/s]");
  if (control == RetractControl::cantilever && !(stiffness > 0.0 && std::isfinite(stiffness)))
    throw DomainError("RetractDrive", "stiffness", stiffness, "finite and > 0 [N/m] (a cantilever's)");
}

std::string RetractDrive::describe() const {
  switch (control) {
    case RetractControl::load: return "load at " + format_double(rate) + " N/s";
    case RetractControl::cantilever:
      return "a cantilever of " + format_double(stiffness) + " N/m at " + format_double(rate) + " m/s";
    default: return "fixed grips at " + format_double(rate) + " m/s";
  }
}

void KineticRetractOptions::validate() const {
  drive.validate();
  detail::require_finite("KineticRetractOptions", "start_force", start_force);
  if (!(max_step_fraction > 0.0 && max_step_fraction <= 0.1))
    throw DomainError("KineticRetractOptions", "max_step_fraction", max_step_fraction, "(0, 0.1]");
  if (max_steps < 100) throw DomainError("KineticRetractOptions", "max_steps", static_cast<double>(max_steps), ">= 100");
}

KineticRetract kinetic_retract(const ContactModelPtr& model, double w0, const CrackKinetics& kinetics,
                               const KineticRetractOptions& options) {
  options.validate();
  kinetics.validate();
  detail::require_positive("kinetic_retract", "w0", w0);
  const RetractDrive& drive = options.drive;
  const AdhesiveSolution sol(model, w0);
  const auto po = sol.pull_off();
  if (!po) throw NumericalError("kinetic_retract: the JKR curve has no pull-off to start above");
  const double a0 = sol.contact_radius_at_force(options.start_force);  // DomainError below the pull-off
  const AdhesiveState start = sol.at(a0);

  KineticRetract r;
  r.equilibrium_pull_off = *po;
  const double a_floor = 1e-6 * a0;
  switch (drive.control) {
    case RetractControl::load: r.equilibrium_separation = *po; break;
    case RetractControl::cantilever: r.equilibrium_separation = cantilever_release(sol, drive.stiffness, po->a, a_floor); break;
    default: {
      const auto grips = sol.fixed_grips_critical();
      r.equilibrium_separation = grips ? *grips : point_of(sol.at(a_floor));
    }
  }
  const double c0 = control_value(drive, start);
  const double c_sep = control_value(drive, AdhesiveState{r.equilibrium_separation.a, r.equilibrium_separation.a,
                                                          r.equilibrium_separation.P, r.equilibrium_separation.delta, {}});
  const double T_eq = std::max(std::abs(c0 - c_sep), 1e-9 * std::abs(c0) + 1e-300) / drive.rate;
  const double h_max = options.max_step_fraction * T_eq;
  // How fast the drive asks the crack to move: the equilibrium retract's mean crack speed, in
  // units of v_star. G/w0 - 1 = (v/v_star)^n, so rho^n is the kinetic correction's order.
  r.rate_ratio = std::abs(a0 - r.equilibrium_separation.a) / T_eq / kinetics.v_star;
  if (!(std::pow(r.rate_ratio, kinetics.n) >= kEquilibriumCorrection)) {
    equilibrium_retract(r, sol, drive, a0, c0);  // the limit v_star -> infinity, not integrated
    return r;
  }
  if (r.rate_ratio > kMaxRateRatio)
    throw DomainError("kinetic_retract", "rate", drive.rate,
                      "(0, " + format_double(drive.rate * kMaxRateRatio / r.rate_ratio) + "] " +
                          (drive.control == RetractControl::load ? "N/s" : "m/s") + ": this drive asks the crack to move " +
                          format_double(r.rate_ratio) + " times v_star (" + kinetics.describe() + "), where the " +
                          "pull-off grows without bound and the integrator cannot follow; at most " +
                          format_double(kMaxRateRatio) + " times");

  detail::KineticStepper stepper([&](double a) { return model->state(a); }, w0, kinetics, drive.control,
                                 drive.stiffness);
  stepper.start(0.0, a0, c0);
  const auto record = [&] {
    const detail::CrackPoint p = stepper.point();
    r.t.push_back(stepper.t());
    r.a.push_back(stepper.a());
    r.P.push_back(p.P);
    r.delta.push_back(p.delta);
    r.G.push_back(p.G);
    r.speed.push_back(stepper.speed());
  };
  record();
  for (std::size_t k = 0; k < options.max_steps; ++k) {
    // The control's line, extended far ahead: every step sees the same constant rate.
    const double t_far = stepper.t() + 1e3 * T_eq;
    if (!stepper.step(t_far, c0 - drive.rate * t_far, h_max))
      throw NumericalError("kinetic_retract: the integrator failed at t = " + format_double(stepper.t()) +
                           " s, a = " + format_double(stepper.a()) + " m (" + drive.describe() + ", " +
                           kinetics.describe() + ")");
    if (stepper.separated()) {
      r.separation_time = stepper.t();
      lowest_force(r, sol, drive.control);
      if (drive.control == RetractControl::load) {  // the force the contact held when it let go
        r.pull_off = {0.0, c0 - drive.rate * r.separation_time, r.delta.back()};
        r.pull_off_time = r.separation_time;
      }
      return r;
    }
    record();
  }
  throw NumericalError("kinetic_retract: the contact was not lost within " + std::to_string(options.max_steps) +
                       " steps (t = " + format_double(stepper.t()) + " s, a = " + format_double(stepper.a()) + " m; " +
                       drive.describe() + ", " + kinetics.describe() + ")");
}

std::string KineticSummary::regime() const {
  return at_equilibrium ? "equilibrium: the kinetic correction rate_ratio^n = " +
                              format_double(rate_ratio) + "^n is below " + format_double(kEquilibriumCorrection) +
                              ": the JKR limit"
                        : "kinetic";
}

std::vector<double> kinetic_pull_off_forces(const ContactModelPtr& model, double w0, const CrackKinetics& kinetics,
                                            const KineticRetractOptions& options, const std::vector<double>& rates) {
  std::vector<double> out;
  for (double rate : rates) {
    KineticRetractOptions o = options;
    o.drive.rate = rate;
    try {
      out.push_back(kinetic_retract(model, w0, kinetics, o).pull_off.P);
    } catch (const DomainError& e) {  // a sweep's rate beyond the crack's reach: no value, not no sweep
      if (e.parameter() != "rate") throw;
      out.push_back(std::numeric_limits<double>::quiet_NaN());
    }
  }
  return out;
}

}  // namespace layerjkr
