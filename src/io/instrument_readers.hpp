// Internal: whole-file reads over the per-format curve sources (curve_source.hpp), for the
// fuzzers and the tests that build files in memory.
#pragma once

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "io/curve_source.hpp"
#include "io/igor_wave.hpp"
#include "layerjkr/instrument.hpp"

namespace layerjkr::detail {

/// Curve i of `source`, its spring constant checked (finite and > 0) as every reader does.
InstrumentCurve checked_curve(const CurveSource& source, std::size_t i, const CurveChannels& channels = {});
/// The curves of `range` with the file's metadata.
InstrumentFile read_all(const CurveSource& source, const CurveRange& range = {});
/// A source over curves already read (formats read whole, such as an Igor wave).
std::unique_ptr<CurveSource> source_of(InstrumentFile file);

/// Igor binary wave v5 (Asylum force curve), read whole.
InstrumentFile read_ibw(const std::string& path);
/// The same from the file's bytes; `path` names it in errors.
InstrumentFile read_ibw_bytes(const std::string& bytes, const std::string& path);
/// What to do with an Asylum map layerjkr does not read (ARDF, HDF5): export it per point.
inline constexpr const char* kAsylumPerPoint =
    "for an Asylum map, export it from AR's software as one .ibw wave per channel per point "
    "(LineLLLLPointPPPP<Channel>.ibw) and give their folder, which layerjkr reads as one map";
/// Why a file of a known vendor format that layerjkr does not read is refused, with what to export
/// instead (Asylum ARDF and HDF5 maps, by the name's extension in any case); empty for any other.
std::string unread_format_reason(const std::string& path);

/// An Asylum map curve's name split: `LineLLLLPointPPPP<channel>` (1-6 digits each; the channel,
/// `Defl`, `ZSnsr`, ..., letters and digits, possibly empty).
struct AsylumPointName {
  int line = 0;
  int point = 0;
  std::string channel;
};
/// The parts of `name` from its last `LineLLLLPointPPPP<channel>` that runs to the end of `name`
/// (a wave's or file stem's name), or with `whole` only if that is all of `name`; nullopt
/// otherwise. Hand-parsed: GCC 12's <regex> trips -Wmaybe-uninitialized under the sanitizers' -O1.
std::optional<AsylumPointName> asylum_point_name(const std::string& name, bool whole = false);
/// (line, point) of an Asylum map's curve from a wave or file name (asylum_point_name).
std::optional<std::pair<int, int>> asylum_line_point(const std::string& name);
/// The segments of an Asylum curve of `rows` rows from its note's Indexes and Direction (without
/// Direction: extend, retract, then pauses), `sample(row, segment)` appending each row's values;
/// `path` names it in errors.
std::vector<InstrumentSegment> asylum_segments(const IgorNote& note, std::size_t rows, double row_step,
                                               const std::function<void(std::size_t, InstrumentSegment&)>& sample,
                                               const std::string& path);

/// Every curve of a JPK archive given as bytes; `path` names it in errors.
InstrumentFile read_jpk_bytes(std::string bytes, const std::string& path, InstrumentFormat format,
                              const ReadLimits& limits);

}  // namespace layerjkr::detail
