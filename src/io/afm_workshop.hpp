// Internal: AFM Workshop's force-distance CSV export (afm_workshop.cpp), read by read_curve_csv
// when a file starts with "Force-Distance Curve", and its maps, a zip archive of such files, one
// per point (afm_workshop_map.cpp).
#pragma once

#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "layerjkr/curve_data.hpp"

namespace layerjkr::detail {

/// True if `text` is an AFM Workshop force-distance export (its first line).
bool is_afm_workshop(std::string_view text);

/// What one AFM Workshop export holds, in SI units, before any calibration is applied.
struct AfmWorkshopRecord {
  std::map<std::string, std::string, std::less<>> header;  ///< `Key:<TAB>value` lines, trimmed
  std::vector<double> z[2];       ///< Z-Sense [m] (grows towards the sample), [extend, retract]
  std::vector<double> signal[2];  ///< force [N], or with `volts` the photodiode's T-B [V]
  bool volts = false;             ///< the export holds T-B(V), not Force(nN)
  std::optional<double> spring_constant;  ///< `Force Constant, nN/nm` [N/m] unless the unset 1.000000
  std::optional<double> sensitivity;      ///< 1e-6 / `Light Lever Gain, mV/nm` [m/V] unless unset
  /// A header number [unit of the file] (e.g. "X, um"), or nullopt if absent or not a number.
  std::optional<double> number(std::string_view key) const;
};

/// Reads an export's header and its columns (without `columns`, the header and the column names
/// alone); throws InputError naming `source` and what is malformed.
AfmWorkshopRecord read_afm_workshop(std::string_view text, const std::string& source, bool columns = true);

/// The curve of an AFM Workshop export: extend rows (segment 0) then retract rows (segment 1),
/// delta = Z-Sense - force / k, P = force; k is options.spring_constant if > 0, else the file's
/// `Force Constant, nN/nm` (1.000000, the software's unset default, counts as absent). T-B(V)
/// columns become force through the sensitivity [m/V] (options.sensitivity if > 0, else that of
/// the file's `Light Lever Gain, mV/nm`: 1e-6 / gain) and k. Throws InputError naming `source` and
/// what is missing (k, the sensitivity) and the option that supplies it, or what is malformed.
CurveData parse_afm_workshop(std::string_view text, const std::string& source, const CsvOptions& options);

}  // namespace layerjkr::detail
