// Igor binary waves, version 5, as Asylum Research saves force curves (instrument.hpp).
// Layout: BinHeader5 (64 bytes), WaveHeader5 (320), the data (wfmSize - 320 bytes,
// column-major), then formula, note, units and dimension labels (32 bytes each, the
// dimension's own label first); Asylum appends a preview trailer, which is ignored.
#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <map>
#include <sstream>

#include "io/instrument_readers.hpp"
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
  std::string text(std::size_t offset, std::size_t size) const {
    if (offset + size > data_.size()) fail("is truncated (its note or labels end past the file)");
    return data_.substr(offset, size);
  }

 private:
  std::string data_, path_;
  bool little_ = true;
};

// Latin-1 note "Key:Value\r..." -> map (first ':' splits; values trimmed).
std::map<std::string, std::string> parse_note(const std::string& note) {
  std::map<std::string, std::string> out;
  std::stringstream in(note);
  for (std::string line; std::getline(in, line, '\r');) {
    const std::size_t colon = line.find(':');
    if (colon == std::string::npos) continue;
    std::string value = line.substr(colon + 1);
    const std::size_t first = value.find_first_not_of(" \t\n");
    value = first == std::string::npos ? "" : value.substr(first, value.find_last_not_of(" \t\n") - first + 1);
    out.emplace(line.substr(0, colon), value);
  }
  return out;
}

std::vector<double> numbers(const std::string& list) {
  std::vector<double> out;
  std::stringstream in(list);
  for (std::string item; std::getline(in, item, ',');) {
    double v = NAN;
    if (!item.empty() && item != "NaN") std::from_chars(item.data(), item.data() + item.size(), v);
    out.push_back(v);
  }
  return out;
}

double note_number(const Bytes& b, const std::map<std::string, std::string>& note, const std::string& key) {
  const auto it = note.find(key);
  if (it == note.end()) b.fail("the wave note has no " + key);
  double v = NAN;
  const auto [end, ec] = std::from_chars(it->second.data(), it->second.data() + it->second.size(), v);
  if (ec != std::errc() || !(v > 0.0)) b.fail("the note's " + key + " = '" + it->second + "' is not a positive number");
  return v;
}

}  // namespace

InstrumentFile read_ibw(const std::string& path) {
  std::ifstream stream(path, std::ios::binary);
  if (!stream) throw InputError(path + ": cannot open the file");
  std::ostringstream content;
  content << stream.rdbuf();
  const Bytes b(content.str(), path);

  const auto wfm_size = static_cast<std::size_t>(b.at<std::int32_t>(4));
  const auto formula_size = static_cast<std::size_t>(b.at<std::int32_t>(8));
  const auto note_size = static_cast<std::size_t>(b.at<std::int32_t>(12));
  const auto data_units_size = static_cast<std::size_t>(b.at<std::int32_t>(16));
  std::size_t dim_units = 0, labels_before = 0;
  for (int d = 0; d < 4; ++d) dim_units += static_cast<std::size_t>(b.at<std::int32_t>(20 + 4 * static_cast<std::size_t>(d)));
  const auto labels0 = static_cast<std::size_t>(b.at<std::int32_t>(36));
  const auto labels1 = static_cast<std::size_t>(b.at<std::int32_t>(40));
  labels_before = labels0;
  const std::size_t wave = kBinHeader;
  const auto type = b.at<std::int16_t>(wave + 16);
  const auto rows = static_cast<std::size_t>(b.at<std::int32_t>(wave + 68));
  const auto cols = static_cast<std::size_t>(std::max(1, b.at<std::int32_t>(wave + 72)));
  const double row_step = b.at<double>(wave + 84);
  const std::size_t width = type == 2 ? 4 : type == 4 ? 8 : 0;
  if (width == 0) b.fail("holds data of Igor type " + std::to_string(type) + "; force curves are float32 or float64");
  if (wfm_size < kWaveHeader || rows * cols * width > wfm_size - kWaveHeader)
    b.fail("announces " + std::to_string(rows) + " x " + std::to_string(cols) + " values that do not fit its wave record");
  const std::size_t data = wave + kWaveHeader;
  const std::size_t note_at = kBinHeader + wfm_size + formula_size;
  const auto note = parse_note(b.text(note_at, note_size));
  const std::size_t labels_at = note_at + note_size + data_units_size + dim_units + labels_before;
  std::map<std::string, std::size_t> column;
  if (labels1 >= kLabel * (cols + 1)) {
    for (std::size_t c = 0; c < cols; ++c) {
      const std::string label = b.text(labels_at + kLabel * (c + 1), kLabel);
      column[label.substr(0, label.find('\0'))] = c;
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
  file.format = "ibw";
  file.software = note.count("Version") ? note.at("Version") : "";
  file.instrument = note.count("MicroscopeModel") ? note.at("MicroscopeModel") : "";
  InstrumentCurve curve;
  curve.spring_constant = note_number(b, note, "SpringConstant");
  curve.sensitivity = note_number(b, note, "InvOLS");
  // Segments between consecutive Indexes: [0, I1], [I1 + 1, I2], ...; Direction 1 extends.
  std::vector<double> idx = note.count("Indexes") ? numbers(note.at("Indexes")) : std::vector<double>{};
  std::vector<double> dir = note.count("Direction") ? numbers(note.at("Direction")) : std::vector<double>{};
  if (idx.size() < 2) idx = {0.0, static_cast<double>(rows - 1)};
  for (std::size_t k = 1; k < idx.size(); ++k) {
    const auto first = k == 1 ? std::size_t{0} : static_cast<std::size_t>(idx[k - 1]) + 1;
    const auto last = static_cast<std::size_t>(idx[k]);
    if (!(idx[k] >= 0.0) || last >= rows || first > last)
      b.fail("the note's Indexes (" + note.at("Indexes") + ") do not fit its " + std::to_string(rows) + " rows");
    InstrumentSegment s;
    const double d = k < dir.size() ? dir[k] : NAN;
    s.style = d > 0 ? "extend" : d < 0 ? "retract" : "pause";
    for (std::size_t r = first; r <= last; ++r) {
      s.force.push_back(value(r, column["Defl"]) * curve.spring_constant);
      s.height.push_back(-value(r, column["ZSnsr"]));
      s.piezo_height.push_back(-value(r, column["Raw"]));
    }
    s.duration = static_cast<double>(last - first + 1) * row_step;
    curve.segments.push_back(std::move(s));
  }
  file.curves.push_back(std::move(curve));
  return file;
}

}  // namespace layerjkr::detail
