// One JPK segment: its header with the shared calibration it links to, and its channels,
// decoded and scaled (see jpk_segment.hpp).
#include "io/jpk_segment.hpp"

#include <limits>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <initializer_list>
#include <type_traits>
#include <vector>

#include "io/csv_rows.hpp"
#include "layerjkr/error.hpp"

namespace layerjkr::detail {

void Reader::fail(const std::string& where, const std::string& what) const {
  throw InputError(path_ + ": " + where + ": " + what);
}

Properties Reader::properties(const std::string& name) const {
  if (!zip_.contains(name)) fail(name, "missing from the archive");
  return parse_properties(zip_.read(name), path_ + ": " + name);
}

double Reader::to_number(std::string_view key, std::string_view text, const std::string& where) const {
  double v = 0.0;
  if (!parse_finite(text, v))
    fail(where, "'" + std::string(key) + "' = '" + std::string(text) + "' is not a finite number");
  return v;
}

long long Reader::whole(std::string_view key, std::string_view text, double lo, double hi,
                        const std::string& where) const {
  const double v = to_number(key, text, where);
  if (!(v >= lo && v <= hi && v == std::floor(v)))
    fail(where, "'" + std::string(key) + "' = '" + std::string(text) + "' is not a whole number in [" +
                    format_double(lo) + ", " + format_double(hi) + "]");
  return static_cast<long long>(v);
}

namespace {

// A lookup key assembled on the stack: a segment takes ~60 lookups, most keys are longer than
// std::string's small buffer, and the malloc per key showed in the profile with two threads.
class Key {
 public:
  Key(std::initializer_list<std::string_view> parts) {
    std::size_t n = 0;
    for (const std::string_view p : parts) n += p.size();
    if (n > sizeof buf_) heap_.resize(n);
    char* const start = n > sizeof buf_ ? heap_.data() : buf_;
    char* out = start;
    for (const std::string_view p : parts)
      if (!p.empty()) {
        std::memcpy(out, p.data(), p.size());
        out += p.size();
      }
    view_ = std::string_view(start, n);
  }
  Key(const Key&) = delete;
  Key& operator=(const Key&) = delete;
  operator std::string_view() const { return view_; }

 private:
  char buf_[160];
  std::string heap_;
  std::string_view view_;
};

// A segment header and the shared blocks it refers to: `<target>...*=<number>` (lcd-info per
// channel, segment-header-info) makes every shared `<block>.<number>.<rest>` read as
// `<target><rest>` unless the segment header gives that key itself. Looked up through the
// links rather than copied in: the copies were a quarter of the reading time.
class SegmentHeader {
 public:
  SegmentHeader(Properties own, const Properties& shared) : own_(std::move(own)), shared_(shared) {
    for (const auto& [key, number] : own_.with_prefix("channel."))
      if (ends_with(key, ".lcd-info.*"))
        links_.push_back({key.substr(0, key.size() - std::strlen("lcd-info.*")), "lcd-info.", number});
    if (const std::optional<std::string_view> number = own_.find("force-segment-header.force-segment-header-info.*"))
      links_.push_back({"force-segment-header.", "force-segment-header-info.", *number});
  }
  SegmentHeader(const SegmentHeader&) = delete;
  SegmentHeader& operator=(const SegmentHeader&) = delete;

  // The first link in key order that holds the key wins, as when they were copied in. The
  // trailing dot keeps lcd-info.1. from matching 10.
  std::optional<std::string_view> find(std::string_view key) const {
    if (const std::optional<std::string_view> v = own_.find(key)) return v;
    for (const Link& link : links_)
      if (starts_with(key, link.target))
        if (const std::optional<std::string_view> v = shared_.find(Key{link.block, link.number, ".", key.substr(link.target.size())}))
          return v;
    return std::nullopt;
  }
  bool contains(std::string_view key) const { return find(key).has_value(); }

 private:
  struct Link {
    std::string_view target, block, number;  // views into own_ (never modified) or literals
  };
  Properties own_;
  const Properties& shared_;
  std::vector<Link> links_;
};

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

struct Step {
  double multiplier, offset;
};

// Whole samples only: the caller checks that bytes.size() is a multiple of sizeof(T). The
// steps are applied one by one, not as one composed affine map, so that the values stay bit
// for bit those of applying them in turn; a loop per step vectorises, one per sample not.
template <class T>
std::vector<double> decode(const std::string& bytes, const std::vector<Step>& steps) {
  std::vector<double> out(bytes.size() / sizeof(T));
  const auto* p = reinterpret_cast<const unsigned char*>(bytes.data());
  for (std::size_t i = 0; i < out.size(); ++i) out[i] = static_cast<double>(big_endian<T>(p + i * sizeof(T)));
  for (const Step& s : steps)
    for (double& x : out) x = s.multiplier * x + s.offset;
  return out;
}

struct ChannelReader {
  const Reader& in;
  const SegmentHeader& seg;
  std::string dir;    // "…/segments/N/"
  std::string where;  // names the segment in errors
  std::optional<std::size_t> points;  // the samples the header announces, if it does

  bool has(std::string_view channel) const { return seg.contains(Key{"channel.", channel, ".data.file.name"}); }

  // The channel's samples in `slot`: raw samples, the encoder's scaling, then the conversion
  // chain from the base slot, all checked before any sample is decoded.
  std::vector<double> values(std::string_view channel, std::string_view slot) const {
    const Key c{"channel.", channel, "."};
    const std::string file = dir + std::string(in.value(seg, Key{c, "data.file.name"}, where));
    const std::string_view enc_part = seg.contains(Key{c, "data.encoder.type"}) ? "data.encoder." : "encoder.";
    std::string_view type;
    if (const std::optional<std::string_view> t = seg.find(Key{c, enc_part, "type"})) type = *t;
    else if (const std::optional<std::string_view> t2 = seg.find(Key{c, "type"})) type = *t2;
    else type = in.value(seg, Key{c, "data.type"}, where);
    struct Encoding {
      const char* name;
      std::size_t width;
      std::vector<double> (*decode)(const std::string&, const std::vector<Step>&);
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
    if (!e) in.fail(where, "channel " + std::string(channel) + " has the unknown data type '" + std::string(type) + "'");
    const std::size_t width = e->width;
    // The header's count bounds the entry before it is unpacked, not only after.
    const std::optional<std::uint64_t> declared = in.declared_size(file);
    if (points && declared && *declared != static_cast<std::uint64_t>(*points) * width)
      in.fail(file, "declares " + std::to_string(*declared) + " bytes; the segment header announces " +
                        std::to_string(*points) + " samples of " + std::to_string(width) + " bytes");
    const std::string bytes = in.read(file);
    if (bytes.empty() || bytes.size() % width != 0)
      in.fail(file, "holds " + std::to_string(bytes.size()) + " bytes, not a whole number of " + std::to_string(width) +
                        "-byte samples (" + std::string(type) + ")");
    if (points && bytes.size() / width != *points)
      in.fail(file, "holds " + std::to_string(bytes.size() / width) + " samples; the segment header announces " +
                        std::to_string(*points));
    std::vector<Step> steps;
    if (seg.contains(Key{c, enc_part, "scaling.multiplier"}))
      steps.push_back({in.number(seg, Key{c, enc_part, "scaling.multiplier"}, where),
                       in.number(seg, Key{c, enc_part, "scaling.offset"}, where)});
    chain(channel, slot, steps);
    return e->decode(bytes, steps);
  }

  // The chain from the base slot to `slot`, outermost last.
  void chain(std::string_view channel, std::string_view slot, std::vector<Step>& steps, int depth = 0) const {
    const Key set{"channel.", channel, ".conversion-set."};
    if (slot == in.value(seg, Key{set, "conversions.base"}, where)) return;
    if (depth > 16) in.fail(where, "channel " + std::string(channel) + ": the conversion chain does not end");
    const Key conv{set, "conversion.", slot, "."};
    chain(channel, in.value(seg, Key{conv, "base-calibration-slot"}, where), steps, depth + 1);
    steps.push_back({in.number(seg, Key{conv, "scaling.multiplier"}, where), in.number(seg, Key{conv, "scaling.offset"}, where)});
  }

  double multiplier(std::string_view channel, std::string_view slot) const {
    return in.number(seg, Key{"channel.", channel, ".conversion-set.conversion.", slot, ".scaling.multiplier"}, where);
  }
};

// A segment's style, spelled as the registry knows it; any other is an error, not a guess.
SegmentStyle read_style(const Reader& in, std::string_view text, const std::string& where) {
  if (const std::optional<SegmentStyle> style = from_string<SegmentStyle>(text)) return *style;
  in.fail(where, "segment style '" + std::string(text) + "' is unknown (known: " + known_names<SegmentStyle>() + ")");
}

}  // namespace

InstrumentSegment read_segment(const Reader& in, const Properties& shared, const std::string& dir,
                               InstrumentCurve& curve, const CurveChannels& channels) {
  const std::string where = dir + "segment-header.properties";
  const SegmentHeader seg(in.properties(where), shared);
  std::optional<std::size_t> points;
  if (const std::optional<std::string_view> n = seg.find("force-segment-header.num-points"))
    points = static_cast<std::size_t>(in.whole("force-segment-header.num-points", *n, 0, 1e15, where));
  const ChannelReader ch{in, seg, dir, where, points};
  InstrumentSegment s;
  s.style = read_style(in, in.value(seg, "force-segment-header.settings.style", where), where);
  s.duration = in.number(seg, "force-segment-header.duration", where);
  if (!ch.has("vDeflection")) in.fail(where, "no vDeflection channel (force)");
  // A file whose force conversion is not defined (the spring constant never calibrated, or
  // removed: afmformats' fmt-jpk-fd_single-modified_2023) holds the deflection [m]: read in the
  // distance slot, the spring constant NaN - to_curve_data then needs one given.
  // Without a distance conversion either (a calibration force-save) it holds volts: both NaN.
  const auto defined = [&](const char* slot) {
    const std::string conv = std::string("channel.vDeflection.conversion-set.conversion.") + slot + ".";
    const std::optional<std::string_view> flag = seg.find(conv + "defined");
    return seg.contains(conv + "base-calibration-slot") && !(flag && *flag == "false");
  };
  const bool has_force = defined("force"), has_distance = defined("distance");
  constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  s.force = ch.values("vDeflection", has_force ? "force" : has_distance ? "distance" : "volts");
  curve.spring_constant = has_force ? ch.multiplier("vDeflection", "force") : kNaN;
  curve.sensitivity = has_distance ? ch.multiplier("vDeflection", "distance") : kNaN;
  bool found = false;
  for (const char* name : {"strainGaugeHeight", "capacitiveSensorHeight", "measuredHeight"})
    if (!found && ch.has(name)) {
      s.height = ch.values(name, "nominal");
      found = true;
    }
  if (!found) in.fail(where, "no measured height channel (strainGaugeHeight, capacitiveSensorHeight or measuredHeight)");
  if (channels.piezo_height && ch.has("height")) s.piezo_height = ch.values("height", "calibrated");
  if (s.height.size() != s.force.size() || (!s.piezo_height.empty() && s.piezo_height.size() != s.force.size()))
    in.fail(where, "channels of different lengths (" + std::to_string(s.force.size()) + " force samples, " +
                       std::to_string(s.height.size()) + " heights)");
  return s;
}

}  // namespace layerjkr::detail
