// layerjkr CLI: `discrete` - the two-model approach on data files (discrete.hpp).
#pragma once

#include <string>

namespace CLI {
class App;
}

namespace layerjkr::cli {

struct DiscreteArguments {
  std::string flat, convex, at, smoothing = "polynomial";
  double w = 0.0, linearity = 0.01;
  int points = 0, bootstrap = 200;
  unsigned seed = 1;
  bool summary = false, single = false;
};

void add_discrete_options(CLI::App& command, DiscreteArguments& args);

/// Curve CSV (a,P,delta,P_H,delta_H,S and the bootstrap's P_err,delta_err) at --at radii or
/// --points N over the data's radii, or with --summary the summary JSON keys and a bootstrap
/// object with the errors of the pull-off force and the zero-load radius.
int run_discrete(const DiscreteArguments& args);

}  // namespace layerjkr::cli
