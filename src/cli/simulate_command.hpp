// layerjkr CLI: `simulate` - a synthetic curve from a scene (simulate.hpp), as CSV.
#pragma once

#include <string>

#include <CLI/CLI.hpp>

#include "layerjkr/simulate.hpp"

namespace layerjkr::cli {

struct SimulateArguments {
  std::string scene, out = "-", branch = "all", control = "grips";
  SimulationOptions options;
  int points = 500;
  CLI::Option* stiffness = nullptr;
  CLI::Option* seed = nullptr;
};

/// Adds simulate's positional scene and its options to `command`.
void add_simulate_options(CLI::App& command, SimulateArguments& args);

/// Writes t,delta,P[,a],segment (t with --speed; a with --with-radius) to args.out after the
/// simulation succeeded; returns the exit code.
int run_simulate(const SimulateArguments& args, const std::string& command_line);

}  // namespace layerjkr::cli
