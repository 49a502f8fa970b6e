// afmformats' tab export (afmformats_tab.hpp). Format learnt from afmformats' own writer and test
// files (tests/data/fmt-tab-fd_version_0.13.3.tab, tests/test_fmt_tab.py; MIT).
#include "io/afmformats_tab.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <vector>

#include <nlohmann/json.hpp>

#include "io/csv_rows.hpp"
#include "layerjkr/error.hpp"
#include "layerjkr/text.hpp"

namespace layerjkr::detail {
namespace {

const std::vector<std::string> kColumns = {"force", "tip position", "height (measured)", "height (piezo)", "segment",
                                           "time", "index"};

}  // namespace

bool is_afmformats_tab(std::string_view text) {
  return text.rfind("# afmformats", 0) == 0 || text.rfind("# BEGIN METADATA", 0) == 0;
}

CurveData parse_afmformats_tab(std::string_view text, const std::string& source, const CsvOptions& options) {
  const auto fail = [&](const std::string& what) -> void { throw InputError(source + ": afmformats tab export: " + what); };
  if (options.length_unit != 1.0 || options.force_unit != 1.0) fail("is in SI units (N, m, s); give no units option");
  if (options.sensitivity > 0.0)
    fail("gives forces [N]: a sensitivity (--sensitivity " + format_double(options.sensitivity) + " m/V) does not apply");
  std::vector<std::string_view> lines;
  for (std::size_t pos = 0; pos < text.size();) {
    std::size_t end = text.find('\n', pos);
    if (end == std::string_view::npos) end = text.size();
    std::string_view l = text.substr(pos, end - pos);
    if (!l.empty() && l.back() == '\r') l.remove_suffix(1);
    lines.push_back(l);
    pos = end + 1;
  }
  // The metadata: the JSON between the markers, each line behind "# ".
  std::string json_text;
  std::size_t k = 0;
  while (k < lines.size() && lines[k] != "# BEGIN METADATA") ++k;
  if (k == lines.size()) fail("has no '# BEGIN METADATA' line");
  for (++k; k < lines.size() && lines[k] != "# END METADATA"; ++k)
    json_text += std::string(lines[k].size() >= 2 ? lines[k].substr(2) : std::string_view()) + "\n";
  if (k == lines.size()) fail("has no '# END METADATA' line");
  nlohmann::json meta;
  try {
    meta = nlohmann::json::parse(json_text);
  } catch (const nlohmann::json::exception& e) {
    fail(std::string("its metadata is not JSON: ") + e.what());
  }
  // The column names: the first comment line after the metadata with a tab.
  for (++k; k < lines.size() && !(lines[k].rfind("# ", 0) == 0 && lines[k].find('\t') != std::string_view::npos); ++k) {
  }
  if (k == lines.size()) fail("has no line of column names ('# force<TAB>...') after its metadata");
  std::vector<std::string_view> tokens;
  split(lines[k].substr(2), tokens, '\t');
  std::vector<std::string> names;
  std::vector<std::string_view> glued;  // afmformats 0.13.3: the first row on the header's line
  for (std::size_t i = 0; i < tokens.size(); ++i) {
    const std::string_view t = tokens[i];
    if (std::find(kColumns.begin(), kColumns.end(), t) != kColumns.end()) {
      names.emplace_back(t);
      continue;
    }
    for (const std::string& c : kColumns)
      if (t.size() > c.size() && t.compare(0, c.size(), c) == 0) {
        names.push_back(c);
        glued.push_back(t.substr(c.size()));
        glued.insert(glued.end(), tokens.begin() + static_cast<std::ptrdiff_t>(i) + 1, tokens.end());
        break;
      }
    if (!glued.empty()) break;
    fail("column '" + printable(std::string(t)) + "' is not one it knows (" + [] {
      std::string all;
      for (const std::string& c : kColumns) all += (all.empty() ? "" : ", ") + c;
      return all;
    }() + ")");
  }
  const auto column = [&](const char* name) -> std::optional<std::size_t> {
    const auto it = std::find(names.begin(), names.end(), name);
    return it == names.end() ? std::nullopt : std::optional<std::size_t>(static_cast<std::size_t>(it - names.begin()));
  };
  const std::optional<std::size_t> force = column("force"), tip = column("tip position"), segment = column("segment"),
                                   time = column("time");
  std::optional<std::size_t> height = column("height (measured)");
  if (!height) height = column("height (piezo)");
  if (!force) fail("has no force column");
  if (!tip && !height) fail("has no tip position, height (measured) or height (piezo) column");
  double spring = options.spring_constant;
  if (!(spring > 0.0) && meta.contains("spring constant") && meta["spring constant"].is_number())
    spring = meta["spring constant"].get<double>();
  if (!tip && !(spring > 0.0 && std::isfinite(spring)))
    fail("gives heights but no spring constant to place the tip (metadata 'spring constant'): give it "
         "(--spring-constant, Python spring_constant=)");
  CurveData d;
  d.source = source;
  d.spring_constant = spring > 0.0 && std::isfinite(spring) ? spring : 0.0;
  if (const auto v = meta.find("software"); v != meta.end() && v->is_string())
    d.notes.push_back("afmformats tab export of a " + printable(v->get<std::string>()) + " curve" +
                      (meta.contains("instrument") && meta["instrument"].is_string()
                           ? " (" + printable(meta["instrument"].get<std::string>()) + ")"
                           : std::string()));
  const auto add_row = [&](const std::vector<std::string_view>& cells, std::size_t line) {
    if (cells.size() != names.size())
      fail("line " + std::to_string(line) + " has " + std::to_string(cells.size()) + " cells, the header names " +
           std::to_string(names.size()));
    const auto number = [&](std::size_t c) {
      double v = 0.0;
      if (!parse_finite(cells[c], v))
        fail("line " + std::to_string(line) + ": '" + printable(std::string(cells[c])) + "' (" + names[c] +
             ") is not a finite number");
      return v;
    };
    const double P = number(*force);
    const double tip_position = tip ? number(*tip) : number(*height) + P / spring;
    d.P.push_back(P);
    d.delta.push_back(-tip_position);
    int label = 0;
    if (segment) {
      const std::string_view s = cells[*segment];
      if (s == "True" || s == "1") label = 1;
      else if (!(s == "False" || s == "0"))
        fail("line " + std::to_string(line) + ": segment '" + printable(std::string(s)) + "' is not False/True or 0/1");
    }
    d.segment.push_back(label);
    if (time) d.t.push_back(number(*time));
  };
  if (!glued.empty()) {
    add_row(glued, k + 1);
    d.notes.push_back("the first sample is written on the column names' line (afmformats 0.13.3's writer): read as "
                      "the first sample");
  }
  std::vector<std::string_view> cells;
  for (std::size_t i = k + 1; i < lines.size(); ++i) {
    if (lines[i].empty() || lines[i][0] == '#') continue;
    split(lines[i], cells, '\t');
    add_row(cells, i + 1);
  }
  if (d.P.empty()) fail("holds no rows");
  d.validate();
  return d;
}

}  // namespace layerjkr::detail
