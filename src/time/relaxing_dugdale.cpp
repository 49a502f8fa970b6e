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

namespace layerjkr {
namespace {

constexpr double kPi = 3.14159265358979323846;

// sqrt(c^2 - x^2) without cancellation near x = c.
double root_gap(double c, double x) { return std::sqrt(std::max((c - x) * (c + x), 0.0)); }

// int_x1^x2 (linear through (x1, q1), (x2, q2)) / sqrt(c^2 - x^2) dx, exactly; x1 < x2 <= c.
double segment_integral(double c, double x1, double q1, double x2, double q2) {
  const double s1 = root_gap(c, x1), s2 = root_gap(c, x2);
  const double angle = std::atan2(x2 * s1 - x1 * s2, x1 * x2 + s1 * s2);  // asin(x2/c) - asin(x1/c)
  const double slope = (q2 - q1) / (x2 - x1);
  return q1 * angle + slope * ((s1 - s2) - x1 * angle);
}

// The elastic contact at modulus kappa pi (no history): the gap mismatch at contact radius a, on
// Gauss-Legendre quadrature of x = c sin(theta) (smooth: no grid), for the grid's extent.
class ElasticDugdale {
 public:
  ElasticDugdale(const Profile& p, double kappa, double sigma0, double h0) : p_(p), kappa_(kappa), s0_(sigma0), h0_(h0) {}
  double zone(double a, double delta) const {
    const double qa = F(a) - delta;
    return qa <= 0.0 ? a : std::hypot(a, kPi * kappa_ * qa / (2.0 * s0_));
  }
  double mismatch(double a, double delta) const {
    const double c = zone(a, delta);
    if (c == a) return -1.0;
    if (!(c < p_.max_radius())) return std::numeric_limits<double>::infinity();
    const double lo = std::atan2(a, root_gap(c, a));
    const double I = boost::math::quadrature::gauss<double, 30>::integrate(
        [&](double th) { return F(c * std::sin(th)) - delta; }, lo, kPi / 2.0);
    return ((2.0 / kPi) * I - 4.0 * s0_ * (c - a) / (kPi * kPi * kappa_)) / h0_ - 1.0;
  }
  // Maugis' force at contact radius a: 2 E* (delta a - int_0^a F) minus the annulus's tension.
  double force(double a, double delta) const {
    const double c = zone(a, delta), s = root_gap(c, a);
    const double I = boost::math::quadrature::gauss<double, 30>::integrate([&](double x) { return F(x); }, 0.0, a);
    return 2.0 * kPi * kappa_ * (delta * a - I) - 2.0 * s0_ * (c * c * std::atan2(s, a) - a * s);
  }
  // The largest root over a geometric scan (0 if none).
  double largest_root(double delta, double a_lo, double a_hi) const {
    const int n = 400;
    a_hi = std::min(a_hi, 0.99 * p_.max_radius());
    double best = 0.0, prev_a = a_lo, prev = mismatch(a_lo, delta);
    for (int k = 1; k <= n; ++k) {
      const double a = a_lo * std::pow(a_hi / a_lo, double(k) / n), m = mismatch(a, delta);
      if ((prev < 0.0) != (m < 0.0)) {
        std::uintmax_t it = 100;
        const auto r = boost::math::tools::toms748_solve([&](double x) { return mismatch(x, delta); }, prev_a, a, prev,
                                                         m, boost::math::tools::eps_tolerance<double>(50), it);
        best = 0.5 * (r.first + r.second);
      }
      prev_a = a, prev = m;
    }
    return best;
  }
  double F(double x) const { return x * p_.sneddon(x).I0; }

 private:
  const Profile& p_;
  double kappa_, s0_, h0_;
};

// The stepper's state on the grid: D(x) and one relaxation state per kernel term per point.
class DugdaleStepper {
 public:
  DugdaleStepper(const Profile& p, double E_star, const detail::RelaxationKernel<double>& K, double sigma0, double h0,
                 double extent, int n)
      : p_(p), Ek_(E_star / kPi), K_(K), s0_(sigma0), h0_(h0), dx_(extent / (n - 1)), x_(n), F_(n), D_(n, 0.0),
        Y_(K.c.size() * n, 0.0), r_(n, 0.0), gh_(n, 0.0) {
    for (int j = 0; j < n; ++j) x_[j] = j * dx_, F_[j] = x_[j] * p.sneddon(x_[j]).I0;
  }

  // Sets up a step of length dt >= 0 (0: a jump, answered at the instantaneous modulus) to delta.
  void prepare(double dt, double delta) {
    delta_ = delta;
    const std::size_t M = K_.c.size(), n = x_.size();
    decay_.assign(M, 1.0), gain_.assign(M, 1.0);
    double psi_bar = 0.0;
    for (std::size_t m = 0; m < M; ++m) {
      if (dt > 0.0) decay_[m] = std::exp(-K_.u[m] * dt), gain_[m] = detail::one_minus_exp_over(K_.u[m] * dt);
      psi_bar += K_.c[m] * gain_[m];
    }
    kappa_ = Ek_ * psi_bar;
    const double inv_kappa = 1.0 / kappa_;
    // Beyond the reach the points have never moved: D, g and r stay 0 there.
    for (std::size_t j = 0; j < reach_; ++j) {
      double h = 0.0;
      for (std::size_t m = 0; m < M; ++m) h += K_.c[m] * decay_[m] * Y_[m * n + j];
      gh_[j] = Ek_ * h;
      r_[j] = D_[j] - gh_[j] * inv_kappa;  // q = r + F - delta
    }
  }

  // q(x) = D_old - g_hist/kappa + F(x) - delta: -g/kappa where x stays in contact.
  double q(double x) const {
    const std::size_t j = std::min<std::size_t>(static_cast<std::size_t>(x / dx_), x_.size() - 2);
    const double t = (x - x_[j]) / dx_;
    return (1.0 - t) * r_[j] + t * r_[j + 1] + x * p_.sneddon(x).I0 - delta_;
  }
  double zone(double a) const {
    const double qa = q(a);
    return qa <= 0.0 ? a : std::hypot(a, kPi * kappa_ * qa / (2.0 * s0_));
  }
  // (gap at c)/h0 - 1 at contact radius a.
  double mismatch(double a) const {
    const double c = zone(a);
    if (c == a) return -1.0;
    if (c >= x_.back()) return std::numeric_limits<double>::infinity();
    double I = 0.0, x1 = a, q1 = q(a);
    for (std::size_t j = static_cast<std::size_t>(a / dx_) + 1; j < x_.size() && x_[j] < c; ++j) {
      const double q2 = r_[j] + F_[j] - delta_;
      I += segment_integral(c, x1, q1, x_[j], q2);
      x1 = x_[j], q1 = q2;
    }
    I += segment_integral(c, x1, q1, c, q(c));
    return ((2.0 / kPi) * I - 4.0 * s0_ * (c - a) / (kPi * kPi * kappa_)) / h0_ - 1.0;
  }
  // The force at contact radius a: 2 pi (int_0^a g + the annulus's), g = -kappa q inside.
  double force(double a) const {
    const double c = zone(a);
    double I = 0.0, x1 = 0.0, q1 = q(0.0);
    for (std::size_t j = 1; j < x_.size() && x_[j] < a; ++j) {
      const double q2 = r_[j] + F_[j] - delta_;
      I += 0.5 * (q1 + q2) * (x_[j] - x1);
      x1 = x_[j], q1 = q2;
    }
    I += 0.5 * (q1 + q(a)) * (a - x1);
    const double s = root_gap(c, a);
    return 2.0 * kPi * (-kappa_ * I) - 2.0 * s0_ * (c * c * std::atan2(s, a) - a * s);
  }
  // Moves every point's history to the end of the step with contact radius a.
  void commit(double a) {
    const double c = zone(a);
    const std::size_t M = K_.c.size(), n = x_.size();
    reach_ = std::min(n, std::max(reach_, static_cast<std::size_t>(c / dx_) + 2));
    for (std::size_t j = 0; j < reach_; ++j) {
      double D = 0.0;
      if (x_[j] < a)
        D = delta_ - F_[j];
      else if (x_[j] < c)
        D = D_[j] + (-(2.0 * s0_ / kPi) * root_gap(c, x_[j]) - gh_[j]) / kappa_;
      else
        D = D_[j] - gh_[j] / kappa_;
      const double dD = D - D_[j];
      for (std::size_t m = 0; m < M; ++m) Y_[m * n + j] = decay_[m] * Y_[m * n + j] + gain_[m] * dD;
      D_[j] = D;
    }
  }
  double extent() const { return x_.back(); }

 private:
  const Profile& p_;
  double Ek_;
  detail::RelaxationKernel<double> K_;
  double s0_, h0_, dx_;
  std::vector<double> x_, F_, D_, Y_, r_, gh_, decay_, gain_;
  double kappa_ = 0.0, delta_ = 0.0;
  std::size_t reach_ = 0;  // the points the zone has ever reached (and two more)
};

// The root of the stepper's mismatch nearest a_prev + da (da: the last step's change, the guess),
// by brackets growing geometrically on both sides from there; 0 when there is none in (a_floor,
// the grid's reach).
double nearest_root(const DugdaleStepper& s, double a_prev, double a_floor, double da = 0.0) {
  const double centre = a_prev + da > a_floor ? a_prev + da : a_prev;
  const double f0 = s.mismatch(centre);
  if (f0 == 0.0) return centre;
  double lo_a = centre, lo_f = f0, hi_a = centre, hi_f = f0;
  bool lo_open = true, hi_open = true;
  auto solve = [&](double x1, double f1, double x2, double f2) {
    std::uintmax_t it = 100;
    const auto r = boost::math::tools::toms748_solve([&](double x) { return s.mismatch(x); }, std::min(x1, x2),
                                                     std::max(x1, x2), x1 < x2 ? f1 : f2, x1 < x2 ? f2 : f1,
                                                     boost::math::tools::eps_tolerance<double>(44), it);
    return 0.5 * (r.first + r.second);
  };
  for (double step = std::max(1e-5 * a_prev, 0.25 * std::abs(da)); lo_open || hi_open; step *= 2.0) {
    if (hi_open) {
      const double a = centre + step, f = s.mismatch(a);
      if (!std::isfinite(f)) {
        hi_open = false;
      } else {
        if ((f < 0.0) != (hi_f < 0.0)) return solve(hi_a, hi_f, a, f);
        hi_a = a, hi_f = f;
      }
    }
    if (lo_open) {
      const double a = centre - step;
      if (a <= a_floor) {
        lo_open = false;
      } else {
        const double f = s.mismatch(a);
        if ((f < 0.0) != (lo_f < 0.0)) return solve(a, f, lo_a, lo_f);
        lo_a = a, lo_f = f;
      }
    }
  }
  return 0.0;
}

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
  out.separated_at = n;
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
    out.a[i] = a, out.c[i] = s.zone(a), out.P[i] = s.force(a);
    if (i + 1 == n) break;
    const double dt = (t[i + 1] - t[i]) / substeps;
    for (int k = 1; k <= substeps && a > 0.0; ++k) {
      s.prepare(dt, delta[i] + (delta[i + 1] - delta[i]) * k / substeps);
      const double a_old = a;
      a = nearest_root(s, a, 1e-4 * a_max, da);
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
