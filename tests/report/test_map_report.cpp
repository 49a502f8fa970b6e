// The force-map report's library side: the thinning rule's guarantees (checked against a
// brute-force reading of the rule on random curves), the batch's opt-in thinned copies (a
// subsequence of the full fit's samples), the embedded data (equal to the items' values, bit
// for bit; the layout; the 16-bit curves within their quantum) and the report directory rule.
#include <catch2/catch.hpp>

#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <random>

#include <nlohmann/json.hpp>

#include "layerjkr/error.hpp"
#include "layerjkr/fit.hpp"
#include "layerjkr/map_report.hpp"
#include "layerjkr/scene.hpp"
#include "layerjkr/simulate.hpp"
#include "support/temp_dir.hpp"

using namespace layerjkr;
using nlohmann::json;
namespace fs = std::filesystem;

namespace {

struct Curve {
  std::vector<double> P, P_fit;
  std::vector<bool> excluded;
};

// Noise, spikes and a few excluded spans.
Curve random_curve(std::size_t n, std::mt19937& rng) {
  std::normal_distribution<double> noise(0.0, 1.0);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  Curve c;
  c.P.resize(n);
  c.P_fit.resize(n);
  c.excluded.assign(n, false);
  for (std::size_t i = 0; i < n; ++i) {
    const double x = static_cast<double>(i) / static_cast<double>(n);
    c.P_fit[i] = x > 0.5 ? 100.0 * (x - 0.5) * (x - 0.5) : 0.0;
    c.P[i] = c.P_fit[i] + noise(rng) + (u(rng) < 0.003 ? 40.0 * (u(rng) - 0.5) : 0.0);
  }
  const int spans = static_cast<int>(u(rng) * 4);
  for (int s = 0; s < spans; ++s) {
    const auto a = static_cast<std::size_t>(u(rng) * static_cast<double>(n));
    const auto b = std::min(n, a + 1 + static_cast<std::size_t>(u(rng) * 0.2 * static_cast<double>(n)));
    for (std::size_t i = a; i < b; ++i) c.excluded[i] = true;
  }
  return c;
}

double lowest(const std::vector<double>& v, std::size_t a, std::size_t b) {
  return *std::min_element(v.begin() + static_cast<long>(a), v.begin() + static_cast<long>(b));
}
double highest(const std::vector<double>& v, std::size_t a, std::size_t b) {
  return *std::max_element(v.begin() + static_cast<long>(a), v.begin() + static_cast<long>(b));
}

// An item of a batch with every field set: `k` makes its values distinct.
BatchItem fitted_item(const std::string& source, int curve, int gx, int gy, double k) {
  BatchItem it;
  it.source = source;
  it.ok = true;
  it.curve = curve;
  it.grid_x = gx;
  it.grid_y = gy;
  it.x = gx >= 0 ? 1e-6 * gx + 1e-7 / 3.0 : std::nan("");
  it.y = gy >= 0 ? 2e-6 * gy : std::nan("");
  FitSummary& s = it.summary;
  s.converged = true;
  s.identifiable = true;  // a verdict is false until a fit has earned it (FitSummary)
  s.identifiability_known = true;
  s.iterations = 7 + static_cast<int>(k);
  s.model = "half_space";
  s.rms_residual = 1.234567890123e-11 * (1 + k);
  s.termination = "Function tolerance reached";
  s.points = 1000;
  s.points_in_contact = 400;
  s.excluded_count = 3;
  s.pull_off_force = -2e-9 * k;
  ParameterEstimate E, d0;
  E.parameter = FitParameter::E;
  E.value = 1.0e4 / 3.0 * (1 + k);
  E.standard_error = 12.3456789 * (1 + k);
  d0.parameter = FitParameter::delta0;
  d0.value = -3.3e-7 - 1e-9 / 7.0 * k;
  d0.standard_error = std::nan("");  // no error bar: null, as the CSV's empty cell
  s.parameters = {E, d0};
  const std::size_t n = 1000;
  for (std::size_t i = 0; i < n; ++i) {
    const double x = 1e-9 * static_cast<double>(i);
    s.delta.push_back(x);
    s.P_fit.push_back(x > 5e-7 ? 1e3 * (x - 5e-7) : 0.0);
    s.P.push_back(s.P_fit.back() + 1e-11 * std::sin(static_cast<double>(i)));
    s.excluded.push_back(i >= 990 || (i >= 100 && i < 103));
  }
  return it;
}

// The curve's 16-bit codes back to values (what the page's decode does).
std::vector<double> decode(const json& e) {
  static const std::string alphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  const std::string text = e["codes"];
  std::vector<std::uint8_t> bytes;
  std::uint32_t acc = 0;
  int bits = 0;
  for (char c : text) {
    if (c == '=') break;
    acc = (acc << 6) | static_cast<std::uint32_t>(alphabet.find(c));
    bits += 6;
    if (bits >= 8) {
      bits -= 8;
      bytes.push_back(static_cast<std::uint8_t>((acc >> bits) & 0xff));
    }
  }
  const double lo = e["lo"], hi = e["hi"];
  std::vector<double> out;
  for (std::size_t i = 0; i + 1 < bytes.size(); i += 2) {
    const int code = bytes[i] | (bytes[i + 1] << 8);
    out.push_back(code == 65535 ? std::nan("") : lo + (hi - lo) * code / 65534.0);
  }
  return out;
}

}  // namespace

TEST_CASE("display_samples keeps every curve of at most max_points samples whole", "[report][thinning]") {
  std::mt19937 rng(3);
  for (std::size_t n : {0, 1, 8, 199, 200}) {
    const Curve c = random_curve(n, rng);
    const auto keep = display_samples(c.P, c.P_fit, c.excluded, 200);
    REQUIRE(keep.size() == n);
    for (std::size_t i = 0; i < n; ++i) CHECK(keep[i] == i);
  }
}

TEST_CASE("display_samples: bins keep their ranges of P and residual, excluded spans their ends, within the bound",
          "[report][thinning]") {
  std::mt19937 rng(11);
  for (int trial = 0; trial < 200; ++trial) {
    const std::size_t n = 201 + static_cast<std::size_t>(rng() % 5000);
    const std::size_t max_points = 8 + static_cast<std::size_t>(rng() % 300);
    Curve c = random_curve(n, rng);
    if (trial % 5 == 0) c.excluded.clear();  // none excluded: an empty flag vector
    const auto keep = display_samples(c.P, c.P_fit, c.excluded, max_points);
    INFO("n " << n << " max_points " << max_points);
    REQUIRE(std::is_sorted(keep.begin(), keep.end()));
    REQUIRE(std::adjacent_find(keep.begin(), keep.end()) == keep.end());
    REQUIRE(!keep.empty());
    CHECK(keep.front() == 0);
    CHECK(keep.back() == n - 1);
    std::size_t changes = 0;
    for (std::size_t i = 1; i < c.excluded.size(); ++i) {
      if (c.excluded[i] == c.excluded[i - 1]) continue;
      ++changes;
      CHECK(std::binary_search(keep.begin(), keep.end(), i - 1));
      CHECK(std::binary_search(keep.begin(), keep.end(), i));
    }
    CHECK(keep.size() <= max_points + 2 * changes);
    if (n > max_points) CHECK(keep.size() < n);
    std::vector<double> r(n);
    for (std::size_t i = 0; i < n; ++i) r[i] = c.P[i] - c.P_fit[i];
    const std::size_t bins = (max_points - 2) / 4;
    for (std::size_t b = 0; b < bins; ++b) {
      const std::size_t lo = b * n / bins, hi = (b + 1) * n / bins;
      std::vector<double> kp, kr;
      for (std::size_t i : keep)
        if (i >= lo && i < hi) {
          kp.push_back(c.P[i]);
          kr.push_back(r[i]);
        }
      REQUIRE(!kp.empty());
      CHECK(lowest(kp, 0, kp.size()) == lowest(c.P, lo, hi));
      CHECK(highest(kp, 0, kp.size()) == highest(c.P, lo, hi));
      CHECK(lowest(kr, 0, kr.size()) == lowest(r, lo, hi));
      CHECK(highest(kr, 0, kr.size()) == highest(r, lo, hi));
    }
  }
}

TEST_CASE("display_samples skips NaN as an extreme and rejects bad arguments", "[report][thinning][errors]") {
  std::vector<double> P(1000, 1.0), P_fit(1000, 0.0);
  for (std::size_t i = 0; i < P.size(); i += 2) P[i] = std::nan("");
  P[501] = 5.0;
  const auto keep = display_samples(P, P_fit, {}, 10);
  CHECK(std::binary_search(keep.begin(), keep.end(), std::size_t{501}));
  for (std::size_t i : keep)
    if (i != 0 && i != 999) CHECK(!std::isnan(P[i]));
  CHECK_THROWS_AS(display_samples(P, P_fit, {}, 7), DomainError);
  CHECK_THROWS_AS(display_samples(P, std::vector<double>(3), {}, 10), InputError);
  CHECK_THROWS_AS(display_samples(P, P_fit, std::vector<bool>(3), 10), InputError);
}

TEST_CASE("fit_batch with display_points keeps a thinned subsequence of each fit's samples",
          "[report][thinning][fit]") {
  const Scene scene = parse_scene(R"({"indenter": {"shape": "paraboloid", "R": 1e-6},
      "medium": {"type": "half_space", "E": 1e5, "nu": 0.5}, "w": 0.0})");
  SimulationOptions so;
  so.branch = Branch::approach;
  so.points_per_branch = 3000;
  so.max_indentation = 5e-7;
  so.noise = 1e-10;
  std::vector<CurveData> curves;
  for (std::uint64_t seed = 1; seed <= 3; ++seed) {
    so.seed = seed;
    curves.push_back(simulate_curve(scene, so));
  }
  FitOptions o;
  o.free = {FitParameter::E, FitParameter::delta0};
  BatchOptions b;
  b.jobs = 2;
  b.display_points = 100;
  const auto items = fit_batch(curves, scene, o, b);
  b.display_points = 0;
  const auto bare = fit_batch(curves, scene, o, b);
  for (std::size_t k = 0; k < curves.size(); ++k) {
    REQUIRE(items[k].ok);
    const FitSummary full = fit(curves[k], scene, o);
    const FitSummary& s = items[k].summary;
    CHECK(bare[k].summary.delta.empty());
    CHECK(s[FitParameter::E].value == full[FitParameter::E].value);
    REQUIRE(full.delta.size() == 3000);
    const auto keep = display_samples(full.P, full.P_fit, full.excluded, 100);
    REQUIRE(s.delta.size() == keep.size());
    CHECK(s.delta.size() <= 100);
    for (std::size_t j = 0; j < keep.size(); ++j) {
      CHECK(s.delta[j] == full.delta[keep[j]]);
      CHECK(s.P[j] == full.P[keep[j]]);
      CHECK(s.P_fit[j] == full.P_fit[keep[j]]);
    }
  }
  b.display_points = 7;
  CHECK_THROWS_AS(fit_batch(curves, scene, o, b), DomainError);
}

TEST_CASE("map_report_data holds the items' values exactly, their layout and their curves", "[report]") {
  std::vector<BatchItem> items;
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 4; ++i)
      items.push_back(fitted_item("a.jpk-qi-data#" + std::to_string(4 * j + i), 4 * j + i, i, j, 4 * j + i));
  items[5].summary.converged = false;
  items[6].summary.identifiable = false;
  items[6].summary.unidentifiable = {"E, delta0"};
  items[7].summary.warnings = {"a warning"};
  items[8].summary.warnings = {"a warning"};
  items[8].summary.converged = false;  // the first that applies: not converged
  BatchItem failed;
  failed.source = "a.jpk-qi-data#12";
  failed.curve = 12;
  failed.error = "cannot read curve 12: <bad> \"data\"";
  items.push_back(failed);  // no pixel: the index view
  items.push_back(fitted_item("b.csv", -1, -1, -1, 13));
  items.push_back(fitted_item("c.jpk-force-map#0", 0, 0, 0, 14));  // a second map
  items.back().summary.delta.clear();                              // fitted without samples kept: no curve
  MapReportOptions r;
  r.free = {FitParameter::E, FitParameter::delta0};
  const json d = json::parse(map_report_data(items, r));
  const json& c = d["columns"];
  REQUIRE(d["count"] == items.size());
  for (std::size_t i = 0; i < items.size(); ++i) {
    const BatchItem& it = items[i];
    INFO("item " << i);
    CHECK(c["file"][i] == it.source);
    CHECK(c["status"][i] == (it.ok ? "ok" : "error"));
    CHECK(c["error"][i] == it.error);
    if (!it.ok) {
      for (const char* k : {"model", "converged", "iterations", "rms_residual", "identifiable", "E", "E_stderr"})
        CHECK(c[k][i].is_null());
      CHECK(c["quality"][i] == "failed");
      continue;
    }
    CHECK(c["rms_residual"][i].get<double>() == it.summary.rms_residual);
    CHECK(c["E"][i].get<double>() == it.summary.parameters[0].value);
    CHECK(c["E_stderr"][i].get<double>() == it.summary.parameters[0].standard_error);
    CHECK(c["delta0"][i].get<double>() == it.summary.parameters[1].value);
    CHECK(c["delta0_stderr"][i].is_null());
    CHECK(c["iterations"][i] == it.summary.iterations);
    CHECK(c["converged"][i] == (it.summary.converged ? 1 : 0));
    if (it.grid_x >= 0) {
      CHECK(c["x"][i].get<double>() == it.x);
      CHECK(c["grid_x"][i] == it.grid_x);
    } else {
      CHECK(c["x"][i].is_null());
      CHECK(c["grid_x"][i].is_null());
    }
    CHECK(c["pull_off_force"][i].get<double>() == it.summary.pull_off_force);
  }
  CHECK(c["quality"][0] == "ok");
  CHECK(c["quality"][5] == "not converged");
  CHECK(c["quality"][6] == "not identifiable");
  CHECK(c["unidentifiable"][6] == json::array({"E, delta0"}));
  CHECK(c["quality"][7] == "warning");
  CHECK(c["quality"][8] == "not converged");
  // Layout: map a as 4 x 3 pixels, map c as 1 x 1, the rest by index (2 items: 2 x 1).
  const json& v = d["views"];
  REQUIRE(v.size() == 3);
  CHECK(v[0]["name"] == "a.jpk-qi-data");
  CHECK(v[0]["nx"] == 4);
  CHECK(v[0]["ny"] == 3);
  for (int k = 0; k < 12; ++k) CHECK(v[0]["cells"][k] == k);
  CHECK(v[1]["name"] == "c.jpk-force-map");
  CHECK(v[1]["cells"] == json::array({14}));
  CHECK(v[2]["kind"] == "index");
  CHECK(v[2]["nx"] == 2);
  CHECK(v[2]["cells"] == json::array({12, 13}));
  // Curves: the thinned samples within half a 16-bit quantum of their range, excluded spans.
  CHECK(d["curves"][12].is_null());
  CHECK(d["curves"][14].is_null());
  const FitSummary& s0 = items[0].summary;
  const auto keep = display_samples(s0.P, s0.P_fit, s0.excluded, r.display_points);
  const json& c0 = d["curves"][0];
  CHECK(c0["n"] == 1000);
  const auto delta = decode(c0["delta"]), P = decode(c0["P"]), P_fit = decode(c0["P_fit"]);
  REQUIRE(delta.size() == keep.size());
  const double qd = (c0["delta"]["hi"].get<double>() - c0["delta"]["lo"].get<double>()) / 65534.0;
  const double qp = (c0["P"]["hi"].get<double>() - c0["P"]["lo"].get<double>()) / 65534.0;
  for (std::size_t j = 0; j < keep.size(); ++j) {
    CHECK(std::abs(delta[j] - s0.delta[keep[j]]) <= 0.5 * qd * (1 + 1e-9));
    CHECK(std::abs(P[j] - s0.P[keep[j]]) <= 0.5 * qp * (1 + 1e-9));
    CHECK(std::abs(P_fit[j] - s0.P_fit[keep[j]]) <= 0.5 * qp * (1 + 1e-9));
  }
  std::vector<bool> flagged(keep.size(), false);
  for (const auto& span : c0["excluded"])
    for (std::size_t j = span[0]; j <= span[1].get<std::size_t>(); ++j) flagged[j] = true;
  for (std::size_t j = 0; j < keep.size(); ++j) CHECK(flagged[j] == s0.excluded[keep[j]]);
  // Fields: each free parameter and its error, rms, iterations, samples, pull-off (set here).
  std::vector<std::string> keys;
  for (const auto& f : d["fields"]) keys.push_back(f["key"]);
  CHECK(keys == std::vector<std::string>{"E", "E_stderr", "delta0", "delta0_stderr", "rms_residual", "iterations",
                                         "points_in_contact", "excluded_count", "pull_off_force"});
}

TEST_CASE("map_report_html is one page with the data inline, unbreakable by the text it holds", "[report]") {
  std::vector<BatchItem> items;
  BatchItem failed;
  failed.source = "x</script><script>alert(1)</script><!--.csv";
  failed.error = "</SCRIPT> <!-- in the error, and bytes that are not UTF-8: \xff\xfe";
  items.push_back(failed);
  items.push_back(fitted_item("y.csv", -1, -1, -1, 1));
  MapReportOptions r;
  r.free = {FitParameter::E, FitParameter::delta0};
  r.title = "a <b>title</b> & more";
  const std::string html = map_report_html(items, r);
  CHECK(html.rfind("<!DOCTYPE html>\n<!-- layerjkr force-map report", 0) == 0);
  // The data element, found by its opening tag and the first closing tag after it, is the data.
  const std::string open = "<script type=\"application/json\" id=\"layerjkr-data\">";
  const std::size_t a = html.find(open);
  REQUIRE(a != std::string::npos);
  const std::size_t b = html.find("</script>", a);
  REQUIRE(b != std::string::npos);
  CHECK(json::parse(html.substr(a + open.size(), b - a - open.size())) == json::parse(map_report_data(items, r)));
  CHECK(html.find("<title>a &lt;b&gt;title&lt;/b&gt; &amp; more</title>") != std::string::npos);
  CHECK(json::parse(map_report_data(items, r))["columns"]["error"][0] ==
        "</SCRIPT> <!-- in the error, and bytes that are not UTF-8: \\xff\\xfe");  // escaped, not lost
  // Self-contained: nothing is loaded from elsewhere.
  for (const char* ref : {" src=", " href=", "@import", "<link"}) CHECK(html.find(ref) == std::string::npos);
  CHECK(html.find("Content-Security-Policy\" content=\"default-src 'none'") != std::string::npos);
  CHECK(html.find("Permission is hereby granted") != std::string::npos);  // plotly.js's MIT licence
  MapReportOptions bad = r;
  bad.display_points = 7;
  CHECK_THROWS_AS(map_report_html(items, bad), DomainError);
  bad = r;
  bad.free = {FitParameter::E, FitParameter::E};
  CHECK_THROWS_AS(map_report_data(items, bad), InputError);
}

TEST_CASE("prepare_report_dir takes a new or empty directory or an earlier report, never a file or other files",
          "[report][errors]") {
  const test::TempDir tmp;
  const std::string fresh = tmp.file("a/b/report");
  prepare_report_dir(fresh, "--report");
  CHECK(fs::is_directory(fresh));
  CHECK(fs::is_empty(fresh));             // the writability probe is gone
  prepare_report_dir(fresh, "--report");  // empty: fine
  std::ofstream(map_report_page(fresh)) << map_report_html({}, MapReportOptions{});
  prepare_report_dir(fresh, "--report");  // an earlier report: fine
  auto message = [](const std::string& dir) {
    try {
      prepare_report_dir(dir, "--report");
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  std::ofstream(tmp.file("a/b/report/notes.txt")) << "mine";
  prepare_report_dir(fresh, "--report", {tmp.file("a/b/report/notes.txt")});  // the caller's own output
  prepare_report_dir(fresh, "--report", {tmp.file("a/b/../b/report/notes.txt")});
  const std::string other = message(fresh);
  CHECK(other.find("--report " + fresh +
                   ": the directory is not empty and is not a previous report (it holds notes.txt)") == 0);
  const std::string page_only = tmp.file("page");
  fs::create_directories(page_only);
  std::ofstream(map_report_page(page_only)) << "<html>someone else's</html>";
  CHECK(message(page_only).find("(it holds index.html)") != std::string::npos);
  const std::string file = tmp.file("file.txt");
  std::ofstream(file) << "x";
  CHECK(message(file) ==
        "--report " + file + ": exists and is not a directory (the report is a directory holding index.html)");
  CHECK(message(file + "/sub").find("--report " + file + "/sub: cannot create the directory") == 0);
  CHECK(message("") == "--report: the directory name is empty");
  if (::geteuid() != 0) {  // root writes anywhere
    const std::string locked = tmp.file("locked");
    fs::create_directories(locked);
    fs::permissions(locked, fs::perms::owner_read | fs::perms::owner_exec);
    CHECK(message(locked).find("cannot write in the directory") != std::string::npos);
    fs::permissions(locked, fs::perms::owner_all);
  }
}
