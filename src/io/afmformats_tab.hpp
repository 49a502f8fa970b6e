// Internal: afmformats' tab-separated export (.tab; how nanite and PyJibe users keep their curves),
// read by read_curve_csv when a file starts with "# afmformats" or "# BEGIN METADATA".
#pragma once

#include <string>
#include <string_view>

#include "layerjkr/curve_data.hpp"

namespace layerjkr::detail {

/// True if `text` is an afmformats tab export: its first line is "# afmformats VERSION" or
/// "# BEGIN METADATA".
bool is_afmformats_tab(std::string_view text);

/// The curve of an afmformats tab export: "# BEGIN METADATA" ... "# END METADATA" (a JSON object,
/// each line behind "# "), then "# " and the tab-separated column names, then the rows. Columns
/// by name: force [N]; tip position [m], or height (measured) / height (piezo) [m] with the
/// spring constant (options.spring_constant if > 0, else the metadata's "spring constant" [N/m]);
/// segment (False/True or 0/1: approach, retract); time [s] where given. delta = -tip position,
/// tip position = height + force / k. afmformats 0.13.3 wrote the first row on the header's line
/// ("...\ttime-6.77e-10\t..."): it is read as the first row, with a note. Throws InputError
/// naming `source` and what is missing or malformed.
CurveData parse_afmformats_tab(std::string_view text, const std::string& source, const CsvOptions& options);

}  // namespace layerjkr::detail
