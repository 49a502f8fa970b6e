// AFM Workshop force-distance CSV exports (io/afm_workshop.hpp). The layout, as the files in
// afmformats' test suite show it (File Format 3, and software 4.0): a first line
// "Force-Distance Curve", `Key:<TAB>value` lines (Date, Mode, X, um, ..., and in newer files
// `Light Lever Gain, mV/nm` and `Force Constant, nN/nm`, whose value 1.000000 is the software's
// unset default), then the columns `Extend Z-Sense(nm),Extend Force(nN),Retract Z-Sense(nm),
// Retract Force(nN)` - or `T-B(V)`, the photodiode's volts, instead of Force - extend and retract
// side by side, each in time order. Z-Sense grows towards the sample.
#include "io/afm_workshop.hpp"

#include <algorithm>
#include <map>
#include <optional>

#include "io/csv_rows.hpp"
#include "layerjkr/error.hpp"
#include "layerjkr/text.hpp"

namespace layerjkr::detail {
namespace {

constexpr std::string_view kFirstLine = "Force-Distance Curve";
constexpr double kUnset = 1.0;  // the value AFM Workshop writes for a gain or constant not set

struct Columns {
  int z[2] = {-1, -1}, force[2] = {-1, -1}, volts[2] = {-1, -1};  // [extend, retract]
};

// A header value of `key` that is a number other than the unset default, or nullopt.
std::optional<double> set_value(const std::map<std::string, std::string, std::less<>>& meta, std::string_view key) {
  const auto it = meta.find(key);
  double v = 0.0;
  if (it == meta.end() || !parse_finite(trim(it->second), v) || v == kUnset || !(v > 0.0)) return std::nullopt;
  return v;
}

}  // namespace

bool is_afm_workshop(std::string_view text) {
  if (text.substr(0, 3) == "\xEF\xBB\xBF") text.remove_prefix(3);
  return text.substr(0, kFirstLine.size()) == kFirstLine;
}

std::optional<double> AfmWorkshopRecord::number(std::string_view key) const {
  const auto it = header.find(key);
  double v = 0.0;
  if (it == header.end() || !parse_finite(trim(it->second), v)) return std::nullopt;
  return v;
}

AfmWorkshopRecord read_afm_workshop(std::string_view text, const std::string& source, bool columns) {
  const auto fail = [&](const std::string& what) -> void {
    throw InputError(source + ": AFM Workshop force-distance file: " + what);
  };
  AfmWorkshopRecord r;
  TextLines lines(text);
  std::string_view header;
  while (const auto next = lines.next()) {
    const std::string_view t = *next;
    if (t.find("Z-Sense(nm)") != std::string_view::npos) {
      header = t;
      break;
    }
    const std::size_t colon = t.find(':');
    if (colon != std::string_view::npos)
      r.header.emplace(std::string(trim(t.substr(0, colon))), std::string(trim(t.substr(colon + 1))));
  }
  if (header.empty()) fail("has no column header naming Z-Sense(nm)");
  std::vector<std::string_view> cells;
  split(header, cells);
  Columns c;
  for (std::size_t i = 0; i < cells.size(); ++i) {
    const std::string_view name = cells[i];
    const int side = name.rfind("Extend ", 0) == 0 ? 0 : name.rfind("Retract ", 0) == 0 ? 1 : -1;
    const std::string_view what = side < 0 ? name : name.substr(side == 0 ? 7 : 8);
    int* slot = what == "Z-Sense(nm)" ? &c.z[side < 0 ? 0 : side]
                : what == "Force(nN)" ? &c.force[side < 0 ? 0 : side]
                : what == "T-B(V)"    ? &c.volts[side < 0 ? 0 : side]
                                      : nullptr;
    if (side < 0 || !slot || *slot >= 0) fail("column '" + printable(std::string(name)) + "' is not one this reader knows");
    *slot = static_cast<int>(i);
  }
  r.volts = c.volts[0] >= 0;
  if (c.z[0] < 0 || c.z[1] < 0 || (r.volts ? c.volts[1] < 0 || c.force[0] >= 0 : c.force[0] < 0 || c.force[1] < 0))
    fail("expected Extend and Retract columns of Z-Sense(nm) with Force(nN) or with T-B(V)");
  r.spring_constant = set_value(r.header, "Force Constant, nN/nm");  // nN/nm = N/m
  if (const std::optional<double> gain = set_value(r.header, "Light Lever Gain, mV/nm")) r.sensitivity = 1e-6 / *gain;
  if (!columns) return r;
  while (const auto next = lines.next()) {
    const std::string_view t = *next;
    if (t.empty()) continue;
    split(t, cells);
    for (int side = 0; side < 2; ++side) {
      const int zc = c.z[side], fc = r.volts ? c.volts[side] : c.force[side];
      double z = 0.0, f = 0.0;
      if (static_cast<std::size_t>(std::max(zc, fc)) >= cells.size() || !parse_finite(cells[static_cast<std::size_t>(zc)], z) ||
          !parse_finite(cells[static_cast<std::size_t>(fc)], f))
        fail("line " + std::to_string(lines.line()) + ": '" + printable(std::string(t), 60) + "' is not a row of numbers");
      r.z[side].push_back(z * 1e-9);
      r.signal[side].push_back(r.volts ? f : f * 1e-9);
    }
  }
  if (r.z[0].empty()) fail("has a column header but no data rows");
  return r;
}

CurveData parse_afm_workshop(std::string_view text, const std::string& source, const CsvOptions& options) {
  const auto fail = [&](const std::string& what) -> void {
    throw InputError(source + ": AFM Workshop force-distance file: " + what);
  };
  if (options.length_unit != 1.0 || options.force_unit != 1.0)
    fail("states its units (Z-Sense in nm, Force in nN); give no units option");
  const AfmWorkshopRecord r = read_afm_workshop(text, source);
  // k and the sensitivity: the user's (as for instrument files) or the file's.
  const double k = options.spring_constant > 0.0 ? options.spring_constant : r.spring_constant.value_or(0.0);
  if (!(k > 0.0))
    fail("gives no spring constant (Force Constant, nN/nm is absent or the unset 1.000000): the tip's position is "
         "Z-Sense minus the deflection, force / k; give the cantilever's spring constant k [N/m] (--spring-constant)");
  const double sensitivity = options.sensitivity > 0.0 ? options.sensitivity : r.sensitivity.value_or(0.0);
  if (r.volts && !(sensitivity > 0.0))
    fail("holds the photodiode's T-B(V), not force, and gives no Light Lever Gain, mV/nm (absent or the unset "
         "1.000000) to make it a deflection: give the deflection sensitivity [m/V] (--sensitivity; 1e-6 / the gain "
         "in mV/nm), or export Force(nN)");
  if (!r.volts && options.sensitivity > 0.0)
    fail("gives forces (Force(nN)), not the photodiode's T-B(V): a sensitivity (--sensitivity " +
         format_double(options.sensitivity) + " m/V) does not apply");
  CurveData d;
  d.source = source;
  d.spring_constant = k;
  for (int side = 0; side < 2; ++side)
    for (std::size_t i = 0; i < r.z[side].size(); ++i) {
      const double force = r.volts ? k * sensitivity * r.signal[side][i] : r.signal[side][i];
      d.delta.push_back(r.z[side][i] - force / k);
      d.P.push_back(force);
      d.segment.push_back(side);
    }
  d.validate();
  return d;
}

}  // namespace layerjkr::detail
