// fit-map's results table (results_table.hpp).
#include "results_table.hpp"

#include <optional>

#include "layerjkr/error.hpp"

namespace layerjkr::cli {
namespace {

// The cells of one line (csv_cell's quoting); nullopt if a quote is left open.
std::optional<std::vector<std::string>> csv_cells(const std::string& line) {
  std::vector<std::string> cells(1);
  bool quoted = false;
  for (std::size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (quoted && c == '"' && i + 1 < line.size() && line[i + 1] == '"') {
      cells.back() += '"';
      ++i;
    } else if (c == '"') {
      quoted = !quoted;
    } else if (c == ',' && !quoted) {
      cells.emplace_back();
    } else {
      cells.back() += c;
    }
  }
  if (quoted) return std::nullopt;
  return cells;
}

}  // namespace

std::string csv_cell(const std::string& s) {
  if (s.find_first_of(",\"\n\r") == std::string::npos) return s;
  std::string q = "\"";
  for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c == '\n' || c == '\r' ? ' ' : c);
  return q + "\"";
}

std::vector<ResultsRow> parse_results_table(const std::string& text, const std::string& header,
                                            const std::string& name) {
  if (text.empty()) return {};  // nothing was written: nothing to keep
  if (text.compare(0, header.size(), header) != 0)
    throw InputError("--resume: the header of " + name + " differs from this run's (other --free?); it is not resumed");
  const std::optional<std::vector<std::string>> head = csv_cells(header.substr(0, header.size() - 1));
  const std::size_t columns = head ? head->size() : 0;
  std::vector<ResultsRow> rows;
  std::size_t pos = header.size();
  for (std::size_t line = 2;; ++line) {
    const std::size_t end = text.find('\n', pos);
    if (end == std::string::npos) break;
    const std::string r = text.substr(pos, end - pos);
    pos = end + 1;
    const auto cells = csv_cells(r);
    if (!cells || cells->size() != columns)
      throw InputError("--resume: " + name + " line " + std::to_string(line) + " is not a row of " +
                       std::to_string(columns) + " cells; the table is damaged");
    rows.push_back({r + "\n", (*cells)[0], (*cells)[1]});
  }
  return rows;
}

}  // namespace layerjkr::cli
