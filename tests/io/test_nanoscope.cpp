// Bruker NanoScope force files: every value of ../shared/data/instrument/bruker/reference.json
// (header values, raw integers, scaled values; the force volume's scaled values shown 256x
// too large), the physical checks that settle the two open rules, synthetic files that pin
// orders and sizes, and damaged files. Real-file cases are skipped, not failed, when
// ../shared is absent.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <functional>
#include <thread>
#include <tuple>

#include <nlohmann/json.hpp>

#include "io/curve_source.hpp"
#include "io/nanoscope_builder.hpp"
#include "io/nanoscope_header.hpp"
#include "io/read_file.hpp"
#include "layerjkr/error.hpp"
#include "support/temp_dir.hpp"
#include "support/test_support.hpp"

using namespace layerjkr;
using detail::open_nanoscope;

namespace {

const std::string kDir = std::string(LAYERJKR_SOURCE_DIR) + "/../shared/data/instrument/bruker/";
bool have_data() { return std::ifstream(kDir + "reference.json").good(); }
nlohmann::json reference() { return nlohmann::json::parse(std::ifstream(kDir + "reference.json")); }

std::string write(const std::string& name, const std::string& bytes) {
  const std::string path = test::scratch().file(name);
  std::ofstream(path, std::ios::binary) << bytes;
  return path;
}
std::string write(const std::string& name, const test::NanoscopeSpec& s) { return write(name, test::nanoscope_file(s)); }

// Samples 1..n (distinct, so that every index is pinned), `curves` curves.
std::vector<std::int64_t> ramp_samples(std::size_t curves, int n, std::int64_t scale = 1) {
  std::vector<std::int64_t> v;
  for (std::size_t c = 0; c < curves; ++c)
    for (int k = 0; k < n; ++k) v.push_back((static_cast<std::int64_t>(c) * 100 + k + 1) * scale);
  return v;
}

// A segment's forces in file order (the approach reversed back to how it is stored).
std::vector<double> stored(const InstrumentSegment& seg, bool reversed) {
  std::vector<double> v = seg.force;
  if (reversed) std::reverse(v.begin(), v.end());
  return v;
}

}  // namespace

TEST_CASE("nanoscope: every reference value of the two PyFMReader files", "[io][nanoscope]") {
  if (!have_data()) return test::report_skip(kDir + " is absent (the shared data beside the repository)");
  const nlohmann::json ref = reference();
  for (const nlohmann::json& r : ref["files"]) {
    const std::string path = kDir + r["file"].get<std::string>();
    INFO(path);
    const auto src = open_nanoscope(path, ReadLimits{});
    const InstrumentFile& f = src->header();
    CHECK(f.format == InstrumentFormat::nanoscope);
    CHECK(f.software == r["version"].get<std::string>());
    CHECK(f.instrument == r["microscope"].get<std::string>());
    REQUIRE(src->size() == r["n_curves"].get<std::size_t>());
    const bool volume = r["operating_mode"] == "Force Volume";
    CHECK(f.grid_shape_y == (volume ? r["grid_lines_x_points"][0].get<int>() : 0));
    CHECK(f.grid_shape_x == (volume ? r["grid_lines_x_points"][1].get<int>() : 0));

    // Header values, through the header parser.
    const std::string text = detail::read_file(path, "the file").substr(0, 80960);
    const detail::NanoscopeHeader h(text.substr(0, text.find(detail::kNanoscopeHeaderEnd)), path);
    CHECK(h.sections().at(1).name == "Force file list");
    CHECK(h.whole(h.need_section("Force file list"), "Data length", 0, 1 << 30) == r["header_data_length_field"]);
    CHECK(h.text(h.need_section("Force file list"), "Start context") == r["start_context"]);
    CHECK(h.text(h.need_section("Ciao scan list"), "Operating mode") == r["operating_mode"]);
    CHECK(h.text(h.need_section("Ciao force list"), "Trigger mode") == r["trigger_mode"]);
    CHECK(h.number(h.need_section("Ciao force list"), "Scan rate") == r["scan_rate_Hz"].get<double>());
    CHECK(h.number(h.need_section("Ciao force list"), "Forward vel.") == r["forward_vel_V_per_s"].get<double>());
    CHECK(h.number(h.need_section("Ciao force list"), "Reverse vel.") == r["reverse_vel_V_per_s"].get<double>());
    CHECK(h.sensitivity("Sens. DeflSens", "test") == r["deflection_sensitivity_nm_per_V"].get<double>());
    CHECK(h.sensitivity("Sens. Zsens", "test") == r["z_piezo_sensitivity_nm_per_V"].get<double>());
    CHECK(h.sensitivity("Sens. ZsensSens", "test") == r["z_sensor_sensitivity_nm_per_V"].get<double>());
    const nlohmann::json& ch = r["channels"][0];
    const detail::NanoscopeSection& s = h.need_section("Ciao force image list");
    CHECK(h.parameter(s, "@4:Image Data").quoted == ch["name"].get<std::string>());
    CHECK(h.whole(s, "Data offset", 0, 1 << 30) == ch["data_offset"]);
    CHECK(h.whole(s, "Data length", 0, 1 << 30) == ch["data_length"]);
    CHECK(h.whole(s, "Bytes/pixel", 0, 8) == ch["header_bytes_per_pixel"]);
    CHECK(ch["data_length"].get<double>() / (src->size() * 2048.0) == ch["derived_bytes_per_sample"].get<double>());
    CHECK(h.wholes(s, "Samps/line", 1, 5000) == ch["samps_per_line_field"].get<std::vector<std::int64_t>>());
    CHECK(h.number(s, "Spring Constant") == ch["spring_constant_N_per_m"].get<double>());
    const detail::NanoscopeParameter z = h.parameter(s, "@4:Z scale");
    CHECK(z.soft_scale == ch["z_scale_soft_scale_name"].get<std::string>());
    CHECK(*z.hard_scale == ch["z_scale_hard_scale_V_per_LSB"].get<double>());
    CHECK(*z.hard_value == ch["z_scale_hard_value_V"].get<double>());
    CHECK(h.sensitivity(z.soft_scale, "test") == ch["soft_scale_value"].get<double>());
    CHECK(*h.parameter(s, "@4:Ramp Size").hard_value == ch["ramp_size_V"].get<double>());
    // The corrupt line of the force volume file parses with its scale missing, its value kept.
    const detail::NanoscopeParameter zsweep = h.parameter(h.need_section("Ciao force list"), "@4:Ramp Size Zsweep");
    CHECK(zsweep.hard_scale.has_value() == !volume);
    CHECK(*zsweep.hard_value == ch["ramp_size_V"].get<double>());
    for (const nlohmann::json& im : r["images"]) {
      const detail::NanoscopeSection& is = h.need_section("Ciao image list");
      CHECK(h.parameter(is, "@2:Image Data").quoted == im["name"].get<std::string>());
      CHECK(h.whole(is, "Data offset", 0, 1 << 30) == im["data_offset"]);
      CHECK(h.whole(is, "Data length", 0, 1 << 30) == im["data_length"]);
      CHECK(h.whole(is, "Samps/line", 0, 1 << 30) == im["cols"]);
      CHECK(h.whole(is, "Number of lines", 0, 1 << 30) == im["rows"]);
      CHECK(h.text(is, "Scan Size") == im["scan_size"].get<std::string>());
      const detail::NanoscopeParameter iz = h.parameter(is, "@2:Z scale");
      CHECK(*iz.hard_scale == im["z_scale"]["hard_scale"].get<double>());
      CHECK(*iz.hard_value == im["z_scale"]["hard_value"].get<double>());
      CHECK(iz.soft_scale == im["z_scale"]["soft"].get<std::string>());
    }

    // Samples. The reader gives N; V = N / (k * DeflSens). The reference's convA is
    // raw * V/LSB: for the single curve that is our V; for the force volume it is 256 x our V,
    // because these v9.2 4-byte force volume samples are 16-bit counts x 256 (the test below
    // shows why): the raw integers agree exactly, the reference's scaled values are wrong by 256.
    const double k = 0.1332, defl_sens = 27.39e-9, lsb = 0.000375, shift = volume ? 256.0 : 1.0;
    const double ramp_nm = ch["ramp_size_nm"].get<double>();
    CHECK(ramp_nm == Approx(ch["ramp_size_V"].get<double>() * 13.203).epsilon(1e-12));
    double all = 0.0;
    for (std::size_t c = 0; c < src->size(); ++c) {
      const InstrumentCurve curve = src->curve(c);
      for (int sg = 0; sg < 2; ++sg)
        for (double v : curve.segments[sg].force) all += v / (k * defl_sens) / lsb * shift;
    }
    if (ch.contains("raw_sum_all_curves")) CHECK(all == Approx(ch["raw_sum_all_curves"].get<double>()).epsilon(1e-12));
    for (const auto& [index, rc] : ch["curves"].items()) {
      const InstrumentCurve curve = src->curve(std::stoul(index));
      INFO("curve " << index);
      CHECK(curve.spring_constant == k);
      CHECK(curve.sensitivity == Approx(defl_sens).epsilon(1e-15));
      for (int sg = 0; sg < 2; ++sg) {
        const nlohmann::json& rs = rc[sg == 0 ? "segment0_stored_first" : "segment1_stored_second"];
        const std::vector<double> force = stored(curve.segments[sg], sg == 0);
        std::vector<double> volts, raw;
        for (double v : force) volts.push_back(v / (k * defl_sens));
        for (double v : volts) raw.push_back(v / lsb * shift);
        for (double v : raw) REQUIRE(v == Approx(std::round(v)).margin(1e-6));  // integers, exactly
        for (int j = 0; j < 5; ++j) {
          CHECK(std::round(raw[j]) == rs["raw_first5"][j].get<double>());
          CHECK(std::round(raw[raw.size() - 5 + j]) == rs["raw_last5"][j].get<double>());
        }
        double sum = 0.0;
        for (double v : raw) sum += std::round(v);
        CHECK(sum == rs["raw_sum"].get<double>());
        CHECK(std::round(*std::min_element(raw.begin(), raw.end())) == rs["raw_min"].get<double>());
        CHECK(std::round(*std::max_element(raw.begin(), raw.end())) == rs["raw_max"].get<double>());
        CHECK(std::max_element(raw.begin(), raw.end()) - raw.begin() == rs["argmax"].get<int>());
        CHECK(volts.front() * shift == Approx(rs["convA_first_V"].get<double>()).epsilon(1e-12));
        CHECK(volts.back() * shift == Approx(rs["convA_last_V"].get<double>()).epsilon(1e-12).margin(1e-15));
        CHECK(force.front() / k * shift == Approx(rs["convA_first_defl_m"].get<double>()).epsilon(1e-12));
        CHECK(force.back() * shift == Approx(rs["convA_last_force_N"].get<double>()).epsilon(1e-12).margin(1e-24));
      }
      // Heights from the ramp: approach from ramp - step down to 0, retract from 0 up.
      const double step = ch["z_step_nm_ramp_over_n"].get<double>() * 1e-9;
      const InstrumentSegment& ext = curve.segments[0];
      CHECK(ext.height.front() == Approx(1023 * step).epsilon(1e-12));
      CHECK(ext.height.back() == 0.0);
      CHECK(curve.segments[1].height[1] == Approx(step).epsilon(1e-12));
      CHECK(ext.duration == Approx(ch["ramp_size_V"].get<double>() / r["forward_vel_V_per_s"].get<double>()));
      CHECK(ext.duration == Approx(0.4915).epsilon(1e-3));  // = 1 / (2 x Scan rate 1.01725 Hz)
    }
  }
}

TEST_CASE("nanoscope: corrected force volume values (V) and the map grid", "[io][nanoscope]") {
  if (!have_data()) return test::report_skip(kDir + " is absent (the shared data beside the repository)");
  const auto src = open_nanoscope(kDir + "20200903_Egel2.0_00023.spm", ReadLimits{});
  // "first"/"last" are in file order, as in reference.json: the approach's stored first sample
  // is its last in time (the turnaround, tip deepest); the retract's first is its first in time.
  const std::vector<std::tuple<std::size_t, double, double, double, double>> expected = {
      {0, 1.219875, 0.026625, 1.21575, 0.0105},
      {1, 1.2195, 0.01725, 1.2135, 0.0},
      {255, 1.20037353515625, -0.02175146484375, 1.19812353515625, -0.02850146484375}};
  for (const auto& [i, e_first, e_last, r_first, r_last] : expected) {
    const InstrumentCurve c = src->curve(i);
    const double volt = 0.1332 * 27.39e-9;
    CHECK(c.segments[0].force.back() / volt == Approx(e_first).epsilon(1e-12));
    CHECK(c.segments[0].force.front() / volt == Approx(e_last).epsilon(1e-12).margin(1e-15));
    CHECK(c.segments[1].force.front() / volt == Approx(r_first).epsilon(1e-12));
    CHECK(c.segments[1].force.back() / volt == Approx(r_last).epsilon(1e-12).margin(1e-15));
    CHECK(c.position_index == static_cast<int>(i));
    CHECK(c.grid_x == static_cast<int>(i % 16));
    CHECK(c.grid_y == static_cast<int>(i / 16));
  }
  const InstrumentFile& f = src->header();
  CHECK(f.grid_size_x == Approx(2e-6));
  CHECK(f.grid_size_y == Approx(2e-6));
  CHECK(f.grid_center_x == 0.0);
  const InstrumentCurve c0 = src->curve(0), c255 = src->curve(255);
  CHECK(c0.x == Approx(-0.9375e-6));  // pixel centres: (0.5 - 8) x 125 nm
  CHECK(c255.y == Approx(0.9375e-6));
}

TEST_CASE("nanoscope: physical consistency settles the force volume /256 rule", "[io][nanoscope]") {
  if (!have_data()) return test::report_skip(kDir + " is absent (the shared data beside the repository)");
  const double volt = 0.1332 * 27.39e-9;
  {  // Single ramp: the approach's force rises at its end (contact), the retract starts high.
    const InstrumentCurve c = open_nanoscope(kDir + "20200904_Egel4-Z1.0_00025.spm", ReadLimits{})->curve(0);
    const std::vector<double>& ext = c.segments[0].force;
    const double peak = *std::max_element(ext.begin(), ext.end());
    CHECK(peak == ext.back());
    CHECK(ext.back() - ext.front() > 1.0 * volt);  // trigger 1.2 V relative
    CHECK(c.segments[1].force.front() > c.segments[1].force.back() + 1.0 * volt);
    CHECK((ext.back() - ext.front()) / volt == Approx(1.2).epsilon(0.10));
  }
  // Force volume: the rise over each approach matches the 1.2 V relative trigger within 10%
  // only with /256 (counts x 256); without it the rise would be 256 x 1.2 V = 307 V, beyond
  // the +-10 V of the deflection ADC. The reader checks the low bytes at read time.
  const auto src = open_nanoscope(kDir + "20200903_Egel2.0_00023.spm", ReadLimits{});
  for (std::size_t i = 0; i < src->size(); ++i) {
    const std::vector<double> ext = src->curve(i).segments[0].force;
    const double rise = (ext.back() - ext.front()) / volt;
    CHECK(rise == Approx(1.2).epsilon(0.10));
    CHECK_FALSE(rise * 256 == Approx(1.2).epsilon(0.10));
  }
}

TEST_CASE("nanoscope synthetic: N1 != N2, 2-byte samples, time order, ramp heights", "[io][nanoscope]") {
  test::NanoscopeSpec s;  // n1 = 5 extend, n2 = 3 retract
  s.defl = ramp_samples(1, 8);
  s.defl[6] = -3;  // a negative 2-byte sample
  const auto src = open_nanoscope(write("single.spm", s), ReadLimits{});
  REQUIRE(src->size() == 1);
  const InstrumentCurve c = src->curve(0);
  const double n_per_lsb = 0.0005 * 20e-9 * 0.25;
  REQUIRE(c.segments.size() == 2);
  CHECK(c.segments[0].style == SegmentStyle::extend);
  CHECK(c.segments[1].style == SegmentStyle::retract);
  REQUIRE(c.segments[0].force.size() == 5);  // the first number of Samps/line
  REQUIRE(c.segments[1].force.size() == 3);
  for (int t = 0; t < 5; ++t) CHECK(c.segments[0].force[t] == Approx((5 - t) * n_per_lsb));  // reversed
  CHECK(c.segments[1].force[0] == Approx(6 * n_per_lsb));
  CHECK(c.segments[1].force[1] == Approx(-3 * n_per_lsb));
  for (int t = 0; t < 5; ++t) CHECK(c.segments[0].height[t] == Approx((4 - t) * 80e-9).margin(1e-20));  // 400 nm / 5
  CHECK(c.segments[1].height[2] == Approx(2 * 400e-9 / 3));
  CHECK(c.segments[0].duration == Approx(40.0 / 80));  // Ramp Size / Forward vel.
  CHECK(c.segments[1].duration == Approx(40.0 / 160));
  CHECK(c.segments[0].piezo_height.empty());
  CHECK(c.sensitivity == Approx(20e-9));
  CHECK(c.grid_x == -1);
  CHECK(c.position_index == -1);
  CHECK(src->header().instrument == "Test AFM 8");
  CHECK(detail::open_nanoscope_bytes(test::nanoscope_file(s), "mem.spm", ReadLimits{})->curve(0).segments[1].force ==
        c.segments[1].force);
}

TEST_CASE("nanoscope synthetic: 3x2 force volume, 4-byte counts x 256, stored Z sensor", "[io][nanoscope]") {
  test::NanoscopeSpec s;
  s.mode = "Force Volume";
  s.points = 3;
  s.lines = 2;
  s.bytes = 4;
  s.defl = ramp_samples(6, 8, 256);
  s.defl[1] = 3 * 256 - 1;  // low byte FF, as in the real file
  s.zsensor = true;
  for (std::size_t c = 0; c < 6; ++c)  // sensor falling along each stored block: sign flipped
    for (int k = 0; k < 8; ++k) s.z.push_back(-(k < 5 ? k : k - 5) * 256 * 100);
  const auto src = open_nanoscope(write("fv.spm", s), ReadLimits{});
  REQUIRE(src->size() == 6);
  const InstrumentFile& f = src->header();
  CHECK(f.grid_shape_x == 3);
  CHECK(f.grid_shape_y == 2);
  CHECK(f.grid_size_x == Approx(3e-6));
  CHECK(f.grid_size_y == Approx(2e-6));  // square pixels
  CHECK(f.grid_center_x == Approx(100e-9));
  CHECK(f.grid_center_y == Approx(-50e-9));
  const InstrumentCurve c4 = src->curve(4);
  CHECK(c4.grid_x == 1);
  CHECK(c4.grid_y == 1);
  CHECK(c4.x == Approx(100e-9));
  CHECK(c4.y == Approx(-50e-9 + 0.5e-6));
  const double n_per_lsb = 0.0005 * 20e-9 * 0.25;
  CHECK(c4.segments[0].force.back() == Approx(401 * n_per_lsb));
  CHECK(src->curve(0).segments[0].force[3] == Approx((3 - 1.0 / 256) * n_per_lsb));
  // Z sensor: 100 counts x 0.0001 V/LSB x 500 nm/V = 5 nm per stored step, rising away from the surface.
  const std::vector<double>& h = c4.segments[0].height;
  CHECK(h.front() == Approx(20e-9));
  CHECK(h.back() == Approx(0.0).margin(1e-18));
  CHECK(c4.segments[1].height[2] == Approx(10e-9));
  // Random access from several threads gives the same curves.
  std::vector<std::thread> threads;
  std::vector<double> seen(6);
  for (std::size_t i = 0; i < 6; ++i) threads.emplace_back([&, i] { seen[i] = src->curve(i).segments[1].force[0]; });
  for (std::thread& t : threads) t.join();
  for (std::size_t i = 0; i < 6; ++i) CHECK(seen[i] == Approx((100.0 * i + 6) * n_per_lsb));
  CHECK_THROWS_AS(src->curve(6), std::out_of_range);
  // A sample that is not counts x 256 is refused rather than scaled by a guess.
  s.defl[9] = 1000;
  CHECK_THAT(test::input_error([&] { open_nanoscope(write("fv_bad.spm", s), ReadLimits{})->curve(1); }),
             Catch::Contains("fv_bad.spm") && Catch::Contains("curve 1") && Catch::Contains("1000"));
}

TEST_CASE("nanoscope: damaged and foreign files give an InputError naming the file and field", "[io][nanoscope]") {
  test::NanoscopeSpec good;
  good.defl = ramp_samples(1, 8);
  const std::string bytes = test::nanoscope_file(good);
  auto error = [](const std::string& name, const std::string& content) {
    return test::input_error([&] { open_nanoscope(write(name, content), ReadLimits{})->curve(0); });
  };
  auto spec_error = [&](const std::string& name, const std::function<void(test::NanoscopeSpec&)>& change) {
    test::NanoscopeSpec s = good;
    change(s);
    return error(name, test::nanoscope_file(s));
  };
  using Catch::Contains;
  // A surface hold is refused, not misread; a hold of 0 samples (every public file's) reads.
  CHECK_THAT(spec_error("hold.spm", [](test::NanoscopeSpec& s) { s.extra_force_lines = "\\Hold Samples: 12\r\n\\Hold Time: 0.5\r\n"; }),
             Contains("hold.spm") && Contains("Hold Samples = 12") && Contains("not read rather than read wrong"));
  {
    test::NanoscopeSpec s = good;
    s.extra_force_lines = "\\Hold Type: Z Drive\r\n\\Hold Samples: 0\r\n\\Hold Time: 0\r\n";
    CHECK(open_nanoscope(write("no_hold.spm", s), ReadLimits{})->curve(0).segments.size() == 2);
  }
  CHECK_THAT(error("trunc_header.spm", bytes.substr(0, 300)), Contains("trunc_header.spm") && Contains("File list end"));
  std::string no_end = bytes;
  no_end.replace(no_end.find("\\*File list end"), 5, "\\*XXX");
  CHECK_THAT(error("no_end.spm", no_end), Contains("no_end.spm") && Contains("File list end"));
  CHECK_THAT(error("nul.spm", std::string(5000, '\0')), Contains("nul.spm") && Contains("Force file list"));
  CHECK_THAT(error("empty.spm", ""), Contains("empty.spm") && Contains("File list end"));
  CHECK_THAT(error("image.spm", "\\*File list\r\n\\Version: 0x0920B046\r\n\\*File list end\r\n"),
             Contains("image.spm") && Contains("image file, not force curves; unsupported"));
  CHECK_THAT(error("trunc_data.spm", bytes.substr(0, bytes.size() - 1)),
             Contains("trunc_data.spm") && Contains("Data offset") && Contains("truncated"));
  CHECK_THAT(spec_error("no_samps.spm", [](auto& s) { s.samps = " "; }), Contains("no_samps.spm") && Contains("Samps/line"));
  std::string no_samps = bytes;
  no_samps.erase(no_samps.find("\\Samps/line: 5 3\r\n\\Spring"), std::string("\\Samps/line: 5 3\r\n").size());
  CHECK_THAT(error("missing_samps.spm", no_samps),
             Contains("missing_samps.spm") && Contains("Ciao force image list") && Contains("no \\Samps/line"));
  CHECK_THAT(spec_error("zero_samps.spm", [](auto& s) { s.samps = "0 8"; }), Contains("Samps/line = '0 8'"));
  CHECK_THAT(spec_error("huge_samps.spm", [](auto& s) { s.samps = "5 99999999999"; }),
             Contains("huge_samps.spm") && Contains("Samps/line = '5 99999999999'"));
  CHECK_THAT(spec_error("one_samps.spm", [](auto& s) { s.samps = "8"; }), Contains("expected two numbers"));
  CHECK_THAT(spec_error("length.spm", [](auto& s) { s.data_length = 18; }),
             Contains("length.spm") && Contains("Data length = 18") && Contains("2 or 4 bytes"));
  CHECK_THAT(spec_error("offset.spm", [](auto& s) { s.data_offset = 1 << 20; }),
             Contains("offset.spm") && Contains("Data offset = 1048576"));
  CHECK_THAT(spec_error("scale.spm", [](auto& s) { s.defl_scale = "V [Sens. DeflSens] (abc V/LSB) 2.5 V"; }),
             Contains("scale.spm") && Contains("@4:Z scale = 'V [Sens. DeflSens] (abc V/LSB) 2.5 V'"));
  CHECK_THAT(spec_error("sens.spm", [](auto& s) { s.defl_sens = "V x"; }),
             Contains("sens.spm") && Contains("@Sens. DeflSens = 'V x'"));
  CHECK_THAT(spec_error("spring.spm", [](auto& s) { s.spring = "0"; }),
             Contains("spring.spm") && Contains("Spring Constant = '0'") && Contains("> 0"));
  CHECK_THAT(spec_error("spring_nan.spm", [](auto& s) { s.spring = "nan"; }), Contains("Spring Constant = 'nan'"));
  CHECK_THAT(spec_error("ramp.spm", [](auto& s) { s.ramp = "V [Sens. Zsens] (0.0067 V/LSB) -1 V"; }),
             Contains("ramp.spm") && Contains("@4:Ramp Size"));
  CHECK_THAT(spec_error("mode.spm", [](auto& s) { s.mode = "Contact"; }),
             Contains("mode.spm") && Contains("Operating mode = 'Contact'"));
  CHECK_THAT(spec_error("grid.spm", [](auto& s) { s.mode = "Force Volume"; s.points = 0; }),
             Contains("grid.spm") && Contains("\\Samps/line = '0'"));
  CHECK_THAT(spec_error("unit.spm", [](auto& s) { s.mode = "Force Volume"; s.scan_size = "3 furlong"; }),
             Contains("unit.spm") && Contains("Scan Size = '3 furlong'"));
  CHECK_THAT(spec_error("version.spm", [](auto& s) { s.mode = "Force Volume"; s.bytes = 4; s.version = "9.2"; }),
             Contains("version.spm") && Contains("Version = '9.2'"));
  CHECK_THAT(test::input_error([] { open_nanoscope(test::scratch().file("missing.spm"), ReadLimits{}); }),
             Contains("missing.spm") && Contains("cannot open"));
  CHECK_THAT(test::input_error([] { open_nanoscope(test::scratch().path().string(), ReadLimits{}); }),
             Contains("not a regular file"));
}

TEST_CASE("nanoscope: fields are read where needed - an empty Ramp Size falls back to the force list's Zsweep",
          "[io][nanoscope]") {
  test::NanoscopeSpec s;
  s.mode = "Force Volume";
  s.points = 2;
  s.lines = 2;
  s.defl = ramp_samples(4, 8);
  s.ramp = "''";  // as a real force volume writes it in its force image list
  const std::unique_ptr<detail::CurveSource> src = open_nanoscope(write("empty_ramp.spm", s), ReadLimits{});
  REQUIRE(src->size() == 4);
  const InstrumentCurve c = src->curve(3);
  // The force list's Ramp Size Zsweep, 1 V x 10 nm/V = 10 nm over the 5 extend samples.
  for (int t = 0; t < 5; ++t) CHECK(c.segments[0].height[t] == Approx((4 - t) * 2e-9).margin(1e-20));
  CHECK(c.segments[0].duration == Approx(1.0 / 80));
  REQUIRE(c.notes.size() == 1);
  CHECK_THAT(c.notes[0], Catch::Contains("Ramp Size is ''") && Catch::Contains("Zsweep (1 V) is used"));
  // 8.15 spells it "Ramp size": the same value.
  test::NanoscopeSpec lower;
  lower.defl = ramp_samples(1, 8);
  std::string bytes = test::nanoscope_file(lower);
  bytes.replace(bytes.find("\\@4:Ramp Size: V"), 16, "\\@4:Ramp size: V");
  const InstrumentCurve l = open_nanoscope(write("lower.spm", bytes), ReadLimits{})->curve(0);
  CHECK(l.segments[0].duration == Approx(40.0 / 80));
  CHECK(l.notes.empty());
  // Neither: the header still opens, and each curve says why it has no height.
  std::string none = test::nanoscope_file(s);
  none.replace(none.find("\\@4:Ramp Size Zsweep"), 20, "\\@4:Ramp Sise Zsweep");
  const std::unique_ptr<detail::CurveSource> broken = open_nanoscope(write("no_ramp.spm", none), ReadLimits{});
  CHECK(broken->size() == 4);
  CHECK(broken->header().grid_shape_x == 2);
  CHECK_THAT(test::input_error([&] { broken->curve(0); }),
             Catch::Contains("no_ramp.spm") && Catch::Contains("Ramp Size = ''") && Catch::Contains("no Z sensor"));
}
