// Instrument files: dispatch by extension, and the curve a fit consumes (instrument.hpp).
#include "layerjkr/instrument.hpp"

#include <cmath>

#include "io/instrument_readers.hpp"
#include "layerjkr/error.hpp"

namespace layerjkr {
namespace {

std::string format_of(const std::string& path) {
  for (const char* ext : {"jpk-force", "jpk-force-map", "jpk-qi-data", "ibw"}) {
    const std::string suffix = std::string(".") + ext;
    if (path.size() > suffix.size() && path.compare(path.size() - suffix.size(), suffix.size(), suffix) == 0)
      return ext;
  }
  return "";
}

}  // namespace

bool is_instrument_file(const std::string& path) { return !format_of(path).empty(); }

InstrumentFile read_instrument_file(const std::string& path) {
  const std::string format = format_of(path);
  if (format.empty())
    throw InputError(path + ": not an instrument file (known: .jpk-force, .jpk-force-map, .jpk-qi-data, .ibw)");
  InstrumentFile file = format == "ibw" ? detail::read_ibw(path) : detail::read_jpk(path, format);
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
    retracting = retracting || seg.style == "retract";
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
