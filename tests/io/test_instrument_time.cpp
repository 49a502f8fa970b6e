// Time and dwell segments read from instrument files: each sample at (the earlier segments'
// durations) + i duration / n, as afmformats computes JPK's and the Igor wave's row scaling
// gives Asylum's; pauses kept as dwell samples (segment 2), not refused, not merged. Checked
// against ../shared/data/instrument/reference.json (every JPK segment's first time, the Igor
// files' row step), afmformats' own assertions on its stress-relaxation file (the mean time and
// force of each of its four segments, a retract sample's time) and its creep-compliance file
// (extend, a 3 s constant-force pause, retract), both copied unchanged to ../shared beside their
// licence (skipped when absent); a JPK archive built here with a pause (always run).
#include <catch2/catch.hpp>

#include <cmath>
#include <fstream>
#include <numeric>

#include <nlohmann/json.hpp>

#include "io/jpk_builder.hpp"
#include "layerjkr/instrument.hpp"
#include "support/temp_dir.hpp"
#include "support/test_support.hpp"

using namespace layerjkr;

namespace {

const std::string kDir = std::string(LAYERJKR_SOURCE_DIR) + "/../shared/data/instrument/";
bool have(const std::string& name) { return std::ifstream(kDir + name).good(); }

// The mean of v over count samples from first.
double mean_of(const std::vector<double>& v, std::size_t first, std::size_t count) {
  return std::accumulate(v.begin() + static_cast<long>(first), v.begin() + static_cast<long>(first + count), 0.0) /
         static_cast<double>(count);
}

}  // namespace

TEST_CASE("instrument time: every JPK segment starts at the earlier ones' durations, Igor rows at the wave's step",
          "[io][instrument]") {
  if (!have("reference.json")) {
    test::report_skip(kDir + " is absent (the shared data beside the repository)");
    return;
  }
  const nlohmann::json ref = nlohmann::json::parse(std::ifstream(kDir + "reference.json"))["files"];
  for (const auto& [name, r] : ref.items()) {
    const InstrumentFile f = read_instrument_file(kDir + name);
    INFO(name);
    if (name.find(".ibw") != std::string::npos) {
      const CurveData d = to_curve_data(f.curves.at(0), name);
      REQUIRE(d.t.size() == d.size());
      CHECK(d.t[1] - d.t[0] == Approx(r["row_delta_s"].get<double>()).epsilon(1e-12));
      CHECK(d.t.back() == Approx((d.size() - 1) * r["row_delta_s"].get<double>()).epsilon(1e-12));
      continue;
    }
    for (std::size_t c = 0; c < f.curves.size(); ++c) {
      const CurveData d = to_curve_data(f.curves[c], name);
      REQUIRE(d.t.size() == d.size());
      std::size_t first = 0;
      for (std::size_t s = 0; s < f.curves[c].segments.size(); ++s) {
        const nlohmann::json& seg = r["curves"][c]["segments"][s];
        INFO("curve " << c << ", segment " << s);
        CHECK(std::abs(d.t[first] - seg["time_first_s"].get<double>()) <= 1e-15);
        first += f.curves[c].segments[s].force.size();
      }
    }
  }
}

TEST_CASE("instrument time: a Bruker ramp lasts its size over its velocity, 0.49152 s for 1 024 samples", "[io][instrument]") {
  const std::string name = "bruker/20200904_Egel4-Z1.0_00025.spm";
  if (!have(name)) {
    test::report_skip(kDir + name + " is absent (the shared data beside the repository)");
    return;
  }
  // Ramp Size 227.2211 V / Forward vel. 462.282 V/s = 0.49152 s = 1 / (2 x Scan rate 1.01725 Hz).
  const CurveData d = to_curve_data(read_instrument_file(kDir + name).curves.at(0), name);
  REQUIRE(d.t.size() == 2048);
  CHECK(d.t[1] - d.t[0] == Approx(0.49152 / 1024).epsilon(1e-5));
  CHECK(d.t[1024] == Approx(0.49152).epsilon(1e-5));
  CHECK(d.t.back() == Approx(2 * 0.49152 - 0.49152 / 1024).epsilon(1e-5));
}

TEST_CASE("instrument time: afmformats' stress-relaxation file - two pauses kept as dwell, its times and forces",
          "[io][instrument]") {
  const std::string name = "fmt-jpk-sr_cell1-0008.jpk-force";
  if (!have(name)) {
    test::report_skip(kDir + name + " is absent (afmformats' test file, copied to ../shared beside its licence)");
    return;
  }
  const InstrumentFile f = read_instrument_file(kDir + name);
  REQUIRE(f.curves.size() == 1);
  const InstrumentCurve& c = f.curves[0];
  REQUIRE(c.segments.size() == 4);
  CHECK(c.segments[0].style == SegmentStyle::pause);
  CHECK(c.segments[1].style == SegmentStyle::extend);
  CHECK(c.segments[2].style == SegmentStyle::pause);
  CHECK(c.segments[3].style == SegmentStyle::retract);
  const CurveData d = to_curve_data(c, name);
  // afmformats' tests/test_mod_stress_relaxation.py: the mean time and force of each segment.
  const double time[] = {0.498046875, 1.499755859375, 16.998046875, 32.47607421875};
  const double force[] = {-1.1667527118459774e-07, 1.2185861117864535e-08, 2.3613889957445826e-08,
                          -1.4864363676098427e-07};
  const int label[] = {2, 0, 2, 1};
  std::size_t first = 0;
  for (std::size_t s = 0; s < 4; ++s) {
    const std::size_t n = c.segments[s].force.size();
    INFO("segment " << s << ": " << n << " samples");
    CHECK(mean_of(d.t, first, n) == Approx(time[s]).epsilon(1e-12));
    CHECK(mean_of(d.P, first, n) == Approx(force[s]).epsilon(1e-12));
    for (std::size_t i = first; i < first + n; ++i) REQUIRE(d.segment[i] == label[s]);
    if (s == 3) CHECK(d.t[first + 20] == Approx(32.009765625).epsilon(1e-12));
    first += n;
  }
  CHECK(d.dwell_count() == 256 + 7680);
  CHECK(d.select(Branch::all).size() == 2048 + 1951);  // no branch holds the dwells
}

TEST_CASE("instrument time: afmformats' creep-compliance file - a constant-force pause between extend and retract",
          "[io][instrument]") {
  const std::string name = "fmt-jpk-cc_pr14-brain-2021.06.30.jpk-force";
  if (!have(name)) {
    test::report_skip(kDir + name + " is absent (afmformats' test file, copied to ../shared beside its licence)");
    return;
  }
  const InstrumentCurve c = read_instrument_file(kDir + name).curves.at(0);
  REQUIRE(c.segments.size() == 3);
  CHECK(c.segments[1].style == SegmentStyle::pause);
  CHECK(c.segments[1].duration == Approx(3.0).epsilon(1e-12));  // afmformats: "duration intermediate" 3 s
  const CurveData d = to_curve_data(c, name);
  CHECK(d.segment[2999] == 0);
  CHECK(d.segment[3000] == 2);
  CHECK(d.segment[6000] == 1);
  CHECK(d.t[3000] == Approx(3.0).epsilon(1e-12));
  CHECK(d.t[6000] == Approx(6.0).epsilon(1e-12));
  CHECK(d.t.back() == Approx(9.0 - 3.0 / 3000.0).epsilon(1e-12));
}

TEST_CASE("instrument time: a pause built here is a dwell with its own times, an Asylum dwell away stays retract",
          "[io][instrument]") {
  const test::TempDir dir;
  // extend 8 samples over 1 s, a pause of 4 over 2 s, a retract of 8 over 1 s.
  std::vector<test::Member> m = test::jpk_members(8);
  const auto segment = [&](int k, const std::string& style, int n, double duration) {
    std::vector<test::Member> one = test::jpk_members(n);
    std::string header = one[1].bytes;
    header.replace(header.find("duration=1.0"), 12, "duration=" + std::to_string(duration));
    header.replace(header.find("style=extend"), 12, "style=" + style);
    const std::string p = "segments/" + std::to_string(k) + "/";
    m.push_back({p + "segment-header.properties", header});
    m.push_back({p + "channels/vDeflection.dat", one[2].bytes});
    m.push_back({p + "channels/strainGaugeHeight.dat", one[3].bytes});
  };
  segment(1, "pause", 4, 2.0);
  segment(2, "retract", 8, 1.0);
  const std::string path = dir.file("paused.jpk-force");
  test::write_zip(path, m);
  const CurveData d = to_curve_data(read_instrument_file(path).curves.at(0), path);
  REQUIRE(d.size() == 20);
  CHECK(d.segment == std::vector<int>{0, 0, 0, 0, 0, 0, 0, 0, 2, 2, 2, 2, 1, 1, 1, 1, 1, 1, 1, 1});
  CHECK(d.t[7] == Approx(7.0 / 8.0));
  CHECK(d.t[8] == Approx(1.0));
  CHECK(d.t[9] == Approx(1.5));
  CHECK(d.t[12] == Approx(3.0));
  CHECK(d.t[19] == Approx(3.875));
  CHECK(d.without_dwell().size() == 16);

  // SciFiDatasets' Asylum point (committed): extend, retract, then a dwell away (Direction 0).
  const std::string ibw = std::string(LAYERJKR_SOURCE_DIR) + "/tests/data/instrument/IgorIBWReader_ForceCurve.ibw";
  const CurveData a = to_curve_data(read_instrument_file(ibw).curves.at(0), ibw);
  REQUIRE(a.t.size() == 1261);
  CHECK(a.t[1] - a.t[0] == Approx(0.0005).epsilon(1e-9));
  CHECK(a.segment[1240] == 1);  // the dwell away is the retract's baseline
  CHECK(a.dwell_count() == 0);
}
