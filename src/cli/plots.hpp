// layerjkr CLI: the pictures `fit --plot` and `fit-map --plot-dir` draw.
#pragma once

#include <string>
#include <vector>

#include "files.hpp"
#include "layerjkr/fit.hpp"

namespace layerjkr::cli {

/// Data, fitted curve and residuals of one fit as a PNG, committed to `png`'s target: against the
/// indentation, or against time for a fit in time (FitSummary::t).
void plot_fit(const FitSummary& s, OutputFile& png);

/// A joint fit's curves one after another in time, each with the joint model.
void plot_joint(const JointFitSummary& j, OutputFile& png);

/// One PNG per free parameter, the measured pull-off, the rms residual and the status over
/// the map grid, in directory `dir` (prepare_plot_dir made it), named map_plot_names(free). A
/// pixel with no curve or a failed fit is blank.
void plot_map_fields(const std::vector<BatchItem>& items, const std::vector<FitParameter>& free,
                     const std::string& dir, bool force);

/// The files plot_map_fields writes: one PNG per free parameter, pull_off, rms_residual, status.
std::vector<std::string> map_plot_names(const std::vector<FitParameter>& free);

/// Creates `dir` and checks, before the work whose plots go there, that it takes files and that
/// none of `names` in it is a file layerjkr did not draw (is_marked_png; `force` replaces them
/// anyway): throws InputError naming the first such file.
void prepare_plot_dir(const std::string& dir, const std::vector<std::string>& names, bool force);

}  // namespace layerjkr::cli
