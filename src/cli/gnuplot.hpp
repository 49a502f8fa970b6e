// layerjkr CLI: drawing with gnuplot (pngcairo) - the one place that starts it.
#pragma once

#include <string>

namespace layerjkr::cli {

/// Runs `script` through gnuplot and checks that it wrote `png`; throws Error naming `what`
/// (the flag that asked for the plot) if gnuplot is missing or fails.
void run_gnuplot(const std::string& script, const std::string& png, const std::string& what);

/// `path` as a gnuplot single-quoted string (quotes doubled), so no file name can end the
/// string and add commands; throws InputError for a name with a line break.
std::string gnuplot_quoted(const std::string& path);

}  // namespace layerjkr::cli
