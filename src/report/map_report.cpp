// The force-map report: the batch's results as JSON, put into the page template with the
// embedded plotting library (assets.hpp), and the directory it goes to.
#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <string_view>
#include <system_error>

#include <unistd.h>
#include <nlohmann/json.hpp>

#include "layerjkr/error.hpp"
#include "layerjkr/text.hpp"
#include "layerjkr/map_report.hpp"
#include "report/assets.hpp"

namespace layerjkr {
namespace {

using nlohmann::json;
namespace fs = std::filesystem;

// A map grid is drawn as a grid while it has at most this many pixels per curve on it (or
// kMinGridCells in all); beyond, its curves are shown by index.
constexpr double kMaxEmptyCellsPerCurve = 16.0;
constexpr double kMinGridCells = 4096.0;

// How every page starts: prepare_report_dir recognises a previous report by it.
constexpr std::string_view kPageStart = "<!DOCTYPE html>\n<!-- layerjkr force-map report";

std::string name_of(FitParameter p) { return to_string(p); }

json number(double v) { return std::isfinite(v) ? json(v) : json(nullptr); }
json printable_list(const std::vector<std::string>& messages) {
  json out = json::array();
  for (const std::string& m : messages) out.push_back(printable(m));
  return out;
}
json index_or_null(int v) { return v >= 0 ? json(v) : json(nullptr); }

// The file an item came from: fit_files names a curve of a file of several `path#curve`.
std::string file_of(const BatchItem& it) {
  if (it.curve < 0) return it.source;
  const std::string tail = "#" + std::to_string(it.curve);
  const std::string& s = it.source;
  if (s.size() > tail.size() && s.compare(s.size() - tail.size(), tail.size(), tail) == 0)
    return s.substr(0, s.size() - tail.size());
  return s;
}

std::string base64(const std::vector<std::uint8_t>& bytes) {
  static const char* const alphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((bytes.size() + 2) / 3 * 4);
  for (std::size_t i = 0; i < bytes.size(); i += 3) {
    const std::uint32_t b0 = bytes[i], b1 = i + 1 < bytes.size() ? bytes[i + 1] : 0,
                        b2 = i + 2 < bytes.size() ? bytes[i + 2] : 0;
    const std::uint32_t v = (b0 << 16) | (b1 << 8) | b2;
    out += alphabet[(v >> 18) & 63];
    out += alphabet[(v >> 12) & 63];
    out += i + 1 < bytes.size() ? alphabet[(v >> 6) & 63] : '=';
    out += i + 2 < bytes.size() ? alphabet[v & 63] : '=';
  }
  return out;
}

// 16-bit codes of `values` over [lo, hi]: 0 .. 65534 linearly, 65535 for a non-finite value.
std::string codes(const std::vector<double>& values, double lo, double hi) {
  std::vector<std::uint8_t> bytes;
  bytes.reserve(2 * values.size());
  for (double v : values) {
    std::uint16_t c = 65535;
    if (std::isfinite(v)) c = hi > lo ? static_cast<std::uint16_t>(std::lround((v - lo) / (hi - lo) * 65534.0)) : 0;
    bytes.push_back(static_cast<std::uint8_t>(c & 0xff));
    bytes.push_back(static_cast<std::uint8_t>(c >> 8));
  }
  return base64(bytes);
}

// [lo, hi] of the finite values of `a` and `b`; [0, 0] for none.
std::pair<double, double> range_of(const std::vector<double>& a, const std::vector<double>& b = {}) {
  double lo = INFINITY, hi = -INFINITY;
  for (const auto* v : {&a, &b})
    for (double x : *v)
      if (std::isfinite(x)) {
        lo = std::min(lo, x);
        hi = std::max(hi, x);
      }
  return lo <= hi ? std::make_pair(lo, hi) : std::make_pair(0.0, 0.0);
}

// A curve's samples for the page: fitted (P_fit aligned, indentation from `delta0`) or, for
// one that failed, as read (no P_fit, no delta0: the page plots the data's displacement).
json curve_of(const FitSummary& full, std::size_t max_points, bool fitted) {
  const bool with_fit = fitted && full.P_fit.size() == full.delta.size();
  if (full.delta.empty() || full.P.size() != full.delta.size() || (fitted && !with_fit)) return nullptr;
  FitSummary s;
  s.delta = full.delta;
  s.P = full.P;
  if (with_fit) s.P_fit = full.P_fit;
  s.excluded = full.excluded;
  thin_for_display(s, max_points);
  json c;
  c["n"] = full.points > 0 ? full.points : full.delta.size();
  const auto d = range_of(s.delta), p = range_of(s.P, s.P_fit);
  c["delta"] = {{"lo", d.first}, {"hi", d.second}, {"codes", codes(s.delta, d.first, d.second)}};
  c["P"] = {{"lo", p.first}, {"hi", p.second}, {"codes", codes(s.P, p.first, p.second)}};
  if (with_fit) {
    c["P_fit"] = {{"lo", p.first}, {"hi", p.second}, {"codes", codes(s.P_fit, p.first, p.second)}};
    c["delta0"] = number(full.model_delta0());
  } else {
    c["P_fit"] = nullptr;
    c["delta0"] = nullptr;
  }
  json spans = json::array();
  for (std::size_t i = 0; i < s.excluded.size(); ++i)
    if (s.excluded[i] && (i == 0 || !s.excluded[i - 1])) {
      std::size_t j = i;
      while (j + 1 < s.excluded.size() && s.excluded[j + 1]) ++j;
      spans.push_back({i, j});
    }
  c["excluded"] = std::move(spans);
  return c;
}

json views_of(const std::vector<BatchItem>& items) {
  json views = json::array();
  std::vector<char> placed(items.size(), 0);
  // Grid views, one per file with pixels, in the order the files first appear.
  std::vector<std::string> order;
  std::map<std::string, std::vector<std::size_t>> by_file;
  for (std::size_t i = 0; i < items.size(); ++i) {
    if (items[i].grid_x < 0 || items[i].grid_y < 0) continue;
    const std::string f = escape_bytes(file_of(items[i]));
    if (!by_file.count(f)) order.push_back(f);
    by_file[f].push_back(i);
  }
  std::size_t sparse = 0;
  for (const std::string& f : order) {
    const auto& members = by_file[f];
    int nx = 0, ny = 0;
    for (std::size_t i : members) {
      nx = std::max(nx, items[i].grid_x + 1);
      ny = std::max(ny, items[i].grid_y + 1);
    }
    // The grid a header announces is bounded by the curves present: a grid mostly empty (a
    // header's 1e6 x 1e6 over 4 curves) is not allocated; its curves go to the index view.
    if (static_cast<double>(nx) * ny > std::max(kMaxEmptyCellsPerCurve * static_cast<double>(members.size()), kMinGridCells)) {
      sparse += members.size();
      continue;
    }
    std::vector<long long> cells(static_cast<std::size_t>(nx) * static_cast<std::size_t>(ny), -1);
    for (std::size_t i : members) {
      auto& cell = cells[static_cast<std::size_t>(items[i].grid_y) * static_cast<std::size_t>(nx) +
                         static_cast<std::size_t>(items[i].grid_x)];
      if (cell >= 0) continue;  // a second curve on a pixel goes to the index view
      cell = static_cast<long long>(i);
      placed[i] = 1;
    }
    views.push_back({{"name", f}, {"kind", "grid"}, {"nx", nx}, {"ny", ny}, {"cells", cells}});
  }
  std::vector<long long> rest;
  for (std::size_t i = 0; i < items.size(); ++i)
    if (!placed[i]) rest.push_back(static_cast<long long>(i));
  if (!rest.empty()) {
    const auto nx = static_cast<std::size_t>(std::ceil(std::sqrt(static_cast<double>(rest.size())) - 1e-9));
    const std::size_t ny = (rest.size() + nx - 1) / nx;
    rest.resize(nx * ny, -1);
    views.push_back({{"name", sparse > 0   ? "curves by index (" + std::to_string(sparse) +
                                                 " on map grids too sparse to draw: a grid of more than " +
                                                 std::to_string(static_cast<int>(kMaxEmptyCellsPerCurve)) +
                                                 " pixels a curve)"
                              : views.empty() ? "all curves, by index"
                                              : "curves without a map pixel, by index"},
                     {"kind", "index"},
                     {"nx", nx},
                     {"ny", ny},
                     {"cells", rest}});
  }
  return views;
}

// Plain text for HTML element content.
std::string html_text(const std::string& s) {
  std::string out;
  for (char c : s) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

// Text that goes inside a <script> element must not end it or open a comment there.
void check_script_text(std::string_view text, const char* what) {
  std::string lower(text);
  std::transform(lower.begin(), lower.end(), lower.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (lower.find("</script") != std::string::npos || lower.find("<!--") != std::string::npos)
    throw Error(std::string("map report: the embedded ") + what + " holds '</script' or '<!--' and cannot be inlined");
}

}  // namespace

void MapReportOptions::validate() const {
  if (display_points < 8)
    throw DomainError("MapReportOptions", "display_points", static_cast<double>(display_points), ">= 8");
  for (std::size_t i = 0; i < free.size(); ++i)
    for (std::size_t j = 0; j < i; ++j)
      if (free[i] == free[j])
        throw InputError("MapReportOptions: free parameter " + name_of(free[i]) + " is listed twice");
}

std::string map_report_data(const std::vector<BatchItem>& items, const MapReportOptions& options) {
  options.validate();
  json columns;
  std::vector<std::string> names = {"file",       "curve",        "x",           "y",     "grid_x",
                                    "grid_y",     "status",       "error",       "model", "converged",
                                    "iterations", "rms_residual", "identifiable", "identifiability", "contact_point",
                                    "contact_point_err", "range_samples"};
  for (FitParameter p : options.free) {
    names.push_back(name_of(p));
    names.push_back(name_of(p) + "_stderr");
  }
  for (const char* extra : {"quality", "warnings", "notices", "unidentifiable", "termination", "points", "points_in_contact",
                            "excluded_count", "pull_off_force", "baseline_slope"})
    names.emplace_back(extra);
  for (const std::string& n : names) columns[n] = json::array();
  // The curves' JSON as text, item by item: as a DOM it would be most of the report's memory.
  std::string curves = "[";
  bool any_pull_off = false, any_slope = false, any_contact = false;
  for (const BatchItem& it : items) {
    const FitSummary& s = it.summary;
    const bool ok = it.ok;
    columns["file"].push_back(escape_bytes(it.source));  // as the results table writes it
    columns["curve"].push_back(index_or_null(it.curve));
    columns["x"].push_back(number(it.x));
    columns["y"].push_back(number(it.y));
    columns["grid_x"].push_back(index_or_null(it.grid_x));
    columns["grid_y"].push_back(index_or_null(it.grid_y));
    columns["status"].push_back(ok ? "ok" : "error");
    columns["error"].push_back(ok ? std::string() : it.skipped ? "skipped: fitted by an earlier run" : printable(it.error));
    columns["model"].push_back(ok ? json(s.model) : json(nullptr));
    columns["converged"].push_back(ok ? json(s.converged ? 1 : 0) : json(nullptr));
    columns["iterations"].push_back(ok ? json(s.iterations) : json(nullptr));
    columns["rms_residual"].push_back(ok ? number(s.rms_residual) : json(nullptr));
    columns["identifiable"].push_back(ok ? json(s.identifiable ? 1 : 0) : json(nullptr));
    // As fit-map's table writes them: the verdict with its reason, the found point.
    columns["identifiability"].push_back(ok ? json(printable(s.identifiability())) : json(nullptr));
    columns["contact_point"].push_back(ok ? number(s.contact_point.value) : json(nullptr));
    columns["contact_point_err"].push_back(ok ? number(s.contact_point.standard_error) : json(nullptr));
    columns["range_samples"].push_back(ok ? json(s.contact_point.samples_in_range) : json(nullptr));
    for (FitParameter p : options.free) {
      const auto e = std::find_if(s.parameters.begin(), s.parameters.end(),
                                  [p](const ParameterEstimate& q) { return q.parameter == p; });
      const bool has = ok && e != s.parameters.end();
      columns[name_of(p)].push_back(has ? number(e->value) : json(nullptr));
      columns[name_of(p) + "_stderr"].push_back(has ? number(e->standard_error) : json(nullptr));
    }
    columns["quality"].push_back(batch_quality(it));
    columns["warnings"].push_back(ok ? printable_list(s.warnings) : json::array());
    columns["notices"].push_back(ok ? printable_list(s.notices) : json::array());
    columns["unidentifiable"].push_back(ok ? json(s.unidentifiable) : json::array());
    columns["termination"].push_back(ok ? json(s.termination) : json(nullptr));
    columns["points"].push_back(ok ? json(s.points) : json(nullptr));
    columns["points_in_contact"].push_back(ok ? json(s.points_in_contact) : json(nullptr));
    columns["excluded_count"].push_back(ok ? json(s.excluded_count) : json(nullptr));
    columns["pull_off_force"].push_back(ok ? number(s.pull_off_force) : json(nullptr));
    columns["baseline_slope"].push_back(ok ? number(s.baseline_slope) : json(nullptr));
    any_pull_off = any_pull_off || (ok && std::isfinite(s.pull_off_force));
    any_slope = any_slope || (ok && s.baseline_slope != 0.0);
    any_contact = any_contact || (ok && std::isfinite(s.contact_point.value));
    if (curves.size() > 1) curves += ',';
    curves += curve_of(s, options.display_points, ok).dump();  // numbers and ASCII only
  }
  json fields = json::array();
  for (FitParameter p : options.free) {
    fields.push_back({{"key", name_of(p)}, {"label", name_of(p)}, {"unit", unit_of(p)}});
    fields.push_back({{"key", name_of(p) + "_stderr"}, {"label", name_of(p) + " standard error"}, {"unit", unit_of(p)}});
  }
  fields.push_back({{"key", "rms_residual"}, {"label", "rms residual"}, {"unit", "N"}});
  if (any_contact) fields.push_back({{"key", "contact_point"}, {"label", "contact point"}, {"unit", "m"}});
  fields.push_back({{"key", "iterations"}, {"label", "iterations"}, {"unit", ""}});
  fields.push_back({{"key", "points_in_contact"}, {"label", "samples in contact"}, {"unit", ""}});
  fields.push_back({{"key", "excluded_count"}, {"label", "excluded samples"}, {"unit", ""}});
  if (any_pull_off) fields.push_back({{"key", "pull_off_force"}, {"label", "pull-off force"}, {"unit", "N"}});
  if (any_slope) fields.push_back({{"key", "baseline_slope"}, {"label", "baseline slope"}, {"unit", "N/m"}});
  json free = json::array();
  for (FitParameter p : options.free) free.push_back(name_of(p));
  curves += ']';
  const json rest = {{"title", printable(options.title)}, {"subtitle", printable(options.subtitle)},
                     {"count", items.size()},    {"free", free},
                     {"fields", fields},         {"columns", columns},
                     {"views", views_of(items)}, {"display_points", options.display_points}};
  // File names and error texts may hold bytes that are not UTF-8 (a path, a binary file's
  // cells): replaced by U+FFFD, not an exception after the fitting.
  std::string text = rest.dump(-1, ' ', false, json::error_handler_t::replace);  // "{...}": the curves go in first
  return "{\"curves\":" + curves + "," + text.substr(1);
}

std::string map_report_html(const std::vector<BatchItem>& items, const MapReportOptions& options) {
  const std::string data = map_report_data(items, options);
  check_script_text(detail::kPlotlyJs, "plotting library");
  check_script_text(detail::kPageJs, "page script");
  check_script_text(detail::kPlotlyLicense, "licence");
  const std::map<std::string_view, std::string> parts = {{"TITLE", html_text(printable(options.title))},
                                                         {"SUBTITLE", html_text(printable(options.subtitle))},
                                                         {"CSS", std::string(detail::kPageCss)},
                                                         {"PLOTLY", std::string(detail::kPlotlyJs)},
                                                         {"PLOTLY_LICENSE", std::string(detail::kPlotlyLicense)},
                                                         {"SCRIPT", std::string(detail::kPageJs)}};
  const std::string_view page = detail::kPageHtml;
  if (page.substr(0, kPageStart.size()) != kPageStart) throw Error("map report: the page template lost its first line");
  std::string out;
  out.reserve(page.size() + detail::kPlotlyJs.size() + data.size() + detail::kPageJs.size() + 4096);
  std::size_t at = 0;
  for (;;) {
    const std::size_t open = page.find("{{", at);
    if (open == std::string_view::npos) break;
    const std::size_t close = page.find("}}", open);
    if (close == std::string_view::npos) break;
    const std::string_view field = page.substr(open + 2, close - open - 2);
    out.append(page.substr(at, open - at));
    if (field == "DATA") {
      // '<' occurs only inside JSON strings, where \u003c means the same: nothing in the data
      // can close the script element that holds it. Appended as it goes: a 128 x 128 map's data
      // is 20 MB.
      for (char c : data) {
        if (c == '<')
          out.append("\\u003c");
        else
          out.push_back(c);
      }
    } else {
      const auto part = parts.find(field);
      if (part == parts.end()) throw Error("map report: unknown template field {{" + std::string(field) + "}}");
      out += part->second;
    }
    at = close + 2;
  }
  out.append(page.substr(at));
  return out;
}

std::string map_report_page(const std::string& dir) { return (fs::path(dir) / "index.html").string(); }

void prepare_report_dir(const std::string& dir, const std::string& flag, const std::vector<std::string>& also) {
  const std::string name = flag + " " + dir;
  if (dir.empty()) throw InputError(flag + ": the directory name is empty");
  std::error_code ec;
  const fs::file_status st = fs::status(dir, ec);
  if (fs::exists(st) && !fs::is_directory(st))
    throw InputError(name + ": exists and is not a directory (the report is a directory holding index.html)");
  if (!fs::exists(st)) {
    fs::create_directories(dir, ec);
    if (ec) throw InputError(name + ": cannot create the directory (" + ec.message() + ")");
  } else {
    std::vector<std::string> others;
    for (fs::directory_iterator e(dir, ec), end; !ec && e != end; e.increment(ec)) {
      const std::string entry = e->path().filename().string();
      std::error_code same_ec;
      const fs::path here = fs::weakly_canonical(e->path(), same_ec);
      if (std::any_of(also.begin(), also.end(), [&](const std::string& a) {
            std::error_code a_ec;
            return !same_ec && fs::weakly_canonical(a, a_ec) == here && !a_ec;
          }))
        continue;  // the caller's own output
      if (entry == "index.html" && e->is_regular_file()) {
        std::ifstream f(e->path(), std::ios::binary);
        std::string start(kPageStart.size(), '\0');
        f.read(start.data(), static_cast<std::streamsize>(start.size()));
        if (f && start == kPageStart) continue;  // a previous report, replaced
      }
      others.push_back(entry);
    }
    if (ec) throw InputError(name + ": cannot list the directory (" + ec.message() + ")");
    if (!others.empty()) {
      std::sort(others.begin(), others.end());
      std::string list;
      for (std::size_t i = 0; i < others.size() && i < 3; ++i) list += (i ? ", " : "") + others[i];
      if (others.size() > 3) list += ", ...";
      throw InputError(name + ": the directory is not empty and is not a previous report (it holds " + list +
                       "); a report goes to a new or empty directory, or replaces one that holds only its index.html");
    }
  }
  std::string probe = (fs::path(dir) / ".layerjkr-probe.XXXXXX").string();
  const int fd = mkstemp(probe.data());
  if (fd < 0)
    throw InputError(name + ": cannot write in the directory (" + std::generic_category().message(errno) + ")");
  close(fd);
  unlink(probe.c_str());
}

}  // namespace layerjkr
