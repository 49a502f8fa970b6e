// layerjkr CLI: the fit and fit-map commands (thin wrappers over fit.hpp).
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "layerjkr/curve_data.hpp"
#include "layerjkr/fit.hpp"
#include "layerjkr/scene.hpp"

namespace CLI {
class App;
}

namespace layerjkr::cli {

/// Options shared by `fit` and `fit-map`, as typed on the command line.
struct FitArguments {
  std::string scene, free, loss = "none", branch = "approach", units = "m,N";
  double spring_constant = 0.0, z_sign = 1.0, deflection_sign = 1.0;
  int extra_starts = 0, max_iterations = 200;
  int curve = -1;  ///< --curve: which curve of a file holding several (-1: it must hold one)
  std::string control = "auto";  ///< --control: auto | load | cantilever | grips
  std::string baseline = "constant";  ///< --baseline: constant | tilt
  std::string window = "all";    ///< --window: all | pull-off | fraction:F
};

/// The arguments as library options (the CLI and the Python module share this mapping).
struct Prepared {
  Scene scene;
  FitOptions options;
  CsvOptions csv;
  bool cantilever_required = false;  ///< --control cantilever: the curve must carry k
};
/// Everything but the scene; throws InputError naming the flag.
Prepared prepare_options(const FitArguments& args);
/// prepare_options and the scene loaded from args.scene.
Prepared prepare(const FitArguments& args);

/// The fit report's JSON keys (fit --out, and the Python module's FitResult).
nlohmann::ordered_json report_json(const FitSummary& summary, Branch branch);

/// Registers the shared options on a subcommand.
void add_fit_options(CLI::App& command, FitArguments& args);

/// `layerjkr fit DATA.csv ...`: summary on stdout, optional JSON report and plot.
int run_fit(const FitArguments& args, const std::string& data, const std::string& report,
            const std::string& plot);

/// `layerjkr export FILE --out OUT.csv`: every curve of an instrument file as one CSV
/// (curve,segment,force,height,tip_position), which `fit` reads back.
int run_export(const std::string& path, const std::string& out);

/// `layerjkr fit-map INPUT... --out RESULTS.csv [--plot-dir DIR]`: one row per curve, progress
/// on stderr; with a plot directory, one heat map per fitted field over the map grid.
int run_fit_map(const FitArguments& args, const std::vector<std::string>& inputs, int jobs,
                const std::string& out, const std::string& plot_dir = "");

}  // namespace layerjkr::cli
