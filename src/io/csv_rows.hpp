// Internal: the CSV row tokenizer the readers share - rows as views of the file's text, cells
// trimmed, numbers by std::from_chars (no stream or string per row).
#pragma once

#include <charconv>
#include <cmath>
#include <optional>
#include <string_view>
#include <system_error>
#include <vector>

namespace layerjkr::detail {

inline std::string_view trim(std::string_view s) {
  const auto b = s.find_first_not_of(" \t\r");
  if (b == std::string_view::npos) return {};
  const auto e = s.find_last_not_of(" \t\r");
  return s.substr(b, e - b + 1);
}

/// The cells of `line` between `separator`s (a comma, or a tab in the vendors' text exports), trimmed.
inline void split(std::string_view line, std::vector<std::string_view>& cells, char separator = ',') {
  cells.clear();
  std::size_t start = 0;
  for (;;) {
    const std::size_t at = line.find(separator, start);
    cells.push_back(trim(line.substr(start, at == std::string_view::npos ? std::string_view::npos : at - start)));
    if (at == std::string_view::npos) break;
    start = at + 1;
  }
}

/// Every line of a text, trimmed, blank ones included, counted from 1 (the vendors' exports, whose
/// headers and rows a reader tells apart itself); a leading UTF-8 byte-order mark is skipped.
class TextLines {
 public:
  explicit TextLines(std::string_view text) : text_(text) {
    if (text_.substr(0, 3) == "\xEF\xBB\xBF") text_.remove_prefix(3);
  }
  /// The next line, or nullopt at the end of the text.
  std::optional<std::string_view> next() {
    if (pos_ >= text_.size()) return std::nullopt;
    std::size_t end = text_.find('\n', pos_);
    if (end == std::string_view::npos) end = text_.size();
    const std::string_view t = trim(text_.substr(pos_, end - pos_));
    pos_ = end + 1;
    ++line_;
    return t;
  }
  /// The number of the line next() returned last.
  std::size_t line() const { return line_; }
  /// True if a whole line (ending in a newline) is ahead: a text's first bytes may end mid-line.
  bool complete_line_ahead() const { return text_.find('\n', pos_) != std::string_view::npos; }

 private:
  std::string_view text_;
  std::size_t pos_ = 0, line_ = 0;
};

/// The data rows of a CSV text: skips blank and '#' comment lines, counts lines from 1.
class CsvRows {
 public:
  // A leading UTF-8 byte-order mark (spreadsheet exports) is skipped, as in scene files.
  explicit CsvRows(std::string_view text) : text_(text) {
    if (text_.substr(0, 3) == "\xEF\xBB\xBF") text_.remove_prefix(3);
  }
  bool next(std::vector<std::string_view>& cells) {
    while (pos_ < text_.size()) {
      std::size_t end = text_.find('\n', pos_);
      if (end == std::string_view::npos) end = text_.size();
      const std::string_view t = trim(text_.substr(pos_, end - pos_));
      pos_ = end + 1;
      ++line_;
      if (t.empty() || t[0] == '#') continue;
      split(t, cells);
      return true;
    }
    return false;
  }
  std::size_t line() const { return line_; }

 private:
  std::string_view text_;
  std::size_t pos_ = 0, line_ = 0;
};

/// A finite number from a cell ('+' allowed); false for anything else.
inline bool parse_finite(std::string_view cell, double& v) {
  if (cell.size() > 1 && cell[0] == '+' && cell[1] != '-') cell.remove_prefix(1);  // from_chars takes no '+'
  const auto [end, ec] = std::from_chars(cell.data(), cell.data() + cell.size(), v);
  return !cell.empty() && ec == std::errc() && end == cell.data() + cell.size() && std::isfinite(v);
}

}  // namespace layerjkr::detail
