// CSV reader for measured curves: strict about every cell, explicit about conventions.
#include "layerjkr/curve_data.hpp"

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <map>
#include <string_view>
#include <unordered_set>

#include "io/afm_workshop.hpp"
#include "io/afmformats_tab.hpp"
#include "io/vendor_text.hpp"
#include "io/csv_rows.hpp"
#include "io/instrument_readers.hpp"
#include "layerjkr/instrument.hpp"
#include "io/read_file.hpp"
#include "layerjkr/error.hpp"
#include "layerjkr/text.hpp"

namespace layerjkr {
namespace {

enum class Column { delta, force, a, weight, segment, tip_position, z, deflection, curve, height, time };

struct ColumnName {
  Column column;
  bool si_labelled;
};

// Recognised header names; a _m / _N suffix labels the column as SI.
const std::map<std::string, ColumnName>& known_columns() {
  static const std::map<std::string, ColumnName> names = {
      {"delta", {Column::delta, false}},     {"delta_m", {Column::delta, true}},
      {"P", {Column::force, false}},         {"P_N", {Column::force, true}},
      {"force", {Column::force, false}},     {"force_N", {Column::force, true}},
      {"a", {Column::a, false}},             {"a_m", {Column::a, true}},
      {"weight", {Column::weight, false}},   {"segment", {Column::segment, false}},
      {"tip_position", {Column::tip_position, false}},
      {"tip_position_m", {Column::tip_position, true}},
      {"z", {Column::z, false}},             {"z_m", {Column::z, true}},
      {"deflection", {Column::deflection, false}},
      {"deflection_m", {Column::deflection, true}},
      {"curve", {Column::curve, false}},     {"height", {Column::height, false}},
      {"height_m", {Column::height, true}},  {"t", {Column::time, false}},
      {"time", {Column::time, false}},       {"t_s", {Column::time, false}}};
  return names;
}

std::string shorten(std::string_view s) { return printable(s, 40); }

}  // namespace

void CurveData::validate() const {
  const std::size_t n = P.size();
  auto fail = [&](const std::string& what) { throw InputError(source + ": " + what); };
  if (delta.empty() && a.empty() && n > 0) fail("has forces but neither delta nor contact radii a");
  if (!delta.empty() && delta.size() != n) fail("columns delta and P differ in length");
  if (!(spring_constant >= 0.0) || !std::isfinite(spring_constant))
    fail("spring constant " + format_double(spring_constant) + " N/m is invalid; valid range: finite and >= 0 (0: unknown)");
  if (!a.empty() && a.size() != n) fail("column a has " + std::to_string(a.size()) + " rows, not " + std::to_string(n));
  if (!weight.empty() && weight.size() != n) fail("column weight has the wrong length");
  if (!segment.empty() && segment.size() != n) fail("column segment has the wrong length");
  if (!t.empty() && t.size() != n) fail("column t has " + std::to_string(t.size()) + " rows, not " + std::to_string(n));
  if (n == 0) fail("has no data rows");
  for (std::size_t i = 0; i < n; ++i) {
    const std::string row = " in row " + std::to_string(i + 1);
    if (!delta.empty() && !std::isfinite(delta[i])) fail("delta = " + format_double(delta[i]) + row + " is not finite");
    if (!std::isfinite(P[i])) fail("P = " + format_double(P[i]) + row + " is not finite");
    if (!a.empty() && !(a[i] >= 0.0 && std::isfinite(a[i])))
      fail("a = " + format_double(a[i]) + row + " is invalid; valid range: finite and >= 0");
    if (!weight.empty() && !(weight[i] > 0.0 && std::isfinite(weight[i])))
      fail("weight = " + format_double(weight[i]) + row + " is invalid; valid range: finite and > 0");
    if (!segment.empty() && segment[i] != 0 && segment[i] != 1 && segment[i] != 2)
      fail("segment = " + std::to_string(segment[i]) + row + " is invalid; valid values: 0 (approach), 1 (retract), 2 (dwell)");
    if (!t.empty() && !std::isfinite(t[i])) fail("t = " + format_double(t[i]) + row + " is not finite");
    if (!t.empty() && i > 0 && !(t[i] > t[i - 1]))
      fail("t = " + format_double(t[i]) + " s" + row + " does not increase (the row before: " + format_double(t[i - 1]) +
           " s); times must increase strictly, in acquisition order");
  }
  bool retracted = false;
  for (std::size_t i = 0; i < segment.size(); ++i) {
    if (segment[i] == 0 && retracted)
      fail("data row " + std::to_string(i + 1) + " returns to segment 0 after retract rows; rows must be in "
           "acquisition order (approach, then retract; dwells anywhere)");
    retracted = retracted || segment[i] == 1;
  }
}

std::size_t CurveData::dwell_count() const {
  return static_cast<std::size_t>(std::count(segment.begin(), segment.end(), 2));
}

CurveData CurveData::without_dwell() const {
  if (dwell_count() == 0) return *this;
  CurveData d = *this;
  for (auto* v : {&d.delta, &d.P, &d.a, &d.weight, &d.t}) v->clear();
  d.segment.clear();
  for (std::size_t i = 0; i < size(); ++i) {
    if (segment[i] == 2) continue;
    if (!delta.empty()) d.delta.push_back(delta[i]);
    d.P.push_back(P[i]);
    if (!a.empty()) d.a.push_back(a[i]);
    if (!weight.empty()) d.weight.push_back(weight[i]);
    if (!t.empty()) d.t.push_back(t[i]);
    d.segment.push_back(segment[i]);
  }
  return d;
}

std::vector<bool> CurveData::retract_mask() const {
  std::vector<bool> mask(size());
  // Without a segment column the retract branch starts after the deepest sample ((P, a) data:
  // none, all loading).
  const std::size_t deepest =
      delta.empty() ? size() : static_cast<std::size_t>(std::max_element(delta.begin(), delta.end()) - delta.begin());
  for (std::size_t i = 0; i < size(); ++i) mask[i] = segment.empty() ? i > deepest : segment[i] == 1;
  return mask;
}

std::vector<std::size_t> CurveData::select(Branch branch) const {
  std::vector<std::size_t> idx;
  const std::vector<bool> retract = retract_mask();
  for (std::size_t i = 0; i < size(); ++i)
    if ((segment.empty() || segment[i] != 2) && (branch == Branch::all || retract[i] == (branch == Branch::retract)))
      idx.push_back(i);
  return idx;
}

void CsvOptions::validate() const {
  const char* fn = "CsvOptions";
  detail::require_positive(fn, "length_unit", length_unit);
  detail::require_positive(fn, "force_unit", force_unit);
  detail::require_non_negative(fn, "spring_constant", spring_constant);
  detail::require_non_negative(fn, "sensitivity", sensitivity);
  if (z_sign != 1.0 && z_sign != -1.0) throw DomainError(fn, "z_sign", z_sign, "+1 or -1");
  if (deflection_sign != 1.0 && deflection_sign != -1.0)
    throw DomainError(fn, "deflection_sign", deflection_sign, "+1 or -1");
  if (curve < -1) throw DomainError(fn, "curve", curve, ">= 0, or -1 for a file of one curve");
  if (max_bytes == 0) throw DomainError(fn, "max_bytes", 0.0, "> 0");
  if (max_rows == 0) throw DomainError(fn, "max_rows", 0.0, "> 0");
}

void parse_units(const std::string& text, CsvOptions& options) {
  static const std::map<std::string, double> lengths = {
      {"m", 1.0}, {"mm", 1e-3}, {"um", 1e-6}, {"nm", 1e-9}, {"pm", 1e-12}};
  static const std::map<std::string, double> forces = {
      {"N", 1.0}, {"mN", 1e-3}, {"uN", 1e-6}, {"nN", 1e-9}, {"pN", 1e-12}};
  const auto comma = text.find(',');
  const std::string len(detail::trim(std::string_view(text).substr(0, comma)));
  const std::string force = comma == std::string::npos ? "" : std::string(detail::trim(std::string_view(text).substr(comma + 1)));
  if (comma == std::string::npos || !lengths.count(len) || !forces.count(force))
    throw InputError("units = \"" + shorten(text) +
                     "\" is invalid; give LENGTH,FORCE with LENGTH in m, mm, um, nm, pm and "
                     "FORCE in N, mN, uN, nN, pN (e.g. nm,nN)");
  options.length_unit = lengths.at(len);
  options.force_unit = forces.at(force);
}

namespace {

// Throws the reader's InputError, naming the source.
struct Fail {
  const std::string& source;
  [[noreturn]] void operator()(const std::string& what) const { throw InputError(source + ": " + what); }
};

// Where each quantity sits in a row, checked against the header's conventions.
struct Layout {
  std::vector<std::string> header;
  std::map<Column, std::size_t> where;
  bool raw = false;  // z,deflection or z,force
  bool radius_only = false;  // P,a: a rig's load and contact radius, no displacement
  bool has(Column c) const { return where.count(c) > 0; }
};

Layout read_layout(std::vector<std::string> header, const CsvOptions& options, const Fail& fail) {
  Layout l;
  bool si_labelled = false;
  for (std::size_t c = 0; c < header.size(); ++c) {
    const auto it = known_columns().find(header[c]);
    if (it == known_columns().end())
      fail("header column " + std::to_string(c + 1) + " '" + shorten(header[c]) +
           "' is unknown (known: delta, P, force, a, weight, segment, t, tip_position, z, "
           "deflection, curve, height; optional _m/_N/_s suffix)");
    if (l.has(it->second.column)) fail("header names the same quantity twice ('" + header[c] + "')");
    l.where[it->second.column] = c;
    si_labelled = si_labelled || it->second.si_labelled;
  }
  if (si_labelled && (options.length_unit != 1.0 || options.force_unit != 1.0))
    fail("the header labels its columns as SI (_m/_N) but non-SI units were requested");
  const int length_forms = int(l.has(Column::delta)) + int(l.has(Column::tip_position)) + int(l.has(Column::z));
  l.radius_only = length_forms == 0 && l.has(Column::a) && l.has(Column::force);
  if (length_forms != 1 && !l.radius_only) {
    std::string joined;
    for (const auto& h : header) joined += (joined.empty() ? "" : ",") + h;
    fail("needs exactly one of the columns delta, tip_position, z - or P with a, a rig's load and contact radius "
         "(header: " + shorten(joined) + ")");
  }
  l.raw = l.has(Column::z);
  if (l.raw) {
    if (!l.has(Column::deflection) && !l.has(Column::force)) fail("column z needs a deflection or a force column");
    if (l.has(Column::force) && l.has(Column::deflection))
      fail("give z with either deflection or force, not both (force = k x deflection)");
    if (!(options.spring_constant > 0.0))
      fail(std::string("z,") + (l.has(Column::force) ? "force" : "deflection") +
           " data need the cantilever spring constant k [N/m] (spring_constant): the tip's position is z minus the "
           "deflection" + (l.has(Column::force) ? ", force / k" : ""));
  } else {
    if (l.has(Column::deflection)) fail("column deflection is only used with z");
    if (!l.has(Column::force)) fail("needs a force column (P or force)");
  }
  if (l.has(Column::a) && !l.has(Column::delta) && !l.radius_only)
    fail("column a is only accepted with the delta,P form, or as P,a (a rig's load and contact radius)");
  if (l.has(Column::height) && !l.has(Column::tip_position))
    fail("column height (layerjkr export) is only accepted with tip_position");
  if (options.curve >= 0 && !l.has(Column::curve))
    fail("curve " + std::to_string(options.curve) + " was selected but the file has no curve column");
  l.header = std::move(header);
  return l;
}

// The numbers of one data row; every cell must be a finite number.
void read_numbers(const std::vector<std::string_view>& cells, const Layout& l, std::size_t line_no,
                  const Fail& fail, std::vector<double>& v) {
  if (cells.size() != l.header.size())
    fail("line " + std::to_string(line_no) + " has " + std::to_string(cells.size()) +
         " cells, the header has " + std::to_string(l.header.size()));
  v.resize(cells.size());
  for (std::size_t c = 0; c < cells.size(); ++c) {
    if (!detail::parse_finite(cells[c], v[c]))
      fail("line " + std::to_string(line_no) + ", column '" + l.header[c] + "': '" + shorten(cells[c]) +
           "' is not a finite number");
  }
}

// One row into the curve, converted to SI delta and P by the layout's convention; rows of
// other curves than the selected one are skipped (the export's curve column).
void append_row(const std::vector<double>& v, const Layout& l, const CsvOptions& options,
                std::size_t line_no, const Fail& fail, CurveData& d, std::unordered_set<double>& curves) {
  auto col = [&](Column c) { return v[l.where.at(c)]; };
  if (l.has(Column::curve)) {
    const double c = col(Column::curve);
    curves.insert(c);  // a hash set: 400 000 curve ids took 39 s with a linear search per row
    if (options.curve >= 0 && c != options.curve) return;
  }
  const double L = options.length_unit, F = options.force_unit;
  if (l.raw && l.has(Column::force)) {  // AFM Workshop, lab scripts: deflection = force / k
    const double P = col(Column::force) * F;
    d.delta.push_back(options.z_sign * col(Column::z) * L - P / options.spring_constant);
    d.P.push_back(P);
  } else if (l.raw) {
    const double dfl = options.deflection_sign * col(Column::deflection) * L;
    d.delta.push_back(options.z_sign * col(Column::z) * L - dfl);
    d.P.push_back(options.spring_constant * dfl);
  } else if (l.radius_only) {
    d.P.push_back(col(Column::force) * F);
  } else {
    d.delta.push_back(l.has(Column::delta) ? col(Column::delta) * L : -col(Column::tip_position) * L);
    d.P.push_back(col(Column::force) * F);
  }
  if (l.has(Column::a)) d.a.push_back(col(Column::a) * L);
  if (l.has(Column::weight)) d.weight.push_back(col(Column::weight));
  if (l.has(Column::segment)) {
    const double s = col(Column::segment);
    if (s != 0.0 && s != 1.0 && s != 2.0)
      fail("line " + std::to_string(line_no) + ", column 'segment': " + format_double(s) +
           " is invalid; valid values: 0 (approach), 1 (retract), 2 (dwell)");
    d.segment.push_back(static_cast<int>(s));
  }
  if (l.has(Column::time)) d.t.push_back(col(Column::time));
}

}  // namespace

bool is_vendor_curve_text(std::string_view text) {
  return detail::is_afm_workshop(text) || detail::is_afmformats_tab(text) || detail::is_chiaro_txt(text) ||
         detail::is_ntmdt_txt(text);
}

CurveData parse_curve_csv(const std::string& text, const std::string& source,
                          const CsvOptions& options) {
  options.validate();
  const Fail fail{source};
  // A format known not to be read is named for what it is, text or not.
  if (const std::string why = detail::unread_format_reason(source); !why.empty()) fail(why);
  // A binary file: say which formats are known rather than only that it is not text.
  if (text.find('\0') != std::string::npos) {
    fail("is not a text file (it contains NUL bytes): not CSV, and its name is not of a known instrument format "
         "(known: " + known_instrument_formats() + ")");
  }
  if (detail::is_afm_workshop(text)) return detail::parse_afm_workshop(text, source, options);
  if (detail::is_afmformats_tab(text)) return detail::parse_afmformats_tab(text, source, options);
  if (detail::is_chiaro_txt(std::string_view(text).substr(0, 4096))) return detail::parse_chiaro_txt(text, source, options);
  if (detail::is_ntmdt_txt(text)) return detail::parse_ntmdt_txt(text, source, options);
  if (options.sensitivity > 0.0)
    fail("is a CSV of named columns: a sensitivity (--sensitivity, Python sensitivity= " +
         format_double(options.sensitivity) + " m/V) does not apply; it turns an instrument's deflection signal into "
         "metres (instrument files, AFM Workshop's T-B(V) and NT-MDT's exports)");
  detail::CsvRows rows(text);
  std::size_t line_no = 0;
  auto next_row = [&](std::vector<std::string_view>* cells) {
    const bool more = rows.next(*cells);
    line_no = rows.line();
    return more;
  };
  std::vector<std::string_view> cells;
  if (!next_row(&cells)) fail("is empty (expected a header row such as delta,P)");
  const Layout layout = read_layout(std::vector<std::string>(cells.begin(), cells.end()), options, fail);
  // Signs that cannot apply are refused, not ignored: the user meant something by them.
  if (options.z_sign != 1.0 && !layout.raw)
    fail("has no z column: a z sign (--z-sign, Python z_sign= " + format_double(options.z_sign) +
         ") applies to z,deflection and z,force data only");
  if (options.deflection_sign != 1.0 && !(layout.raw && layout.has(Column::deflection)))
    fail("has no z,deflection columns: a deflection sign (--deflection-sign, Python deflection_sign= " +
         format_double(options.deflection_sign) + ") applies to z,deflection data only");
  CurveData d;
  d.source = source;
  d.spring_constant = options.spring_constant;
  const std::size_t estimate = text.size() / 32;  // rows are ~30-60 characters
  d.delta.reserve(estimate);
  d.P.reserve(estimate);
  std::unordered_set<double> curves;
  std::vector<double> values;
  const std::size_t max_rows = options.max_rows;
  std::size_t n_rows = 0;
  while (next_row(&cells)) {
    if (++n_rows > max_rows)
      fail("has more than " + std::to_string(max_rows) +
           " data rows, the limit (raise it with the option max_rows)");
    read_numbers(cells, layout, line_no, fail, values);
    append_row(values, layout, options, line_no, fail, d, curves);
  }
  if (options.curve < 0 && curves.size() > 1)
    fail("holds " + std::to_string(curves.size()) + " curves (column curve); select one (option curve = N)");
  if (options.curve >= 0 && d.P.empty())
    fail("has no rows of curve " + std::to_string(options.curve));
  if (d.P.empty()) fail("has a header but no data rows");
  // Order matters for the branch split (approach rows, then retract rows; CurveData::validate).
  // Rows repeating their predecessor are kept: real exports contain them (jpk_spot3_0192 rows
  // 127-128 are identical; the instrument's height signal is quantised).
  d.validate();
  return d;
}

CurveData read_curve_csv(const std::string& path, const CsvOptions& options) {
  options.validate();
  return parse_curve_csv(detail::read_file(path, "the data file", options.max_bytes,
                                           "the option max_bytes"),
                         path, options);
}

}  // namespace layerjkr
