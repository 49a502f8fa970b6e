// Igor binary waves, version 5, as Asylum Research saves force curves (instrument.hpp).
// Layout: BinHeader5 (64 bytes), WaveHeader5 (320), the data (wfmSize - 320 bytes,
// column-major), then formula, note, units and dimension labels (32 bytes each, the
// dimension's own label first); Asylum appends a preview trailer, which is ignored.
#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <cctype>
#include <map>
#include <optional>
#include <set>
#include <sstream>

#include "io/csv_rows.hpp"
#include "io/instrument_readers.hpp"
#include "io/read_file.hpp"
#include "layerjkr/error.hpp"

namespace layerjkr::detail {
namespace {

constexpr std::size_t kBinHeader = 64, kWaveHeader = 320, kLabel = 32;

class Bytes {
 public:
  Bytes(std::string data, std::string path) : data_(std::move(data)), path_(std::move(path)) {
    if (data_.size() < kBinHeader + kWaveHeader) fail("is " + std::to_string(data_.size()) + " bytes, too short for an Igor wave");
    const auto* p = reinterpret_cast<const unsigned char*>(data_.data());
    little_ = p[0] == 5 && p[1] == 0;
    if (!little_ && !(p[0] == 0 && p[1] == 5)) fail("is not an Igor binary wave of version 5");
  }
  [[noreturn]] void fail(const std::string& what) const { throw InputError(path_ + ": " + what); }

  template <class T>
  T at(std::size_t offset) const {
    if (offset + sizeof(T) > data_.size()) fail("is truncated (needs byte " + std::to_string(offset + sizeof(T)) + ")");
    unsigned char b[sizeof(T)];
    std::memcpy(b, data_.data() + offset, sizeof(T));
    if (!little_) std::reverse(b, b + sizeof(T));
    T v;
    std::memcpy(&v, b, sizeof(T));
    return v;
  }
  // A size field: non-negative and no larger than the file, so sums of a few never overflow.
  std::size_t size_at(std::size_t offset, const char* what) const {
    const auto v = at<std::int32_t>(offset);
    if (v < 0 || static_cast<std::size_t>(v) > data_.size())
      fail(std::string("is truncated or corrupt: its ") + what + " is " + std::to_string(v) + " in a file of " +
           std::to_string(data_.size()) + " bytes");
    return static_cast<std::size_t>(v);
  }
  std::size_t size() const { return data_.size(); }
  std::string text(std::size_t offset, std::size_t size) const {
    if (offset + size > data_.size()) fail("is truncated (its note or labels end past the file)");
    return data_.substr(offset, size);
  }

 private:
  std::string data_, path_;
  bool little_ = true;
};

// Latin-1 note "Key:Value\r..." (first ':' splits; values trimmed). Asylum writes keys more than
// once: SaveForce and SaveImage in every force file, and in the curves its ARDF export writes
// (AR 13.16) the map's header block first and each curve's own block after its Indexes, with
// SpringConstant, MostPosZVoltage, ... repeated. A repeat with the same value is one value. Where
// the copies differ (XLVDT, YLVDT, DisplaySpringConstant there) the last - the curve's own block -
// is used, as afmformats, SciFiReaders and magic-afm read it, and a note says so.
class Note {
 public:
  Note(const std::string& note, const Bytes& b) : b_(b) {
    std::stringstream in(note);
    for (std::string line; std::getline(in, line, '\r');) {
      const std::size_t colon = line.find(':');
      if (colon == std::string::npos) continue;
      std::string value = line.substr(colon + 1);
      const std::size_t first = value.find_first_not_of(" \t\n");
      value = first == std::string::npos ? "" : value.substr(first, value.find_last_not_of(" \t\n") - first + 1);
      values_[line.substr(0, colon)].push_back(value);
    }
  }

  const std::string* find(const std::string& key) const {
    const auto it = values_.find(key);
    if (it == values_.end()) return nullptr;
    const std::vector<std::string>& copies = it->second;
    if (std::any_of(copies.begin(), copies.end(), [&](const std::string& v) { return v != copies.front(); }) &&
        noted_.insert(key).second) {
      std::string list;
      for (const std::string& v : copies) list += (list.empty() ? "'" : ", '") + v + "'";
      notes_.push_back("the wave note gives " + key + " " + std::to_string(copies.size()) + " times with different values (" +
                       list + "); the last, the curve's own block in Asylum's exports, is used");
    }
    return &copies.back();
  }
  /// The notes find() made, in the order it made them.
  const std::vector<std::string>& notes() const { return notes_; }
  std::string text(const std::string& key) const {
    const std::string* v = find(key);
    return v ? *v : "";
  }

  // The whole value must be one finite number > 0: "1,1841" or "1e-3e5" are errors, not 1 or 0.001.
  double positive(const std::string& key) const {
    const std::string* text = find(key);
    if (!text) b_.fail("the wave note has no " + key);
    double v = 0.0;
    if (!parse_finite(*text, v) || !(v > 0.0)) b_.fail("the note's " + key + " = '" + *text + "' is not a finite number > 0");
    return v;
  }

  // A comma-separated list of finite numbers or NaN (Direction's marker for a pause), an
  // empty last item allowed ("NaN,1,-1,"); anything else is an error naming the key.
  std::vector<double> list(const std::string& key) const {
    std::vector<double> out;
    const std::string* text = find(key);
    if (!text) return out;
    std::stringstream in(*text);
    for (std::string item; std::getline(in, item, ',');) {
      const std::string_view cell = trim(item);
      double v = NAN;
      // NaN in any case: Asylum's own lines write NaN, its ARDF export "Nan" (AR 13.16).
      const bool nan = cell.size() == 3 && std::tolower(static_cast<unsigned char>(cell[0])) == 'n' &&
                       std::tolower(static_cast<unsigned char>(cell[1])) == 'a' &&
                       std::tolower(static_cast<unsigned char>(cell[2])) == 'n';
      if (!nan && !parse_finite(cell, v))
        b_.fail("the note's " + key + " = '" + *text + "' holds '" + item + "', not a number");
      out.push_back(v);
    }
    return out;
  }

 private:
  const Bytes& b_;
  std::map<std::string, std::vector<std::string>> values_;
  mutable std::set<std::string> noted_;
  mutable std::vector<std::string> notes_;
};

}  // namespace

InstrumentFile read_ibw(const std::string& path) {
  return read_ibw_bytes(read_file(path, "the file"), path);
}

InstrumentFile read_ibw_bytes(std::string bytes, const std::string& path) {
  const Bytes b(std::move(bytes), path);

  const std::size_t wfm_size = b.size_at(4, "wave size");
  const std::size_t formula_size = b.size_at(8, "formula size");
  const std::size_t note_size = b.size_at(12, "note size");
  const std::size_t data_units_size = b.size_at(16, "units size");
  std::size_t dim_units = 0, labels_before = 0;
  for (std::size_t d = 0; d < 4; ++d) dim_units += b.size_at(20 + 4 * d, "dimension units size");
  const std::size_t labels0 = b.size_at(36, "label size");
  const std::size_t labels1 = b.size_at(40, "label size");
  labels_before = labels0;
  const std::size_t wave = kBinHeader;
  const auto type = b.at<std::int16_t>(wave + 16);
  const std::size_t rows = b.size_at(wave + 68, "row count");
  const std::size_t cols = std::max<std::size_t>(1, b.size_at(wave + 72, "column count"));
  const double row_step = b.at<double>(wave + 84);
  const std::size_t width = type == 2 ? 4 : type == 4 ? 8 : 0;
  if (width == 0) b.fail("holds data of Igor type " + std::to_string(type) + "; force curves are float32 or float64");
  if (rows == 0) b.fail("holds an empty wave");
  if (wfm_size < kWaveHeader || rows * cols > (wfm_size - kWaveHeader) / width)
    b.fail("announces " + std::to_string(rows) + " x " + std::to_string(cols) + " values that do not fit its wave record");
  const std::size_t data = wave + kWaveHeader;
  const std::size_t note_at = kBinHeader + wfm_size + formula_size;
  const Note note(b.text(note_at, note_size), b);
  const std::size_t labels_at = note_at + note_size + data_units_size + dim_units + labels_before;
  std::map<std::string, std::size_t> column;
  if (labels1 >= kLabel * (cols + 1)) {
    for (std::size_t c = 0; c < cols; ++c) {
      const std::string label = b.text(labels_at + kLabel * (c + 1), kLabel);
      const std::string name = label.substr(0, label.find('\0'));
      if (!column.emplace(name, c).second) b.fail("labels two columns " + name);
    }
  }
  for (const char* name : {"Raw", "Defl", "ZSnsr"})
    if (!column.count(name)) b.fail(std::string("has no column labelled ") + name + " (Asylum force curves have Raw, Defl, ZSnsr)");
  auto value = [&](std::size_t row, std::size_t col) {
    const std::size_t at = data + (col * rows + row) * width;
    return width == 4 ? static_cast<double>(b.at<float>(at)) : b.at<double>(at);
  };

  InstrumentFile file;
  file.path = path;
  file.format = InstrumentFormat::ibw;
  file.software = note.text("Version");
  file.instrument = note.text("MicroscopeModel");
  InstrumentCurve curve;
  curve.spring_constant = note.positive("SpringConstant");
  curve.sensitivity = note.positive("InvOLS");
  // Segments between consecutive Indexes: [0, I1], [I1 + 1, I2], ...; Direction 1 extends.
  std::vector<double> idx = note.list("Indexes");
  const std::vector<double> dir = note.list("Direction");
  if (idx.size() < 2) idx = {0.0, static_cast<double>(rows - 1)};
  for (std::size_t k = 1; k < idx.size(); ++k) {
    const auto fits = [&](double v) { return v >= 0.0 && v < static_cast<double>(rows) && v == std::floor(v); };
    if (!fits(idx[k]) || (k > 1 && !fits(idx[k - 1])))
      b.fail("the note's Indexes (" + note.text("Indexes") + ") do not fit its " + std::to_string(rows) + " rows");
    const auto first = k == 1 ? std::size_t{0} : static_cast<std::size_t>(idx[k - 1]) + 1;
    const auto last = static_cast<std::size_t>(idx[k]);
    if (first > last)
      b.fail("the note's Indexes (" + note.text("Indexes") + ") are not increasing");
    InstrumentSegment s;
    const double d = k < dir.size() ? dir[k] : NAN;
    s.style = d > 0 ? SegmentStyle::extend : d < 0 ? SegmentStyle::retract : SegmentStyle::pause;
    for (std::size_t r = first; r <= last; ++r) {
      s.force.push_back(value(r, column["Defl"]) * curve.spring_constant);
      s.height.push_back(-value(r, column["ZSnsr"]));
      s.piezo_height.push_back(-value(r, column["Raw"]));
    }
    s.duration = static_cast<double>(last - first + 1) * row_step;
    curve.segments.push_back(std::move(s));
  }
  curve.notes = note.notes();
  file.curves.push_back(std::move(curve));
  return file;
}

}  // namespace layerjkr::detail
