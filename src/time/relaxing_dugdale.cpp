// The Maugis-Dugdale contact on a relaxing half-space, stepped in time (viscoelastic_adhesion.hpp,
// docs/theory.md s.8a): each grid point x carries its own hereditary state, and each step solves
// for the contact radius a alone - continuity of g at a gives the zone's radius c in closed form,
// and the gap at c equal to h0 is one equation in a.
#include "layerjkr/viscoelastic_adhesion.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <utility>

#include <boost/math/quadrature/gauss.hpp>
#include <boost/math/tools/roots.hpp>

#include "layerjkr/error.hpp"
#include "relaxation_kernel.hpp"
#include "relaxing_dugdale_stepper.hpp"

namespace layerjkr {

// The stepping's pieces (relaxing_dugdale_stepper.hpp), in this file only.
using namespace detail::dugdale;

namespace {

void check_inputs(double E_star, const RelaxationLaw& law, double w, double sigma0, const std::vector<double>& t,
                  const std::vector<double>& delta) {
  auto positive = [](const char* name, double v) {
    if (!(v > 0.0) || !std::isfinite(v))
      throw DomainError("relaxing_dugdale_response", name, v, "finite and > 0");
  };
  positive("E_star", E_star), positive("w", w), positive("sigma0", sigma0);
  law.validate();
  if (law.kind == RelaxationLaw::Kind::power_law)
    throw DomainError("relaxing_dugdale_response", "law (" + law.describe() + ": an infinite instantaneous modulus, "
                      "so the contact cannot snap in)", law.beta,
                      "a law with a finite instantaneous modulus: elastic, prony, sls, maxwell2, fractional_sls, "
                      "fractional_maxwell");
  if (t.size() != delta.size() || t.size() < 2)
    throw InputError("relaxing_dugdale_response: t and delta must have the same length, at least 2 (got " +
                     std::to_string(t.size()) + " and " + std::to_string(delta.size()) + ")");
  for (std::size_t i = 0; i < t.size(); ++i)
    if (!std::isfinite(t[i]) || !std::isfinite(delta[i]) || (i > 0 && !(t[i] > t[i - 1])))
      throw InputError("relaxing_dugdale_response: sample " + std::to_string(i) + " (t = " + format_double(t[i]) +
                       " s, delta = " + format_double(delta[i]) + " m) is not finite or its time does not increase");
}

}  // namespace

void RelaxingDugdaleOptions::validate() const {
  if (grid_points < 201)
    throw DomainError("RelaxingDugdaleOptions", "grid_points", grid_points, ">= 201");
  if (!(extent >= 0.0) || !std::isfinite(extent))
    throw DomainError("RelaxingDugdaleOptions", "extent [m]", extent, "0 (automatic) or finite > 0");
  if (substeps < 0) throw DomainError("RelaxingDugdaleOptions", "substeps", substeps, "0 (automatic) or >= 1");
  if (!(cantilever_stiffness >= 0.0) || !std::isfinite(cantilever_stiffness))
    throw DomainError("RelaxingDugdaleOptions", "cantilever_stiffness [N/m]", cantilever_stiffness,
                      "0 (fixed grips) or finite > 0");
  if (!(tolerance > 0.0 && tolerance < 1.0))
    throw DomainError("RelaxingDugdaleOptions", "tolerance", tolerance, "in (0, 1)");
  if (max_substeps < 2) throw DomainError("RelaxingDugdaleOptions", "max_substeps", max_substeps, ">= 2");
}

namespace {

// One level of the time step: `substeps` equal steps per sample interval.
RelaxingDugdaleResponse run_level(const Profile& profile, double E_star, const RelaxationLaw& law, double w,
                                  double sigma0, const std::vector<double>& t, const std::vector<double>& delta,
                                  const RelaxingDugdaleOptions& o, int substeps) {
  const std::size_t n = t.size();
  double t_lo = 0.0, t_hi = 0.0;
  detail::time_scales(t, &t_lo, &t_hi);
  const auto K = detail::kernel_of(law, t_lo / substeps, t_hi);
  const double h0 = w / sigma0, d_max = *std::max_element(delta.begin(), delta.end());
  // The elastic contact at the modulus the history's longest time leaves bounds the zone.
  const double a_scale = std::sqrt(std::max(d_max, h0) * profile.length_scale());
  double extent = o.extent;
  if (extent == 0.0) {
    const ElasticDugdale relaxed(profile, E_star / kPi * K.value(t_hi), sigma0, h0);
    const double a = relaxed.largest_root(d_max, 1e-4 * a_scale, 1e3 * a_scale);
    if (a == 0.0)
      throw InputError("relaxing_dugdale_response: no contact at the deepest indentation " + format_double(d_max) + " m");
    extent = 1.5 * relaxed.zone(a, d_max);
  }
  if (!(extent < profile.max_radius()))
    throw DomainError("relaxing_dugdale_response", "the adhesive zone's radius [m]", extent / 1.5,
                      "below the profile's largest radius " + format_double(profile.max_radius()) + " m");
  DugdaleStepper s(profile, E_star, K, sigma0, h0, extent, o.grid_points);
  RelaxingDugdaleResponse out;
  out.extent = extent, out.grid_points = o.grid_points;
  out.P.assign(n, 0.0), out.a.assign(n, 0.0), out.c.assign(n, 0.0);
  out.tip = delta;  // free once lost: the unbent lever's tip is at its base
  out.separated_at = n;
  const double k_lever = o.cantilever_stiffness;
  double tip = delta[0];
  // The snap-in: the instantaneous elastic contact at delta[0], its largest radius.
  const ElasticDugdale instantaneous(profile, E_star / kPi * K.value(0.0) , sigma0, h0);
  double a = instantaneous.largest_root(delta[0], 1e-4 * a_scale, 0.6 * extent);
  s.prepare(0.0, delta[0]);
  if (a > 0.0) a = nearest_root(s, a, 0.0);
  if (a == 0.0)
    throw InputError("relaxing_dugdale_response: no adhesive contact at delta[0] = " + format_double(delta[0]) +
                     " m (the history must start where the tip snaps in)");
  double a_max = a, da = 0.0;
  for (std::size_t i = 0;; ++i) {
    s.commit(a);
    out.a[i] = a, out.c[i] = s.zone(a), out.P[i] = s.force(a), out.tip[i] = tip;
    if (i + 1 == n) break;
    const double dt = (t[i + 1] - t[i]) / substeps;
    for (int k = 1; k <= substeps && a > 0.0; ++k) {
      const double control = delta[i] + (delta[i + 1] - delta[i]) * k / substeps;
      const double a_old = a;
      if (k_lever > 0.0) {
        s.prepare(dt, tip);
        double d_new = tip, a_new = 0.0;
        a = lever_balance(s, k_lever, control, tip, a_old, 1e-4 * a_max, &d_new, &a_new) ? a_new : 0.0;
        if (a > 0.0) tip = d_new, s.set_delta(tip);
      } else {
        s.prepare(dt, control);
        a = nearest_root(s, a, 1e-4 * a_max, da);
        tip = control;
      }
      da = a > 0.0 ? a - a_old : 0.0;
      if (a > 0.0 && k < substeps) s.commit(a);
    }
    if (a == 0.0) {
      out.separated_at = i + 1;
      break;
    }
    if (s.zone(a) >= 0.999 * extent)
      throw NumericalError("relaxing_dugdale_response: the adhesive zone reached the grid's extent " +
                           format_double(extent) + " m at t = " + format_double(t[i + 1]) + " s (give a larger extent)");
    a_max = std::max(a_max, a);
  }
  // Once lost, the contact stays lost while the history withdraws; noise in a measured retract
  // steps back a little, but a return by more than 2 % of the indentation's span is an approach
  // that would form the contact again.
  double lowest = std::numeric_limits<double>::infinity();
  for (std::size_t i = out.separated_at; i < n; ++i) {
    lowest = std::min(lowest, delta[i]);
    if (delta[i] - lowest > 0.02 * (d_max - delta[0]))
      throw InputError("relaxing_dugdale_response: the history comes back from delta = " + format_double(lowest) +
                       " to " + format_double(delta[i]) + " m at t = " + format_double(t[i]) +
                       " s after the contact was lost; forming it again is not modelled");
  }
  out.substeps = substeps;
  return out;
}

}  // namespace

RelaxingDugdaleResponse relaxing_dugdale_response(const Profile& profile, double E_star, const RelaxationLaw& law,
                                                  double w, double sigma0, const std::vector<double>& t,
                                                  const std::vector<double>& delta, const RelaxingDugdaleOptions& o) {
  o.validate();
  check_inputs(E_star, law, w, sigma0, t, delta);
  if (o.substeps > 0) return run_level(profile, E_star, law, w, sigma0, t, delta, o, o.substeps);
  // Halve the step until two levels agree: the error is second order in the step, so the finer
  // level's is about a third of their difference, which is reported.
  RelaxingDugdaleResponse coarse = run_level(profile, E_star, law, w, sigma0, t, delta, o, 1);
  for (int s = 2;; s *= 2) {
    RelaxingDugdaleResponse fine = run_level(profile, E_star, law, w, sigma0, t, delta, o, s);
    double diff = 0.0, scale = 0.0;
    for (std::size_t i = 0; i < t.size(); ++i) {
      diff = std::max(diff, std::abs(fine.P[i] - coarse.P[i]));
      scale = std::max(scale, std::abs(fine.P[i]));
    }
    fine.force_error = diff / 3.0;
    fine.converged = fine.force_error <= o.tolerance * scale && fine.separated_at == coarse.separated_at;
    if (fine.converged || 2 * s > o.max_substeps) return fine;
    coarse = std::move(fine);
  }
}

double dugdale_zero_load_indentation(const Profile& profile, double E_star, double w, double sigma0) {
  const char* fn = "dugdale_zero_load_indentation";
  for (const auto& [name, v] : {std::pair{"E_star", E_star}, {"w", w}, {"sigma0", sigma0}})
    if (!(v > 0.0) || !std::isfinite(v)) throw DomainError(fn, name, v, "finite and > 0");
  const double h0 = w / sigma0, L = profile.length_scale();
  const ElasticDugdale e(profile, E_star / kPi, sigma0, h0);
  // The force on the largest contact at delta; NaN where there is none.
  const auto force = [&](double delta) {
    const double a = e.largest_root(delta, 1e-6 * L, 1e2 * L);
    return a > 0.0 ? e.force(a, delta) : std::numeric_limits<double>::quiet_NaN();
  };
  // The zero-load contact lies between a tensile and a compressive one: grow the step from 0 both
  // ways (the adhesive zone's range h0 sets the first).
  double lo = 0.0, f_lo = force(0.0), hi = 0.0, f_hi = f_lo;
  for (double step = h0; !(f_lo < 0.0 && f_hi > 0.0); step *= 2.0) {
    if (step > 1e3 * L) throw NumericalError(std::string(fn) + ": no zero-load contact found");
    if (!(f_hi > 0.0)) hi = step, f_hi = force(hi);
    if (!(f_lo < 0.0)) lo = -step, f_lo = force(lo);
  }
  std::uintmax_t it = 200;
  const auto r = boost::math::tools::toms748_solve(force, lo, hi, f_lo, f_hi, boost::math::tools::eps_tolerance<double>(48), it);
  return 0.5 * (r.first + r.second);
}

}  // namespace layerjkr
