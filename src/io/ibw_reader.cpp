// Asylum Research force curves saved as Igor binary waves (instrument.hpp): one 2-D float wave,
// columns by label (Raw, Defl, ZSnsr), calibration from the note (igor_wave.hpp).
#include <cmath>
#include <map>
#include <algorithm>
#include <cctype>

#include "io/igor_wave.hpp"
#include "io/instrument_readers.hpp"
#include "io/read_file.hpp"
#include "layerjkr/error.hpp"

namespace layerjkr::detail {

namespace {

// The 1-6 digits at `pos` of `s` as a number, advancing `pos`; nullopt without digits or with more.
std::optional<int> short_index(const std::string& s, std::size_t& pos) {
  const std::size_t start = pos;
  int v = 0;
  while (pos < s.size() && std::isdigit(static_cast<unsigned char>(s[pos])) && pos - start < 7)
    v = 10 * v + (s[pos++] - '0');
  if (pos == start || pos - start > 6) return std::nullopt;
  return v;
}

std::optional<AsylumPointName> point_name_at(const std::string& s, std::size_t pos) {
  AsylumPointName out;
  pos += 4;  // "Line"
  const auto line = short_index(s, pos);
  if (!line || s.compare(pos, 5, "Point") != 0) return std::nullopt;
  pos += 5;
  const auto point = short_index(s, pos);
  if (!point) return std::nullopt;
  out.line = *line;
  out.point = *point;
  out.channel = s.substr(pos);
  const bool alnum = std::all_of(out.channel.begin(), out.channel.end(),
                                 [](char c) { return std::isalnum(static_cast<unsigned char>(c)) != 0; });
  if (!alnum) return std::nullopt;
  return out;
}

}  // namespace

std::optional<AsylumPointName> asylum_point_name(const std::string& name, bool whole) {
  if (whole) return name.rfind("Line", 0) == 0 ? point_name_at(name, 0) : std::nullopt;
  for (std::size_t pos = name.rfind("Line"); pos != std::string::npos;
       pos = pos == 0 ? std::string::npos : name.rfind("Line", pos - 1))
    if (auto parts = point_name_at(name, pos)) return parts;
  return std::nullopt;
}

std::optional<std::pair<int, int>> asylum_line_point(const std::string& name) {
  const auto parts = asylum_point_name(name);
  if (!parts) return std::nullopt;
  return std::make_pair(parts->line, parts->point);
}

std::vector<InstrumentSegment> asylum_segments(const IgorNote& note, std::size_t rows, double row_step,
                                               const std::function<void(std::size_t, InstrumentSegment&)>& sample,
                                               const std::string& path) {
  // Segments between consecutive Indexes: [0, I1], [I1 + 1, I2], ...; Direction 1 extends, -1
  // retracts, NaN or 0 pauses. Without Direction (per-channel map exports): extend, retract, then
  // pauses (a dwell away from the surface).
  std::vector<double> idx = note.list("Indexes");
  const std::vector<double> dir = note.list("Direction");
  if (idx.size() < 2) idx = {0.0, static_cast<double>(rows - 1)};
  std::vector<InstrumentSegment> out;
  for (std::size_t k = 1; k < idx.size(); ++k) {
    const auto fits = [&](double v) { return v >= 0.0 && v < static_cast<double>(rows) && v == std::floor(v); };
    if (!fits(idx[k]) || (k > 1 && !fits(idx[k - 1])))
      throw InputError(path + ": the note's Indexes (" + note.text("Indexes") + ") do not fit its " + std::to_string(rows) +
                       " rows");
    const auto first = k == 1 ? std::size_t{0} : static_cast<std::size_t>(idx[k - 1]) + 1;
    const auto last = static_cast<std::size_t>(idx[k]);
    if (first > last) throw InputError(path + ": the note's Indexes (" + note.text("Indexes") + ") are not increasing");
    InstrumentSegment s;
    const double d = dir.empty() ? (k == 1 ? 1.0 : k == 2 ? -1.0 : 0.0) : k < dir.size() ? dir[k] : NAN;
    s.style = d > 0 ? SegmentStyle::extend : d < 0 ? SegmentStyle::retract : SegmentStyle::pause;
    for (std::size_t r = first; r <= last; ++r) sample(r, s);
    s.duration = static_cast<double>(last - first + 1) * row_step;
    out.push_back(std::move(s));
  }
  return out;
}

InstrumentFile read_ibw(const std::string& path) { return read_ibw_bytes(read_file(path, "the file"), path); }

InstrumentFile read_ibw_bytes(const std::string& bytes, const std::string& path) {
  const IgorWave w = parse_igor_wave(bytes, path);
  const auto fail = [&](const std::string& what) -> void { throw InputError(path + ": " + what); };
  if (w.is_image())
    fail("is an image (" + std::to_string(w.dims[0]) + " x " + std::to_string(w.dims[1]) +
         (w.dims[2] ? " x " + std::to_string(w.dims[2]) : std::string()) +
         (w.labels[2].empty() ? std::string() : ", layers " + w.labels[2].front() + "...") +
         "), not force curves: a force map's picture; fit the map's curves (fit-map on the folder that holds them)");
  std::map<std::string, std::size_t> column;
  for (std::size_t c = 0; c < w.labels[1].size() && c < w.columns(); ++c)
    if (!column.emplace(w.labels[1][c], c).second) fail("labels two columns " + w.labels[1][c]);
  if (w.dims[1] == 0 && asylum_line_point(w.name))
    fail("holds one channel (" + (w.labels[1].empty() ? w.name : w.labels[1].back()) + ") of one point of an Asylum "
         "force map exported a file per channel: fit-map on the folder that holds them reads every point as one map");
  for (const char* name : {"Raw", "Defl", "ZSnsr"})
    if (!column.count(name)) fail(std::string("has no column labelled ") + name + " (Asylum force curves have Raw, Defl, ZSnsr)");
  const std::size_t rows = w.rows();
  const auto value = [&](std::size_t row, const char* col) { return w.data[column[col] * rows + row]; };

  InstrumentFile file;
  file.path = path;
  file.format = InstrumentFormat::ibw;
  file.software = w.note.text("Version");
  file.instrument = w.note.text("MicroscopeModel");
  InstrumentCurve curve;
  curve.spring_constant = w.note.positive("SpringConstant");
  curve.sensitivity = w.note.positive("InvOLS");
  // A curve of a map exported a file per point (LineLLLLPointPPPP): its pixel from the name.
  if (const auto lp = asylum_line_point(w.name)) {
    curve.grid_x = lp->second;
    curve.grid_y = lp->first;
  }
  const double k = curve.spring_constant;
  curve.segments = asylum_segments(w.note, rows, w.row_step,
                                   [&](std::size_t r, InstrumentSegment& s) {
                                     s.force.push_back(value(r, "Defl") * k);
                                     s.height.push_back(-value(r, "ZSnsr"));
                                     s.piezo_height.push_back(-value(r, "Raw"));
                                   },
                                   path);
  curve.notes = w.note.notes();
  file.curves.push_back(std::move(curve));
  return file;
}

}  // namespace layerjkr::detail
