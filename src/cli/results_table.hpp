// layerjkr CLI: the cells of fit-map's results table, written and read back (--resume).
#pragma once

#include <string>
#include <vector>

namespace layerjkr::cli {

/// `s` as one CSV cell (RFC 4180): quoted when it holds a comma, a quote or a line break, quotes
/// doubled; a line break stays inside the quotes (a row may span lines, as RFC 4180 allows).
std::string csv_cell(const std::string& s);

/// One row of an earlier table: its text (with the final newline) and its file, curve and
/// status cells (the file cell as written: escape_bytes of the name).
struct ResultsRow {
  std::string line, file, curve, status;
};

/// The rows of the table `text` (read from `name`): none if it is empty, else it must start with
/// `header` (a line, with its newline) and hold whole rows of as many cells, quoted cells spanning
/// lines included; a last row without its newline was cut off mid-write and is dropped (its curve
/// is fitted again). Throws InputError naming `name` and the line otherwise.
std::vector<ResultsRow> parse_results_table(const std::string& text, const std::string& header,
                                            const std::string& name);

}  // namespace layerjkr::cli
