// NT-MDT Nova and Optics11 Chiaro text exports (io/vendor_text.hpp). The layouts, as the files
// in afmformats' test suite show them (fmt-ntmdt-txt-fd_2015_01_17_gel4-...txt,
// fmt-chiaro-txt_AEBP1_Indentation_002.txt), and the conversions afmformats applies
// (fmt_ntmdt_txt.py, fmt_chiaro_txt.py; MIT), re-derived here: NT-MDT writes no metadata at all,
// Chiaro a free-form header (ISO-8859-1: `µ` is one byte) whose only value used is k.
#include "io/vendor_text.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <vector>

#include "io/csv_rows.hpp"
#include "layerjkr/error.hpp"
#include "layerjkr/text.hpp"

namespace layerjkr::detail {
namespace {

// A number written with a decimal comma or point.
bool parse_decimal(std::string_view cell, double& v) {
  std::array<char, 64> buf{};
  if (cell.empty() || cell.size() >= buf.size()) return false;
  std::copy(cell.begin(), cell.end(), buf.begin());
  std::replace(buf.begin(), buf.begin() + static_cast<std::ptrdiff_t>(cell.size()), ',', '.');
  return parse_finite(std::string_view(buf.data(), cell.size()), v);
}

// Three numbers from a line of tab-separated cells, or nullopt.
std::optional<std::array<double, 3>> three_numbers(std::string_view line, std::vector<std::string_view>& cells) {
  split(line, cells, '\t');
  std::array<double, 3> v{};
  if (cells.size() != 3) return std::nullopt;
  for (std::size_t i = 0; i < 3; ++i)
    if (!parse_decimal(cells[i], v[i])) return std::nullopt;
  return v;
}

// The first row of `defl` to keep: the rows before the deflection first changes are padding the
// export added at the turnaround; the last of them is kept. nullopt if it never changes.
std::optional<std::size_t> first_unpadded(const std::vector<double>& defl) {
  for (std::size_t i = 1; i < defl.size(); ++i)
    if (defl[i] != defl[0]) return i - 1;
  return std::nullopt;
}

[[noreturn]] void fail_at(const std::string& source, const std::string& kind, const std::string& what) {
  throw InputError(source + ": " + kind + ": " + what);
}

}  // namespace

bool is_ntmdt_txt(std::string_view text) {
  TextLines lines(text);
  if (!lines.complete_line_ahead()) return false;  // a first line cut short cannot be judged
  std::vector<std::string_view> cells;
  const auto first = lines.next();
  return first && three_numbers(*first, cells).has_value();
}

CurveData parse_ntmdt_txt(std::string_view text, const std::string& source, const CsvOptions& options) {
  const std::string kind = "NT-MDT Nova text export";
  if (options.length_unit != 1.0 || options.force_unit != 1.0)
    fail_at(source, kind, "its units are fixed (height in nm, deflection in nA); give no units option");
  if (!(options.spring_constant > 0.0) || !(options.sensitivity > 0.0))
    fail_at(source, kind,
            "holds no calibration (height [nm] and the deflection signal [nA] only): give the cantilever's spring "
            "constant [N/m] (--spring-constant) and the deflection sensitivity [m per A of the signal] (--sensitivity)");
  TextLines lines(text);
  std::vector<std::string_view> cells;
  std::vector<double> height, approach, retract;
  while (const auto line = lines.next()) {
    if (line->empty()) continue;
    const auto v = three_numbers(*line, cells);
    if (!v)
      fail_at(source, kind, "line " + std::to_string(lines.line()) + ": '" + printable(std::string(*line), 60) +
                                "' is not three tab-separated numbers (height, approach and retract deflection)");
    height.push_back((*v)[0] * 1e-9);
    approach.push_back((*v)[1]);
    retract.push_back((*v)[2]);
  }
  const auto a0 = first_unpadded(approach), r0 = first_unpadded(retract);
  if (!a0 || !r0) fail_at(source, kind, std::string("its ") + (a0 ? "retract" : "approach") + " deflection is constant");
  const double k = options.spring_constant;
  const double newtons = 1e-9 * options.sensitivity * k;  // nA -> A -> m of deflection -> N
  CurveData d;
  d.source = source;
  d.spring_constant = k;
  const auto add = [&](std::size_t i, double signal, int segment) {
    const double force = signal * newtons;
    d.delta.push_back(-(height[i] + force / k));
    d.P.push_back(force);
    d.segment.push_back(segment);
  };
  for (std::size_t i = height.size(); i-- > *a0;) add(i, approach[i], 0);
  for (std::size_t i = *r0; i < height.size(); ++i) add(i, retract[i], 1);
  const std::size_t dropped = *a0 + *r0;
  if (dropped > 0)
    d.notes.push_back("dropped " + std::to_string(*a0) + " approach and " + std::to_string(*r0) +
                      " retract rows of constant padding at the turnaround");
  d.validate();
  return d;
}

bool is_chiaro_txt(std::string_view text) {
  return text.find("\nDevice:\tChiaro") != std::string_view::npos;
}

CurveData parse_chiaro_txt(std::string_view text, const std::string& source, const CsvOptions& options) {
  const std::string kind = "Optics11 Chiaro export";
  if (options.length_unit != 1.0 || options.force_unit != 1.0)
    fail_at(source, kind, "states its units (Load in uN, lengths in nm); give no units option");
  if (options.sensitivity > 0.0)
    fail_at(source, kind, "its deflection (Cantilever) is measured in nm: a sensitivity does not apply");
  TextLines lines(text);
  std::vector<std::string_view> cells;
  double file_k = 0.0;
  std::optional<std::size_t> time, load, cantilever, piezo;
  std::size_t columns = 0;
  while (const auto line = lines.next()) {
    split(*line, cells, '\t');
    if (cells.size() >= 2 && cells[0] == "k (N/m)" && !parse_decimal(cells[1], file_k))
      fail_at(source, kind, "line " + std::to_string(lines.line()) + ": k (N/m) '" + printable(std::string(cells[1]), 30) +
                                "' is not a number");
    if (cells.empty() || cells[0] != "Time (s)") continue;
    columns = cells.size();
    for (std::size_t i = 0; i < cells.size(); ++i) {
      if (cells[i] == "Time (s)") time = i;
      if (cells[i] == "Load (uN)") load = i;
      if (cells[i] == "Cantilever (nm)") cantilever = i;
      if (cells[i] == "Piezo (nm)") piezo = i;
    }
    break;
  }
  if (!time || !load || !cantilever || !piezo)
    fail_at(source, kind, "has no column line with Time (s), Load (uN), Cantilever (nm) and Piezo (nm)");
  const double k = options.spring_constant > 0.0 ? options.spring_constant : file_k;
  if (!(k > 0.0))
    fail_at(source, kind, "gives no spring constant (k (N/m)): give it (--spring-constant)");
  const double load_scale = options.spring_constant > 0.0 && file_k > 0.0 ? k / file_k : 1.0;
  CurveData d;
  d.source = source;
  d.spring_constant = k;
  while (const auto line = lines.next()) {
    if (line->empty()) continue;
    split(*line, cells, '\t');
    std::array<double, 4> v{};
    const std::array<std::size_t, 4> at{*time, *load, *cantilever, *piezo};
    bool ok = cells.size() == columns;
    for (std::size_t j = 0; ok && j < 4; ++j) ok = parse_decimal(cells[at[j]], v[j]);
    if (!ok)
      fail_at(source, kind, "line " + std::to_string(lines.line()) + ": '" + printable(std::string(*line), 60) +
                                "' is not a row of " + std::to_string(columns) + " numbers");
    d.t.push_back(v[0]);
    d.P.push_back(v[1] * 1e-6 * load_scale);
    d.delta.push_back((v[3] - v[2]) * 1e-9);
  }
  if (d.P.empty()) fail_at(source, kind, "has its column line but no data rows");
  // The approach ends at the largest load (its first occurrence), as afmformats splits the curve.
  const std::size_t peak = static_cast<std::size_t>(std::max_element(d.P.begin(), d.P.end()) - d.P.begin());
  d.segment.assign(d.P.size(), 1);
  std::fill(d.segment.begin(), d.segment.begin() + static_cast<std::ptrdiff_t>(peak) + 1, 0);
  d.validate();
  return d;
}

}  // namespace layerjkr::detail
