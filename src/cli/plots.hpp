// layerjkr CLI: the pictures `fit --plot` and `fit-map --plot-dir` draw.
#pragma once

#include <string>
#include <vector>

#include "files.hpp"
#include "layerjkr/fit.hpp"

namespace layerjkr::cli {

/// Data, fitted curve and residuals of one fit as a PNG, committed to `png`'s target.
void plot_fit(const FitSummary& s, OutputFile& png);

/// One PNG per free parameter, the measured pull-off, the rms residual and the status over
/// the map grid, in directory `dir` (prepare_plot_dir made it). A pixel with no curve or a failed fit is blank.
void plot_map_fields(const std::vector<BatchItem>& items, const std::vector<FitParameter>& free,
                     const std::string& dir);

/// Creates `dir` and checks that it takes files, before the work whose plots go there.
void prepare_plot_dir(const std::string& dir);

}  // namespace layerjkr::cli
