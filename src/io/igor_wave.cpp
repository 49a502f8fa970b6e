// Igor binary waves, version 5 (igor_wave.hpp).
#include "io/igor_wave.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <sstream>

#include "io/csv_rows.hpp"
#include "layerjkr/error.hpp"

namespace layerjkr::detail {
namespace {

constexpr std::size_t kBinHeader = 64, kWaveHeader = 320, kLabel = 32;

class Bytes {
 public:
  Bytes(const std::string& data, const std::string& path) : data_(data), path_(path) {
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
  const std::string& data_;
  const std::string& path_;
  bool little_ = true;
};

bool is_nan_word(std::string_view s) {
  return s.size() == 3 && std::tolower(static_cast<unsigned char>(s[0])) == 'n' &&
         std::tolower(static_cast<unsigned char>(s[1])) == 'a' && std::tolower(static_cast<unsigned char>(s[2])) == 'n';
}

}  // namespace

IgorNote::IgorNote(const std::string& text, std::string path) : path_(std::move(path)) {
  std::stringstream in(text);
  for (std::string line; std::getline(in, line, '\r');) {
    const std::size_t colon = line.find(':');
    if (colon == std::string::npos) continue;
    std::string value = line.substr(colon + 1);
    const std::size_t first = value.find_first_not_of(" \t\n");
    value = first == std::string::npos ? "" : value.substr(first, value.find_last_not_of(" \t\n") - first + 1);
    values_[line.substr(0, colon)].push_back(value);
  }
}

void IgorNote::fail(const std::string& what) const { throw InputError(path_ + ": " + what); }

const std::string* IgorNote::find(const std::string& key) const {
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

std::string IgorNote::text(const std::string& key) const {
  const std::string* v = find(key);
  return v ? *v : "";
}

double IgorNote::positive(const std::string& key) const {
  const std::string* text = find(key);
  if (!text) fail("the wave note has no " + key);
  double v = 0.0;
  if (!parse_finite(*text, v) || !(v > 0.0)) fail("the note's " + key + " = '" + *text + "' is not a finite number > 0");
  return v;
}

std::vector<double> IgorNote::list(const std::string& key) const {
  std::vector<double> out;
  const std::string* text = find(key);
  if (!text) return out;
  std::stringstream in(*text);
  for (std::string item; std::getline(in, item, ',');) {
    const std::string_view cell = trim(item);
    double v = NAN;
    if (!is_nan_word(cell) && !parse_finite(cell, v))
      fail("the note's " + key + " = '" + *text + "' holds '" + item + "', not a number");
    out.push_back(v);
  }
  return out;
}

bool IgorWave::is_image() const {
  if (dims[2] > 0) return true;
  static const std::set<std::string> channels = {"Raw", "Defl", "ZSnsr", "DeflV", "LVDT", "Amp", "Phase"};
  const bool force_columns = std::any_of(labels[1].begin(), labels[1].end(), [](const std::string& l) { return channels.count(l) > 0; });
  return dims[1] > 1 && !force_columns && note.text("ForceMapImage") == "1";
}

IgorWave parse_igor_wave(const std::string& bytes, const std::string& path) {
  const Bytes b(bytes, path);
  const std::size_t wfm_size = b.size_at(4, "wave size");
  const std::size_t formula_size = b.size_at(8, "formula size");
  const std::size_t note_size = b.size_at(12, "note size");
  const std::size_t data_units_size = b.size_at(16, "units size");
  std::size_t dim_units = 0;
  for (std::size_t d = 0; d < 4; ++d) dim_units += b.size_at(20 + 4 * d, "dimension units size");
  std::array<std::size_t, 4> label_sizes{};
  for (std::size_t d = 0; d < 4; ++d) label_sizes[d] = b.size_at(36 + 4 * d, "label size");
  const std::size_t wave = kBinHeader;
  const auto type = b.at<std::int16_t>(wave + 16);
  const std::size_t width = type == 2 ? 4 : type == 4 ? 8 : 0;
  if (width == 0) b.fail("holds data of Igor type " + std::to_string(type) + "; force curves are float32 or float64");
  const std::size_t note_at = kBinHeader + wfm_size + formula_size;
  IgorWave w{{}, b.at<double>(wave + 84), {}, {}, {}, IgorNote(b.text(note_at, note_size), path)};
  for (std::size_t d = 0; d < 4; ++d) w.dims[d] = b.size_at(wave + 68 + 4 * d, "dimension size");
  const std::string name = b.text(wave + 28, 32);
  w.name = name.substr(0, name.find('\0'));
  if (w.dims[0] == 0) b.fail("holds an empty wave");
  std::size_t values = 1;
  for (std::size_t d = 0; d < 4 && w.dims[d] > 0; ++d) {
    if (values > (wfm_size + 1) / w.dims[d]) b.fail("announces more values than its wave record holds");
    values *= w.dims[d];
  }
  if (wfm_size < kWaveHeader || values > (wfm_size - kWaveHeader) / width)
    b.fail("announces " + std::to_string(values) + " values that do not fit its wave record");
  const std::size_t data = wave + kWaveHeader;
  w.data.resize(values);
  for (std::size_t i = 0; i < values; ++i)
    w.data[i] = width == 4 ? static_cast<double>(b.at<float>(data + i * width)) : b.at<double>(data + i * width);
  std::size_t at = note_at + note_size + data_units_size + dim_units;
  for (std::size_t d = 0; d < 4; ++d) {
    const std::size_t n = label_sizes[d] / kLabel;
    for (std::size_t k = 1; k < n; ++k) {
      const std::string label = b.text(at + kLabel * k, kLabel);
      w.labels[d].push_back(label.substr(0, label.find('\0')));
    }
    at += label_sizes[d];
  }
  return w;
}

}  // namespace layerjkr::detail
