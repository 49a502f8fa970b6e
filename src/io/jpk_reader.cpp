// JPK force archives (.jpk-force, .jpk-force-map, .jpk-qi-data): see instrument.hpp for the
// conventions and ../shared/data/instrument/README.md for the format notes they follow.
#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <map>
#include <optional>
#include <set>
#include <string_view>

#include "io/csv_rows.hpp"
#include "io/curve_source.hpp"
#include "io/java_properties.hpp"
#include "io/zip_archive.hpp"
#include "layerjkr/error.hpp"

namespace layerjkr::detail {
namespace {

class Reader {
 public:
  Reader(std::string path, const ZipArchive& zip) : path_(std::move(path)), zip_(zip) {}

  [[noreturn]] void fail(const std::string& where, const std::string& what) const {
    throw InputError(path_ + ": " + where + ": " + what);
  }

  Properties properties(const std::string& name) const {
    if (!zip_.contains(name)) fail(name, "missing from the archive");
    return parse_properties(zip_.read(name), path_ + ": " + name);
  }

  const std::string& value(const Properties& p, const std::string& key, const std::string& where) const {
    const auto it = p.find(key);
    if (it == p.end()) fail(where, "no '" + key + "'");
    return it->second;
  }

  // The whole value must be one finite number: "1,5", "1e-3e5", "NaN" and "Infinity" are
  // errors, not 1, 0.001 or a NaN passed on.
  double number(const Properties& p, const std::string& key, const std::string& where) const {
    return to_number(key, value(p, key, where), where);
  }
  double to_number(const std::string& key, const std::string& text, const std::string& where) const {
    double v = 0.0;
    if (!parse_finite(text, v)) fail(where, "'" + key + "' = '" + text + "' is not a finite number");
    return v;
  }
  // A whole number in [lo, hi], so that the cast to an integer type is defined.
  long long whole(const std::string& key, const std::string& text, double lo, double hi,
                  const std::string& where) const {
    const double v = to_number(key, text, where);
    if (!(v >= lo && v <= hi && v == std::floor(v)))
      fail(where, "'" + key + "' = '" + text + "' is not a whole number in [" + format_double(lo) + ", " +
                      format_double(hi) + "]");
    return static_cast<long long>(v);
  }

  std::string read(const std::string& name) const { return zip_.read(name); }
  std::optional<std::uint64_t> declared_size(const std::string& name) const { return zip_.declared_size(name); }

 private:
  std::string path_;
  const ZipArchive& zip_;
};

bool starts_with(std::string_view s, std::string_view prefix) { return s.substr(0, prefix.size()) == prefix; }
bool ends_with(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

// The number that starts `s` and ends at the next '/' ("12/segments/..." -> 12, rest
// "segments/..."), or none.
std::optional<int> leading_number(std::string_view& s) {
  const std::size_t slash = s.find('/');
  if (slash == std::string_view::npos || slash == 0) return std::nullopt;
  int v = 0;
  const auto [end, ec] = std::from_chars(s.data(), s.data() + slash, v);
  if (ec != std::errc() || end != s.data() + slash || v < 0) return std::nullopt;
  s.remove_prefix(slash + 1);
  return v;
}

// Where each curve lives: "index/N/" (maps) or "" (a single curve) and its segment numbers,
// both numerically sorted, from one pass over the archive's names.
struct CurveLocation {
  int number = 0;
  std::string prefix;
  std::vector<int> segments;
};

std::vector<CurveLocation> locate_curves(const ZipArchive& zip) {
  std::map<int, std::set<int>> maps;
  std::set<int> single;
  for (std::size_t i = 0; i < zip.size(); ++i) {
    std::string_view n = zip.name(i);
    std::set<int>* segments = &single;
    if (starts_with(n, "index/")) {
      n.remove_prefix(6);
      const std::optional<int> curve = leading_number(n);
      if (!curve) continue;
      segments = &maps[*curve];
    }
    if (!starts_with(n, "segments/")) continue;
    n.remove_prefix(9);
    if (const std::optional<int> s = leading_number(n)) segments->insert(*s);
  }
  std::vector<CurveLocation> out;
  if (maps.empty()) out.push_back({0, "", {single.begin(), single.end()}});
  for (const auto& [number, segments] : maps)
    out.push_back({number, "index/" + std::to_string(number) + "/", {segments.begin(), segments.end()}});
  return out;
}

// Copies every shared `<block>.<number>.<rest>` to `<target><rest>` for the header's
// `<target>...*=<number>` references (lcd-info per channel, segment-header-info), keeping
// what the segment header says itself. The trailing dot keeps lcd-info.1. from matching 10.
void resolve_shared(Properties& seg, const Properties& shared) {
  std::vector<std::pair<std::string, std::string>> links;  // (target prefix, shared prefix)
  for (const auto& [key, number] : seg) {
    if (starts_with(key, "channel.") && ends_with(key, ".lcd-info.*"))
      links.emplace_back(key.substr(0, key.size() - std::strlen("lcd-info.*")), "lcd-info." + number + ".");
    if (key == "force-segment-header.force-segment-header-info.*")
      links.emplace_back("force-segment-header.", "force-segment-header-info." + number + ".");
  }
  for (const auto& [target, prefix] : links)
    for (auto it = shared.lower_bound(prefix); it != shared.end() && starts_with(it->first, prefix); ++it)
      seg.emplace(target + it->first.substr(prefix.size()), it->second);
}

template <class T>
T big_endian(const unsigned char* p) {
  std::uint64_t v = 0;
  for (std::size_t i = 0; i < sizeof(T); ++i) v = (v << 8) | p[i];
  if constexpr (std::is_floating_point_v<T>) {
    using U = std::conditional_t<sizeof(T) == 4, std::uint32_t, std::uint64_t>;
    const U bits = static_cast<U>(v);
    T out;
    std::memcpy(&out, &bits, sizeof out);
    return out;
  } else {
    using U = std::make_unsigned_t<T>;
    return static_cast<T>(static_cast<U>(v));
  }
}

// Whole samples only: the caller checks that bytes.size() is a multiple of sizeof(T).
template <class T>
std::vector<double> decode(const std::string& bytes) {
  std::vector<double> out(bytes.size() / sizeof(T));
  const auto* p = reinterpret_cast<const unsigned char*>(bytes.data());
  for (std::size_t i = 0; i < out.size(); ++i) out[i] = static_cast<double>(big_endian<T>(p + i * sizeof(T)));
  return out;
}

struct ChannelReader {
  const Reader& in;
  const Properties& seg;
  std::string dir;    // "…/segments/N/"
  std::string where;  // names the segment in errors
  std::optional<std::size_t> points;  // the samples the header announces, if it does

  bool has(const std::string& channel) const { return seg.count("channel." + channel + ".data.file.name") > 0; }

  // Raw samples after the encoder (the base slot's values).
  std::vector<double> base_values(const std::string& channel) const {
    const std::string c = "channel." + channel + ".";
    const std::string file = dir + in.value(seg, c + "data.file.name", where);
    const std::string enc = seg.count(c + "data.encoder.type") ? c + "data.encoder." : c + "encoder.";
    std::string type;
    if (seg.count(enc + "type")) type = seg.at(enc + "type");
    else if (seg.count(c + "type")) type = seg.at(c + "type");
    else type = in.value(seg, c + "data.type", where);
    struct Encoding {
      const char* name;
      std::size_t width;
      std::vector<double> (*decode)(const std::string&);
    };
    static const Encoding encodings[] = {
        {"signedshort", 2, decode<std::int16_t>},    {"unsignedshort", 2, decode<std::uint16_t>},
        {"signedinteger", 4, decode<std::int32_t>},  {"unsignedinteger", 4, decode<std::uint32_t>},
        {"signedlong", 8, decode<std::int64_t>},     {"float-data", 4, decode<float>},
        {"float", 4, decode<float>},                 {"double-data", 8, decode<double>},
        {"double", 8, decode<double>}};
    const Encoding* e = nullptr;
    for (const Encoding& candidate : encodings)
      if (type == candidate.name) e = &candidate;
    if (!e) in.fail(where, "channel " + channel + " has the unknown data type '" + type + "'");
    const std::size_t width = e->width;
    // The header's count bounds the entry before it is unpacked, not only after.
    const std::optional<std::uint64_t> declared = in.declared_size(file);
    if (points && declared && *declared != static_cast<std::uint64_t>(*points) * width)
      in.fail(file, "declares " + std::to_string(*declared) + " bytes; the segment header announces " +
                        std::to_string(*points) + " samples of " + std::to_string(width) + " bytes");
    const std::string bytes = in.read(file);
    if (bytes.empty() || bytes.size() % width != 0)
      in.fail(file, "holds " + std::to_string(bytes.size()) + " bytes, not a whole number of " + std::to_string(width) +
                        "-byte samples (" + type + ")");
    if (points && bytes.size() / width != *points)
      in.fail(file, "holds " + std::to_string(bytes.size() / width) + " samples; the segment header announces " +
                        std::to_string(*points));
    std::vector<double> v = e->decode(bytes);
    if (seg.count(enc + "scaling.multiplier")) {
      const double m = in.number(seg, enc + "scaling.multiplier", where), o = in.number(seg, enc + "scaling.offset", where);
      for (double& x : v) x = x * m + o;
    }
    return v;
  }

  // The chain from the base slot to `slot`, outermost last: (multiplier, offset) pairs.
  void chain(const std::string& channel, const std::string& slot, std::vector<std::pair<double, double>>& steps,
             int depth = 0) const {
    const std::string set = "channel." + channel + ".conversion-set.";
    if (slot == in.value(seg, set + "conversions.base", where)) return;
    if (depth > 16) in.fail(where, "channel " + channel + ": the conversion chain does not end");
    const std::string conv = set + "conversion." + slot + ".";
    chain(channel, in.value(seg, conv + "base-calibration-slot", where), steps, depth + 1);
    steps.emplace_back(in.number(seg, conv + "scaling.multiplier", where), in.number(seg, conv + "scaling.offset", where));
  }

  std::vector<double> values(const std::string& channel, const std::string& slot) const {
    std::vector<double> v = base_values(channel);
    std::vector<std::pair<double, double>> steps;
    chain(channel, slot, steps);
    for (const auto& [m, o] : steps)
      for (double& x : v) x = m * x + o;
    return v;
  }

  double multiplier(const std::string& channel, const std::string& slot) const {
    return in.number(seg, "channel." + channel + ".conversion-set.conversion." + slot + ".scaling.multiplier", where);
  }
};

// The first value whose key ends in `suffix` (headers prefix keys by the scan type).
const std::string* find_suffix(const Properties& p, const std::string& suffix) {
  for (const auto& [k, v] : p)
    if (ends_with(k, suffix)) return &v;
  return nullptr;
}

// The value of the first key ending in `suffix` as a finite number, or `fallback` if no key does.
double suffix_number(const Reader& in, const Properties& p, const std::string& suffix, double fallback,
                     const std::string& where) {
  const std::string* v = find_suffix(p, suffix);
  return v ? in.to_number(suffix.substr(1), *v, where) : fallback;
}

// The same as a whole number in [lo, hi] (a float-to-int conversion out of range is undefined).
int suffix_int(const Reader& in, const Properties& p, const std::string& suffix, int fallback, double lo, double hi,
               const std::string& where) {
  const std::string* v = find_suffix(p, suffix);
  return v ? static_cast<int>(in.whole(suffix.substr(1), *v, lo, hi, where)) : fallback;
}

// A segment's style, spelled as the registry knows it; any other is an error, not a guess.
SegmentStyle read_style(const Reader& in, const std::string& text, const std::string& where) {
  if (const std::optional<SegmentStyle> style = from_string<SegmentStyle>(text)) return *style;
  in.fail(where, "segment style '" + text + "' is unknown (known: " + known_names<SegmentStyle>() + ")");
}

InstrumentSegment read_segment(const Reader& in, const Properties& shared, const std::string& dir,
                               InstrumentCurve& curve) {
  const std::string where = dir + "segment-header.properties";
  Properties seg = in.properties(where);
  resolve_shared(seg, shared);
  std::optional<std::size_t> points;
  if (seg.count("force-segment-header.num-points"))
    points = static_cast<std::size_t>(
        in.whole("force-segment-header.num-points", seg.at("force-segment-header.num-points"), 0, 1e15, where));
  const ChannelReader ch{in, seg, dir, where, points};
  InstrumentSegment s;
  s.style = read_style(in, in.value(seg, "force-segment-header.settings.style", where), where);
  s.duration = in.number(seg, "force-segment-header.duration", where);
  if (!ch.has("vDeflection")) in.fail(where, "no vDeflection channel (force)");
  s.force = ch.values("vDeflection", "force");
  curve.spring_constant = ch.multiplier("vDeflection", "force");
  curve.sensitivity = ch.multiplier("vDeflection", "distance");
  bool found = false;
  for (const char* name : {"strainGaugeHeight", "capacitiveSensorHeight", "measuredHeight"})
    if (!found && ch.has(name)) {
      s.height = ch.values(name, "nominal");
      found = true;
    }
  if (!found) in.fail(where, "no measured height channel (strainGaugeHeight, capacitiveSensorHeight or measuredHeight)");
  if (ch.has("height")) s.piezo_height = ch.values("height", "calibrated");
  if (s.height.size() != s.force.size() || (!s.piezo_height.empty() && s.piezo_height.size() != s.force.size()))
    in.fail(where, "channels of different lengths (" + std::to_string(s.force.size()) + " force samples, " +
                       std::to_string(s.height.size()) + " heights)");
  return s;
}

// The map grid of the top header: every value present and finite, the shape at least one
// pixel, the size positive, so that the pixel of a position is always defined.
void read_grid(const Reader& in, const Properties& top, InstrumentFile& file) {
  if (!find_suffix(top, ".position-pattern.grid.ilength")) return;
  const std::string where = "header.properties";
  auto need = [&](const std::string& suffix) -> const std::string& {
    const std::string* v = find_suffix(top, suffix);
    if (!v) in.fail(where, "the map grid has no '*" + suffix + "'");
    return *v;
  };
  auto shape = [&](const std::string& suffix) {
    return static_cast<int>(in.whole(suffix.substr(1), need(suffix), 1, 1e6, where));
  };
  auto size = [&](const std::string& suffix) {
    const double v = in.to_number(suffix.substr(1), need(suffix), where);
    if (!(v > 0.0)) in.fail(where, "'" + suffix.substr(1) + "' = '" + need(suffix) + "' must be > 0 (m)");
    return v;
  };
  file.grid_shape_x = shape(".position-pattern.grid.ilength");
  file.grid_shape_y = shape(".position-pattern.grid.jlength");
  file.grid_size_x = size(".position-pattern.grid.ulength");
  file.grid_size_y = size(".position-pattern.grid.vlength");
  file.grid_center_x = in.to_number("xcenter", need(".position-pattern.grid.xcenter"), where);
  file.grid_center_y = in.to_number("ycenter", need(".position-pattern.grid.ycenter"), where);
}

void describe(const Properties& header, InstrumentFile& file) {
  if (file.instrument.empty())
    if (const std::string* v = find_suffix(header, ".description.instrument")) file.instrument = *v;
  if (file.software.empty())
    if (const std::string* v = find_suffix(header, ".description.source-software")) file.software = *v;
}

// Opening reads the top and shared headers and locates the curves; curve(i) reads curve i's
// header, segment headers and channels, nothing else.
class JpkSource final : public CurveSource {
 public:
  JpkSource(std::unique_ptr<ZipArchive> zip, const std::string& path, InstrumentFormat format)
      : zip_(std::move(zip)), in_(path, *zip_) {
    file_.path = path;
    file_.format = format;
    top_ = in_.properties("header.properties");
    if (zip_->contains("shared-data/header.properties")) shared_ = in_.properties("shared-data/header.properties");
    describe(top_, file_);
    read_grid(in_, top_, file_);
    curves_ = locate_curves(*zip_);
    // Maps name the instrument in each curve's header: the first one's completes the metadata.
    if ((file_.instrument.empty() || file_.software.empty()) && !curves_.front().prefix.empty())
      describe(in_.properties(curves_.front().prefix + "header.properties"), file_);
  }

  const InstrumentFile& header() const override { return file_; }
  std::size_t size() const override { return curves_.size(); }
  int number(std::size_t i) const override { return curves_.at(i).number; }

  InstrumentCurve curve(std::size_t i) const override {
    const CurveLocation& at = curves_.at(i);
    const std::string& p = at.prefix;
    InstrumentCurve curve;
    curve.index = at.number;
    const Properties own = p.empty() ? Properties{} : in_.properties(p + "header.properties");
    const Properties& header = p.empty() ? top_ : own;
    const std::string where = p + "header.properties";
    curve.position_index = suffix_int(in_, header, ".header.position-index", -1, -1, 1e9, where);
    curve.x = suffix_number(in_, header, ".header.position.x", curve.x, where);
    curve.y = suffix_number(in_, header, ".header.position.y", curve.y, where);
    if (file_.grid_shape_x > 0 && std::isfinite(curve.x) && std::isfinite(curve.y)) {
      auto pixel = [](double v, double center, double size, int shape) {
        const double k = std::floor((v - (center - 0.5 * size)) / size * shape);
        return std::isnan(k) ? 0 : static_cast<int>(std::clamp(k, 0.0, static_cast<double>(shape - 1)));
      };
      curve.grid_x = pixel(curve.x, file_.grid_center_x, file_.grid_size_x, file_.grid_shape_x);
      curve.grid_y = pixel(curve.y, file_.grid_center_y, file_.grid_size_y, file_.grid_shape_y);
    }
    if (at.segments.empty()) in_.fail(p.empty() ? "the archive" : p, "holds no segments");
    for (int s : at.segments)
      curve.segments.push_back(read_segment(in_, shared_, p + "segments/" + std::to_string(s) + "/", curve));
    return curve;
  }

 private:
  std::unique_ptr<ZipArchive> zip_;
  Reader in_;
  InstrumentFile file_;
  Properties top_, shared_;
  std::vector<CurveLocation> curves_;
};

}  // namespace

std::unique_ptr<CurveSource> open_jpk(const std::string& path, InstrumentFormat format, const ReadLimits& limits) {
  return std::make_unique<JpkSource>(std::make_unique<ZipArchive>(path, limits), path, format);
}

std::unique_ptr<CurveSource> open_jpk_bytes(std::string bytes, const std::string& path, InstrumentFormat format,
                                            const ReadLimits& limits) {
  return std::make_unique<JpkSource>(std::make_unique<ZipArchive>(std::move(bytes), path, limits), path, format);
}

}  // namespace layerjkr::detail
