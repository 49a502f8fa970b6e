// Critical points and inverse lookups on the adhesive curve, searched in ln a.
#include "layerjkr/contact.hpp"

#include <cmath>
#include <cstdint>
#include <limits>
#include <mutex>
#include <sstream>

#include <boost/math/differentiation/finite_difference.hpp>
#include <boost/math/tools/minima.hpp>
#include <boost/math/tools/roots.hpp>

#include "layerjkr/error.hpp"

namespace layerjkr {
namespace {
constexpr double kInf = std::numeric_limits<double>::infinity();

// A value computed at most once by its first successful request; concurrent requests wait
// for it. A mutex rather than std::call_once: libstdc++'s call_once is not reliable when
// the callable throws (GCC PR 66146), and a search may throw (the model's NumericalError).
template <class T>
class Once {
 public:
  template <class Compute>
  T get(Compute compute) {
    const std::lock_guard<std::mutex> lock(mutex_);
    if (!value_) value_ = compute();
    return *value_;
  }

 private:
  std::mutex mutex_;
  std::optional<T> value_;
};
}  // namespace

// One mutex per point: pull-off's search asks for the zero-load radius and the fixed-grips
// search for the pull-off, always in that order, so holding one while waiting for the next
// cannot deadlock.
struct detail::JkrCriticalPoints {
  Once<std::optional<double>> zero_load_radius;
  Once<std::optional<CriticalPoint>> pull_off;
  Once<std::optional<CriticalPoint>> fixed_grips;
};

void JkrOptions::validate() const {
  const char* fn = "JkrOptions::validate";
  if (scan_points < 8) throw DomainError(fn, "scan_points", scan_points, ">= 8");
  if (!(scan_decades > 0.0) || !std::isfinite(scan_decades))
    throw DomainError(fn, "scan_decades", scan_decades, "finite and > 0");
  if (max_windows < 1) throw DomainError(fn, "max_windows", max_windows, ">= 1");
  if (max_bracket_steps < 10)
    throw DomainError(fn, "max_bracket_steps", max_bracket_steps, ">= 10");
}

AdhesiveSolution::AdhesiveSolution(ContactModelPtr model, double w, JkrOptions options)
    : AdhesiveSolution(model ? make_jkr_law(std::move(model), w)
                             : throw Error("layerjkr::JkrSolution: the model is null"),
                       options) {}

AdhesiveSolution::AdhesiveSolution(AdhesiveLawPtr law, JkrOptions options)
    : law_(std::move(law)), options_(options), critical_(std::make_shared<detail::JkrCriticalPoints>()) {
  if (!law_) throw Error("layerjkr::AdhesiveSolution: the adhesive law is null");
  model_ = law_->contact();
  w_ = law_->w();
  options_.validate();
}

AdhesiveState AdhesiveSolution::at(double a) const { return law_->at(a); }

std::vector<AdhesiveState> AdhesiveSolution::curve(const std::vector<double>& radii) const {
  return law_->curve(radii);
}

double AdhesiveSolution::upper_radius() const {
  const double m = model_->max_radius();
  if (!std::isfinite(m)) return kInf;
  // Data: the largest radius measured, less the ulp by which exp(log(m)) in the scans may pass it.
  if (!model_->has_profile()) return m * (1.0 - 1e-12);
  return model_->profile().contains(m) ? m : m * (1.0 - 1e-9);  // open bound (sphere: a < R)
}

double AdhesiveSolution::seed_radius() const {
  const double seed = std::min(model_->typical_radius(), 0.5 * upper_radius());
  return std::max(seed, 2.0 * model_->min_radius());
}

// Minimum of P(a) (force) or delta(a) over (0, a_hi]: log-grid scan, stepping the window
// down while the minimum sits at its lower edge, then Brent on the bracketing cells. A
// minimum is accepted only if it beats the lower edge by more than the rounding noise
// of the two terms of (19); otherwise the curve is monotone there (e.g. Winkler's
// delta(a)) and the search goes on below.
std::optional<double> AdhesiveSolution::minimise(bool force, double a_hi) const {
  auto of = [force](const AdhesiveState& s) { return force ? s.P : s.delta; };
  auto value = [&](double x) { return of(at(std::exp(x))); };
  // Rounding noise of the two terms of (19), from a state the scan already holds.
  auto noise = [force](const AdhesiveState& s) {
    double terms = force ? std::abs(s.hertz.P_H) + std::abs(s.hertz.P_H - s.P)
                         : std::abs(s.hertz.delta_H) + std::abs(s.hertz.delta_H - s.delta);
    if (!std::isfinite(terms)) terms = std::abs(force ? s.P : s.delta);  // a law with no separate non-adhesive part
    return 64.0 * std::numeric_limits<double>::epsilon() * terms;
  };
  const int n = options_.scan_points;
  double top = std::log(a_hi);
  const double span = options_.scan_decades * std::log(10.0);
  const double a_min = model_->min_radius();
  const double floor = a_min > 0.0 ? std::log(a_min * (1.0 + 1e-9)) : -kInf;
  for (int window = 0; window < options_.max_windows; ++window) {
    if (!(top > floor)) break;
    const double lo = std::max(top - span, floor), step = (top - lo) / (n - 1);
    std::vector<AdhesiveState> states;
    states.reserve(static_cast<std::size_t>(n));
    std::size_t best = 0;
    for (int i = 0; i < n; ++i) {
      states.push_back(at(std::exp(lo + i * step)));
      if (of(states.back()) < of(states[best])) best = states.size() - 1;
    }
    const AdhesiveState& first = states.front();
    if (best == 0 || of(first) - of(states[best]) <= noise(first) + noise(states[best])) {
      if (lo == floor) break;  // monotone down to the model's smallest radius: no minimum
      top = lo + step;
      continue;
    }
    const int k = static_cast<int>(best);
    const double left = lo + (k - 1) * step;
    const double right = lo + std::min(k + 1, n - 1) * step;
    // Brent locates a minimum only to sqrt(eps); the root of the derivative (6th-order
    // finite differences, error ~eps^(6/7)) pins it to ~1e-13, which matters wherever
    // the other coordinate is not stationary (P at the fixed-grips point).
    auto slope = [&](double x) {
      return boost::math::differentiation::finite_difference_derivative<decltype(value), double, 6>(
          value, x);
    };
    const double s_left = slope(left), s_right = slope(right);
    if (s_left < 0.0 && s_right > 0.0) {
      std::uintmax_t iterations = 200;
      const auto r = boost::math::tools::toms748_solve(
          slope, left, right, s_left, s_right, boost::math::tools::eps_tolerance<double>(50),
          iterations);
      return std::exp(0.5 * (r.first + r.second));
    }
    std::uintmax_t iterations = 200;
    const auto r = boost::math::tools::brent_find_minima(value, left, right,
                                                         std::numeric_limits<double>::digits / 2,
                                                         iterations);
    return std::exp(r.first);
  }
  return std::nullopt;
}

// Smallest a above a_lo (or, for a_lo = 0, the crossing nearest the seed) where the
// increasing quantity P(a) or delta(a) reaches target; nullopt if it cannot be bracketed.
std::optional<double> AdhesiveSolution::first_root(bool force, double target, double a_lo) const {
  auto g = [&](double a) {
    const AdhesiveState s = at(a);
    return (force ? s.P : s.delta) - target;
  };
  const double upper = upper_radius();
  double lo, g_lo, hi = 0.0, g_hi = 0.0;
  bool have_hi = false;
  // A law with a state at a = 0 (DMT) starts its curve there: delta(0) is where the retract
  // lets go, so a = 0 itself is a candidate root.
  if (a_lo > 0.0 || law_->has_zero_radius_state()) {
    lo = a_lo;
    g_lo = g(lo);
    if (g_lo >= 0.0) return g_lo == 0.0 ? std::optional<double>(lo) : std::nullopt;
  } else {
    lo = seed_radius();
    g_lo = g(lo);
    int steps = 0;
    while (g_lo >= 0.0) {
      if (g_lo == 0.0) return lo;
      hi = lo, g_hi = g_lo, have_hi = true;
      const double floor = model_->min_radius() * (1.0 + 1e-9);
      if (++steps > options_.max_bracket_steps || lo <= floor) return std::nullopt;
      lo = std::max(0.5 * lo, floor);
      g_lo = g(lo);
    }
  }
  for (int steps = 0; !have_hi; ++steps) {
    if (steps > options_.max_bracket_steps || lo >= upper) return std::nullopt;
    const double next = std::min(lo > 0.0 ? 2.0 * lo : seed_radius(), upper);
    const double g_next = g(next);
    if (g_next >= 0.0) {
      hi = next, g_hi = g_next, have_hi = true;
    } else {
      lo = next, g_lo = g_next;
    }
  }
  if (g_hi == 0.0) return hi;
  std::uintmax_t iterations = 200;
  const auto r = boost::math::tools::toms748_solve(
      g, lo, hi, g_lo, g_hi, boost::math::tools::eps_tolerance<double>(50), iterations);
  return 0.5 * (r.first + r.second);
}

std::optional<double> AdhesiveSolution::zero_load_radius() const {
  return critical_->zero_load_radius.get([this] { return search_zero_load_radius(); });
}

std::optional<CriticalPoint> AdhesiveSolution::pull_off() const {
  return critical_->pull_off.get([this] { return search_pull_off(); });
}

std::optional<CriticalPoint> AdhesiveSolution::fixed_grips_critical() const {
  return critical_->fixed_grips.get([this] { return search_fixed_grips_critical(); });
}

std::optional<double> AdhesiveSolution::search_zero_load_radius() const {
  if (w_ == 0.0) return 0.0;
  return first_root(true, 0.0, 0.0);
}

std::optional<CriticalPoint> AdhesiveSolution::search_pull_off() const {
  if (w_ == 0.0) return std::nullopt;
  const std::optional<double> a0 = zero_load_radius();
  const double a_hi = a0 ? *a0 : upper_radius();
  if (!std::isfinite(a_hi)) return std::nullopt;
  const std::optional<double> a = minimise(true, a_hi);
  // With a state at a = 0 (the adhesive zone pulling with no contact), load-controlled pull-off
  // is the lowest force over a >= 0: it sits at a = 0 where P(a) rises from there.
  if (law_->has_zero_radius_state()) {
    const AdhesiveState zero = at(0.0);
    if (!a || zero.P <= at(*a).P) return CriticalPoint{zero.a, zero.P, zero.delta};
  }
  if (!a) return std::nullopt;
  const AdhesiveState s = at(*a);
  return CriticalPoint{s.a, s.P, s.delta};
}

std::optional<CriticalPoint> AdhesiveSolution::search_fixed_grips_critical() const {
  if (w_ == 0.0) return std::nullopt;
  // On the fixed-grips critical point dP/da = -S' sqrt(4 pi w a / S') < 0, so it lies
  // below the pull-off radius.
  const std::optional<CriticalPoint> po = pull_off();
  const double a_hi = po ? po->a : upper_radius();
  if (!std::isfinite(a_hi)) return std::nullopt;
  const std::optional<double> a = minimise(false, a_hi);
  if (!a) return std::nullopt;
  const AdhesiveState s = at(*a);
  return CriticalPoint{s.a, s.P, s.delta};
}

double AdhesiveSolution::contact_radius_at_force(double P) const {
  detail::require_finite("AdhesiveSolution::contact_radius_at_force", "P", P);
  double a_lo = 0.0;
  if (w_ == 0.0) {
    if (P < 0.0)
      throw DomainError("AdhesiveSolution::contact_radius_at_force", "P", P, ">= 0 for w = 0");
    if (P == 0.0) return 0.0;
  } else if (const auto po = pull_off()) {
    if (P < po->P)
      throw DomainError("AdhesiveSolution::contact_radius_at_force", "P", P,
                        ">= the pull-off force " + format_double(po->P));
    a_lo = po->a;
  }
  const std::optional<double> a = first_root(true, P, a_lo);
  if (!a)
    throw DomainError("AdhesiveSolution::contact_radius_at_force", "P", P,
                      "forces reachable by " + model_->name() +
                          (model_->has_profile() ? " with " + model_->profile().describe() : std::string(" (data)")) +
                          " (a <= " +
                          format_double(model_->max_radius()) + " m)");
  return *a;
}

double AdhesiveSolution::contact_radius_at_delta(double delta) const {
  detail::require_finite("AdhesiveSolution::contact_radius_at_delta", "delta", delta);
  double a_lo = 0.0;
  if (const auto fg = fixed_grips_critical()) {
    if (delta < fg->delta)
      throw DomainError("AdhesiveSolution::contact_radius_at_delta", "delta", delta,
                        ">= the fixed-grips critical approach " + format_double(fg->delta));
    a_lo = fg->a;
  }
  const std::optional<double> a = first_root(false, delta, a_lo);
  if (!a)
    throw DomainError("AdhesiveSolution::contact_radius_at_delta", "delta", delta,
                      "approaches reachable on the stable branch of " + model_->name());
  return *a;
}

double AdhesiveSolution::force_at_delta(double delta) const {
  const double a = contact_radius_at_delta(delta);
  if (a == 0.0 && !law_->has_zero_radius_state()) return 0.0;
  return at(a).P;
}

ContactSummary summarize(const AdhesiveSolution& solution) {
  ContactSummary s;
  s.model = solution.law().name();
  s.adhesion = solution.law().model();
  s.w = solution.w();
  s.zero_load_radius = solution.zero_load_radius();
  s.pull_off = solution.pull_off();
  s.fixed_grips = solution.fixed_grips_critical();
  return s;
}

std::string ContactSummary::brief_report() const {
  std::ostringstream out;
  auto point = [&](const char* label, const std::optional<CriticalPoint>& p) {
    out << label;
    if (p)
      out << "P = " << format_double(p->P) << " N at a = " << format_double(p->a)
          << " m, delta = " << format_double(p->delta) << " m\n";
    else
      out << "none\n";
  };
  out << "layerjkr contact summary: model " << model << ", w = " << format_double(w)
      << " J/m^2, adhesion " << to_string(adhesion) << "\n";
  out << "  zero-load contact radius: "
      << (zero_load_radius ? format_double(*zero_load_radius) + " m" : std::string("none"))
      << "\n";
  point("  pull-off (load control):  ", pull_off);
  point("  critical (fixed grips):   ", fixed_grips);
  return out.str();
}

}  // namespace layerjkr
