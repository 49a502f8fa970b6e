// Header values are read strictly (issue #21): the whole token must be one finite number
// ("1,1841" is not 1, "1e-3e5" not 0.001), a key the reader needs may not be given twice,
// and counts, indices and map grids are checked before any cast to an integer. Hand-made
// .properties text, synthetic JPK archives and Igor waves; the real files still read as
// tests/io/test_instrument.cpp asserts.
#include <catch2/catch.hpp>

#include "io/instrument_readers.hpp"
#include "io/java_properties.hpp"
#include "jpk_builder.hpp"
#include "layerjkr/error.hpp"
#include "layerjkr/instrument.hpp"
#include "support/temp_dir.hpp"
#include "support/test_support.hpp"

using namespace layerjkr;

using test::input_error;

namespace {

// The minimal archive with `key=value` in member `member` (0: header, 1: segment header)
// replaced by `key=replacement`, or `extra` appended.
std::string archive(const test::TempDir& dir, std::size_t member, const std::string& line,
                    const std::string& replacement) {
  std::vector<test::Member> members = test::jpk_members();
  std::string& text = members[member].bytes;
  if (line.empty()) {
    text += replacement + "\n";
  } else {
    const std::size_t at = text.find(line + "\n");
    REQUIRE(at != std::string::npos);
    text.replace(at, line.size(), replacement);
  }
  const std::string path = dir.file("hand.jpk-force");
  test::write_zip(path, members);
  return path;
}

const std::string kNote =
    "Version:16.11.212\rMicroscopeModel:MFP3D\rSaveForce:1\rSaveForce:2\rInvOLS: 4.499e-08\r"
    "Indexes: 0,2,5\rDirection: NaN,1,-1,\r";

InstrumentFile igor(const std::string& note) { return detail::read_ibw_bytes(test::igor_wave(note), "hand.ibw"); }

}  // namespace

TEST_CASE(".properties: a key given twice with two values is an error naming it - escapes and continuations still read",
          "[io][headers]") {
  const detail::Properties p = detail::parse_properties("a=1\n# c\nb : two\\\n  words\nc\\=d=3\n", "x.properties");
  CHECK(p.at("a") == "1");
  CHECK(p.at("b") == "twowords");
  CHECK(p.at("c=d") == "3");
  CHECK_THAT(input_error([] { detail::parse_properties("a=1\nb=2\na=3\n", "seg/header.properties"); }),
             Catch::Contains("seg/header.properties") && Catch::Contains("'a' is given twice") &&
                 Catch::Contains("'1' and '3'"));
  CHECK(detail::parse_properties("a=1\nb=2\na=1\n", "seg/header.properties").at("a") == "1");
}

TEST_CASE("JPK header numbers: the whole value must be one finite number", "[io][headers]") {
  test::TempDir dir;
  const std::string key = "channel.vDeflection.conversion-set.conversion.force.scaling.multiplier";
  CHECK(read_instrument_file(archive(dir, 1, key + "=0.05", key + "=0.05")).curves[0].spring_constant == 0.05);
  for (const char* bad : {"0,05", "5e-2e5", "0.05x", "NaN", "Infinity", "-Infinity", "inf", "1e999", ""}) {
    INFO(bad);
    CHECK_THAT(input_error([&] { read_instrument_file(archive(dir, 1, key + "=0.05", key + "=" + bad)); }),
               Catch::Contains("hand.jpk-force") && Catch::Contains(key) && Catch::Contains("not a finite number"));
  }
  CHECK_THAT(input_error([&] {
               read_instrument_file(archive(dir, 1, "force-segment-header.num-points=8", "force-segment-header.num-points=8.5"));
             }),
             Catch::Contains("num-points") && Catch::Contains("whole number"));
  CHECK_THAT(input_error([&] {
               read_instrument_file(archive(dir, 0, "force-scan-series.header.position-index=0",
                                            "force-scan-series.header.position-index=1e20"));
             }),
             Catch::Contains("position-index") && Catch::Contains("whole number in [-1, 1000000000]"));
  CHECK_THAT(input_error([&] {
               read_instrument_file(archive(dir, 0, "force-scan-series.header.position.x=1.0E-6",
                                            "force-scan-series.header.position.x=1,0E-6"));
             }),
             Catch::Contains("position.x"));
}

TEST_CASE("JPK headers: a key given twice with two values fails the file, naming the member and the key", "[io][headers]") {
  test::TempDir dir;
  // The same value twice is one value.
  CHECK(read_instrument_file(archive(dir, 1, "", "force-segment-header.duration=1.0")).curves.size() == 1);
  CHECK_THAT(input_error([&] { read_instrument_file(archive(dir, 1, "", "force-segment-header.duration=2.0")); }),
             Catch::Contains("hand.jpk-force") && Catch::Contains("segments/0/segment-header.properties") &&
                 Catch::Contains("'force-segment-header.duration' is given twice"));
}

TEST_CASE("JPK map grid: NaN, infinite, fractional or non-positive values are refused before any cast", "[io][headers]") {
  test::TempDir dir;
  const std::string grid =
      "force-scan-map.position-pattern.grid.ilength=2\nforce-scan-map.position-pattern.grid.jlength=2\n"
      "force-scan-map.position-pattern.grid.ulength=1.0E-5\nforce-scan-map.position-pattern.grid.vlength=1.0E-5\n"
      "force-scan-map.position-pattern.grid.xcenter=0.0\nforce-scan-map.position-pattern.grid.ycenter=0.0";
  const InstrumentFile good = read_instrument_file(archive(dir, 0, "", grid));
  CHECK(good.grid_shape_x == 2);
  CHECK(good.curves[0].grid_x == 1);  // x = 1 um in a 10 um grid centred on 0: the right half
  struct Case {
    const char* line;
    const char* bad;
  };
  for (const Case& c : {Case{"grid.xcenter=0.0", "grid.xcenter=nan"}, Case{"grid.ycenter=0.0", "grid.ycenter=Infinity"},
                        Case{"grid.ilength=2", "grid.ilength=2.5"}, Case{"grid.jlength=2", "grid.jlength=1e300"},
                        Case{"grid.ilength=2", "grid.ilength=0"}, Case{"grid.ulength=1.0E-5", "grid.ulength=-1.0E-5"},
                        Case{"grid.vlength=1.0E-5", "grid.vlength=NaN"}}) {
    std::string text = grid;
    text.replace(text.find(c.line), std::string(c.line).size(), c.bad);
    INFO(c.bad);
    CHECK_THAT(input_error([&] { read_instrument_file(archive(dir, 0, "", text)); }),
               Catch::Contains("hand.jpk-force") && Catch::Contains("header.properties") &&
                   Catch::Contains(std::string(c.bad).substr(5, std::string(c.bad).find('=') - 5)));
  }
  std::string missing = grid;
  missing.erase(missing.find("force-scan-map.position-pattern.grid.xcenter"));
  CHECK_THAT(input_error([&] { read_instrument_file(archive(dir, 0, "", missing)); }), Catch::Contains("xcenter"));
}

TEST_CASE("Igor notes: SpringConstant and InvOLS must be whole finite numbers > 0", "[io][headers]") {
  const InstrumentFile f = igor(kNote + "SpringConstant: 1.1841\r");
  REQUIRE(f.curves.size() == 1);
  CHECK(f.curves[0].spring_constant == 1.1841);
  CHECK(f.curves[0].segments.size() == 2);
  for (const char* bad : {"1,1841", "1e-3e5", "1.1841 N/m", "NaN", "inf", "-1", "0", ""}) {
    INFO(bad);
    CHECK_THAT(input_error([&] { igor(kNote + "SpringConstant: " + bad + "\r"); }),
               Catch::Contains("hand.ibw") && Catch::Contains("SpringConstant") && Catch::Contains("finite number > 0"));
  }
}

TEST_CASE("Igor notes: a repeated key is one value - copies that differ give the last, the curve's own, and a note",
          "[io][headers]") {
  // As Asylum's ARDF export writes them (AR 13.16): the map's header block, then the curve's own.
  const InstrumentFile same = igor(kNote + "SpringConstant: 1.1841\rSaveImage:1\rSaveImage:0\rSpringConstant: 1.1841\r");
  CHECK(same.curves[0].spring_constant == 1.1841);
  CHECK(same.curves[0].notes.empty());  // SaveImage is not read; a repeat with the same value is no news
  const InstrumentFile differ = igor(kNote + "SpringConstant: 1.1841\rSpringConstant: 0.5\rInvOLS: 4.5e-08\r");
  CHECK(differ.curves[0].spring_constant == 0.5);
  CHECK(differ.curves[0].sensitivity == 4.5e-08);
  REQUIRE(differ.curves[0].notes.size() == 2);
  CHECK_THAT(differ.curves[0].notes[0], Catch::Contains("SpringConstant 2 times with different values ('1.1841', '0.5')") &&
                                            Catch::Contains("the last"));
  CHECK_THAT(differ.curves[0].notes[1], Catch::Contains("InvOLS"));
  // The notes reach the fit's notices, not its warnings.
  const CurveData d = to_curve_data(differ.curves[0], "hand.ibw");
  CHECK(d.notes == differ.curves[0].notes);
}

TEST_CASE("Igor notes: NaN in Direction in any case - Asylum's export writes Nan", "[io][headers]") {
  for (const char* nan : {"NaN", "Nan", "nan", "NAN"}) {
    std::string note = kNote + "SpringConstant: 1.1841\r";
    note.replace(note.find("Direction: NaN,1,-1,"), 20, std::string("Direction: ") + nan + ",1,-1,0,");
    INFO(nan);
    const InstrumentFile f = igor(note);
    REQUIRE(f.curves[0].segments.size() == 2);
    CHECK(f.curves[0].segments[0].style == SegmentStyle::extend);
    CHECK(f.curves[0].segments[1].style == SegmentStyle::retract);
  }
}

TEST_CASE("Igor notes: Indexes and Direction are lists of numbers, nothing else", "[io][headers]") {
  std::string note = kNote + "SpringConstant: 1.1841\r";
  const std::string good = "Indexes: 0,2,5";
  for (const char* bad : {"Indexes: 0,2x,5", "Indexes: 0,,5", "Indexes: 0,2;5", "Indexes: 0,2,1e-3e5"}) {
    std::string text = note;
    text.replace(text.find(good), good.size(), bad);
    INFO(bad);
    CHECK_THAT(input_error([&] { igor(text); }), Catch::Contains("hand.ibw") && Catch::Contains("Indexes"));
  }
  std::string direction = note;
  direction.replace(direction.find("Direction: NaN,1,-1,"), 20, "Direction: NaN,one,-1");
  CHECK_THAT(input_error([&] { igor(direction); }), Catch::Contains("Direction") && Catch::Contains("'one'"));
}

TEST_CASE("JPK files without a spring constant or a sensitivity read, and need them given", "[io][headers]") {
  // Issue 41: afmformats' fmt-jpk-fd_single-modified_2023.jpk-force (force conversion removed)
  // failed with "no '...conversion.force.base-calibration-slot'" and could not be read even with
  // a spring constant; afmformats asks for one (MissingMetaDataError) and takes an override:
  // force[0] = -5.261711536426128e-07 N with k = 12, and -0.2454449015321114 N with k = 10 and
  // sensitivity 0.05 m/V - what `layerjkr export --spring-constant` gives on that file.
  const test::TempDir dir;
  const InstrumentFile calibrated = read_instrument_file(archive(dir, 1, "", ""));
  const double volts = calibrated.curves[0].segments[0].force[1] / (5e-8 * 0.05);  // sample 1: not 0
  const std::string no_k = archive(dir, 1, "channel.vDeflection.conversion-set.conversion.force.base-calibration-slot=distance",
                                   "channel.vDeflection.conversion-set.conversion.force.defined=false");
  const InstrumentCurve c = read_instrument_file(no_k).curves[0];
  CHECK(std::isnan(c.spring_constant));
  CHECK(c.sensitivity == 5e-8);
  CHECK_THAT(input_error([&] { to_curve_data(c, "hand.jpk-force"); }),
             Catch::Contains("hand.jpk-force: the file gives no spring constant") && Catch::Contains("--spring-constant"));
  CHECK(to_curve_data(c, "hand.jpk-force", 12.0).P[1] == Approx(volts * 5e-8 * 12.0).epsilon(1e-14));
  CHECK(to_curve_data(c, "hand.jpk-force", 10.0, 0.05).P[1] == Approx(volts * 0.05 * 10.0).epsilon(1e-14));
  // A calibrated file: a sensitivity given rescales its deflection, a spring constant its force.
  const InstrumentCurve k = calibrated.curves[0];
  CHECK(to_curve_data(k, "x", 0.0, 1e-7).P[1] == Approx(volts * 1e-7 * 0.05).epsilon(1e-14));
  // Neither conversion (a calibration force-save: volts): both must be given.
  std::vector<test::Member> members = test::jpk_members();
  std::string& seg = members[1].bytes;
  for (const char* slot : {"distance", "force"}) {
    const std::string key = std::string("channel.vDeflection.conversion-set.conversion.") + slot + ".base-calibration-slot=";
    seg.erase(seg.find(key), seg.find('\n', seg.find(key)) - seg.find(key) + 1);
  }
  const std::string path = dir.file("volts.jpk-force");
  test::write_zip(path, members);
  const InstrumentCurve v = read_instrument_file(path).curves[0];
  CHECK(std::isnan(v.sensitivity));
  CHECK_THAT(input_error([&] { to_curve_data(v, "volts.jpk-force", 0.1); }),
             Catch::Contains("no deflection sensitivity (its deflection is in volts)") && Catch::Contains("--sensitivity"));
  CHECK(to_curve_data(v, "volts.jpk-force", 0.1, 5e-8).P[1] == Approx(volts * 5e-8 * 0.1).epsilon(1e-14));
}

TEST_CASE("JPK QI series (.jpk-qi-series): one curve, its header keyed by the scan type", "[io][headers]") {
  // Issue 41: the JPK format afmformats opens by the suffix .jpk-qi-series was "not an instrument
  // file". Its archive is a .jpk-force's with quantitative-imaging-series.* header keys (afmformats'
  // fmt-jpk-fd_qi-data-2021.04.13.jpk-qi-series: two segments of 1 000 samples, position-index 170).
  const test::TempDir dir;
  std::vector<test::Member> members = test::jpk_members();
  std::string& top = members[0].bytes;
  for (std::size_t at; (at = top.find("force-scan-series.")) != std::string::npos;)
    top.replace(at, std::string("force-scan-series.").size(), "quantitative-imaging-series.");
  const std::string path = dir.file("hand.jpk-qi-series");
  test::write_zip(path, members);
  REQUIRE(instrument_format(path) == InstrumentFormat::jpk_qi_series);
  const InstrumentFile f = read_instrument_file(path);
  CHECK(f.format == InstrumentFormat::jpk_qi_series);
  REQUIRE(f.curves.size() == 1);
  CHECK(f.curves[0].x == 1e-6);
  CHECK(f.curves[0].y == 2e-6);
  const InstrumentFile same = read_instrument_file(archive(dir, 0, "", ""));
  CHECK(f.curves[0].segments[0].force == same.curves[0].segments[0].force);
}
