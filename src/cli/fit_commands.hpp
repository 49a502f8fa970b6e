// layerjkr CLI: the fit, fit-map and export commands (thin wrappers over fit.hpp and
// instrument.hpp).
#pragma once

#include <string>
#include <vector>

#include "fit_options.hpp"

namespace layerjkr::cli {

/// `layerjkr fit DATA ...`: summary on stdout, optional JSON report (with its provenance: the
/// version, scene, options, the input's SHA-256 and `command_line`) and plot. With `joint`, two or
/// more DATA are fitted together (fit_joint): the report holds "joint" (the joint fit), "curves"
/// (each curve's place in the joint samples and its fit alone) and the provenance of every input.
int run_fit(const FitArguments& args, const std::vector<std::string>& data, bool joint, const std::string& report,
            const std::string& plot, const std::vector<std::string>& command_line);

/// `layerjkr fit --from-report R.json [--out ...] [--plot ...]`: the fit R.json records, rerun
/// from its provenance (scene, options, input) after checking the input's SHA-256 (InputError
/// naming the file and both hashes otherwise). A report of another layerjkr version is rerun
/// with a warning on stderr.
int run_fit_from_report(const std::string& from, const std::string& report, const std::string& plot,
                        const std::vector<std::string>& command_line);

/// `layerjkr export FILE --out OUT.csv [--curves A:B]`: every curve (or those at positions A to
/// B - 1) of an instrument file as one CSV (curve,segment,force,height,tip_position), which
/// `fit` reads back; written curve by curve.
/// spring_constant [N/m] and sensitivity [m/V], when > 0, replace the file's (to_curve_data).
int run_export(const std::string& path, const std::string& out, const std::string& curves = "",
               double spring_constant = 0.0, double sensitivity = 0.0);

/// fit-map's exit codes besides 0 (every curve of the table fitted), 1 (an internal failure), 2
/// (invalid input, before any fit) and 130 / 143 (stopped by SIGINT / SIGTERM).
inline constexpr int kExitSomeFailed = 3;  ///< the table holds failed curves beside fitted ones
inline constexpr int kExitNoneFitted = 4;  ///< no curve of the table was fitted

/// Where fit-map writes and how.
struct MapOutputs {
  std::string out;         ///< the results table: a file, `-` or another stream (OutputFile)
  std::string plot_dir;    ///< heat maps of every fitted field (empty: none)
  std::string report_dir;  ///< the interactive report, DIR/index.html (empty: none)
  std::string tiff_dir;    ///< each fitted field of each map as a float TIFF (empty: none; map_tiffs.hpp)
  int jobs = 1;            ///< worker threads
  bool resume = false;     ///< keep the rows of an existing table and fit only the curves it lacks
  /// Replace derived files layerjkr did not write (a record beside the table that is not a
  /// fit-map record, pictures in the plot directory that layerjkr did not draw).
  bool force = false;
};

/// `layerjkr fit-map INPUT... --out RESULTS.csv [--plot-dir DIR] [--resume]`: one row per curve,
/// written in input order as the curves finish, progress on stderr; with a plot directory, one
/// heat map per fitted field over the map grid. SIGINT / SIGTERM stop it cleanly: no new curve
/// starts, the running ones finish, the table so far is committed, and it returns 130 / 143.
/// With `resume`, the rows of an existing table (same header) are kept and their curves not fitted
/// again: a row belongs to the file its file cell named when it was written (the record's
/// canonical path and SHA-256; map_resume.hpp), however this run spells the path.
/// `report_dir` gets the interactive report (map_report.hpp) as index.html.
/// `curves` ("A:B", empty for all) selects the curves of each map by position; reading skips
/// the rest. The progress bar (curves/s, time left) is drawn only when stderr is a terminal.
/// Beside a table that is a file, its record (sidecar_path(out)) holds the provenance of every
/// row: version, scene, options, each input file's path, size and SHA-256, the command line,
/// written and committed with the table; a file there that is not a fit-map record is not
/// replaced (InputError before any fit) unless `force`. --resume refuses (InputError) a table whose
/// record is missing or names another scene or other options, or an input whose SHA-256 changed.
/// Returns 0, kExitSomeFailed or kExitNoneFitted (or 130 / 143).
int run_fit_map(const FitArguments& args, const std::vector<std::string>& inputs, const std::string& curves,
                const MapOutputs& outputs, const std::vector<std::string>& command_line);

/// `layerjkr fit-map --from-report OUT.json --out NEW.csv [--jobs N] [--plot-dir DIR] [--report DIR]`: the map a
/// record describes, rerun with its scene, options, inputs (each input's SHA-256 checked first) and
/// curve range. Inputs are named as the first run named them where that still resolves to the
/// recorded file, so rerun from the same directory the table is the same, byte for byte.
int run_fit_map_from_report(const std::string& from, const MapOutputs& outputs,
                            const std::vector<std::string>& command_line);

/// fit-map's record beside its table: OUT.csv -> OUT.json; a name not ending in .csv gets .json
/// appended (OUT.txt -> OUT.txt.json).
std::string sidecar_path(const std::string& out);

}  // namespace layerjkr::cli
