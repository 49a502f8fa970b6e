// fit() step 2: a start that needs no guess - baseline, contact-point scan with a linear
// stiffness solve at each trial, and w matched to the retract dip.
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>
#include <utility>

#include <Eigen/Dense>

#include "fit/run/fit_steps.hpp"
#include "layerjkr/error.hpp"

namespace layerjkr::detail {
namespace {

// The w search of the start brackets w in these multiples of the data's force per length,
// force_span / span [J/m^2]: far wider than any adhesion the curve can show.
constexpr double kWBracketLow = 1e-12;
constexpr double kWBracketHigh = 1e6;
// An adhesive start is sought from the scene's stiffness and from these multiples of it (the
// scene's first: it decides what is refused); each settles by itself, the best scan is kept.
constexpr double kStartStiffnessFactors[] = {1.0, 0.1, 10.0};

struct Start {
  double delta0 = 0.0, P0 = 0.0, stiffness_factor = 1.0, w = 0.0;
  double cost = std::numeric_limits<double>::infinity();  ///< the scan's sum of squares at delta0 [N^2]
  std::size_t contact = 0;
  bool found = true;  ///< false: no trial put >= 3 samples in contact with a positive stiffness
};

// The non-adhesive master curve P(t) at the reference stiffness, tabulated once so a scan
// over contact points costs one interpolation per sample.
struct MasterCurve {
  std::vector<double> t, P;
};

MasterCurve master_curve(const CurveEvaluator& ev, const CurveParameters<double>& p, double span,
                         bool retract) {
  MasterCurve m;
  detail::BranchStart bs;
  if (!ev.branch_start(p, retract ? detail::StartKind::pull_off : detail::StartKind::zero_load, &bs)) throw InputError("fit: the initial guess has no stable branch");
  // Uniform in t = delta - delta0 over every offset the scan tries.
  const double t_hi = 2.0 * span;
  m.t.push_back(bs.delta);
  double P_start, d_start;
  ev.curve(p, bs.a, &d_start, &P_start, nullptr, nullptr);
  m.P.push_back(P_start);
  double lo = bs.a;
  const int n = 160;
  for (int k = 1; k <= n && bs.delta < t_hi; ++k) {
    const double t = bs.delta + (t_hi - bs.delta) * k / n;
    double P;
    const double a = ev.solve_radius(p, t, lo, lo, &P);
    if (!std::isfinite(a)) break;
    lo = a;
    m.t.push_back(t);
    m.P.push_back(P);
  }
  return m;
}

// Contact point and stiffness by a scan: for each trial delta0 the stiffness factor is the
// linear least-squares solution, so a scene's stiffness may be off by any factor.
Start scan_start(const FitData& d, const MasterCurve& approach, const MasterCurve& retract,
                 const ParameterMap& map, double P0, double span) {
  const bool free_d0 = map.is_free(FitParameter::delta0);
  const bool free_k = map.is_free(FitParameter::K) || map.is_free(FitParameter::E);
  const std::size_t n = d.delta.size(), stride = std::max<std::size_t>(1, n / 48);
  const double dmin = *std::min_element(d.delta.begin(), d.delta.end());
  // A subsample per branch, sorted by delta, so each trial walks the master curve once.
  std::array<std::vector<std::pair<double, double>>, 2> pts;
  for (std::size_t i = 0; i < n; i += stride) pts[d.retract[i] ? 1 : 0].emplace_back(d.delta[i], d.P[i] - P0);
  for (auto& v : pts) std::sort(v.begin(), v.end());
  const std::array<const MasterCurve*, 2> masters{&approach, &retract};
  auto trial = [&](double d0, Start* s) {
    double spp = 0.0, spy = 0.0, syy = 0.0, base = 0.0;
    std::size_t contact = 0;
    for (int b = 0; b < 2; ++b) {
      const MasterCurve& mc = *masters[b];
      std::size_t k = 0;
      for (const auto& [delta, y] : pts[b]) {
        const double x = delta - d0;
        if (x < mc.t.front()) {
          base += y * y;
          continue;
        }
        while (k + 1 < mc.t.size() && mc.t[k + 1] <= x) ++k;
        const double m = k + 1 < mc.t.size()
                             ? mc.P[k] + (x - mc.t[k]) / (mc.t[k + 1] - mc.t[k]) * (mc.P[k + 1] - mc.P[k])
                             : mc.P.back();
        ++contact;
        spp += m * m;
        spy += m * y;
        syy += y * y;
      }
    }
    double k = free_k ? (spp > 0.0 ? std::max(spy / spp, 0.0) : 0.0) : 1.0;
    const double cost = base + syy - 2.0 * k * spy + k * k * spp;
    s->delta0 = d0;
    s->stiffness_factor = k > 0.0 ? k : 1.0;
    s->contact = contact;
    return contact >= 3 && k > 0.0 ? cost : std::numeric_limits<double>::infinity();
  };
  Start best;
  best.P0 = P0;
  if (!free_d0 || d.contact_given) {
    best.cost = trial(0.0, &best);
    best.found = std::isfinite(best.cost);
    return best;
  }
  double best_cost = std::numeric_limits<double>::infinity();
  double step = span / 16.0;
  double centre = dmin + 0.5 * span;
  int count = 17;
  for (int pass = 0; pass < 3; ++pass) {
    const double c0 = centre;
    for (int k = 0; k < count; ++k) {
      Start s;
      s.P0 = P0;
      const int offset = k - count / 2;
      const double d0 = c0 + offset * step;
      const double c = trial(d0, &s);
      if (c < best_cost) {
        best_cost = c;
        best = s;
      }
    }
    centre = best.delta0;
    step /= 4.0;
    count = 9;
  }
  best.found = std::isfinite(best_cost);
  best.cost = best_cost;
  return best;
}

}  // namespace

void find_start(FitData& data, ParameterMap& map, const CurveEvaluator& ev, std::vector<double>& x,
                const std::string& source) {
  const double span = map.L, force_span = map.F;
  // Data-driven start: the baseline of the shallowest quarter (select_fit_data), then a
  // contact-point scan with the stiffness solved linearly at each trial.
  // Unloading-only data hold no samples at rest: their shallowest quarter is the pull-off or a
  // tail, not a baseline, so P0 starts at 0 (the force's own zero).
  const double P0_start = map.is_free(FitParameter::P0) && !data.unloading_only ? data.baseline : 0.0;
  // Alternate the contact-point scan (at the current w) and the adhesion estimate: w from the
  // measured pull-off (read from the data before the fit: data.dip, data.adhesive, data.contact),
  // where the model's pull-off must match it.
  const double dip = data.dip;
  const bool estimate_w = map.is_free(FitParameter::w) && data.adhesive;
  const int stiffness_index = static_cast<int>(map.is_free(FitParameter::K) ? FitParameter::K : FitParameter::E);
  // The stiffness reference times f, and a free G's scale with it (the curve's shape stays).
  const auto scale_stiffness = [&](double f) {
    map.ref[stiffness_index] *= f;
    if (map.is_free(FitParameter::G) && !map.G_log) map.G_scale *= f;
    if (map.is_free(FitParameter::G) && map.G_log) map.ref[static_cast<int>(FitParameter::G)] *= f;
  };
  // One start: alternate the scan and the w estimate from the map's current stiffness until both
  // settle; returns the last scan's cost (infinite where no trial put samples in contact).
  const auto start_from = [&]() -> double {
    double cost = std::numeric_limits<double>::infinity();
    // The last pass that found a start: a later w estimate that leaves no trial in contact (a
    // tension-only unloading with P0 free) falls back to it rather than refusing the curve.
    std::optional<std::pair<ParameterMap, std::vector<double>>> last_found;
    double last_cost = cost;
    for (int pass = 0; pass < 8; ++pass) {
      CurveParameters<double> p;
      double d0, P0;
      map.physical(x.data(), &p, &d0, &P0);
      const bool any_retract = std::find(data.retract.begin(), data.retract.end(), true) != data.retract.end();
      const bool any_approach = std::find(data.retract.begin(), data.retract.end(), false) != data.retract.end();
      const MasterCurve none{{std::numeric_limits<double>::infinity()}, {0.0}};
      const Start start = scan_start(data, any_approach ? master_curve(ev, p, span, false) : none,
                                     any_retract ? master_curve(ev, p, span, true) : none, map, P0_start, span);
      cost = start.cost;
      if (!start.found && last_found) {
        map = last_found->first;
        x = last_found->second;
        cost = last_cost;
        break;
      }
      if (!start.found) {
        // An all-tensile retract (w = 0 cannot produce it): put the contact point at the
        // observed pull-off, keep the scene's stiffness, estimate w and scan again.
        if (!(pass == 0 && estimate_w))
          throw InputError(source + ": no contact region - no trial contact point puts three or more "
                           "samples in contact with a positive stiffness" + no_contact_hint(data));
        const auto deepest = std::min_element(data.P.begin(), data.P.end()) - data.P.begin();
        map.ref[static_cast<int>(FitParameter::delta0)] = data.delta[static_cast<std::size_t>(deepest)];
        map.ref[static_cast<int>(FitParameter::P0)] = P0_start;
      }
      if (start.found) {
        map.ref[static_cast<int>(FitParameter::delta0)] = start.delta0;
        map.ref[static_cast<int>(FitParameter::P0)] = start.P0;
      }
      if (map.is_free(FitParameter::K) || map.is_free(FitParameter::E)) scale_stiffness(start.stiffness_factor);
      if (start.found) {
        last_found.emplace(map, x);
        last_cost = start.cost;
      }
      // Without adhesion and shear term the curve's shape does not depend on the stiffness.
      const bool settled = start.found && (std::abs(std::log(start.stiffness_factor)) < 0.01 || (p.s == 0.0 && p.G == 0.0));
      if (!estimate_w && settled) break;
      if (estimate_w && settled && pass >= 2) break;
      if (!estimate_w) continue;
      map.physical(x.data(), &p, &d0, &P0);
      double lo = std::log(kWBracketLow * force_span / span), hi = std::log(kWBracketHigh * force_span / span);
      for (int it = 0; it < 40; ++it) {
        const double mid = 0.5 * (lo + hi);
        p.s = std::sqrt(std::exp(mid));
        if (map.fixed.sigma0_per_w > 0.0 && !map.is_free(FitParameter::sigma0)) p.sigma0 = map.fixed.sigma0_per_w * p.s * p.s;
        detail::BranchStart bs;
        double P = 0.0, d;
        const bool ok = ev.branch_start(p, detail::StartKind::pull_off, &bs);
        if (ok) ev.curve(p, bs.a, &d, &P, nullptr, nullptr);
        (ok && P > dip ? lo : hi) = mid;
      }
      map.s_scale = std::sqrt(std::exp(0.5 * (lo + hi)));
      x[static_cast<std::size_t>(map.index(FitParameter::w))] = 1.0;
    }
    return cost;
  };
  const bool free_stiffness = map.is_free(FitParameter::K) || map.is_free(FitParameter::E);
  if (!estimate_w || !free_stiffness) {
    start_from();
    return;
  }
  // With adhesion the curve's shape depends on the stiffness, and the alternation can settle on a
  // wrong pair from a scene far off (E 6x high from a start 3x high on a tension-only unloading).
  // It starts from the scene's stiffness and from kStartStiffnessFactors times it; the start whose
  // scan follows the data best is kept, so the start does not depend on the scene's guess.
  const ParameterMap scene_map = map;
  const std::vector<double> scene_x = x;
  ParameterMap best_map = map;
  std::vector<double> best_x = x;
  double best_cost = std::numeric_limits<double>::infinity();
  std::optional<InputError> scene_refusal;
  for (double factor : kStartStiffnessFactors) {
    map = scene_map;
    x = scene_x;
    scale_stiffness(factor);
    double cost = std::numeric_limits<double>::infinity();
    try {
      cost = start_from();
    } catch (const InputError& e) {
      // A start that fails from the scene's stiffness (no stable branch for a film 10x too
      // soft) may succeed from another: the curve is refused only when every start fails, with
      // the scene's own reason.
      if (factor == 1.0) scene_refusal.emplace(e);
    }
    if (cost < best_cost) {
      best_cost = cost;
      best_map = map;
      best_x = x;
    }
  }
  if (!std::isfinite(best_cost) && scene_refusal) throw *scene_refusal;
  map = best_map;
  x = best_x;
}

void find_radius_start(FitData& data, ParameterMap& map, const CurveEvaluator& ev, std::vector<double>& x) {
  CurveParameters<double> p;
  double d0 = 0.0, P0 = 0.0;
  map.physical(x.data(), &p, &d0, &P0);
  const bool free_k = map.is_free(FitParameter::K) || map.is_free(FitParameter::E);
  const bool free_w = map.is_free(FitParameter::w), free_P0 = map.is_free(FitParameter::P0);
  // Columns h (the non-adhesive force), g (the adhesive term at w = 1) and 1; unknowns k, c, P0.
  const double w_fixed = p.s * p.s;
  Eigen::MatrixXd A(static_cast<Eigen::Index>(data.P.size()), 3);
  Eigen::VectorXd b(static_cast<Eigen::Index>(data.P.size()));
  for (std::size_t i = 0; i < data.P.size(); ++i) {
    double d = 0.0, h = 0.0, q = 0.0;
    p.s = 0.0;
    ev.curve(p, data.a[i], &d, &h, nullptr, nullptr);
    p.s = 1.0;
    ev.curve(p, data.a[i], &d, &q, nullptr, nullptr);
    const auto r = static_cast<Eigen::Index>(i);
    const double sw = data.sqrt_weight[i];
    A(r, 0) = sw * h;
    A(r, 1) = -sw * (h - q);
    A(r, 2) = sw;
    // What is not free is known: moved to the right-hand side.
    b(r) = sw * (data.P[i] - (free_P0 ? 0.0 : P0) - (free_k ? 0.0 : h) + (free_w ? 0.0 : std::sqrt(w_fixed) * (h - q)));
  }
  std::vector<Eigen::Index> cols;
  if (free_k) cols.push_back(0);
  if (free_w) cols.push_back(1);
  if (free_P0) cols.push_back(2);
  double k = 1.0, c = std::sqrt(w_fixed), P0_start = free_P0 ? 0.0 : P0;
  if (!cols.empty()) {
    Eigen::MatrixXd M(A.rows(), static_cast<Eigen::Index>(cols.size()));
    for (std::size_t j = 0; j < cols.size(); ++j) M.col(static_cast<Eigen::Index>(j)) = A.col(cols[j]);
    const Eigen::VectorXd sol = M.colPivHouseholderQr().solve(b);
    for (std::size_t j = 0; j < cols.size(); ++j) {
      const double v = sol(static_cast<Eigen::Index>(j));
      if (cols[j] == 0 && v > 0.0) k = v;
      if (cols[j] == 1) c = std::max(v, 0.0);
      if (cols[j] == 2) P0_start = v;
    }
  }
  if (free_k) map.ref[static_cast<int>(map.is_free(FitParameter::K) ? FitParameter::K : FitParameter::E)] *= k;
  if (free_P0) map.ref[static_cast<int>(FitParameter::P0)] = P0_start;
  if (free_w) {
    // c = sqrt(k w) at the reference stiffness; a w of zero starts just above its bound.
    const double w = c * c / k;
    map.s_scale = w > 0.0 ? std::sqrt(w) : map.s_scale;
    x[static_cast<std::size_t>(map.index(FitParameter::w))] = w > 0.0 ? 1.0 : 1e-3;
  }
  data.adhesive = c > 0.0;
}

}  // namespace layerjkr::detail
