// Internal: the force of a contact on a relaxing medium under a prescribed indentation history -
// Lee & Radok (1960) while the contact grows, Ting (1966) when it recedes - for any medium that
// scales with one relaxation function psi (viscoelastic.hpp, docs/theory.md s.8). Templated on
// the scalar so that ceres::Jet carries the fit's derivatives.
//
// With d(s) the indentation and P_H(s) = P_H(d(s)) the medium's elastic force at the instantaneous
// modulus, both piecewise linear in time between the samples:
//   * up to the deepest sample m (loading): P(t) = int_tc^t psi(t - s) dP_H(s), tc the first contact;
//   * after it: P(t) = int_tc^t1 psi(t - s) dP_H(s), where the contact has the radius it had at
//     t1 <= t_m, found from int_t1^t psi(t - s) dd(s) = 0 (theory.md s.8 derives this for the layer
//     and the stack: the edge's bounded pressure forces it, whatever the medium's kernel).
// Costs O(N M) for N samples and M exponential terms (1 to 4 for Prony laws, ~60 for a power law,
// relaxation_kernel.hpp): the history is carried by M states, updated exactly over each linear
// piece; the newest piece is integrated with psi itself, so the power law's singular psi(0) is
// exact; t1 is found by galloping from the previous sample's over the stored loading states.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include <boost/math/tools/roots.hpp>

#include "relaxation_kernel.hpp"

namespace layerjkr::detail {

/// What the contact does at a sample.
enum class ContactPhase : signed char {
  free = 0,       ///< before the first contact
  loading = 1,    ///< the contact grows (at or before the deepest sample): Lee-Radok
  holding = 2,    ///< after it, at the largest radius (a dwell, or a retract not yet felt)
  receding = 3,   ///< the radius is that of the loading time t1 < t_m: Ting
  separated = 4,  ///< the contact has been lost (t1 back at the first contact)
};

template <class T>
struct HereditaryResult {
  std::vector<T> P;                  ///< [N] at each sample, 0 where free or separated
  std::vector<ContactPhase> phase;
  /// With want_radius: the indentation at t1 [m] - the contact radius is the elastic one there
  /// (the sample's own indentation while loading, 0 where free or separated) - and t1 itself [s]
  /// (NaN where free or separated).
  std::vector<double> d1, t1;
};

namespace hereditary {

// One exponential term's state over a linear piece of slope `slope` and length dt: the state's
// decay exp(-u dt) and the piece's own contribution slope dt (1 - exp(-u dt)) / (u dt).
template <class T>
struct Step {
  T decay, gain;
};

template <class T>
Step<T> step(const T& u, const T& dt) {
  using std::exp;
  return {exp(-u * dt), dt * one_minus_exp_over(u * dt)};
}

// The loading knots: the first contact and every sample up to the deepest - their times, the
// states of P_H and of d there (flat, M per knot), and the slopes of the piece ending at each
// (the first knot has zero states and no piece).
template <class T>
struct Knots {
  std::size_t M = 0;
  std::vector<T> time, slope_P, slope_d, Z, Y;
  std::vector<double> Yv, d;  // value_of(Y) for the search, the indentation [m]
  std::size_t size() const { return time.size(); }
  // Empties the knots for `knots` of M states each, keeping the storage: a fit evaluates the
  // response hundreds of times, and a dwell's knots with Jet states are tens of MB, which freshly
  // allocated cost more in page faults than the response itself (measured: 35 % of a real dwell's fit).
  void reset(std::size_t states, std::size_t knots) {
    M = states;
    for (std::vector<T>* v : {&time, &slope_P, &slope_d}) v->clear(), v->reserve(knots);
    for (std::vector<T>* v : {&Z, &Y}) v->clear(), v->reserve(knots * states);
    Yv.clear(), Yv.reserve(knots * states);
    d.clear(), d.reserve(knots);
  }
  void push(const T& at, const T& sP, const T& sd, const std::vector<T>& z, const std::vector<T>& y, double dk) {
    time.push_back(at);
    slope_P.push_back(sP);
    slope_d.push_back(sd);
    Z.insert(Z.end(), z.begin(), z.end());
    Y.insert(Y.end(), y.begin(), y.end());
    for (const T& v : y) Yv.push_back(value_of(v));
    d.push_back(dk);
  }
};

}  // namespace hereditary

/// Fills `out` for samples t (strictly increasing [s]), model indentations d [m] and elastic forces
/// PH [N] (P_H(d), 0 where d <= 0), relaxing by `K`. False when the history starts in contact (d[0]
/// > 0: the loading before the first sample is unknown), when t does not increase, or when a
/// value is not finite.
template <class T>
bool hereditary_response(const std::vector<double>& t, const std::vector<T>& d, const std::vector<T>& PH,
                         const RelaxationKernel<T>& K, HereditaryResult<T>* out, bool want_radius = false) {
  using std::exp;
  const std::size_t n = t.size(), M = K.c.size();
  out->P.assign(n, T(0.0));
  out->phase.assign(n, ContactPhase::free);
  if (want_radius) {
    out->d1.assign(n, 0.0);
    out->t1.assign(n, std::numeric_limits<double>::quiet_NaN());
  }
  if (n == 0) return true;
  for (std::size_t i = 0; i < n; ++i)
    if (!std::isfinite(t[i]) || !std::isfinite(value_of(d[i])) || !std::isfinite(value_of(PH[i])) ||
        (i > 0 && !(t[i] > t[i - 1])))
      return false;
  if (value_of(d[0]) > 0.0) return false;
  std::size_t first = n;  // the first sample in contact
  for (std::size_t i = 0; i < n; ++i)
    if (value_of(d[i]) > 0.0) {
      first = i;
      break;
    }
  if (first == n) return true;
  std::size_t m = first;  // the deepest sample
  for (std::size_t i = first; i < n; ++i)
    if (value_of(d[i]) > value_of(d[m])) m = i;
  const auto pos = [](const T& x) { return value_of(x) > 0.0 ? x : T(0.0); };

  std::vector<double> cv(M), uv(M);
  for (std::size_t j = 0; j < M; ++j) {
    cv[j] = value_of(K.c[j]);
    uv[j] = value_of(K.u[j]);
  }
  // The first contact, where d crosses 0 between samples first - 1 and first.
  const T tc = T(t[first - 1]) + (t[first] - t[first - 1]) * (-d[first - 1]) / (d[first] - d[first - 1]);
  std::vector<T> Z(M, T(0.0)), Y(M, T(0.0));
  static thread_local hereditary::Knots<T> knots;  // storage reused across calls (reset says why)
  knots.reset(M, m - first + 2);
  knots.push(tc, T(0.0), T(0.0), Z, Y, 0.0);
  T t_prev = tc, P_prev(0.0), d_prev(0.0);
  std::size_t q = 0;  // the receding contact's knot, from one sample to the next

  // Phi at knot j for the sample at time tk with A = int_tc^tk psi(tk - s) dd(s): double, for the search.
  const auto phi_value = [&](std::size_t j, double tk, double A) {
    double B = 0.0;
    const double age = tk - value_of(knots.time[j]);
    const double* y = &knots.Yv[j * M];
    for (std::size_t i = 0; i < M; ++i) B += cv[i] * std::exp(-uv[i] * age) * y[i];
    return A - B;
  };
  // Instruments sample evenly: each term's decay exp(-u dt) and gain per unit time (1 - exp(-u dt))
  // / (u dt), and the newest piece's integral per unit time, are computed once per step length (to
  // 1e-12 of it, far below the power law's 4e-10) and scaled by each sample's own dt - a third of
  // the cost of a fit in time; the elastic limit stays exact. The first piece starts at the
  // contact time, which moves with the parameters, and is never reused.
  // Ting's t1 search runs on values: the kernel converted once, not per receding sample.
  const RelaxationKernel<double> Kv = want_radius ? K.values() : RelaxationKernel<double>{};
  std::vector<hereditary::Step<T>> rates(M);  // decay, gain / dt
  T local_rate(0.0);
  double cached_dt = -1.0;
  for (std::size_t k = first; k < n; ++k) {
    const T dt = T(t[k]) - t_prev;
    const T dk = pos(d[k]);
    const T sP = (PH[k] - P_prev) / dt, sd = (dk - d_prev) / dt;
    const double dtv = value_of(dt);
    const bool reuse = k > first + 1 && std::abs(dtv - cached_dt) <= 1e-12 * cached_dt;
    if (!reuse) {
      local_rate = K.integral(T(0.0), dt) / dt;
      for (std::size_t j = 0; j < M; ++j) {
        rates[j] = hereditary::step(K.u[j], dt);
        rates[j].gain /= dt;
      }
      cached_dt = k > first ? dtv : -1.0;
    }
    const T local = local_rate * dt;
    // The history's response at t[k] (each state decayed over the new piece) plus the new piece's.
    T hist_P(0.0), hist_d(0.0);
    for (std::size_t j = 0; j < M; ++j) {
      const hereditary::Step<T> s{rates[j].decay, rates[j].gain * dt};
      hist_P += K.c[j] * s.decay * Z[j];
      hist_d += K.c[j] * s.decay * Y[j];
      Z[j] = s.decay * Z[j] + sP * s.gain;
      Y[j] = s.decay * Y[j] + sd * s.gain;
    }
    t_prev = T(t[k]);
    P_prev = PH[k];
    d_prev = dk;
    if (k <= m) {  // loading: Lee-Radok
      out->P[k] = hist_P + sP * local;
      out->phase[k] = ContactPhase::loading;
      knots.push(T(t[k]), sP, sd, Z, Y, value_of(dk));
      if (want_radius) {
        out->d1[k] = value_of(dk);
        out->t1[k] = t[k];
      }
      q = knots.size() - 1;
      continue;
    }
    // Receding: the largest knot j with Phi_j >= 0, galloping from the last one.
    const T A = hist_d + sd * local;
    const double Av = value_of(A);
    const std::size_t top = knots.size() - 1;
    const auto ok = [&](std::size_t j) { return phi_value(j, t[k], Av) >= 0.0; };
    std::size_t lo, hi;  // ok(lo), !ok(hi) once bracketed
    if (ok(top)) {
      lo = hi = top;
    } else if (!ok(0)) {
      lo = hi = knots.size();  // separated
    } else {
      q = std::min(q, top - 1);
      std::size_t stride = 1;
      if (ok(q)) {
        lo = q;
        hi = std::min(q + stride, top);
        while (ok(hi)) {
          lo = hi;
          stride *= 2;
          hi = std::min(hi + stride, top);
        }
      } else {
        hi = q;
        lo = q >= stride ? q - stride : 0;
        while (!ok(lo)) {
          hi = lo;
          stride *= 2;
          lo = lo >= stride ? lo - stride : 0;
        }
      }
      while (hi - lo > 1) {
        const std::size_t mid = lo + (hi - lo) / 2;
        (ok(mid) ? lo : hi) = mid;
      }
    }
    if (lo == knots.size()) {
      out->phase[k] = ContactPhase::separated;
      continue;
    }
    q = lo;
    const T age = T(t[k]) - knots.time[q];
    T P_hist(0.0), B(0.0);
    for (std::size_t j = 0; j < M; ++j) {
      const T decay = exp(-K.u[j] * age);
      P_hist += K.c[j] * decay * knots.Z[q * M + j];
      B += K.c[j] * decay * knots.Y[q * M + j];
    }
    if (q == top) {  // the largest radius still holds
      out->P[k] = P_hist;
      out->phase[k] = ContactPhase::holding;
      if (want_radius) {
        out->d1[k] = knots.d[q];
        out->t1[k] = value_of(knots.time[q]);
      }
      continue;
    }
    // t1 inside the piece (q, q+1), where P_H and d are both linear in time: P rises from P_hist by
    // the piece's dP_H/dd times Phi_q (theory.md s.8), continuous as t1 crosses a knot.
    const T phi = A - B;
    out->P[k] = P_hist + knots.slope_P[q + 1] / knots.slope_d[q + 1] * phi;
    out->phase[k] = ContactPhase::receding;
    if (want_radius) {
      // slope_d int_t_q^t1 psi(t_k - s) ds = Phi_q for t1 in [t_q, t_{q+1}].
      const double tq = value_of(knots.time[q]), tn = value_of(knots.time[q + 1]);
      const double sdv = value_of(knots.slope_d[q + 1]), target = value_of(phi) / sdv;
      const auto g = [&](double s) { return Kv.integral(t[k] - s, t[k] - tq) - target; };
      double t1 = target > 0.0 ? tn : tq;
      if (target > 0.0 && g(tn) > 0.0) {
        std::uintmax_t iterations = 200;
        const auto r = boost::math::tools::toms748_solve(g, tq, tn, -target, g(tn),
                                                         boost::math::tools::eps_tolerance<double>(50), iterations);
        t1 = 0.5 * (r.first + r.second);
      }
      out->t1[k] = t1;
      out->d1[k] = knots.d[q] + sdv * (t1 - tq);
    }
  }
  return true;
}

}  // namespace layerjkr::detail
