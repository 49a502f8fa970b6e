// Instrument files: dispatch by extension, and the curve a fit consumes (instrument.hpp).
#include "layerjkr/instrument.hpp"

#include <algorithm>
#include <atomic>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <stdexcept>
#include <optional>
#include <string_view>

#include "io/curve_source.hpp"
#include "io/instrument_readers.hpp"
#include "io/zip_archive.hpp"
#include "layerjkr/error.hpp"

namespace layerjkr {
namespace {

bool ends_with(const std::string& s, std::string_view suffix) {
  return s.size() >= suffix.size() && std::string_view(s).substr(s.size() - suffix.size()) == suffix;
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

// A file's first bytes, to name what an unreadable file is (never more than `n`).
std::string first_bytes(const std::string& path, std::size_t n) {
  std::ifstream f(path, std::ios::binary);
  std::string head(n, '\0');
  f.read(head.data(), static_cast<std::streamsize>(n));
  head.resize(static_cast<std::size_t>(std::max<std::streamsize>(f.gcount(), 0)));
  return head;
}

// The format of a file whose name says none: a NanoScope force file by its header (it keeps it
// when renamed); anything else is refused, naming what it is where that can be told.
InstrumentFormat format_by_content(const std::string& path) {
  const std::string known = " (known: " + known_instrument_formats() + ")";
  // Refused before its header is looked at: a .pfc's header looks like a force file's.
  if (ends_with(path, ".pfc"))
    throw InputError(path + ": Bruker PeakForce Capture (.pfc) files are not supported: their layout is not "
                            "documented publicly" + known);
  if (const std::string why = detail::unread_format_reason(path); !why.empty()) throw InputError(path + ": " + why + known);
  const std::string head = first_bytes(path, 32);
  if (head.rfind("\\*Force file list", 0) == 0) return InstrumentFormat::nanoscope;
  if (head.rfind("\\*File list", 0) == 0)
    throw InputError(path + ": a Bruker NanoScope image file, not force curves: unsupported" + known);
  throw InputError(path + ": not an instrument file" + known);
}

std::atomic<detail::Hdf5Opener>& hdf5_opener() {
  static std::atomic<detail::Hdf5Opener> opener{nullptr};
  return opener;
}

std::unique_ptr<detail::CurveSource> open_source(const std::string& path, const ReadLimits& limits) {
  if (std::vector<std::string> files = detail::asylum_channel_files(path); !files.empty())
    return detail::open_asylum_map(path, files);
  const std::optional<InstrumentFormat> named = instrument_format(path);
  const InstrumentFormat format = named ? *named : format_by_content(path);
  switch (format) {
    case InstrumentFormat::ibw: return detail::open_ibw(path);
    case InstrumentFormat::nanoscope: return detail::open_nanoscope(path, limits);
    case InstrumentFormat::jpk_force:
    case InstrumentFormat::jpk_force_map:
    case InstrumentFormat::jpk_qi_data:
    case InstrumentFormat::jpk_qi_series: return detail::open_jpk(path, format, limits);
    case InstrumentFormat::ibw_map: return detail::open_asylum_map(path, detail::asylum_channel_files(path));
    case InstrumentFormat::afm_workshop_map: return detail::open_afm_workshop_map(path, limits);
    case InstrumentFormat::afmformats_hdf5:
      if (const detail::Hdf5Opener open = hdf5_opener().load()) return open(path, limits);
      throw InputError(path + ": " + detail::unread_format_reason(path));
  }
  throw Error(path + ": InstrumentFormat " + std::to_string(static_cast<int>(format)) + " has no reader");
}

}  // namespace

ReadLimits ReadLimits::from_environment() {
  ReadLimits limits;
  limits.max_member_bytes = env_mib(detail::kMaxMemberEnv, limits.max_member_bytes);
  limits.max_archive_bytes = env_mib(detail::kMaxArchiveEnv, limits.max_archive_bytes);
  return limits;
}

std::optional<InstrumentFormat> instrument_format(const std::string& path) {
  for (InstrumentFormat f : {InstrumentFormat::jpk_force, InstrumentFormat::jpk_force_map,
                             InstrumentFormat::jpk_qi_data, InstrumentFormat::jpk_qi_series, InstrumentFormat::ibw})
    if (ends_with(path, std::string(".") + to_string(f))) return f;
  if (ends_with(path, ".spm")) return InstrumentFormat::nanoscope;
  if (ends_with(path, ".zip")) return InstrumentFormat::afm_workshop_map;
  if (ends_with(path, ".h5") || ends_with(path, ".hdf5")) return InstrumentFormat::afmformats_hdf5;
  // NanoScope numbers its files: name.000, name.001, ...
  const std::size_t dot = path.rfind('.');
  const std::size_t slash = path.find_last_of("/\\");
  if (dot != std::string::npos && (slash == std::string::npos || dot > slash) && path.size() - dot == 4 &&
      std::all_of(path.begin() + static_cast<std::ptrdiff_t>(dot) + 1, path.end(),
                  [](char c) { return c >= '0' && c <= '9'; }))
    return InstrumentFormat::nanoscope;
  return std::nullopt;
}

bool is_instrument_file(const std::string& path) { return instrument_format(path).has_value(); }

bool is_asylum_map_export(const std::string& path) { return !detail::asylum_channel_files(path).empty(); }

namespace detail {

void set_hdf5_opener(Hdf5Opener opener) { hdf5_opener().store(opener); }

std::string unread_format_reason(const std::string& path) {
  std::string lower = path;
  std::transform(lower.begin(), lower.end(), lower.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  const std::string per_point = kAsylumPerPoint;
  if (ends_with(lower, ".tnd"))
    return "a JPK thermal noise file (the lever's calibration spectrum), not force curves: its header's sensitivity "
           "and spring constant can be given to a curve that lacks them (--sensitivity [m/V], --spring-constant [N/m])";
  if (ends_with(lower, ".uff"))
    return "PyFMReader's UFF file, its copy of a vendor's curves (Entry_filename names the original): read the original";
  if ((ends_with(lower, ".h5") || ends_with(lower, ".hdf5")) && !hdf5_opener().load())
    return "HDF5 files are not read by this program: afmformats' HDF5 exports are read where libhdf5 is linked - "
           "the layerjkr CLI (layerjkr export FILE.h5 --out FILE.csv) - not here (the Python wheel does not carry "
           "libhdf5 and its 34 libraries); or write the curve with afmformats as .tab (export_data(path, "
           "fmt=\"tab\")), which is read; " + per_point;
  if (ends_with(lower, ".ardf")) return "Asylum Research ARDF force maps are not read yet: " + per_point;
  return "";
}

}  // namespace detail

std::string known_instrument_formats() {
  return ".jpk-force, .jpk-force-map, .jpk-qi-data, .jpk-qi-series (JPK), .ibw (Asylum / Igor), .spm or .000-.999 (Bruker NanoScope), .zip (AFM Workshop map: a CSV export per point), .h5 (afmformats' HDF5 export)";
}

CurveRange CurveRange::parse(const std::string& text, const std::string& what) {
  const std::size_t colon = text.find(':');
  auto bad = [&]() -> InputError {
    return InputError(what + " = '" + text + "': must be A:B, A: or :B with whole numbers 0 <= A <= B (curves A to B - 1)");
  };
  if (colon == std::string::npos || text.find(':', colon + 1) != std::string::npos) throw bad();
  CurveRange r;
  auto number = [&](std::string_view s, std::size_t& out) {
    if (s.empty()) return;
    const auto [stop, ec] = std::from_chars(s.data(), s.data() + s.size(), out);
    if (ec != std::errc() || stop != s.data() + s.size()) throw bad();
  };
  number(std::string_view(text).substr(0, colon), r.begin);
  number(std::string_view(text).substr(colon + 1), r.end);
  if (r.begin > r.end) throw bad();
  return r;
}

void CurveRange::require_any(std::size_t count, const std::string& path) const {
  if (begin < end_in(count)) return;
  throw InputError(path + ": the curve range " + std::to_string(begin) + ":" +
                   (end == CurveRange{}.end ? std::string() : std::to_string(end)) + " selects none of its " +
                   std::to_string(count) + " curves" +
                   (count ? " (positions 0 to " + std::to_string(count - 1) + ")" : std::string()));
}

struct InstrumentReader::Impl {
  std::unique_ptr<detail::CurveSource> source;
};

InstrumentReader::InstrumentReader(const std::string& path, const ReadLimits& limits)
    : impl_(std::make_unique<Impl>(Impl{open_source(path, limits)})) {}
InstrumentReader::~InstrumentReader() = default;
InstrumentReader::InstrumentReader(InstrumentReader&&) noexcept = default;
InstrumentReader& InstrumentReader::operator=(InstrumentReader&&) noexcept = default;

const InstrumentFile& InstrumentReader::header() const { return impl_->source->header(); }
std::size_t InstrumentReader::size() const { return impl_->source->size(); }

InstrumentCurve InstrumentReader::curve(std::size_t i, const CurveChannels& channels) const {
  return detail::checked_curve(*impl_->source, i, channels);
}

int InstrumentReader::curve_number(std::size_t i) const {
  if (i >= size())
    throw std::out_of_range("InstrumentReader::curve_number: position " + std::to_string(i) + " of a file of " +
                            std::to_string(size()) + " curves");
  return impl_->source->number(i);
}

namespace detail {

InstrumentCurve checked_curve(const CurveSource& source, std::size_t i, const CurveChannels& channels) {
  if (i >= source.size())
    throw std::out_of_range("InstrumentReader::curve: position " + std::to_string(i) + " of a file of " +
                            std::to_string(source.size()) + " curves");
  InstrumentCurve c = source.curve(i, channels);
  if (!channels.piezo_height)
    for (InstrumentSegment& s : c.segments) s.piezo_height.clear();  // the same answer from every format
  // NaN: the file gives none (to_curve_data then needs one given); anything else must be a stiffness.
  if (!std::isnan(c.spring_constant) && (!(c.spring_constant > 0.0) || !std::isfinite(c.spring_constant)))
    throw InputError(source.header().path + ": curve " + std::to_string(c.index) + " has spring constant " +
                     format_double(c.spring_constant) + " N/m; it must be finite and > 0");
  return c;
}

InstrumentFile read_all(const CurveSource& source, const CurveRange& range) {
  InstrumentFile file = source.header();
  for (std::size_t i = range.begin; i < range.end_in(source.size()); ++i) file.curves.push_back(checked_curve(source, i));
  return file;
}

namespace {

class ReadWhole final : public CurveSource {
 public:
  explicit ReadWhole(InstrumentFile file) : curves_(std::move(file.curves)), file_(std::move(file)) {
    file_.curves.clear();
  }
  const InstrumentFile& header() const override { return file_; }
  std::size_t size() const override { return curves_.size(); }
  InstrumentCurve curve(std::size_t i, const CurveChannels& /*read already*/) const override { return curves_.at(i); }

 private:
  std::vector<InstrumentCurve> curves_;
  InstrumentFile file_;
};

}  // namespace

std::unique_ptr<CurveSource> source_of(InstrumentFile file) { return std::make_unique<ReadWhole>(std::move(file)); }

std::unique_ptr<CurveSource> open_ibw(const std::string& path) { return source_of(read_ibw(path)); }

InstrumentFile read_jpk_bytes(std::string bytes, const std::string& path, InstrumentFormat format,
                              const ReadLimits& limits) {
  return read_all(*open_jpk_bytes(std::move(bytes), path, format, limits));
}

}  // namespace detail

InstrumentFile read_instrument_file(const std::string& path) {
  return read_instrument_file(path, ReadLimits::from_environment());
}

InstrumentFile read_instrument_file(const std::string& path, const ReadLimits& limits, const CurveRange& range) {
  return detail::read_all(*open_source(path, limits), range);
}

std::vector<double> InstrumentCurve::tip_position(std::size_t s) const {
  const InstrumentSegment& seg = segments.at(s);
  std::vector<double> out(seg.force.size());
  for (std::size_t i = 0; i < out.size(); ++i) out[i] = seg.height[i] + seg.force[i] / spring_constant;
  return out;
}

CurveData to_curve_data(const InstrumentCurve& curve, const std::string& source, double spring_constant,
                        double sensitivity) {
  detail::require_non_negative("to_curve_data", "spring_constant", spring_constant);
  detail::require_non_negative("to_curve_data", "sensitivity", sensitivity);
  // A file without a deflection sensitivity (NaN: a JPK calibration force-save) holds volts.
  const bool volts = std::isnan(curve.sensitivity);
  if (volts && !(sensitivity > 0.0))
    throw InputError(source + ": the file gives no deflection sensitivity (its deflection is in volts): give the "
                              "sensitivity [m/V] (--sensitivity, Python sensitivity=) and the spring constant");
  if (std::isnan(curve.spring_constant) && !(spring_constant > 0.0))
    throw InputError(source + ": the file gives no spring constant (its force conversion is not defined, or an Asylum "
                              "map export without its map image): give the cantilever's spring constant k [N/m] "
                              "(--spring-constant, Python spring_constant=)");
  const double k = spring_constant > 0.0 ? spring_constant : curve.spring_constant;
  // Without the file's k its force is the deflection [m]: force = k x deflection. A sensitivity
  // given turns volts into metres, or rescales the deflection the file's made (where it has one).
  const double deflection = volts ? sensitivity : sensitivity > 0.0 && curve.sensitivity > 0.0 ? sensitivity / curve.sensitivity : 1.0;
  const double scale = (std::isnan(curve.spring_constant) ? k : k / curve.spring_constant) * deflection;
  CurveData d;
  d.source = source;
  d.spring_constant = k;
  d.notes = curve.notes;
  // Time runs on through every segment, each sample at start + i duration / n (afmformats'
  // convention for JPK; the Igor wave's own row scaling; Bruker's ramp over its velocity).
  bool timed = !curve.segments.empty();
  for (const InstrumentSegment& seg : curve.segments)
    timed = timed && (seg.force.empty() || (seg.duration > 0.0 && std::isfinite(seg.duration)));
  double t0 = 0.0;
  bool retracting = false;
  for (const InstrumentSegment& seg : curve.segments) {
    retracting = retracting || seg.style == SegmentStyle::retract;
    // A pause before the retract is a dwell (2); one after it rests away from the surface, the
    // retract's own baseline (1).
    const int label = seg.style == SegmentStyle::extend ? (retracting ? 1 : 0)
                      : seg.style == SegmentStyle::retract || retracting ? 1
                                                                          : 2;
    const std::size_t n = seg.force.size();
    for (std::size_t i = 0; i < n; ++i) {
      const double force = seg.force[i] * scale;
      d.delta.push_back(-(seg.height[i] + force / k));
      d.P.push_back(force);
      d.segment.push_back(label);
      if (timed) d.t.push_back(t0 + seg.duration * static_cast<double>(i) / static_cast<double>(n));
    }
    t0 += seg.duration;
  }
  d.validate();
  return d;
}

}  // namespace layerjkr
