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

#include "io/csv_rows.hpp"
#include "io/instrument_readers.hpp"
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

bool starts_with(const std::string& s, const std::string& prefix) { return s.compare(0, prefix.size(), prefix) == 0; }
bool ends_with(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

// The numbered sub-directories of `prefix` ("index/" -> 0, 1, 9, 10, ...), numerically sorted.
std::vector<int> numbered_dirs(const std::vector<std::string>& names, const std::string& prefix) {
  std::set<int> found;
  for (const std::string& n : names) {
    if (!starts_with(n, prefix)) continue;
    const std::size_t slash = n.find('/', prefix.size());
    if (slash == std::string::npos || slash == prefix.size()) continue;
    int v = 0;
    const char* b = n.data() + prefix.size();
    const auto [end, ec] = std::from_chars(b, n.data() + slash, v);
    if (ec == std::errc() && end == n.data() + slash) found.insert(v);
  }
  return {found.begin(), found.end()};
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

InstrumentFile read_archive(const ZipArchive& zip, const std::string& path, InstrumentFormat format) {
  const Reader in(path, zip);
  InstrumentFile file;
  file.path = path;
  file.format = format;
  const Properties top = in.properties("header.properties");
  const Properties shared = zip.contains("shared-data/header.properties") ? in.properties("shared-data/header.properties")
                                                                           : Properties{};
  if (const std::string* v = find_suffix(top, ".description.instrument")) file.instrument = *v;
  if (const std::string* v = find_suffix(top, ".description.source-software")) file.software = *v;
  if (find_suffix(top, ".position-pattern.grid.ilength")) {
    // A map's grid: every value present and finite, the shape at least one pixel, the
    // size positive, so that the pixel of a position is always defined.
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
  const std::vector<int> indices = numbered_dirs(zip.names(), "index/");
  std::vector<std::string> prefixes;
  if (indices.empty()) prefixes.emplace_back("");
  for (int i : indices) prefixes.push_back("index/" + std::to_string(i) + "/");
  for (std::size_t c = 0; c < prefixes.size(); ++c) {
    const std::string& p = prefixes[c];
    InstrumentCurve curve;
    curve.index = indices.empty() ? 0 : indices[c];
    const Properties header = p.empty() ? top : in.properties(p + "header.properties");
    if (file.instrument.empty())
      if (const std::string* v = find_suffix(header, ".description.instrument")) file.instrument = *v;
    if (file.software.empty())
      if (const std::string* v = find_suffix(header, ".description.source-software")) file.software = *v;
    const std::string where = p + "header.properties";
    curve.position_index = suffix_int(in, header, ".header.position-index", -1, -1, 1e9, where);
    curve.x = suffix_number(in, header, ".header.position.x", curve.x, where);
    curve.y = suffix_number(in, header, ".header.position.y", curve.y, where);
    if (file.grid_shape_x > 0 && std::isfinite(curve.x) && std::isfinite(curve.y)) {
      auto pixel = [](double v, double center, double size, int shape) {
        const double i = std::floor((v - (center - 0.5 * size)) / size * shape);
        return std::isnan(i) ? 0 : static_cast<int>(std::clamp(i, 0.0, static_cast<double>(shape - 1)));
      };
      curve.grid_x = pixel(curve.x, file.grid_center_x, file.grid_size_x, file.grid_shape_x);
      curve.grid_y = pixel(curve.y, file.grid_center_y, file.grid_size_y, file.grid_shape_y);
    }
    const std::vector<int> segments = numbered_dirs(zip.names(), p + "segments/");
    if (segments.empty()) in.fail(p.empty() ? "the archive" : p, "holds no segments");
    for (int s : segments)
      curve.segments.push_back(read_segment(in, shared, p + "segments/" + std::to_string(s) + "/", curve));
    file.curves.push_back(std::move(curve));
  }
  return file;
}

}  // namespace

InstrumentFile read_jpk(const std::string& path, InstrumentFormat format, const ReadLimits& limits) {
  const ZipArchive zip(path, limits);
  return read_archive(zip, path, format);
}

InstrumentFile read_jpk_bytes(std::string bytes, const std::string& path, InstrumentFormat format,
                              const ReadLimits& limits) {
  const ZipArchive zip(std::move(bytes), path, limits);
  return read_archive(zip, path, format);
}

}  // namespace layerjkr::detail
