// Asylum Research force maps exported one Igor wave per channel per point (curve_source.hpp).
// Layout, as AR writes it and SOFA's public test data show it: LineLLLL/LineLLLLPointPPPP<Chan>.ibw
// (or the files without the folders), each a 1-D float wave in metres whose note holds only
// XLVDT, YLVDT and Indexes (no Direction: extend, retract, then a dwell away); the map's image
// (a wave of MapHeight/MapAdhesion layers whose note says ForceMapImage:1) beside them holds the
// calibration (SpringConstant, InvOLS) and the scan (FMapScanPoints/Lines, Fast/SlowScanSize,
// X/YOffset, ScanAngle). Points sit on the scan's edges: the pitch is ScanSize / (N - 1).
#include <glob.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <map>

#include "io/csv_rows.hpp"
#include "io/igor_wave.hpp"
#include "io/instrument_readers.hpp"
#include "io/read_file.hpp"
#include "layerjkr/error.hpp"

namespace layerjkr::detail {
namespace fs = std::filesystem;
namespace {

// A per-channel file's (line, point, channel), or nullopt.
std::optional<std::tuple<int, int, std::string>> channel_file(const fs::path& p) {
  const std::string name = p.filename().string();
  const std::string suffix = ".ibw";
  if (name.size() <= suffix.size() || name.compare(name.size() - suffix.size(), suffix.size(), suffix) != 0)
    return std::nullopt;
  auto parts = asylum_point_name(name.substr(0, name.size() - suffix.size()), true);
  if (!parts || parts->channel.empty() || !std::isalpha(static_cast<unsigned char>(parts->channel[0])))
    return std::nullopt;
  return std::make_tuple(parts->line, parts->point, parts->channel);
}

bool is_glob(const std::string& s) { return s.find_first_of("*?[") != std::string::npos; }

std::vector<fs::path> listing(const fs::path& dir) {
  std::vector<fs::path> out;
  std::error_code ec;
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) out.push_back(it->path());
  std::sort(out.begin(), out.end());
  return out;
}

double number_or(const IgorNote& note, const std::string& key, double fallback) {
  const std::string* v = note.find(key);
  double x = 0.0;
  return v && parse_finite(*v, x) ? x : fallback;
}

class AsylumMap final : public CurveSource {
 public:
  AsylumMap(const std::string& path, const std::vector<std::string>& files) {
    file_.path = path;
    file_.format = InstrumentFormat::ibw_map;
    // A point whose channel files appear twice (a flat export beside the LineLLLL folders, two
    // folders given together) is two measurements: each set of files is a curve of its own, in
    // the order the files come, and a note says so - none is dropped.
    for (const std::string& f : files) {
      const auto [line, point, name] = *channel_file(f);
      const std::string channel = name;  // a lambda cannot capture a structured binding in C++17
      std::vector<std::map<std::string, std::string>>& copies = points_[{line, point}];
      auto free = std::find_if(copies.begin(), copies.end(), [&](const auto& c) { return !c.count(channel); });
      if (free == copies.end()) free = copies.insert(copies.end(), std::map<std::string, std::string>{});
      (*free)[channel] = f;
    }
    for (const auto& [lp, copies] : points_) {
      for (std::size_t k = 0; k < copies.size(); ++k) order_.push_back({lp, k});
      if (copies.size() > 1) {
        std::string where;
        for (const auto& c : copies) where += (where.empty() ? "" : ", ") + c.begin()->second;
        notes_.push_back("line " + std::to_string(lp.first) + " point " + std::to_string(lp.second) + " is given by " +
                         std::to_string(copies.size()) + " sets of files (" + where + "): each is a curve of its own");
      }
    }
    int max_line = 0, max_point = 0;
    for (const auto& [lp, copy] : order_) max_line = std::max(max_line, lp.first), max_point = std::max(max_point, lp.second);
    find_image(files, max_point + 1, max_line + 1);
    nx_ = image_ ? static_cast<int>(number_or(image_->note, "FMapScanPoints", max_point + 1)) : max_point + 1;
    ny_ = image_ ? static_cast<int>(number_or(image_->note, "FMapScanLines", max_line + 1)) : max_line + 1;
    if (nx_ <= max_point || ny_ <= max_line) {
      notes_.push_back("the map image says " + std::to_string(nx_) + " x " + std::to_string(ny_) +
                       " points, the files go to point " + std::to_string(max_point) + " of line " +
                       std::to_string(max_line) + ": the grid is the files'");
      nx_ = std::max(nx_, max_point + 1);
      ny_ = std::max(ny_, max_line + 1);
    }
    file_.grid_shape_x = nx_;
    file_.grid_shape_y = ny_;
    if (image_) {
      const IgorNote& n = image_->note;
      scan_x_ = number_or(n, "FastScanSize", number_or(n, "ScanSize", 0.0));
      scan_y_ = number_or(n, "SlowScanSize", number_or(n, "ScanSize", 0.0));
      file_.grid_center_x = number_or(n, "XOffset", 0.0);
      file_.grid_center_y = number_or(n, "YOffset", 0.0);
      // N points on the edges of the scan: N pixels of pitch ScanSize / (N - 1).
      file_.grid_size_x = nx_ > 1 ? scan_x_ * nx_ / (nx_ - 1) : scan_x_;
      file_.grid_size_y = ny_ > 1 ? scan_y_ * ny_ / (ny_ - 1) : scan_y_;
      file_.software = n.text("Version");
      file_.instrument = n.text("MicroscopeModel");
      spring_constant_ = number_or(n, "SpringConstant", NAN);
      sensitivity_ = number_or(n, "InvOLS", NAN);
      if (const double angle = number_or(n, "ScanAngle", 0.0); angle != 0.0)
        notes_.push_back("the map was scanned at ScanAngle " + format_double(angle) +
                         " degrees: positions are in the scan's own frame, not rotated");
    } else {
      notes_.push_back("no map image (a wave whose note says ForceMapImage:1) beside the curves: positions are each "
                       "point's XLVDT, YLVDT (absolute sensor readings), the spring constant the points' own or none");
    }
  }

  const InstrumentFile& header() const override { return file_; }
  std::size_t size() const override { return order_.size(); }

  InstrumentCurve curve(std::size_t i, const CurveChannels& /*channels: a by-product of the height here*/) const override {
    const auto [lp, copy] = order_.at(i);
    const auto [line, point] = lp;
    const std::map<std::string, std::string>& channels = points_.at(lp).at(copy);
    const std::string where = file_.path + ": line " + std::to_string(line) + " point " + std::to_string(point);
    for (const char* need : {"Defl", "ZSnsr"})
      if (!channels.count(need))
        throw InputError(where + " has no " + need + " file (LineLLLLPointPPPP" + need + ".ibw); a curve needs Defl and ZSnsr");
    const IgorWave defl = wave(channels.at("Defl"));
    const IgorWave z = wave(channels.at("ZSnsr"));
    std::optional<IgorWave> raw;
    if (channels.count("Raw")) raw = wave(channels.at("Raw"));
    const std::size_t rows = defl.rows();
    if (z.rows() != rows || (raw && raw->rows() != rows))
      throw InputError(where + ": its channels have " + std::to_string(rows) + " (Defl) and " + std::to_string(z.rows()) +
                       " (ZSnsr) rows; they must have as many");
    InstrumentCurve c;
    c.index = static_cast<int>(i);
    c.position_index = line * nx_ + point;
    c.grid_x = point;
    c.grid_y = line;
    c.notes = notes_;
    // The point's own calibration where the image gives none.
    c.spring_constant = std::isnan(spring_constant_) ? number_or(defl.note, "SpringConstant", NAN) : spring_constant_;
    c.sensitivity = std::isnan(sensitivity_) ? number_or(defl.note, "InvOLS", 0.0) : sensitivity_;
    if (image_) {
      c.x = file_.grid_center_x + (nx_ > 1 ? (static_cast<double>(point) / (nx_ - 1) - 0.5) * scan_x_ : 0.0);
      c.y = file_.grid_center_y + (ny_ > 1 ? (static_cast<double>(line) / (ny_ - 1) - 0.5) * scan_y_ : 0.0);
    } else {
      c.x = number_or(defl.note, "XLVDT", NAN);
      c.y = number_or(defl.note, "YLVDT", NAN);
    }
    // Without a spring constant the force is the deflection [m] (to_curve_data needs one given).
    const double k = std::isnan(c.spring_constant) ? 1.0 : c.spring_constant;
    c.segments = asylum_segments(defl.note, rows, defl.row_step,
                                 [&](std::size_t r, InstrumentSegment& s) {
                                   s.force.push_back(defl.data[r] * k);
                                   s.height.push_back(-z.data[r]);
                                   if (raw) s.piezo_height.push_back(-raw->data[r]);
                                 },
                                 channels.at("Defl"));
    for (const std::string& n : defl.note.notes()) c.notes.push_back(n);
    return c;
  }

 private:
  static IgorWave wave(const std::string& path) { return parse_igor_wave(read_file(path, "the file"), path); }

  // The map image: a wave whose note says ForceMapImage:1 and whose scan holds the files' points
  // (FMapScanPoints x FMapScanLines at least `points` x `lines`), nearest first: the curves'
  // folder, the folder above LineLLLL folders, and the one above that (where SOFA's public data
  // keep it); in one folder an image of exactly the files' grid first.
  void find_image(const std::vector<std::string>& files, int points, int lines) {
    std::vector<fs::path> dirs;
    const auto add = [&](const fs::path& d) {
      if (!d.empty() && std::find(dirs.begin(), dirs.end(), d) == dirs.end()) dirs.push_back(d);
    };
    for (const std::string& f : files) add(fs::path(f).parent_path());
    for (std::size_t k = 0, n = dirs.size(); k < n; ++k)
      if (dirs[k].filename().string().rfind("Line", 0) == 0) add(dirs[k].parent_path());
    for (std::size_t k = 0, n = dirs.size(); k < n; ++k) add(dirs[k].parent_path());
    for (const fs::path& d : dirs) {
      std::optional<IgorWave> fits;
      std::string name;
      for (const fs::path& p : listing(d)) {
        std::error_code ec;
        if (p.extension() != ".ibw" || channel_file(p) || !fs::is_regular_file(p, ec) || fs::file_size(p, ec) > (64u << 20))
          continue;
        try {
          IgorWave w = wave(p.string());
          const double np = number_or(w.note, "FMapScanPoints", 0.0), nl = number_or(w.note, "FMapScanLines", 0.0);
          if (w.note.text("ForceMapImage") != "1" || np < points || nl < lines) continue;
          const bool exact = np == points && nl == lines;
          if (!fits || exact) {
            fits = std::move(w);
            name = p.string();
          }
          if (exact) break;
        } catch (const InputError&) {  // not a wave: not the image
        }
      }
      if (fits) {
        image_ = std::move(fits);
        notes_.push_back("calibration and scan from the map image " + name);
        return;
      }
    }
  }

  InstrumentFile file_;
  /// (line, point) -> each set of its files: channel -> file.
  std::map<std::pair<int, int>, std::vector<std::map<std::string, std::string>>> points_;
  std::vector<std::pair<std::pair<int, int>, std::size_t>> order_;  ///< curve i: (line, point), which set
  std::optional<IgorWave> image_;
  int nx_ = 0, ny_ = 0;
  double scan_x_ = 0.0, scan_y_ = 0.0;
  double spring_constant_ = NAN, sensitivity_ = NAN;
  std::vector<std::string> notes_;
};

}  // namespace

std::vector<std::string> asylum_channel_files(const std::string& path) {
  std::vector<std::string> out;
  const auto take = [&](const fs::path& p) {
    if (channel_file(p)) out.push_back(p.string());
  };
  std::error_code ec;
  if (is_glob(path)) {
    glob_t g{};
    std::size_t matches = 0;
    if (::glob(path.c_str(), 0, nullptr, &g) == 0)
      for (std::size_t i = 0; i < g.gl_pathc; ++i, ++matches) take(g.gl_pathv[i]);
    globfree(&g);
    if (out.size() != matches) out.clear();  // only a pattern every match of which is a channel file names a map
    return out;
  }
  if (!fs::is_directory(path, ec)) return out;
  for (const fs::path& p : listing(path)) {
    if (fs::is_directory(p, ec) && p.filename().string().rfind("Line", 0) == 0)
      for (const fs::path& q : listing(p)) take(q);
    else
      take(p);
  }
  return out;
}

std::unique_ptr<CurveSource> open_asylum_map(const std::string& path, const std::vector<std::string>& files) {
  if (files.empty())
    throw InputError(path + ": holds no Asylum map export (LineLLLLPointPPPP<Channel>.ibw files, in LineLLLL folders or not)");
  return std::make_unique<AsylumMap>(path, files);
}

}  // namespace layerjkr::detail
