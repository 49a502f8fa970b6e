// layerjkr CLI: writing results safely and expanding input lists.
#pragma once

#include <string>
#include <vector>

namespace layerjkr::cli {

/// Writes `text` to `path` through a temporary name, so a failure never leaves a partial
/// file; throws InputError naming the path.
void write_atomically(const std::string& path, const std::string& text);

/// Directories (every .csv and instrument file, sorted), glob patterns and files, in the
/// order given; throws InputError for an input that names nothing.
std::vector<std::string> expand_inputs(const std::vector<std::string>& inputs);

}  // namespace layerjkr::cli
