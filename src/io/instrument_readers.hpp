// Internal: the per-format readers behind read_instrument_file (instrument.hpp).
#pragma once

#include <string>

#include "layerjkr/instrument.hpp"

namespace layerjkr::detail {

/// JPK archive of one of the three JPK formats.
InstrumentFile read_jpk(const std::string& path, InstrumentFormat format, const ReadLimits& limits);
/// The same from the archive's bytes; `path` names it in errors.
InstrumentFile read_jpk_bytes(std::string bytes, const std::string& path, InstrumentFormat format,
                              const ReadLimits& limits);
/// Igor binary wave v5 (Asylum force curve).
InstrumentFile read_ibw(const std::string& path);
/// The same from the file's bytes; `path` names it in errors.
InstrumentFile read_ibw_bytes(std::string bytes, const std::string& path);

}  // namespace layerjkr::detail
