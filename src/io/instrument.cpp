// Instrument files: dispatch by extension, and the curve a fit consumes (instrument.hpp).
#include "layerjkr/instrument.hpp"

#include <charconv>
#include <cmath>
#include <cstdlib>
#include <optional>
#include <string_view>

#include "io/instrument_readers.hpp"
#include "io/zip_archive.hpp"
#include "layerjkr/error.hpp"

namespace layerjkr {
namespace {

// The format an extension names (the registry's spellings are the extensions).
std::optional<InstrumentFormat> format_of(const std::string& path) {
  const auto dot = path.rfind('.');
  if (dot == std::string::npos) return std::nullopt;
  return from_string<InstrumentFormat>(std::string_view(path).substr(dot + 1));
}

// A limit in MiB from the environment, or `fallback` when the variable is unset.
std::uint64_t env_mib(const char* name, std::uint64_t fallback) {
  const char* text = std::getenv(name);
  if (!text) return fallback;
  constexpr std::uint64_t max_mib = std::uint64_t{1} << 20;
  const std::string_view s(text);
  std::uint64_t v = 0;
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  if (ec != std::errc() || end != s.data() + s.size() || v < 1 || v > max_mib)
    throw InputError(std::string(name) + " = '" + text + "': must be a whole number of MiB in [1, " +
                     std::to_string(max_mib) + "]");
  return v << 20;
}

}  // namespace

ReadLimits ReadLimits::from_environment() {
  ReadLimits limits;
  limits.max_member_bytes = env_mib(detail::kMaxMemberEnv, limits.max_member_bytes);
  limits.max_archive_bytes = env_mib(detail::kMaxArchiveEnv, limits.max_archive_bytes);
  return limits;
}

bool is_instrument_file(const std::string& path) { return format_of(path).has_value(); }

InstrumentFile read_instrument_file(const std::string& path) {
  return read_instrument_file(path, ReadLimits::from_environment());
}

InstrumentFile read_instrument_file(const std::string& path, const ReadLimits& limits) {
  const std::optional<InstrumentFormat> format = format_of(path);
  if (!format)
    throw InputError(path + ": not an instrument file (known: .jpk-force, .jpk-force-map, .jpk-qi-data, .ibw)");
  InstrumentFile file =
      *format == InstrumentFormat::ibw ? detail::read_ibw(path) : detail::read_jpk(path, *format, limits);
  for (const InstrumentCurve& c : file.curves)
    if (!(c.spring_constant > 0.0) || !std::isfinite(c.spring_constant))
      throw InputError(path + ": curve " + std::to_string(c.index) + " has spring constant " +
                       format_double(c.spring_constant) + " N/m; it must be finite and > 0");
  return file;
}

std::vector<double> InstrumentCurve::tip_position(std::size_t s) const {
  const InstrumentSegment& seg = segments.at(s);
  std::vector<double> out(seg.force.size());
  for (std::size_t i = 0; i < out.size(); ++i) out[i] = seg.height[i] + seg.force[i] / spring_constant;
  return out;
}

CurveData to_curve_data(const InstrumentCurve& curve, const std::string& source, double spring_constant) {
  detail::require_non_negative("to_curve_data", "spring_constant", spring_constant);
  const double k = spring_constant > 0.0 ? spring_constant : curve.spring_constant;
  const double scale = k / curve.spring_constant;
  CurveData d;
  d.source = source;
  d.spring_constant = k;
  bool retracting = false;
  for (const InstrumentSegment& seg : curve.segments) {
    retracting = retracting || seg.style == SegmentStyle::retract;
    for (std::size_t i = 0; i < seg.force.size(); ++i) {
      const double force = seg.force[i] * scale;
      d.delta.push_back(-(seg.height[i] + force / k));
      d.P.push_back(force);
      d.segment.push_back(retracting ? 1 : 0);
    }
  }
  d.validate();
  return d;
}

}  // namespace layerjkr
