// layerjkr CLI: the pictures `fit --plot` and `fit-map --plot-dir` draw.
#pragma once

#include <string>
#include <vector>

#include "layerjkr/fit.hpp"

namespace layerjkr::cli {

/// Data, fitted curve and residuals of one fit as a PNG at `path`.
void plot_fit(const FitSummary& s, const std::string& path);

/// One PNG per free parameter, the measured pull-off, the rms residual and the status over
/// the map grid, in directory `dir` (created). A pixel with no curve or a failed fit is blank.
void plot_map_fields(const std::vector<BatchItem>& items, const std::vector<FitParameter>& free,
                     const std::string& dir);

}  // namespace layerjkr::cli
