// AFM Workshop force maps (curve_source.hpp): the software writes one force-distance CSV per
// point (afm_workshop.hpp), `Mode: Mapping`, `Point: N` counting from 1 and the point's `X, um` /
// `Y, um`; afmformats reads a zip archive of them, in the order of the members' names, as one
// map, and so does layerjkr. The grid is the distinct X and Y positions, sorted; its size spans the
// points plus one pitch (points sit at pixel centres), its centre is the positions' mean, as in
// afmformats' ws_map. Opening reads every member's header (a few hundred bytes each after
// inflation); curve(i) reads member i alone.
#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <set>

#include "io/afm_workshop.hpp"
#include "io/curve_source.hpp"
#include "io/zip_archive.hpp"
#include "layerjkr/error.hpp"

namespace layerjkr::detail {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

struct GridAxis {
  std::vector<double> values;  // distinct positions [m], sorted
  int index(double v) const {
    return static_cast<int>(std::lower_bound(values.begin(), values.end(), v) - values.begin());
  }
  double size() const {
    const std::size_t n = values.size();
    return n > 1 ? (values.back() - values.front()) * (1.0 + 1.0 / static_cast<double>(n - 1)) : 0.0;
  }
  double centre() const {
    return values.empty() ? 0.0 : std::accumulate(values.begin(), values.end(), 0.0) / static_cast<double>(values.size());
  }
};

class AfmWorkshopMap final : public CurveSource {
 public:
  AfmWorkshopMap(const std::string& path, const ReadLimits& limits) : zip_(path, limits) {
    file_.path = path;
    file_.format = InstrumentFormat::afm_workshop_map;
    file_.instrument = "AFM Workshop";
    for (std::size_t i = 0; i < zip_.size(); ++i)
      if (const std::string_view n = zip_.name(i); !n.empty() && n.back() != '/') names_.emplace_back(n);
    std::sort(names_.begin(), names_.end());
    if (names_.empty())
      throw InputError(path + ": a zip archive without files; layerjkr reads a .zip as an AFM Workshop force map (one "
                              "force-distance CSV export per point)");
    std::set<double> xs, ys;
    for (std::size_t i = 0; i < names_.size(); ++i) {
      const std::string text = member(i);
      if (!is_afm_workshop(text) && is_vendor_curve_text(std::string_view(text).substr(0, 4096)))
        throw InputError(where(i) + ": a curve export layerjkr reads (Chiaro, NT-MDT, afmformats tab), zipped: unpack "
                                    "the archive and give the file itself; a .zip is read as an AFM Workshop force map");
      if (!is_afm_workshop(text))
        throw InputError(where(i) + ": not an AFM Workshop force-distance export (its first line is not 'Force-Distance "
                                    "Curve'); layerjkr reads a .zip as an AFM Workshop force map, one export per point");
      const AfmWorkshopRecord r = read_afm_workshop(text, where(i), false);
      Point p;
      p.number = r.number("Point");
      p.x = r.number("X, um").value_or(kNaN) * 1e-6;
      p.y = r.number("Y, um").value_or(kNaN) * 1e-6;
      if (!std::isfinite(p.x) || !std::isfinite(p.y))
        throw InputError(where(i) + ": AFM Workshop map point without its position (X, um and Y, um)");
      if (p.number && *p.number != static_cast<double>(i + 1))
        notes_.push_back(names_[i] + " says Point " + format_double(*p.number) + " but is member " +
                         std::to_string(i + 1) + " in name order: read in name order, placed by its X and Y");
      if (i == 0 && r.header.count("Software Version")) file_.software = r.header.at("Software Version");
      xs.insert(p.x);
      ys.insert(p.y);
      points_.push_back(p);
    }
    x_.values.assign(xs.begin(), xs.end());
    y_.values.assign(ys.begin(), ys.end());
    file_.grid_shape_x = static_cast<int>(x_.values.size());
    file_.grid_shape_y = static_cast<int>(y_.values.size());
    file_.grid_size_x = x_.size();
    file_.grid_size_y = y_.size();
    file_.grid_center_x = x_.centre();
    file_.grid_center_y = y_.centre();
  }

  const InstrumentFile& header() const override { return file_; }
  std::size_t size() const override { return names_.size(); }

  InstrumentCurve curve(std::size_t i, const CurveChannels& /*every channel is read*/) const override {
    const AfmWorkshopRecord r = read_afm_workshop(member(i), where(i));
    InstrumentCurve c;
    c.index = static_cast<int>(i);
    c.position_index = points_[i].number ? static_cast<int>(*points_[i].number) : -1;
    c.x = points_[i].x;
    c.y = points_[i].y;
    c.grid_x = x_.index(c.x);
    c.grid_y = y_.index(c.y);
    c.notes = notes_;
    // What the file knows sets the units of `force`: newtons with k (and, for volts, the
    // sensitivity), metres of deflection with the sensitivity alone, volts with neither
    // (InstrumentCurve; to_curve_data completes it from what the user gives).
    c.sensitivity = r.volts ? r.sensitivity.value_or(kNaN) : 0.0;
    c.spring_constant = r.spring_constant.value_or(kNaN);
    if (!r.volts && std::isnan(c.spring_constant))
      throw InputError(where(i) + ": AFM Workshop export of Force(nN) without its spring constant (Force Constant, "
                                  "nN/nm): the tip's position needs it; export T-B(V) or set the constant in the header");
    const double scale = r.volts ? (std::isnan(c.sensitivity) ? 1.0 : c.sensitivity) *
                                       (std::isnan(c.spring_constant) ? 1.0 : c.spring_constant)
                                 : 1.0;
    for (int side = 0; side < 2; ++side) {
      InstrumentSegment s;
      s.style = side == 0 ? SegmentStyle::extend : SegmentStyle::retract;
      s.height.reserve(r.z[side].size());
      s.force.reserve(r.z[side].size());
      for (std::size_t k = 0; k < r.z[side].size(); ++k) {
        s.height.push_back(-r.z[side][k]);  // Z-Sense grows towards the sample; height away from it
        s.force.push_back(r.signal[side][k] * scale);
      }
      c.segments.push_back(std::move(s));
    }
    return c;
  }

 private:
  struct Point {
    std::optional<double> number;  // the file's Point
    double x = kNaN, y = kNaN;     // [m]
  };
  std::string member(std::size_t i) const { return zip_.read(names_[i]); }
  std::string where(std::size_t i) const { return file_.path + ": " + names_[i]; }

  ZipArchive zip_;
  InstrumentFile file_;
  std::vector<std::string> names_;
  std::vector<Point> points_;
  std::vector<std::string> notes_;
  GridAxis x_, y_;
};

}  // namespace

std::unique_ptr<CurveSource> open_afm_workshop_map(const std::string& path, const ReadLimits& limits) {
  return std::make_unique<AfmWorkshopMap>(path, limits);
}

}  // namespace layerjkr::detail
