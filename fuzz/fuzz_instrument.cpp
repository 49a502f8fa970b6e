// libFuzzer target: the instrument readers' text and binary parsing. The first byte picks
// the reader: even, an Igor binary wave from the remaining bytes; odd, a JPK header
// (.properties). Any input must give consistent curves or throw layerjkr::Error.
#include <cmath>
#include <cstdint>
#include <string>

#include "io/instrument_readers.hpp"
#include "io/java_properties.hpp"
#include "layerjkr/error.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const std::string bytes(reinterpret_cast<const char*>(data + 1), size - 1);
  if (data[0] & 1) {
    try {
      const layerjkr::detail::Properties p = layerjkr::detail::parse_properties(bytes, "fuzz.properties");
      for (const auto& [k, v] : p)
        if (k.size() > bytes.size() * 3 + 3 || v.size() > bytes.size() * 3 + 3) __builtin_trap();  // UTF-8 grows 3x at most
    } catch (const layerjkr::InputError&) {  // a repeated key
    }
    return 0;
  }
  try {
    const layerjkr::InstrumentFile f = layerjkr::detail::read_ibw_bytes(bytes, "fuzz.ibw");
    for (const auto& c : f.curves)
      for (const auto& s : c.segments)
        if (s.force.size() != s.height.size() || s.force.empty()) __builtin_trap();
  } catch (const layerjkr::Error&) {
  }
  return 0;
}
