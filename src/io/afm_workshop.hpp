// Internal: AFM Workshop's force-distance CSV export (afm_workshop.cpp), read by read_curve_csv
// when a file starts with "Force-Distance Curve".
#pragma once

#include <string>
#include <string_view>

#include "layerjkr/curve_data.hpp"

namespace layerjkr::detail {

/// True if `text` is an AFM Workshop force-distance export (its first line).
bool is_afm_workshop(std::string_view text);

/// The curve of an AFM Workshop export: extend rows (segment 0) then retract rows (segment 1),
/// delta = Z-Sense - force / k, P = force; k is options.spring_constant if > 0, else the file's
/// `Force Constant, nN/nm` (1.000000, the software's unset default, counts as absent). T-B(V)
/// columns become force through the file's `Light Lever Gain, mV/nm` and k. Throws InputError
/// naming `source` and what is missing (k, the gain) or malformed.
CurveData parse_afm_workshop(std::string_view text, const std::string& source, const CsvOptions& options);

}  // namespace layerjkr::detail
