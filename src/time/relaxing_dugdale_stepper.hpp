// Internal: the pieces of the relaxing Maugis-Dugdale stepping (viscoelastic_adhesion.hpp,
// relaxing_dugdale.cpp) - the zone's gap integral, the elastic contact that sizes the grid and
// snaps the contact in, the stepper that carries each Copson point's history, and the roots a step
// solves (the contact radius; under a cantilever, the tip's indentation too).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include <boost/math/quadrature/gauss.hpp>
#include <boost/math/tools/roots.hpp>

#include "layerjkr/profile.hpp"
#include "relaxation_kernel.hpp"

namespace layerjkr::detail::dugdale {

constexpr double kPi = 3.14159265358979323846;

// sqrt(c^2 - x^2) without cancellation near x = c.
inline double root_gap(double c, double x) { return std::sqrt(std::max((c - x) * (c + x), 0.0)); }

// int_x1^x2 (linear through (x1, q1), (x2, q2)) / sqrt(c^2 - x^2) dx, exactly; x1 < x2 <= c.
inline double segment_integral(double c, double x1, double q1, double x2, double q2) {
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
  DugdaleStepper(const Profile& p, double E_star, const RelaxationKernel<double>& K, double sigma0, double h0,
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
      if (dt > 0.0) decay_[m] = std::exp(-K_.u[m] * dt), gain_[m] = one_minus_exp_over(K_.u[m] * dt);
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

  // Another indentation for the step prepared (the history's part does not depend on it).
  void set_delta(double delta) { delta_ = delta; }
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
  RelaxationKernel<double> K_;
  double s0_, h0_, dx_;
  std::vector<double> x_, F_, D_, Y_, r_, gh_, decay_, gain_;
  double kappa_ = 0.0, delta_ = 0.0;
  std::size_t reach_ = 0;  // the points the zone has ever reached (and two more)
};

// The root of the stepper's mismatch nearest a_prev + da (da: the last step's change, the guess),
// by brackets growing geometrically on both sides from there; 0 when there is none in (a_floor,
// the grid's reach).
inline double nearest_root(const DugdaleStepper& s, double a_prev, double a_floor, double da = 0.0) {
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

// Under a cantilever of stiffness k whose base is at z: the tip's indentation delta, between the
// last step's d_prev and z, where delta + P(delta)/k = z on the contact's branch (its radius the
// root nearest a_prev); false where the lever has let go (no such delta: past dP/d delta = -k).
inline bool lever_balance(DugdaleStepper& s, double k, double z, double d_prev, double a_prev, double a_floor, double* delta,
                   double* a) {
  const auto imbalance = [&](double d, double* a_at) {
    s.set_delta(d);
    *a_at = nearest_root(s, a_prev, a_floor);
    return *a_at > 0.0 ? d + s.force(*a_at) / k - z : std::numeric_limits<double>::quiet_NaN();
  };
  double a_lo = 0.0, a_hi = 0.0;
  double lo = d_prev, f_lo = imbalance(lo, &a_lo);
  if (!std::isfinite(f_lo)) return false;
  // The tip moves towards the base's new place: step from d_prev that way until the sign turns,
  // starting at the imbalance itself (the root is at f / (1 + S/k), further where the lever nears
  // letting go). Past the grips' end of the branch (no radius), the step is halved back towards
  // the last balance checked: a sign turn there is the root, none means the lever has let go.
  const double dir = f_lo < 0.0 ? 1.0 : -1.0;
  double step = std::max(std::abs(f_lo), 1e-12 * (std::abs(z) + std::abs(d_prev)) + 1e-18), hi = lo, f_hi = f_lo;
  for (int k_try = 0; k_try < 200; ++k_try) {
    hi = lo + dir * step;
    f_hi = imbalance(hi, &a_hi);
    if (!std::isfinite(f_hi)) {
      if (step < 1e-9 * std::abs(f_lo) + 1e-18) return false;  // the branch ends before the lever balances
      step *= 0.5;
      continue;
    }
    if ((f_hi < 0.0) != (f_lo < 0.0)) break;
    lo = hi, f_lo = f_hi;
    step *= 2.0;
  }
  if ((f_hi < 0.0) == (f_lo < 0.0)) return false;
  std::uintmax_t it = 100;
  double a_mid = 0.0;
  const auto r = boost::math::tools::toms748_solve(
      [&](double d) {
        const double v = imbalance(d, &a_mid);
        return std::isfinite(v) ? v : (dir > 0.0 ? 1.0 : -1.0) * std::abs(f_lo);
      },
      std::min(lo, hi), std::max(lo, hi), lo < hi ? f_lo : f_hi, lo < hi ? f_hi : f_lo,
      boost::math::tools::eps_tolerance<double>(44), it);
  *delta = 0.5 * (r.first + r.second);
  return std::isfinite(imbalance(*delta, a)) && *a > 0.0;
}

}  // namespace layerjkr::detail::dugdale
