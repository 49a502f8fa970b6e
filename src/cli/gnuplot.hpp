// layerjkr CLI: drawing with gnuplot (pngcairo) - the one place that starts it.
#pragma once

#include <string>

namespace layerjkr::cli {

/// Runs `script` through gnuplot and checks that it wrote `png`; throws Error naming `what`
/// (the flag that asked for the plot) if gnuplot is missing or fails.
void run_gnuplot(const std::string& script, const std::string& png, const std::string& what);

}  // namespace layerjkr::cli
