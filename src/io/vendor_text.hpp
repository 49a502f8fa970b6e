// Internal: text exports of instruments that write no file of their own that layerjkr reads, read
// by read_curve_csv by their content (vendor_text.cpp): NT-MDT Nova's three-column text and
// Optics11 Chiaro's indentation text.
#pragma once

#include <string>
#include <string_view>

#include "layerjkr/curve_data.hpp"

namespace layerjkr::detail {

/// True if `text` (a file's first bytes) begins an NT-MDT Nova force-curve export: no header, its
/// first line three tab-separated numbers (decimal comma or point).
bool is_ntmdt_txt(std::string_view text);

/// The curve of an NT-MDT Nova export: columns height [nm], the approach's and the retract's
/// deflection [nA] on the same heights, the rows running from the turnaround outwards; constant
/// padding at the turnaround is dropped (one padded row kept), as afmformats does. The file holds
/// no calibration: force = deflection x options.sensitivity [m/A] x options.spring_constant [N/m],
/// both required (InputError naming the options otherwise). Approach rows (segment 0) run from the
/// farthest height in, retract rows (segment 1) outwards; delta = -(height + force / k).
CurveData parse_ntmdt_txt(std::string_view text, const std::string& source, const CsvOptions& options);

/// True if `text` (a file's first 4 KiB) begins an Optics11 Chiaro indentation export (its header
/// says `Device:<TAB>Chiaro`).
bool is_chiaro_txt(std::string_view text);

/// The curve of an Optics11 Chiaro export: the header (k (N/m), ...), then the columns Time (s),
/// Load (uN), Indentation (nm), Cantilever (nm), Piezo (nm), Auxiliary. P = load, delta = piezo -
/// cantilever (the tip's travel towards the sample), t = time; samples up to the largest load are
/// the approach (segment 0), the rest the retract (1), as afmformats splits them. A spring
/// constant given (options.spring_constant) rescales the load, which the file computed with its
/// own k, by k / the file's k; the deflection is measured in nm, so a sensitivity is refused.
CurveData parse_chiaro_txt(std::string_view text, const std::string& source, const CsvOptions& options);

}  // namespace layerjkr::detail
