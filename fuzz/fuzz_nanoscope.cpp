// libFuzzer target: the NanoScope force reader (header parser, checks, every curve) from
// memory. Any input must give curves of consistent, finite samples or throw layerjkr::Error.
#include <cmath>
#include <cstdint>
#include <string>

#include "io/curve_source.hpp"
#include "layerjkr/error.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string bytes(reinterpret_cast<const char*>(data), size);
  try {
    const auto src = layerjkr::detail::open_nanoscope_bytes(bytes, "fuzz.spm", layerjkr::ReadLimits{});
    // The header was checked against the input's size: no more curves than bytes.
    if (src->size() > size) __builtin_trap();
    for (std::size_t i = 0; i < src->size() && i < 64; ++i) {
      const layerjkr::InstrumentCurve c = src->curve(i);
      if (c.segments.size() != 2 || !(c.spring_constant > 0.0)) __builtin_trap();
      for (const auto& s : c.segments) {
        if (s.force.empty() || s.force.size() != s.height.size()) __builtin_trap();
        for (std::size_t k = 0; k < s.force.size(); ++k)
          if (!std::isfinite(s.force[k]) || !std::isfinite(s.height[k])) __builtin_trap();
      }
    }
  } catch (const layerjkr::Error&) {
  }
  return 0;
}
