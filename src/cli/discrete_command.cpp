#include "discrete_command.hpp"

#include <cmath>
#include <iostream>

#include <CLI/CLI.hpp>

#include "layerjkr/contact.hpp"
#include "layerjkr/discrete.hpp"
#include "layerjkr/error.hpp"
#include "limits.hpp"
#include "reports.hpp"

namespace layerjkr::cli {

void add_discrete_options(CLI::App& c, DiscreteArguments& a) {
  c.add_option("--flat", a.flat, "Flat-punch load steps, CSV a,delta,P (4 or more radii); not with --single-model");
  c.add_option("--convex", a.convex, "Convex-indenter curve, CSV delta,P[,a]")->required();
  c.add_option("--w", a.w, "Work of adhesion [J/m^2], >= 0")->required();
  c.add_option("--at", a.at, "Comma-separated contact radii [m]");
  c.add_option("--points", a.points, "N radii evenly spread over the data's range");
  c.add_flag("--summary", a.summary, "Print the summary JSON (pull-off, zero load, fixed grips)");
  c.add_flag("--single-model", a.single, "Use the convex data alone (S' by two differentiations), for comparison");
  c.add_option("--linearity", a.linearity, "Largest rms deviation of a flat-punch step from its line (default 0.01)");
  c.add_option("--smoothing", a.smoothing, "Log-log smoothing of both data sets: polynomial (default) or spline");
  c.add_option("--bootstrap", a.bootstrap, "Replicates of the residual bootstrap behind the error columns (default 200, 20 .. 100000)");
  c.add_option("--seed", a.seed, "Seed of the bootstrap's resampling (default 1)");
}

namespace {

void warn_failed(const DiscreteUncertainty& u) {
  if (u.failed > 0)
    std::cerr << "layerjkr: warning: " << u.failed << " of " << u.replicates
              << " bootstrap replicates made no model (the resampled data no longer overlap); the errors use the rest\n";
}

Smoothing parse_smoothing(const std::string& name) {
  if (name == "polynomial") return Smoothing::log_polynomial;
  if (name == "spline") return Smoothing::log_spline;
  throw InputError("--smoothing = '" + name + "' is not known (polynomial or spline)");
}

}  // namespace

int run_discrete(const DiscreteArguments& a) {
  if (!(a.w >= 0.0) || !std::isfinite(a.w)) throw InputError("--w = " + format_double(a.w) + " must be finite and >= 0");
  const int modes = int(!a.at.empty()) + int(a.points > 0) + int(a.summary);
  if (modes != 1) throw InputError("discrete needs exactly one of --at, --points N (N >= 1) or --summary");
  if (a.points > 0) check_count("--points", a.points, 1, kMaxPoints);
  if (a.single == !a.flat.empty())
    throw InputError(a.single ? "--single-model uses the convex data alone: drop --flat" : "discrete needs --flat FILE (or --single-model)");
  DiscreteOptions o;
  o.linearity_tolerance = a.linearity;
  o.smoothing = parse_smoothing(a.smoothing);
  BootstrapOptions b;
  b.replicates = a.bootstrap;
  b.seed = a.seed;
  b.validate();
  const ConvexData convex = read_convex_csv(a.convex);
  const FlatPunchData flat = a.single ? FlatPunchData{} : read_flat_punch_csv(a.flat);
  const ContactModelPtr model = a.single ? make_single_model(convex, o) : make_discrete_model(flat, convex, o);
  const DiscreteApproach approach = a.single ? DiscreteApproach::single_model : DiscreteApproach::two_models;
  const JkrSolution jkr(model, a.w);
  // The data's radii (min_radius() carries a rounding margin below the smallest).
  const double a_lo = model->min_radius() / (1.0 - 1e-12), a_hi = model->max_radius();
  if (a.summary) {
    const DiscreteUncertainty u = bootstrap_discrete(flat, convex, a.w, {}, approach, o, b);
    warn_failed(u);
    const ContactSummary summary = summarize(jkr);
    auto j = contact_json(summary, "(data)");
    const std::string range = "[" + format_double(a_lo) + ", " + format_double(a_hi) + "] m";
    std::vector<std::string> warnings;
    if (!summary.pull_off) warnings.push_back("no pull-off force within the data's radii " + range + "; it needs data that reach it");
    if (!summary.zero_load_radius) warnings.push_back("no zero-load radius within the data's radii " + range);
    if (!summary.fixed_grips) warnings.push_back("no fixed-grips critical point within the data's radii " + range);
    for (const std::string& line : warnings) std::cerr << "layerjkr: warning: " << line << "\n";
    j["warnings"] = warnings;
    auto finite = [](double v) { return std::isfinite(v) ? nlohmann::ordered_json(v) : nullptr; };
    j["bootstrap"] = {{"replicates", u.replicates},
                      {"failed", u.failed},
                      {"pull_off_force_err", finite(u.pull_off_force_err)},
                      {"zero_load_radius_err", finite(u.zero_load_radius_err)}};
    std::cout << j.dump(2) << "\n";
    return 0;
  }
  std::vector<double> radii;
  if (!a.at.empty()) {
    radii = parse_radii(a.at);
  } else {
    for (int i = 0; i < a.points; ++i) radii.push_back(a.points == 1 ? a_lo : a_lo + (a_hi - a_lo) * i / (a.points - 1));
  }
  const std::vector<AdhesiveState> states = jkr.curve(radii);
  const DiscreteUncertainty u = bootstrap_discrete(flat, convex, a.w, radii, approach, o, b);
  warn_failed(u);
  for (std::size_t k = 0; k < radii.size(); ++k)
    if (u.used[k] < u.replicates - u.failed)
      std::cerr << "layerjkr: warning: a = " << format_double(radii[k]) << " m lies outside the radius range of "
                << (u.replicates - u.failed - u.used[k]) << " bootstrap replicates (the edge of the data); its errors use the other "
                << u.used[k] << (u.used[k] < 2 ? " and are not defined (nan)" : "") << "\n";
  std::string out = "a,P,delta,P_H,delta_H,S,P_err,delta_err\n";
  for (std::size_t k = 0; k < states.size(); ++k) {
    const AdhesiveState& s = states[k];
    out += format_double(s.a) + "," + format_double(s.P) + "," + format_double(s.delta) + "," + format_double(s.hertz.P_H) +
           "," + format_double(s.hertz.delta_H) + "," + format_double(s.hertz.S) + "," + format_double(u.P_err[k]) + "," +
           format_double(u.delta_err[k]) + "\n";
  }
  std::cout << out;
  return 0;
}

}  // namespace layerjkr::cli
