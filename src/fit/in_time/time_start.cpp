// The start of a fit in time, and what the fitted law says of itself (time_fit.hpp).
#include <algorithm>
#include <cmath>
#include <limits>

#include "fit/run/fit_steps.hpp"
#include "layerjkr/error.hpp"
#include "fit/in_time/time_fit.hpp"

namespace layerjkr::detail {
namespace {

bool has(const std::vector<FitParameter>& free, FitParameter q) {
  return std::find(free.begin(), free.end(), q) != free.end();
}

// The loading time [s]: from the first sample past delta0 to the deepest.
double loading_time(const FitData& data, double delta0) {
  std::size_t first = data.P.size(), deepest = 0;
  for (std::size_t i = 0; i < data.P.size(); ++i) {
    if (first == data.P.size() && data.delta[i] - delta0 > 0.0) first = i;
    if (data.delta[i] > data.delta[deepest]) deepest = i;
  }
  if (first >= deepest) return data.t.size() > 1 ? data.t.back() - data.t.front() : 1.0;
  return data.t[deepest] - data.t[first];
}

// The mean of psi over a loading of length T: a standard linear solid's and a power law's.
double mean_relaxation_sls(double ratio, double tau, double T) {
  const double x = T / tau;
  return ratio + (1.0 - ratio) * (x < 1e-8 ? 1.0 : -std::expm1(-x) / x);
}

double cost_at(ResidualModel& ev, const std::vector<double>& x) {
  if (!ev.evaluate(x.data(), false)) return std::numeric_limits<double>::infinity();
  return least_squares_cost(ev.residuals());
}

int slot(const ParameterMap& map, FitParameter q) { return map.index(q); }

}  // namespace

void start_in_time(const CurveData& curve, const Scene& elastic, const Scene& scene, const FitOptions& options,
                   const FitData& data, ResidualModel& ev, ParameterMap& map, std::vector<double>& x, FitSummary* out) {
  const bool relaxes = scene.medium.relaxation.kind != RelaxationLaw::Kind::elastic;
  const RelaxationLaw& law = scene.medium.relaxation;
  FitOptions e = options;
  e.free.clear();
  for (FitParameter q : options.free)
    if (!time_parameter(q)) e.free.push_back(q);
  e.compute_covariance = false;
  e.extra_starts = 0;
  // The approach alone: a relaxing medium's retract and a kinetic retract would bend an elastic fit
  // (its contact point most: 3.6 um off on a kinetic curve at 3 um/s); the approach is the law's
  // loading, or JKR's equilibrium itself.
  e.branch = Branch::approach;
  double E_elastic = map.fixed_value(FitParameter::E), delta0 = 0.0;
  std::string said;
  if (!e.free.empty()) {
    const FitSummary s = fit(curve, elastic, e);
    for (const ParameterEstimate& p : s.parameters) {
      const int k = static_cast<int>(p.parameter);
      switch (p.parameter) {
        case FitParameter::w: x[static_cast<std::size_t>(slot(map, p.parameter))] = std::sqrt(p.value) / map.s_scale; break;
        case FitParameter::G:
          if (map.G_log) map.ref[k] = p.value;
          else x[static_cast<std::size_t>(slot(map, p.parameter))] = p.value / map.G_scale;
          break;
        default: map.ref[k] = p.value;
      }
      if (p.parameter == FitParameter::E) E_elastic = p.value;
      if (p.parameter == FitParameter::delta0) delta0 = p.value;
      said += (said.empty() ? "" : ", ") + std::string(to_string(p.parameter)) + " = " + short_number(p.value);
    }
  }
  // The elastic fit's E averages the modulus over the loading; the law's E is its start.
  const double T = loading_time(data, delta0);
  const bool E_free = has(options.free, FitParameter::E);
  const auto E_for = [&](double psi_mean) { return E_free ? E_elastic / psi_mean : map.fixed_value(FitParameter::E); };
  struct Candidate {
    double E, E_inf, tau, beta, v_star, w_factor = 1.0, E_2 = 0.0, tau_2 = 0.0;
  };
  std::vector<Candidate> candidates;
  const double E_inf0 = map.ref[static_cast<int>(FitParameter::E_inf)], tau0 = map.ref[static_cast<int>(FitParameter::tau)];
  const double beta0 = map.fixed_value(FitParameter::beta), v0 = map.ref[static_cast<int>(FitParameter::v_star)];
  if (relaxes && law.kind == RelaxationLaw::Kind::prony && law.g.size() == 1) {
    const double ratio0 = map.fixed_value(FitParameter::E_inf) / map.fixed_value(FitParameter::E);
    std::vector<double> taus{tau0}, ratios{ratio0};
    if (has(options.free, FitParameter::tau)) taus = {tau0, T / 30, T / 10, T / 3, T, 3 * T};
    if (has(options.free, FitParameter::E_inf)) ratios = {ratio0, 0.25, 0.5, 0.75};
    for (double tau : taus)
      for (double r : ratios) {
        const double E = E_for(mean_relaxation_sls(r, tau, T));
        candidates.push_back({E, r * E, tau, beta0, v0});
      }
  } else if (relaxes && law.kind == RelaxationLaw::Kind::power_law) {
    std::vector<double> betas{beta0}, ratios{law.plateau};
    if (has(options.free, FitParameter::beta)) betas = {beta0, 0.03, 0.1, 0.2, 0.35, 0.5};
    if (law.plateau_form) {
      ratios = {map.fixed_value(FitParameter::E_inf) / map.fixed_value(FitParameter::E)};
      // E_inf is fitted on a log scale: the candidates are plateaus > 0.
      if (has(options.free, FitParameter::E_inf)) ratios = {ratios[0] > 0.0 ? ratios[0] : 0.1, 0.25, 0.5, 0.75};
    }
    for (double b : betas)
      for (double r : ratios) {
        const double E = E_for(r + (1.0 - r) * std::pow(0.5 * T / law.t0, -b));
        candidates.push_back({E, law.plateau_form ? r * E : E_inf0, tau0, b, v0});
      }
  } else if (relaxes && law.two_term_form) {
    // A fast and a slow arm: the fast one from a thirtieth to a third of the loading, the slow one
    // from the loading to ten times it, each with the scene's own values.
    const double E0 = map.fixed_value(FitParameter::E);
    const double r_inf0 = map.fixed_value(FitParameter::E_inf) / E0, r_20 = map.fixed_value(FitParameter::E_2) / E0;
    const double tau_20 = map.ref[static_cast<int>(FitParameter::tau_2)];
    std::vector<double> taus{tau0}, taus_2{tau_20}, r_infs{r_inf0}, r_2s{r_20};
    if (has(options.free, FitParameter::tau)) taus = {tau0, T / 30, T / 5};
    if (has(options.free, FitParameter::tau_2)) taus_2 = {tau_20, T, 10 * T};
    if (has(options.free, FitParameter::E_inf)) r_infs = {r_inf0 > 0.0 ? r_inf0 : 0.25, 0.3};
    if (has(options.free, FitParameter::E_2)) r_2s = {r_20, 0.3};
    for (double tau : taus)
      for (double tau_2 : taus_2)
        for (double r_inf : r_infs)
          for (double r_2 : r_2s) {
            if (!(r_inf + r_2 < 1.0) || !(tau < tau_2)) continue;
            const double mean = r_inf + (1.0 - r_inf - r_2) * mean_relaxation_sls(0.0, tau, T) +
                                r_2 * mean_relaxation_sls(0.0, tau_2, T);
            const double E = E_for(mean);
            Candidate c{E, r_inf * E, tau, beta0, v0};
            c.E_2 = r_2 * E;
            c.tau_2 = tau_2;
            candidates.push_back(c);
          }
    if (candidates.empty()) candidates.push_back({E_for(1.0), r_inf0 * E0, tau0, beta0, v0, 1.0, r_20 * E0, tau_20});
  } else if (relaxes && law.kind == RelaxationLaw::Kind::fractional) {
    std::vector<double> betas{beta0}, taus{tau0}, ratios{law.plateau};
    if (has(options.free, FitParameter::beta)) betas = {beta0, 0.15, 0.35, 0.6};
    if (has(options.free, FitParameter::tau)) taus = {tau0, T / 30, T / 3, 3 * T};
    if (law.plateau_form) {
      ratios = {map.fixed_value(FitParameter::E_inf) / map.fixed_value(FitParameter::E)};
      if (has(options.free, FitParameter::E_inf)) ratios = {ratios[0] > 0.0 ? ratios[0] : 0.1, 0.3, 0.6};
    }
    for (double b : betas)
      for (double tau : taus)
        for (double r : ratios) {
          // The law's value at half the loading stands for its mean there, as for the power law.
          const double E = E_for(RelaxationLaw::fractional_sls(b, tau, r).relative_modulus(0.5 * T));
          candidates.push_back({E, law.plateau_form ? r * E : E_inf0, tau, b, v0});
        }
  } else if (relaxes) {
    double g_inf = 1.0, mean = 1.0;  // a longer Prony law: its mean over the loading
    for (std::size_t i = 0; i < law.g.size(); ++i) g_inf -= law.g[i];
    mean = g_inf;
    for (std::size_t i = 0; i < law.g.size(); ++i) mean += law.g[i] * mean_relaxation_sls(0.0, law.tau[i], T);
    candidates.push_back({E_for(mean), E_inf0, tau0, beta0, v0});
  } else {
    // The crack's speed scale: the scene's, and two decades either way in half decades.
    std::vector<double> speeds{v0};
    if (has(options.free, FitParameter::v_star))
      for (int k = -6; k <= 6; ++k)
        if (k != 0) speeds.push_back(v0 * std::pow(10.0, 0.5 * k));
    // The approach tells w0 only through the loading curve's shape: a few decades around its value.
    std::vector<double> w_factors{1.0};
    if (has(options.free, FitParameter::w)) w_factors = {1.0, 0.3, 0.1, 3.0};
    for (double f : w_factors)
      for (double v : speeds) candidates.push_back({map.ref[static_cast<int>(FitParameter::E)], E_inf0, tau0, beta0, v, f});
  }
  // The references sit at the scene's values; each candidate is a point x.
  const std::vector<double> x_elastic = x;
  const auto put = [&](const Candidate& c) {
    if (map.is_free(FitParameter::w)) {
      const auto k = static_cast<std::size_t>(map.index(FitParameter::w));
      // An approach without adhesive signal leaves w at 0: the scene's w then sets the scale.
      const double x_w = x_elastic[k] > 0.0 ? x_elastic[k] : std::sqrt(map.fixed_value(FitParameter::w)) / map.s_scale;
      x[k] = x_w * std::sqrt(c.w_factor);
    }
    const auto set_log = [&](FitParameter q, double v) {
      if (map.is_free(q)) x[static_cast<std::size_t>(map.index(q))] = std::log(v / map.ref[static_cast<int>(q)]);
    };
    if (relaxes) set_log(FitParameter::E, c.E);
    set_log(FitParameter::E_inf, c.E_inf);
    set_log(FitParameter::tau, c.tau);
    if (c.tau_2 > 0.0) {
      set_log(FitParameter::E_2, c.E_2);
      set_log(FitParameter::tau_2, c.tau_2);
    }
    set_log(FitParameter::v_star, c.v_star);
    if (map.is_free(FitParameter::beta))
      x[static_cast<std::size_t>(map.index(FitParameter::beta))] = (c.beta - map.ref[static_cast<int>(FitParameter::beta)]) / map.beta_scale;
  };
  ev.invalidate();
  double best = std::numeric_limits<double>::infinity();
  std::vector<double> best_x = x;
  for (const Candidate& c : candidates) {
    put(c);
    const double cost = cost_at(ev, x);
    if (cost < best) {
      best = cost;
      best_x = x;
    }
  }
  x = best_x;
  std::string law_start;
  for (FitParameter q : options.free)
    if (q == FitParameter::E || q == FitParameter::E_inf || q == FitParameter::tau || q == FitParameter::beta ||
        q == FitParameter::E_2 || q == FitParameter::tau_2 ||
        q == FitParameter::v_star || (q == FitParameter::w && !relaxes))
      law_start += (law_start.empty() ? "" : ", ") + std::string(to_string(q)) + " = " + short_number(map.value(q, x.data()));
  out->notices.push_back("start: " + (said.empty() ? std::string("the scene's values") : "an elastic fit of the " +
                         std::string(to_string(e.branch)) + " (" + said + ")") +
                         (law_start.empty() ? std::string() : "; then " + law_start + ", the best of " +
                                                                  std::to_string(candidates.size()) + " starts of the law"));
}

void judge_law(const ParameterMap& map, const std::vector<double>& x, const Scene& scene, const FitData& data,
               FitSummary* out) {
  const RelaxationLaw& law = scene.medium.relaxation;
  CurveParameters<double> p;
  double d0 = 0.0, P0 = 0.0;
  map.physical(x.data(), &p, &d0, &P0);
  const double span = data.t.size() > 1 ? data.t.back() - data.t.front() : 0.0;
  double step = span;
  for (std::size_t i = 1; i < data.t.size(); ++i) step = std::min(step, data.t[i] - data.t[i - 1]);
  // A free time beyond the data's scales: one warning, with what it means for this law.
  const auto beyond_scales = [&](FitParameter q, const std::string& meaning) {
    const double v = map.value(q, x.data());
    if (map.is_free(q) && (v < step || v > 10.0 * span))
      out->warnings.push_back(std::string(to_string(q)) + " = " + short_number(v) + " s lies outside the data's time " +
                              "scales (" + short_number(step) + " s between samples, " + short_number(span) +
                              " s in all): " + meaning);
  };
  if (law.kind == RelaxationLaw::Kind::prony && law.g.size() == 1) {
    if (p.E_inf > p.E)
      out->warnings.push_back("the relaxed modulus E_inf = " + short_number(p.E_inf) + " Pa exceeds the instantaneous E = " +
                              short_number(p.E) + " Pa: the data stiffen in time rather than relax; the law does not "
                              "describe them");
    beyond_scales(FitParameter::tau, std::string("the data cannot tell its value, only that relaxation is ") +
                                         (p.tau < step ? "faster" : "slower") + " than they resolve");
  }
  if (law.kind == RelaxationLaw::Kind::power_law && map.is_free(FitParameter::beta) && p.beta < 1e-3)
    out->notices.push_back("beta = " + short_number(p.beta) + ": no relaxation the data resolve");
  if (law.two_term_form)
    for (FitParameter q : {FitParameter::tau, FitParameter::tau_2})
      beyond_scales(q, "that arm is a constant or an instant to these data; one arm (\"sls\") may describe them as "
                       "well - compare by AIC");
  if (law.kind == RelaxationLaw::Kind::fractional) {
    beyond_scales(FitParameter::tau, "the fractional law's tau and E trade off there; a power law describes the same "
                                     "data with fewer parameters");
    if (map.is_free(FitParameter::beta) && p.beta > 0.9)
      out->notices.push_back("beta = " + short_number(p.beta) + " is near the fractional law's limit of 0.95, where it "
                             "becomes the standard linear solid (\"sls\"): compare the two by AIC");
  }
}

}  // namespace layerjkr::detail
