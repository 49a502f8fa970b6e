// Bruker NanoScope force files (single ramps and force volumes) as a CurveSource: opening
// parses and checks the text header only; curve(i) then reads curve i's bytes alone (pread).
// Conventions and their evidence: docs/instrument-files.md (NanoScope) and
// ../shared/data/instrument/bruker/FORMAT_NOTES.md.
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <cstdint>
#include <optional>

#include "io/csv_rows.hpp"
#include "io/curve_source.hpp"
#include "io/nanoscope_header.hpp"
#include "io/positioned_file.hpp"
#include "io/read_file.hpp"
#include "layerjkr/error.hpp"

namespace layerjkr::detail {
namespace {

constexpr std::int64_t kMaxSamples = 10'000'000;  // per segment: 100 s at 100 kHz
constexpr std::int64_t kMaxGrid = 4096;  // per side of a force volume (16.7 M curves: an int)
constexpr std::int64_t kMaxOffset = std::int64_t{1} << 50;

// Exactly n bytes at `offset` of the file (the caller checked offset + n <= size()); `what`
// names them in the error.
std::string read_bytes(const PositionedFile& in, const std::string& path, std::uint64_t offset, std::size_t n,
                       const std::string& what) {
  std::string out(n, '\0');
  if (!in.read(offset, n, out.data()))
    throw InputError(path + ": " + what + ": cannot read " + std::to_string(n) + " bytes at offset " +
                     std::to_string(offset) + " (the file ends or changed since it was opened)");
  return out;
}

// The text up to `\*File list end`, read in 64 KiB steps so that only the header is read.
std::string read_header_text(const PositionedFile& in, const std::string& path) {
  constexpr std::size_t step = std::size_t{1} << 16;
  std::string text;
  for (;;) {
    const std::size_t from = text.size() >= kNanoscopeHeaderEnd.size() ? text.size() - kNanoscopeHeaderEnd.size() : 0;
    const std::uint64_t left = in.size() - text.size();
    if (left == 0 || text.size() >= kMaxNanoscopeHeader) break;
    text += read_bytes(in, path, text.size(), static_cast<std::size_t>(std::min<std::uint64_t>(step, left)), "the header");
    if (text.size() == std::min<std::uint64_t>(in.size(), step)) {  // the first chunk: what file is this?
      if (text.compare(0, 11, "\\*File list") == 0)
        throw InputError(path + ": NanoScope image file, not force curves; unsupported (its first line is \\*File list)");
      if (text.compare(0, 17, "\\*Force file list") != 0)
        throw InputError(path + ": not a NanoScope force file: it does not start with \\*Force file list");
    }
    const std::size_t end = text.find(kNanoscopeHeaderEnd, from);
    if (end != std::string::npos) return text.substr(0, end + kNanoscopeHeaderEnd.size());
  }
  throw InputError(path + ": the header has no \\*File list end in " +
                   (text.size() >= kMaxNanoscopeHeader ? "its first " + describe_bytes(kMaxNanoscopeHeader)
                                                       : "the file's " + std::to_string(in.size()) + " bytes") +
                   " (truncated or not a NanoScope file)");
}

// One stored force channel (`\*Ciao force image list`): where its curves are and how an LSB
// becomes metres.
struct Channel {
  std::string name;
  std::uint64_t offset = 0;
  std::size_t n1 = 0, n2 = 0, bytes = 0;
  double metres_per_lsb = 0.0;
  bool shifted = false;  // v9.2 force volume: 4-byte samples hold counts * 256
};

// A metres factor for a length unit of the header ("nm", "~m" = um in its latin-1 rendering).
std::optional<double> unit_metres(const std::string& unit) {
  if (unit == "nm") return 1e-9;
  if (unit == "~m" || unit == "um" || unit == "\xB5m" || unit == "\xC2\xB5m") return 1e-6;
  if (unit == "pm") return 1e-12;
  if (unit == "mm") return 1e-3;
  return std::nullopt;
}

class NanoscopeSource final : public CurveSource {
 public:
  NanoscopeSource(std::unique_ptr<PositionedFile> in, const std::string& path, const ReadLimits& limits)
      : in_(std::move(in)), header_text_(read_header_text(*in_, path)), h_(header_text_, path) {
    file_.path = path;
    file_.format = InstrumentFormat::nanoscope;
    const NanoscopeSection& top = h_.need_section("Force file list");
    file_.software = h_.text(top, "Version");
    if (const NanoscopeSection* eq = h_.section("Equipment list")) {
      const std::string* m = eq->find("Microscope");
      if (!m || m->empty()) m = eq->find("Description");
      if (m) file_.instrument = *m;
    }
    const NanoscopeSection& scan = h_.need_section("Ciao scan list");
    const std::string& mode = h_.text(scan, "Operating mode");
    if (mode != "Force" && mode != "Force Volume")
      h_.fail(scan, "\\Operating mode = '" + mode + "': expected Force or Force Volume (force curves)");
    volume_ = mode == "Force Volume";
    if (volume_) read_grid(scan);
    curves_ = volume_ ? static_cast<std::size_t>(file_.grid_shape_x) * static_cast<std::size_t>(file_.grid_shape_y) : 1;

    const NanoscopeSection* defl_section = nullptr;
    const NanoscopeSection* sensor_section = nullptr;
    for (const NanoscopeSection& s : h_.sections()) {
      if (s.name != "Ciao force image list") continue;
      const NanoscopeParameter id = s.find("@4:Image Data") ? h_.parameter(s, "@4:Image Data") : NanoscopeParameter{};
      if (!defl_section && id.quoted.find("Deflection") != std::string::npos) defl_section = &s;
      if (!sensor_section && (id.quoted == "Height Sensor" || id.soft_scale == "ZSensor")) sensor_section = &s;
    }
    if (!defl_section)
      throw InputError(path + ": the header has no \\*Ciao force image list of a deflection channel "
                              "(\\@4:Image Data naming \"Deflection ...\")");
    defl_ = channel(*defl_section);
    if (sensor_section) {
      sensor_ = channel(*sensor_section);
      if (sensor_->n1 != defl_.n1 || sensor_->n2 != defl_.n2)
        h_.fail(*sensor_section, "\\Samps/line = '" + h_.text(*sensor_section, "Samps/line") +
                                     "': expected the deflection channel's " + std::to_string(defl_.n1) + " " +
                                     std::to_string(defl_.n2));
    }
    const std::uint64_t curve_bytes = (defl_.n1 + defl_.n2) * defl_.bytes;
    if (curve_bytes > limits.max_member_bytes)
      h_.fail(*defl_section, "a curve of " + std::to_string(curve_bytes) + " bytes exceeds the limit of " +
                                 describe_bytes(limits.max_member_bytes) + "; raise it with LAYERJKR_MAX_MEMBER_MB");

    spring_constant_ = h_.number(*defl_section, "Spring Constant");
    if (!(spring_constant_ > 0.0))
      h_.fail(*defl_section, "\\Spring Constant = '" + h_.text(*defl_section, "Spring Constant") +
                                 "': expected a spring constant > 0 N/m");
    const NanoscopeParameter z = h_.parameter(*defl_section, "@4:Z scale");
    sensitivity_ = h_.sensitivity(z.soft_scale, "\\@4:Z scale of " + defl_.name) * 1e-9;

    // The commanded ramp: its length is needed for the height unless a Z sensor is stored;
    // the durations are derived when the velocities are given (V/s, like the ramp size in V).
    // Fields are read where needed: a ramp that is missing or empty ('') costs the durations
    // (0, unknown) and, without a Z sensor, the height of each curve - never the file.
    const NanoscopeSection* force = h_.section("Ciao force list");
    // A surface hold (dwell) stored with each curve: AtomicJ reads its samples after the retract
    // block, but no public file has one, so where they lie is unverified - refused, not misread.
    if (force)
      if (const std::string* hold = force->find_any_case("Hold Samples")) {
        char* end = nullptr;
        const double n = std::strtod(hold->c_str(), &end);
        if (end != hold->c_str() && n > 0.0)
          h_.fail(*force, "\\Hold Samples = " + *hold + ": each curve stores a surface hold (a dwell), whose place "
                          "among the curve's samples no public file lets us check (AtomicJ reads it after the retract); "
                          "it is not read rather than read wrong - a file with a hold would let it be checked");
      }
    const NanoscopeParameter ramp = ramp_parameter(*defl_section, force);
    if (!sensor_) {
      if (ramp.hard_value)
        ramp_m_ = *ramp.hard_value * h_.sensitivity(ramp.soft_scale, "\\@4:Ramp Size") * 1e-9;
      else
        ramp_error_ = path + ": \\*Ciao force image list: \\@4:Ramp Size = '" +
                      (defl_section->find_any_case("@4:Ramp Size") ? *defl_section->find_any_case("@4:Ramp Size") : std::string()) +
                      "': expected a ramp size > 0 V (or, where it is empty, a \\@4:Ramp Size Zsweep in \\*Ciao force "
                      "list): the height axis needs it, as no Z sensor is stored";
    }
    if (force && ramp.hard_value) {
      duration_extend_ = duration(*force, "Forward vel.", *ramp.hard_value);
      duration_retract_ = duration(*force, "Reverse vel.", *ramp.hard_value);
    }
  }

  const InstrumentFile& header() const override { return file_; }
  std::size_t size() const override { return curves_; }

  InstrumentCurve curve(std::size_t i, const CurveChannels& /*channels: a by-product of the height here*/) const override {
    if (i >= curves_) throw std::out_of_range("nanoscope curve " + std::to_string(i) + " of " + std::to_string(curves_));
    if (!ramp_error_.empty()) throw InputError(ramp_error_);
    InstrumentCurve c;
    c.notes = notes_;
    c.index = static_cast<int>(i);
    c.spring_constant = spring_constant_;
    c.sensitivity = sensitivity_;
    if (volume_) {
      const auto nx = static_cast<std::size_t>(file_.grid_shape_x);
      c.position_index = c.index;
      c.grid_x = static_cast<int>(i % nx);
      c.grid_y = static_cast<int>(i / nx);
      c.x = file_.grid_center_x + (c.grid_x + 0.5 - file_.grid_shape_x / 2.0) * file_.grid_size_x / file_.grid_shape_x;
      c.y = file_.grid_center_y + (c.grid_y + 0.5 - file_.grid_shape_y / 2.0) * file_.grid_size_y / file_.grid_shape_y;
    }
    const std::vector<double> defl = samples(defl_, i);
    const std::vector<double> z = sensor_ ? samples(*sensor_, i) : std::vector<double>{};
    // Both blocks are stored from Z fully extended to Z retracted: a stored sensor rises
    // along them in our height (larger = farther), whatever its sign in the file.
    const std::size_t n1 = defl_.n1, n2 = defl_.n2;
    const double sign = z.empty() || (z[n1 - 1] - z[0]) + (z[n1 + n2 - 1] - z[n1]) >= 0.0 ? 1.0 : -1.0;
    for (int s = 0; s < 2; ++s) {
      InstrumentSegment seg;
      seg.style = s == 0 ? SegmentStyle::extend : SegmentStyle::retract;
      const std::size_t n = s == 0 ? n1 : n2;
      seg.duration = s == 0 ? duration_extend_ : duration_retract_;
      const double step = ramp_m_ / static_cast<double>(n);
      for (std::size_t t = 0; t < n; ++t) {
        // Time order: the approach block is stored newest first, the retract block in order.
        const std::size_t k = s == 0 ? n1 - 1 - t : n1 + t;
        seg.force.push_back(defl[k] * spring_constant_);
        const double ramp_height = static_cast<double>(s == 0 ? n - 1 - t : t) * step;
        seg.height.push_back(z.empty() ? ramp_height : sign * z[k]);
      }
      c.segments.push_back(std::move(seg));
    }
    return c;
  }

 private:
  void read_grid(const NanoscopeSection& scan) {
    file_.grid_shape_x = static_cast<int>(h_.whole(scan, "Samps/line", 1, kMaxGrid));
    file_.grid_shape_y = static_cast<int>(h_.whole(scan, "Lines", 1, kMaxGrid));
    std::string unit;
    const double size = h_.number(scan, "Scan Size", &unit);
    const std::optional<double> m = unit_metres(unit);
    if (!m || !(size > 0.0))
      h_.fail(scan, "\\Scan Size = '" + h_.text(scan, "Scan Size") + "': expected a length > 0 in nm, ~m, um or pm");
    // One size is given: square pixels (Bruker's Lines shorten the slow axis).
    file_.grid_size_x = size * *m;
    file_.grid_size_y = file_.grid_size_x * file_.grid_shape_y / file_.grid_shape_x;
    file_.grid_center_x = offset(scan, "X Offset");
    file_.grid_center_y = offset(scan, "Y Offset");
  }
  double offset(const NanoscopeSection& scan, const char* key) const {
    if (!scan.find(key)) return 0.0;
    std::string unit;
    const double v = h_.number(scan, key, &unit);
    const std::optional<double> m = unit_metres(unit);
    if (!m && v != 0.0) h_.fail(scan, "\\" + std::string(key) + " = '" + h_.text(scan, key) + "': expected a length in nm or um");
    return m ? v * *m : 0.0;
  }
  // The force image list's `@4:Ramp Size` (8.15 spells it `Ramp size`), else the force list's
  // `@4:Ramp Size Zsweep`, which holds the same value in every file seen (16.72241, 151.4807,
  // 227.2211 V) and is used, with a note, where the first holds no number (missing, or a force
  // volume's `\@4:Ramp Size: ''`); nothing (no hard value) if neither is a number > 0. A number
  // that is not > 0 is not replaced: it is wrong, not missing.
  NanoscopeParameter ramp_parameter(const NanoscopeSection& image, const NanoscopeSection* force) {
    const std::string* own = image.find_any_case("@4:Ramp Size");
    NanoscopeParameter ramp = own ? parse_nanoscope_parameter(*own) : NanoscopeParameter{};
    if (ramp.hard_value) return *ramp.hard_value > 0.0 ? ramp : NanoscopeParameter{};
    const std::string* sweep = force ? force->find_any_case("@4:Ramp Size Zsweep") : nullptr;
    NanoscopeParameter fallback = sweep ? parse_nanoscope_parameter(*sweep) : NanoscopeParameter{};
    if (!fallback.hard_value || !(*fallback.hard_value > 0.0)) return {};
    notes_.push_back("the force image list's \\@4:Ramp Size is '" + (own ? *own : std::string()) +
                     "': the force list's \\@4:Ramp Size Zsweep (" + format_double(*fallback.hard_value) +
                     " V) is used for the ramp");
    return fallback;
  }
  double duration(const NanoscopeSection& force, const char* key, double ramp_volts) const {
    const std::string* v = force.find(key);
    double vel = 0.0;
    return v && parse_finite(*v, vel) && vel > 0.0 ? ramp_volts / vel : 0.0;
  }

  Channel channel(const NanoscopeSection& s) const {
    Channel c;
    c.name = h_.parameter(s, "@4:Image Data").quoted;
    const auto offset = static_cast<std::uint64_t>(h_.whole(s, "Data offset", 0, kMaxOffset));
    const auto length = static_cast<std::uint64_t>(h_.whole(s, "Data length", 1, kMaxOffset));
    const std::vector<std::int64_t> n = h_.wholes(s, "Samps/line", 1, kMaxSamples);
    if (n.size() != 2)
      h_.fail(s, "\\Samps/line = '" + h_.text(s, "Samps/line") + "': expected two numbers (extend, retract samples)");
    c.offset = offset;
    c.n1 = static_cast<std::size_t>(n[0]);
    c.n2 = static_cast<std::size_t>(n[1]);
    // `\Bytes/pixel` says 2 in v9 files holding 4-byte samples: the size is derived instead.
    const std::uint64_t samples = curves_ * (c.n1 + c.n2);
    c.bytes = static_cast<std::size_t>(length / samples);
    if (length % samples != 0 || (c.bytes != 2 && c.bytes != 4))
      h_.fail(s, "\\Data length = " + std::to_string(length) + ": expected " + std::to_string(curves_) +
                     " curve(s) x (" + std::to_string(c.n1) + " + " + std::to_string(c.n2) +
                     ") samples x 2 or 4 bytes");
    if (offset < header_text_.size() || offset > in_->size() || length > in_->size() - offset)
      h_.fail(s, "\\Data offset = " + std::to_string(offset) + " with \\Data length = " + std::to_string(length) +
                     ": expected the data between the header's end (" + std::to_string(header_text_.size()) +
                     ") and the file's end (" + std::to_string(in_->size()) + " bytes; truncated file?)");
    const NanoscopeParameter z = h_.parameter(s, "@4:Z scale");
    if (!z.hard_scale || *z.hard_scale == 0.0)
      h_.fail(s, "\\@4:Z scale = '" + h_.text(s, "@4:Z scale") + "': expected a non-zero number of V/LSB in parentheses");
    c.shifted = c.bytes == 4 && volume_ && version() >= 0x09200000U;
    c.metres_per_lsb = *z.hard_scale * h_.sensitivity(z.soft_scale, "\\@4:Z scale of " + c.name) * 1e-9 /
                       (c.shifted ? 256.0 : 1.0);
    return c;
  }
  // `\Version: 0x0920B046` (NanoScope 9.20); asked for only where the scaling depends on it.
  std::uint32_t version() const {
    const NanoscopeSection& top = h_.need_section("Force file list");
    const std::string& v = h_.text(top, "Version");
    std::uint32_t x = 0;
    const char* b = v.data() + (v.compare(0, 2, "0x") == 0 ? 2 : 0);
    const auto [end, ec] = std::from_chars(b, v.data() + v.size(), x, 16);
    if (ec != std::errc() || end != v.data() + v.size() || b == end)
      h_.fail(top, "\\Version = '" + v + "': expected a hex number such as 0x0920B046 (it decides the scale of "
                                         "4-byte force volume samples)");
    return x;
  }

  // Curve i's samples in file order, in metres of the channel's quantity.
  std::vector<double> samples(const Channel& ch, std::size_t i) const {
    const std::size_t n = ch.n1 + ch.n2;
    const std::string what = "curve " + std::to_string(i) + " (" + ch.name + ")";
    const std::string raw = read_bytes(*in_, file_.path, ch.offset + i * n * ch.bytes, n * ch.bytes, what);
    const auto* p = reinterpret_cast<const unsigned char*>(raw.data());
    std::vector<double> out(n);
    for (std::size_t k = 0; k < n; ++k, p += ch.bytes) {
      std::uint32_t u = std::uint32_t{p[0]} | (std::uint32_t{p[1]} << 8);
      if (ch.bytes == 4) u |= (std::uint32_t{p[2]} << 16) | (std::uint32_t{p[3]} << 24);
      const std::int32_t v = ch.bytes == 4 ? static_cast<std::int32_t>(u) : static_cast<std::int16_t>(u);
      // The evidence for counts * 256 (docs): a 16-bit ADC count shifted up, the low byte 0x00
      // or 0xFF. A sample that breaks it would be scaled by a guess: refused instead.
      if (ch.shifted && ((p[0] != 0x00 && p[0] != 0xFF) || v / 256 > 32767 || v / 256 < -32768))
        throw InputError(h_.path() + ": " + what + ": sample " + std::to_string(k) + " = " + std::to_string(v) +
                         " is not a 16-bit count times 256 (low byte 00 or FF), which the NanoScope 9.2 force "
                         "volume scaling (/256) assumes");
      out[k] = v * ch.metres_per_lsb;
    }
    return out;
  }

  std::unique_ptr<PositionedFile> in_;
  std::string header_text_;
  NanoscopeHeader h_;
  InstrumentFile file_;
  bool volume_ = false;
  std::size_t curves_ = 0;
  Channel defl_;
  std::optional<Channel> sensor_;
  double spring_constant_ = 0.0, sensitivity_ = 0.0, ramp_m_ = 0.0;
  std::string ramp_error_;          // why no height can be made (no sensor, no ramp): each curve says it
  std::vector<std::string> notes_;  // the reader's choices, on every curve
  double duration_extend_ = 0.0, duration_retract_ = 0.0;
};

}  // namespace

std::unique_ptr<CurveSource> open_nanoscope(const std::string& path, const ReadLimits& limits) {
  return std::make_unique<NanoscopeSource>(PositionedFile::open(path), path, limits);
}

std::unique_ptr<CurveSource> open_nanoscope_bytes(std::string bytes, const std::string& path, const ReadLimits& limits) {
  return std::make_unique<NanoscopeSource>(PositionedFile::of_bytes(std::move(bytes)), path, limits);
}

}  // namespace layerjkr::detail
