// layerjkr CLI: the fit, fit-map and export commands (thin wrappers over fit.hpp and
// instrument.hpp).
#pragma once

#include <string>
#include <vector>

#include "fit_options.hpp"

namespace layerjkr::cli {

/// `layerjkr fit DATA ...`: summary on stdout, optional JSON report and plot.
int run_fit(const FitArguments& args, const std::string& data, const std::string& report,
            const std::string& plot);

/// `layerjkr export FILE --out OUT.csv [--curves A:B]`: every curve (or those at positions A to
/// B - 1) of an instrument file as one CSV (curve,segment,force,height,tip_position), which
/// `fit` reads back; written curve by curve.
int run_export(const std::string& path, const std::string& out, const std::string& curves = "");

/// `layerjkr fit-map INPUT... --out RESULTS.csv [--plot-dir DIR] [--resume]`: one row per curve,
/// written in input order as the curves finish, progress on stderr; with a plot directory, one
/// heat map per fitted field over the map grid. SIGINT / SIGTERM stop it cleanly: no new curve
/// starts, the running ones finish, the table so far is committed, and it returns 130 / 143.
/// With `resume`, the rows of an existing table (same header) are kept and their curves (by
/// file and curve cells) not fitted again.
/// `report_dir` (empty for none) gets the interactive report (map_report.hpp) as index.html.
/// `curves` ("A:B", empty for all) selects the curves of each map by position; reading skips
/// the rest. The progress bar (curves/s, time left) is drawn only when stderr is a terminal.
int run_fit_map(const FitArguments& args, const std::vector<std::string>& inputs, int jobs,
                const std::string& out, const std::string& plot_dir = "", bool resume = false,
                const std::string& curves = "", const std::string& report_dir = "");

}  // namespace layerjkr::cli
