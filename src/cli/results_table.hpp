// layerjkr CLI: the cells of fit-map's results table, written and read back (--resume).
#pragma once

#include <string>
#include <vector>

namespace layerjkr::cli {

/// `s` as one CSV cell: quoted when it holds a comma, a quote or a line break (quotes doubled,
/// line breaks as spaces, so a row stays one line).
std::string csv_cell(const std::string& s);

/// One row of an earlier table: its line (with the newline) and its file and curve cells.
struct ResultsRow {
  std::string line, file, curve;
};

/// The rows of the table `text` (read from `name`): none if it is empty, else it must start with `header` (a line,
/// with its newline) and hold whole rows of as many cells; a last line without its newline was
/// cut off mid-write and is dropped (its curve is fitted again). Throws InputError naming `name`
/// and the line otherwise.
std::vector<ResultsRow> parse_results_table(const std::string& text, const std::string& header,
                                            const std::string& name);

}  // namespace layerjkr::cli
