// Instrument readers against ../shared/data/instrument/reference.json (values confirmed by
// afmformats' tests and by CSV exports; README there): every curve, segment, calibration,
// map position and sum. Skipped, not failed, when ../shared is absent. The bad-input suite
// builds truncated, corrupt and wrong-format files in a temporary directory.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <numeric>

#include <nlohmann/json.hpp>

#include "layerjkr/error.hpp"
#include "layerjkr/instrument.hpp"
#include "support/temp_dir.hpp"
#include "support/test_support.hpp"

using namespace layerjkr;
using test::rel_err;

namespace {

const std::string kDir = std::string(LAYERJKR_SOURCE_DIR) + "/../shared/data/instrument/";
bool have_data() { return std::ifstream(kDir + "reference.json").good(); }
nlohmann::json reference() { return nlohmann::json::parse(std::ifstream(kDir + "reference.json")); }

double sum(const std::vector<double>& v) { return std::accumulate(v.begin(), v.end(), 0.0); }
double min_of(const std::vector<double>& v) { return *std::min_element(v.begin(), v.end()); }
double max_of(const std::vector<double>& v) { return *std::max_element(v.begin(), v.end()); }

std::string write(const test::TempDir& dir, const std::string& name, const std::string& bytes) {
  const std::string path = dir.file(name);
  std::ofstream(path, std::ios::binary) << bytes;
  return path;
}

}  // namespace

TEST_CASE("JPK archives: every reference value (single, shared-data, force map, QI)", "[io][instrument]") {
  if (!have_data()) {
    test::report_skip(kDir + " is absent (the shared data beside the repository)");
    return;
  }
  const nlohmann::json ref = reference()["files"];
  int files = 0;
  for (const auto& [name, r] : ref.items()) {
    if (name.find(".ibw") != std::string::npos) continue;
    ++files;
    const InstrumentFile f = read_instrument_file(kDir + name);
    INFO(name);
    CHECK(f.instrument == r["instrument"].get<std::string>());
    CHECK(f.software == r["software_version"].get<std::string>());
    REQUIRE(f.curves.size() == r["n_curves"].get<std::size_t>());
    if (r.contains("grid")) {
      CHECK(f.grid_shape_x == r["grid"]["shape_x"].get<int>());
      CHECK(f.grid_shape_y == r["grid"]["shape_y"].get<int>());
      CHECK(f.grid_size_x == r["grid"]["size_x"].get<double>());
      CHECK(f.grid_center_y == r["grid"]["center_y"].get<double>());
    }
    for (std::size_t c = 0; c < f.curves.size(); ++c) {
      const InstrumentCurve& curve = f.curves[c];
      const auto& rc = r["curves"][c];
      INFO("curve " << c);
      CHECK(curve.index == rc["enum"].get<int>());
      CHECK(curve.position_index == rc["position_index"].get<int>());
      CHECK(curve.x == rc["position_x_m"].get<double>());
      CHECK(curve.y == rc["position_y_m"].get<double>());
      if (rc.contains("grid_index_x")) {
        CHECK(curve.grid_x == rc["grid_index_x"].get<int>());
        CHECK(curve.grid_y == rc["grid_index_y"].get<int>());
      }
      REQUIRE(curve.segments.size() == rc["n_segments"].get<std::size_t>());
      for (std::size_t s = 0; s < curve.segments.size(); ++s) {
        const InstrumentSegment& seg = curve.segments[s];
        const auto& rs = rc["segments"][s];
        INFO("segment " << s);
        CHECK(to_string(seg.style) == rs["style"].get<std::string>());
        REQUIRE(seg.force.size() == rs["n_points"].get<std::size_t>());
        CHECK(seg.duration == rs["duration_s"].get<double>());
        CHECK(curve.spring_constant == rs["spring_constant_N_per_m"].get<double>());
        CHECK(curve.sensitivity == rs["sensitivity_m_per_V"].get<double>());
        // Bit-identical: each step m*x + o rounded separately, as the format defines it.
        CHECK(seg.force.front() == rs["force_N_first"].get<double>());
        CHECK(seg.force.back() == rs["force_N_last"].get<double>());
        CHECK(min_of(seg.force) == rs["force_N_min"].get<double>());
        CHECK(max_of(seg.force) == rs["force_N_max"].get<double>());
        CHECK(rel_err(sum(seg.force), rs["force_N_sum"].get<double>()) < 1e-12);
        CHECK(seg.height.front() == rs["height_measured_m_first"].get<double>());
        CHECK(seg.height.back() == rs["height_measured_m_last"].get<double>());
        CHECK(min_of(seg.height) == rs["height_measured_m_min"].get<double>());
        CHECK(rel_err(sum(seg.height), rs["height_measured_m_sum"].get<double>()) < 1e-12);
        CHECK(seg.piezo_height.front() == rs["height_piezo_m_first"].get<double>());
        CHECK(seg.piezo_height.back() == rs["height_piezo_m_last"].get<double>());
        CHECK(rel_err(sum(seg.piezo_height), rs["height_piezo_m_sum"].get<double>()) < 1e-12);
      }
    }
  }
  CHECK(files == 4);
}

TEST_CASE("Igor waves: calibration from the note, columns by label, segments from Indexes", "[io][instrument]") {
  if (!have_data()) {
    test::report_skip(kDir + " is absent (the shared data beside the repository)");
    return;
  }
  const nlohmann::json ref = reference()["files"];
  for (const char* name : {"fmt-igor-fd_SiN_FD_plot.ibw", "fmt-igor-fd_U3_3_p10004.ibw"}) {
    const auto& r = ref[name];
    INFO(name);
    const InstrumentFile f = read_instrument_file(kDir + name);
    REQUIRE(f.curves.size() == 1);
    const InstrumentCurve& c = f.curves[0];
    CHECK(c.spring_constant == r["spring_constant_N_per_m"].get<double>());
    CHECK(c.sensitivity == r["sensitivity_m_per_V"].get<double>());
    std::vector<double> force, height;
    for (const auto& s : c.segments) {
      force.insert(force.end(), s.force.begin(), s.force.end());
      height.insert(height.end(), s.height.begin(), s.height.end());
    }
    REQUIRE(force.size() == r["n_points"].get<std::size_t>());
    const auto& whole = r["force_N_whole_curve"];
    CHECK(rel_err(force.front(), whole["first"].get<double>()) < 1e-15);
    CHECK(rel_err(force.back(), whole["last"].get<double>()) < 1e-15);
    CHECK(rel_err(max_of(force), whole["max"].get<double>()) < 1e-15);
    CHECK(rel_err(sum(force), whole["sum"].get<double>()) < 1e-12);
    CHECK(height.front() == r["height_measured_m_whole_curve"]["first"].get<double>());
    CHECK(min_of(height) == r["height_measured_m_whole_curve"]["min"].get<double>());
    const auto& segs = r["segments_from_Indexes"];
    REQUIRE(c.segments.size() == segs.size());
    for (std::size_t s = 0; s < c.segments.size(); ++s) {
      CHECK(c.segments[s].force.size() == segs[s]["n_points"].get<std::size_t>());
      CHECK(rel_err(sum(c.segments[s].force), segs[s]["force_N_sum"].get<double>()) < 1e-12);
      CHECK(c.segments[s].height.back() == segs[s]["height_measured_m_last"].get<double>());
      CHECK(c.segments[s].style == (s == 0 ? SegmentStyle::extend : SegmentStyle::retract));
      CHECK(c.segments[s].duration == Approx(c.segments[s].force.size() * r["row_delta_s"].get<double>()));
    }
  }
}

TEST_CASE("an instrument curve as fit data: delta = -(height + F/k), segments from the styles", "[io][instrument]") {
  if (!have_data()) {
    test::report_skip(kDir + " is absent (the shared data beside the repository)");
    return;
  }
  const InstrumentFile f = read_instrument_file(kDir + "fmt-jpk-fd_spot3-0192.jpk-force");
  const CurveData d = to_curve_data(f.curves[0], "spot3");
  REQUIRE(d.size() == 4000);
  const InstrumentSegment& approach = f.curves[0].segments[0];
  CHECK(d.delta[5] == -(approach.height[5] + approach.force[5] / f.curves[0].spring_constant));
  CHECK(d.P[5] == approach.force[5]);
  CHECK(d.segment[1999] == 0);
  CHECK(d.segment[2000] == 1);
  // The nanite export (../real) has tip_position = height + F/k exactly (README there).
  CHECK(rel_err(-d.delta[1999], 1.7817247568217007e-05 + 3.479918274951986e-09 / 0.043493666407368466) < 1e-15);
}

TEST_CASE("instrument files: truncated, corrupt and wrong-format input fails with the file's name", "[io][instrument][errors]") {
  test::TempDir dir;
  const std::string bogus = write(dir, "bogus.jpk-force", "this is not a zip archive");
  CHECK_THROWS_WITH(read_instrument_file(bogus), Catch::Contains("bogus.jpk-force") && Catch::Contains("zip"));
  CHECK_THROWS_WITH(read_instrument_file(dir.file("missing.jpk-force")), Catch::Contains("missing.jpk-force"));
  CHECK_THROWS_WITH(read_instrument_file(write(dir, "curve.txt", "1,2")), Catch::Contains("not an instrument file"));
  CHECK_THROWS_WITH(read_instrument_file(write(dir, "short.ibw", std::string(100, '\0'))), Catch::Contains("too short"));
  CHECK_THROWS_WITH(read_instrument_file(write(dir, "wrong.ibw", std::string(400, '\x07'))), Catch::Contains("version 5"));
  if (!have_data()) {
    test::report_skip(kDir + " is absent: the truncated-archive cases need the real files");
    return;
  }
  auto bytes = [](const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
  };
  const std::string whole = bytes(kDir + "fmt-jpk-fd_spot3-0192.jpk-force");
  for (std::size_t cut : {whole.size() / 2, whole.size() - 30}) {
    const std::string truncated = write(dir, "cut" + std::to_string(cut) + ".jpk-force", whole.substr(0, cut));
    CHECK_THROWS_AS(read_instrument_file(truncated), InputError);
  }
  std::string corrupt = whole;
  for (std::size_t i = 2000; i < 2400; ++i) corrupt[i] = static_cast<char>(corrupt[i] ^ 0x5A);  // inside deflated data
  CHECK_THROWS_AS(read_instrument_file(write(dir, "corrupt.jpk-force", corrupt)), InputError);
  const std::string ibw = bytes(kDir + "fmt-igor-fd_SiN_FD_plot.ibw");
  CHECK_THROWS_WITH(read_instrument_file(write(dir, "cut.ibw", ibw.substr(0, 20000))), Catch::Contains("truncated"));
}

TEST_CASE("the archives agree row by row with the nanite CSV exports of the same curves", "[io][instrument]") {
  // ../real holds afmformats/nanite exports: force minus a baseline constant, tip position
  // (height + F/k) plus a constant (README there). An independent oracle for every sample.
  const std::string real = std::string(LAYERJKR_SOURCE_DIR) + "/../shared/data/real/";
  if (!have_data() || !std::ifstream(real + "jpk_spot3_0192_full.csv").good()) {
    test::report_skip("../shared/data is absent (the shared data beside the repository)");
    return;
  }
  struct Pair {
    const char* archive;
    const char* csv;
  };
  for (const Pair& p : {Pair{"fmt-jpk-fd_spot3-0192.jpk-force", "jpk_spot3_0192_full.csv"},
                        Pair{"fmt-jpk-fd_flipsign_2015.05.22-15.31.49.352.jpk-force", "jpk_flipsign_2015_full.csv"}}) {
    INFO(p.archive);
    const CurveData mine = to_curve_data(read_instrument_file(kDir + p.archive).curves[0], p.archive);
    const CurveData theirs = read_curve_csv(real + p.csv);
    REQUIRE(mine.size() == theirs.size());
    // Their tip_position column is read as delta = -tip: compare offsets against the first row.
    const double dF = mine.P[0] - theirs.P[0], dTip = mine.delta[0] - theirs.delta[0];
    double worst_force = 0.0, worst_tip = 0.0;
    for (std::size_t i = 0; i < mine.size(); ++i) {
      worst_force = std::max(worst_force, std::abs(mine.P[i] - theirs.P[i] - dF));
      worst_tip = std::max(worst_tip, std::abs(mine.delta[i] - theirs.delta[i] - dTip));
    }
    CHECK(worst_force < 1e-22);  // forces ~1e-9 N: equal to the last bits
    CHECK(worst_tip < 1e-17);    // positions ~1e-5 m
  }
}
