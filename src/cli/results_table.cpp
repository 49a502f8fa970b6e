// fit-map's results table (results_table.hpp).
#include "results_table.hpp"

#include <algorithm>

#include "layerjkr/error.hpp"

namespace layerjkr::cli {
namespace {

// The cells of the row starting at text[pos] (RFC 4180 quoting, line breaks inside quotes);
// `pos` moves past its newline. False if the text ends before the row does (no newline, or a
// quote left open).
bool next_row(const std::string& text, std::size_t& pos, std::vector<std::string>& cells) {
  cells.assign(1, std::string());
  bool quoted = false;
  for (std::size_t i = pos; i < text.size(); ++i) {
    const char c = text[i];
    if (quoted && c == '"' && i + 1 < text.size() && text[i + 1] == '"') {
      cells.back() += '"';
      ++i;
    } else if (c == '"') {
      quoted = !quoted;
    } else if (c == ',' && !quoted) {
      cells.emplace_back();
    } else if (c == '\n' && !quoted) {
      pos = i + 1;
      return true;
    } else {
      cells.back() += c;
    }
  }
  return false;
}

}  // namespace

std::string csv_cell(const std::string& s) {
  if (s.find_first_of(",\"\n\r") == std::string::npos) return s;
  std::string q = "\"";
  for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c);
  return q + "\"";
}

std::vector<ResultsRow> parse_results_table(const std::string& text, const std::string& header,
                                            const std::string& name) {
  if (text.empty()) return {};  // nothing was written: nothing to keep
  if (text.compare(0, header.size(), header) != 0)
    throw InputError("--resume: the header of " + name + " differs from this run's (other --free?); it is not resumed");
  std::vector<std::string> cells;
  std::size_t pos = 0;
  next_row(header, pos, cells);
  const std::size_t columns = cells.size();
  std::vector<ResultsRow> rows;
  pos = header.size();
  for (std::size_t line = 2; pos < text.size();) {
    const std::size_t start = pos;
    if (!next_row(text, pos, cells)) break;  // cut off mid-write
    if (cells.size() != columns || columns < 7)
      throw InputError("--resume: " + name + " line " + std::to_string(line) + " is not a row of " +
                       std::to_string(columns) + " cells; the table is damaged");
    rows.push_back({text.substr(start, pos - start), cells[0], cells[1], cells[6]});
    line += static_cast<std::size_t>(std::count(rows.back().line.begin(), rows.back().line.end(), '\n'));
  }
  return rows;
}

}  // namespace layerjkr::cli
