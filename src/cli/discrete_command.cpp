#include "discrete_command.hpp"

#include <cmath>
#include <iostream>
#include <sstream>

#include <CLI/CLI.hpp>

#include "layerjkr/contact.hpp"
#include "layerjkr/discrete.hpp"
#include "layerjkr/error.hpp"
#include "summary_json.hpp"

namespace layerjkr::cli {

void add_discrete_options(CLI::App& c, DiscreteArguments& a) {
  c.add_option("--flat", a.flat, "Flat-punch load steps, CSV a,delta,P (4 or more radii)")->required();
  c.add_option("--convex", a.convex, "Convex-indenter curve, CSV delta,P[,a]")->required();
  c.add_option("--w", a.w, "Work of adhesion [J/m^2], >= 0")->required();
  c.add_option("--at", a.at, "Comma-separated contact radii [m]");
  c.add_option("--points", a.points, "N radii evenly spread over the data's range");
  c.add_flag("--summary", a.summary, "Print the summary JSON (pull-off, zero load, fixed grips)");
  c.add_flag("--single-model", a.single, "Use the convex data alone (S' by two differentiations), for comparison");
  c.add_option("--linearity", a.linearity, "Largest rms deviation of a flat-punch step from its line (default 0.01)");
}

int run_discrete(const DiscreteArguments& a) {
  if (!(a.w >= 0.0) || !std::isfinite(a.w)) throw InputError("--w = " + format_double(a.w) + " must be finite and >= 0");
  const int modes = int(!a.at.empty()) + int(a.points > 0) + int(a.summary);
  if (modes != 1) throw InputError("discrete needs exactly one of --at, --points N (N >= 1) or --summary");
  DiscreteOptions o;
  o.linearity_tolerance = a.linearity;
  const ConvexData convex = read_convex_csv(a.convex);
  const ContactModelPtr model = a.single ? make_single_model(convex, o) : make_discrete_model(read_flat_punch_csv(a.flat), convex, o);
  const JkrSolution jkr(model, a.w);
  if (a.summary) {
    std::cout << summary_json(summarize(jkr), "(data)").dump(2) << "\n";
    return 0;
  }
  std::vector<double> radii;
  if (!a.at.empty()) {
    std::stringstream in(a.at);
    for (std::string item; std::getline(in, item, ',');) {
      char* end = nullptr;
      const double v = std::strtod(item.c_str(), &end);
      if (item.empty() || *end != '\0' || !std::isfinite(v)) throw InputError("--at: '" + item + "' is not a finite number");
      radii.push_back(v);
    }
  } else {
    const double lo = model->min_radius() / (1.0 - 1e-12), hi = model->max_radius();
    for (int i = 0; i < a.points; ++i) radii.push_back(a.points == 1 ? lo : lo + (hi - lo) * i / (a.points - 1));
  }
  std::string out = "a,P,delta,P_H,delta_H,S\n";
  for (const AdhesiveState& s : jkr.curve(radii))
    out += format_double(s.a) + "," + format_double(s.P) + "," + format_double(s.delta) + "," + format_double(s.hertz.P_H) +
           "," + format_double(s.hertz.delta_H) + "," + format_double(s.hertz.S) + "\n";
  std::cout << out;
  return 0;
}

}  // namespace layerjkr::cli
