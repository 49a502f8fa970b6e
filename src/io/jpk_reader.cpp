// JPK force archives (.jpk-force, .jpk-force-map, .jpk-qi-data, .jpk-qi-series): see instrument.hpp for the
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
#include "io/jpk_segment.hpp"
#include "layerjkr/error.hpp"

namespace layerjkr::detail {
namespace {

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

// The first value whose key ends in `suffix` (headers prefix keys by the scan type).
std::optional<std::string_view> find_suffix(const Properties& p, std::string_view suffix) {
  for (const auto& [k, v] : p)
    if (ends_with(k, suffix)) return v;
  return std::nullopt;
}

// The value of the first key ending in `suffix` as a finite number, or `fallback` if no key does.
double suffix_number(const Reader& in, const Properties& p, const std::string& suffix, double fallback,
                     const std::string& where) {
  const std::optional<std::string_view> v = find_suffix(p, suffix);
  return v ? in.to_number(suffix.substr(1), *v, where) : fallback;
}

// The same as a whole number in [lo, hi] (a float-to-int conversion out of range is undefined).
int suffix_int(const Reader& in, const Properties& p, const std::string& suffix, int fallback, double lo, double hi,
               const std::string& where) {
  const std::optional<std::string_view> v = find_suffix(p, suffix);
  return v ? static_cast<int>(in.whole(suffix.substr(1), *v, lo, hi, where)) : fallback;
}

// The map grid of the top header: every value present and finite, the shape at least one
// pixel, the size positive, so that the pixel of a position is always defined.
void read_grid(const Reader& in, const Properties& top, InstrumentFile& file) {
  if (!find_suffix(top, ".position-pattern.grid.ilength")) return;
  const std::string where = "header.properties";
  auto need = [&](const std::string& suffix) {
    const std::optional<std::string_view> v = find_suffix(top, suffix);
    if (!v) in.fail(where, "the map grid has no '*" + suffix + "'");
    return *v;
  };
  auto shape = [&](const std::string& suffix) {
    return static_cast<int>(in.whole(suffix.substr(1), need(suffix), 1, 1e6, where));
  };
  auto size = [&](const std::string& suffix) {
    const double v = in.to_number(suffix.substr(1), need(suffix), where);
    if (!(v > 0.0)) in.fail(where, "'" + suffix.substr(1) + "' = '" + std::string(need(suffix)) + "' must be > 0 (m)");
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
    if (const std::optional<std::string_view> v = find_suffix(header, ".description.instrument")) file.instrument = *v;
  if (file.software.empty())
    if (const std::optional<std::string_view> v = find_suffix(header, ".description.source-software"))
      file.software = *v;
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

  InstrumentCurve curve(std::size_t i, const CurveChannels& channels) const override {
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
      curve.segments.push_back(read_segment(in_, shared_, p + "segments/" + std::to_string(s) + "/", curve, channels));
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
