// libFuzzer target: JPK archives from their bytes - the zip directory and local headers
// (libzip), the CRC-32 and size checks, the .properties headers and the header path (shared
// data, channel encoders, conversion chains, map grid). Limits are set low so that a
// declared size the fuzzer invents fails as it would for a user, without exhausting the
// -rss_limit_mb. Any input must give consistent curves or throw layerjkr::Error.
#include <cstdint>
#include <string>

#include "io/instrument_readers.hpp"
#include "layerjkr/error.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  layerjkr::ReadLimits limits;
  limits.max_member_bytes = std::uint64_t{16} << 20;
  limits.max_archive_bytes = std::uint64_t{64} << 20;
  try {
    const layerjkr::InstrumentFile f = layerjkr::detail::read_jpk_bytes(
        std::string(reinterpret_cast<const char*>(data), size), "fuzz.jpk-force", layerjkr::InstrumentFormat::jpk_force,
        limits);
    for (const auto& c : f.curves) {
      if (c.segments.empty()) __builtin_trap();
      for (const auto& s : c.segments)
        if (s.force.size() != s.height.size() || s.force.empty() ||
            (!s.piezo_height.empty() && s.piezo_height.size() != s.force.size()))
          __builtin_trap();
      if (f.grid_shape_x > 0 && (c.grid_x >= f.grid_shape_x || c.grid_y >= f.grid_shape_y)) __builtin_trap();
    }
  } catch (const layerjkr::Error&) {
  }
  return 0;
}
