// afmformats' own test files (tests/data/instrument/README.md) read to the values afmformats'
// tests assert (tests/test_fmt_ntmdt_txt.py, test_fmt_chiaro_txt.py, test_fmt_workshop.py,
// test_fmt_tab.py at 731b5ad), with its conversions re-derived: NT-MDT Nova's text, Optics11
// Chiaro's text, AFM Workshop's single exports and maps, afmformats' own tab export.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iterator>

#include "io/jpk_builder.hpp"
#include "io/zip_archive.hpp"
#include "layerjkr/curve_data.hpp"
#include "layerjkr/error.hpp"
#include "layerjkr/instrument.hpp"
#include "support/temp_dir.hpp"
#include "support/test_support.hpp"

using namespace layerjkr;

namespace {
const std::string kDir = std::string(LAYERJKR_SOURCE_DIR) + "/tests/data/instrument/";
const std::string kNtmdt = kDir + "fmt-ntmdt-txt-fd_2015_01_17_gel4-0,1_mQ_adh_6B_Curve_DFL_Height_51.txt";
const std::string kMap = kDir + "fmt-afm-workshop-fd_mapping_16_2018-08-01_13.07.zip";

void check_close(double got, double expected) {
  INFO(got << " vs " << expected);
  CHECK(std::abs(got - expected) <= 1e-12 * std::abs(expected));
}

std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), {}};
}

// How many samples lie before and at the largest force: afmformats' split of approach and retract.
std::size_t through_peak(const CurveData& d) {
  return static_cast<std::size_t>(std::max_element(d.P.begin(), d.P.end()) - d.P.begin()) + 1;
}
}  // namespace

TEST_CASE("afmformats suite: NT-MDT Nova text - no calibration in the file, both given", "[io][public][afmformats]") {
  CHECK_THAT(test::input_error([] { read_curve_csv(kNtmdt); }),
             Catch::Contains("NT-MDT Nova text export") && Catch::Contains("--spring-constant") &&
                 Catch::Contains("--sensitivity"));
  CsvOptions o;
  o.spring_constant = 0.055;  // afmformats' meta_override
  o.sensitivity = 61.0;
  const CurveData d = read_curve_csv(kNtmdt, o);
  REQUIRE(d.size() == 1644);  // afmformats: force.size == 1644
  const auto approach = static_cast<std::size_t>(std::count(d.segment.begin(), d.segment.end(), 0));
  CHECK(approach == through_peak(d));  // "maximum force is at end of 1st segment"
  CHECK(approach == 822);
  // The approach starts at the file's last row (-0,0006 nm; -1,1033 nA) and runs inwards.
  const double f0 = -1.1033e-9 * 61.0 * 0.055;
  check_close(d.P[0], f0);
  check_close(d.delta[0], -(-0.0006e-9 + f0 / 0.055));
  // The retract starts at the last padded row of its column and ends at the file's last row.
  check_close(d.P.back(), -1.0926e-9 * 61.0 * 0.055);
  CHECK(d.notes.size() == 1);
  // A file of one constant deflection is refused, naming the column.
  CHECK_THAT(test::input_error([&] { parse_curve_csv("1,0\t2,0\t3,0\n2,0\t2,0\t3,0\n", "flat.txt", o); }),
             Catch::Contains("flat.txt: NT-MDT Nova text export: its approach deflection is constant"));
}

TEST_CASE("afmformats suite: Optics11 Chiaro text - k from the header, time, split at the peak load",
          "[io][public][afmformats]") {
  const detail::ZipArchive zip(kDir + "fmt-chiaro-txt_AEBP1_Indentation_002.zip");
  const std::string text = zip.read("fmt-chiaro-txt_AEBP1_Indentation_002.txt");
  REQUIRE(is_vendor_curve_text(text.substr(0, 4096)));
  const CurveData d = parse_curve_csv(text, "chiaro.txt");
  REQUIRE(d.size() == 13827);                 // afmformats: force.size == 13827
  check_close(d.P[2000], 9.399999999999999e-11);  // afmformats: force[2000]
  CHECK(static_cast<std::size_t>(std::count(d.segment.begin(), d.segment.end(), 0)) == through_peak(d));
  CHECK(d.spring_constant == 0.019);  // k (N/m)
  REQUIRE(d.t.size() == d.size());
  CHECK(d.t[1] == 0.001);
  // Row 0: Cantilever -16.214418 nm, Piezo 64.971622 nm: the tip has travelled piezo - cantilever.
  check_close(d.delta[0], (64.971622 + 16.214418) * 1e-9);
  // A spring constant given rescales the load the file computed with its own k.
  CsvOptions o;
  o.spring_constant = 0.038;
  check_close(parse_curve_csv(text, "chiaro.txt", o).P[2000], 2.0 * 9.399999999999999e-11);
  o = {};
  o.sensitivity = 1e-7;
  CHECK_THAT(test::input_error([&] { parse_curve_csv(text, "chiaro.txt", o); }),
             Catch::Contains("measured in nm: a sensitivity does not apply"));
}

TEST_CASE("afmformats suite: an AFM Workshop map, a zip of one export per point", "[io][public][afmformats]") {
  REQUIRE(instrument_format(kMap) == InstrumentFormat::afm_workshop_map);
  const InstrumentFile f = read_instrument_file(kMap);
  REQUIRE(f.curves.size() == 16);  // afmformats: len(data) == 16, shape (4, 4)
  CHECK(f.grid_shape_x == 4);
  CHECK(f.grid_shape_y == 4);
  check_close(f.grid_size_x, 2.533333333333333e-05);
  check_close(f.grid_size_y, 2.533333333333333e-05);
  check_close(f.grid_center_x, 1.05e-05);
  check_close(f.grid_center_y, 1.1499999999999998e-05);
  const InstrumentCurve& c1 = f.curves[1];
  CHECK(c1.grid_x == 1);
  CHECK(c1.grid_y == 0);
  check_close(c1.x, 7.333333333333332e-06);
  check_close(c1.y, 2e-6);
  for (std::size_t i = 0; i < f.curves.size(); ++i)  // "these changes were made manually"
    check_close(f.curves[i].segments[0].height[0], -(13761.9288 + static_cast<double>(i)) * 1e-9);
  // T-B volts without a gain: the sensitivity and k are needed, and named.
  CHECK_THAT(test::input_error([&] { to_curve_data(f.curves[0], "ws", 20.0); }), Catch::Contains("--sensitivity"));
  const CurveData d = to_curve_data(f.curves[0], "ws", 20.0, 0.01e-6);
  check_close(d.P[0], 0.6875 * 0.01e-6 * 20.0);  // afmformats: force[0] == 0.6875 sens k
  // A zip of anything else is refused, naming the member.
  test::TempDir dir;
  const std::string bad = dir.file("other.zip");
  test::write_zip(bad, {{"notes.txt", "hello\n"}});
  CHECK_THAT(test::input_error([&] { read_instrument_file(bad); }),
             Catch::Contains("notes.txt: not an AFM Workshop force-distance export"));
  // afmformats ships its Chiaro file zipped: named for what it is, with what to do.
  CHECK_THAT(test::input_error([&] { read_instrument_file(kDir + "fmt-chiaro-txt_AEBP1_Indentation_002.zip"); }),
             Catch::Contains("zipped: unpack the archive and give the file itself"));
}

TEST_CASE("afmformats suite: AFM Workshop 4.0 exports - unset constants, a given sensitivity, forces without k",
          "[io][public][afmformats]") {
  const std::string tb = kDir + "fmt-afm-workshop-fd_single_2021-01-15.csv";
  // Light Lever Gain and Force Constant are 1.000000, the unset default: both must be given.
  CHECK_THAT(test::input_error([&] { read_curve_csv(tb); }), Catch::Contains("--spring-constant"));
  CsvOptions o;
  o.spring_constant = 20.0;
  CHECK_THAT(test::input_error([&] { read_curve_csv(tb, o); }), Catch::Contains("--sensitivity"));
  o.sensitivity = 0.01e-6;
  check_close(read_curve_csv(tb, o).P[0], 1.6524e-07);  // afmformats, the same meta_override
  // The header's gain (100 mV/nm: 1e-8 m/V) and constant, as afmformats' valid-metadata test sets them.
  std::string text = slurp(tb);
  text.replace(text.find("Light Lever Gain, mV/nm:\t1.000000"), 33, "Light Lever Gain, mV/nm:\t100");
  text.replace(text.find("Force Constant, nN/nm:\t1.000000"), 31, "Force Constant, nN/nm:\t20.0");
  const CurveData h = parse_curve_csv(text, "set.csv");
  CHECK(h.spring_constant == 20.0);
  check_close(h.P[0], 1.6524e-07);
  // Force in nN without k: the force is read, the tip's position needs k.
  const std::string nn = kDir + "fmt-afm-workshop-fd_single_2021-10-22_14.16.csv";
  CHECK_THAT(test::input_error([&] { read_curve_csv(nn); }), Catch::Contains("no spring constant"));
  CsvOptions k;
  k.spring_constant = 0.1;
  check_close(read_curve_csv(nn, k).P[0], 0.0531e-9);
}

TEST_CASE("afmformats suite: its tab export 0.13.3, the first row on the names' line", "[io][public][afmformats]") {
  const CurveData d = read_curve_csv(kDir + "fmt-tab-fd_version_0.13.3.tab");
  // afmformats skips the glued first row: its force[2000] is this reader's sample 2001.
  CHECK(d.P[2001] == -6.7762282e-10);
  CHECK(d.spring_constant > 0.0);
  // A sensitivity given where the file holds forces is refused, never silently unused.
  CsvOptions o;
  o.sensitivity = 1e-7;
  CHECK_THAT(test::input_error([&] { read_curve_csv(kDir + "fmt-tab-fd_version_0.13.3.tab", o); }),
             Catch::Contains("a sensitivity (--sensitivity 1e-07 m/V) does not apply"));
  CHECK_THAT(test::input_error([&] { parse_curve_csv("delta,P\n0,0\n1e-9,1e-9\n", "plain.csv", o); }),
             Catch::Contains("plain.csv: is a CSV of named columns: a sensitivity"));
}

TEST_CASE("other suites' files that are not force curves are named for what they are", "[io][public]") {
  // PyFMReader's tests/testfiles: a JPK thermal-noise file (.tnd, text behind a zip) and its own
  // UFF copy of a NanoScope curve. Both were "not an instrument file"; fit read the .tnd as CSV.
  test::TempDir dir;
  const std::string tnd = dir.file("noise.tnd"), uff = dir.file("copy.uff");
  std::ofstream(tnd) << "# thermal noise data\n# sensitivity: 11.0399 nm/V\n";
  std::ofstream(uff) << "HE UFF_code:                        _1_2_3_4_5\n";
  for (const std::string& path : {tnd, uff}) {
    const std::string what = path == tnd ? "a JPK thermal noise file" : "PyFMReader's UFF file";
    CHECK_THAT(test::input_error([&] { read_instrument_file(path); }), Catch::Contains(what));
    CHECK_THAT(test::input_error([&] { read_curve_csv(path); }), Catch::Contains(what));
  }
}
