// Public instrument files as their vendors wrote them (tests/data/instrument/README.md): what
// the source suites assert, and values computed independently (a Python parser of the Igor
// binary wave v5 layout reading the float32 columns with struct.unpack; the NanoScope LSB values
// of the research note in the README's commit, scaled by the header's V/LSB and sensitivity).
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iterator>

#include "layerjkr/curve_data.hpp"
#include "layerjkr/instrument.hpp"
#include "support/test_support.hpp"

using namespace layerjkr;

namespace {
const std::string kDir = std::string(LAYERJKR_SOURCE_DIR) + "/tests/data/instrument/";

void check_close(double got, double expected) {
  INFO(got << " vs " << expected);
  CHECK(std::abs(got - expected) <= 1e-12 * std::abs(expected));
}
}  // namespace

TEST_CASE("public files: Asylum's ARDF export (AR 13.16) - repeated keys, Nan, a dwell after the retract",
          "[io][public]") {
  const InstrumentFile f = read_instrument_file(kDir + "IgorIBWReader_ForceCurve.ibw");
  REQUIRE(f.curves.size() == 1);
  const InstrumentCurve& c = f.curves[0];
  CHECK(f.software == "13.16.100");
  // SciFiReaders asserts SpringConstant 0.018189, InvOLS 1e-07 and three columns of 1261 rows.
  CHECK(c.spring_constant == 0.018189);
  CHECK(c.sensitivity == 1e-07);
  CHECK(c.notes.empty());  // SpringConstant is repeated with the same value; the differing keys are not read
  REQUIRE(c.segments.size() == 3);
  CHECK(c.segments[0].style == SegmentStyle::extend);
  CHECK(c.segments[1].style == SegmentStyle::retract);
  CHECK(c.segments[2].style == SegmentStyle::pause);  // Direction 0: the dwell away from the surface
  CHECK(c.segments[0].force.size() == 225);
  CHECK(c.segments[1].force.size() == 1008);
  CHECK(c.segments[2].force.size() == 28);
  // Force = Defl x k, height = -ZSnsr: rows 0, 224, 225, 1232, 1233, 1260 of the independent parser.
  check_close(c.segments[0].force.front(), -4.912699548924593e-09);
  check_close(c.segments[0].force.back(), -4.640870858423796e-09);
  check_close(c.segments[1].force.front(), -4.640447983121021e-09);
  check_close(c.segments[1].force.back(), -4.949035807214841e-09);
  check_close(c.segments[2].force.front(), -4.9509738995254795e-09);
  check_close(c.segments[2].force.back(), -4.952494286158071e-09);
  check_close(c.segments[0].height.front(), -4.897278358839685e-06);
  check_close(c.segments[0].height.back(), -4.937620360578876e-06);
  check_close(c.segments[2].height.back(), -4.73379077448044e-06);
  // 2000 points a second (NumPtsPerSec): 225 rows of extend are 0.1125 s.
  check_close(c.segments[0].duration, 225 * 0.0005);
  // The dwell after the retract is on the retract branch of the curve a fit reads.
  const CurveData d = to_curve_data(c, "ar13");
  CHECK(d.size() == 1261);
  CHECK(std::count(d.segment.begin(), d.segment.end(), 1) == 1036);
}

TEST_CASE("public files: a NanoScope 8.15 curve on sapphire - Ramp size, a Height Sensor, 2-byte samples",
          "[io][public][nanoscope]") {
  const InstrumentFile f = read_instrument_file(kDir + "BrukerReader_ForceCurve_Sapphire_TAP525.001");
  REQUIRE(f.curves.size() == 1);
  const InstrumentCurve& c = f.curves[0];
  CHECK(c.spring_constant == 90.0);  // the deflection channel's list (the Height Sensor's says 0.0677954)
  // SciFiReaders asserts two channels of 512 samples; here extend and retract of 512 each.
  REQUIRE(c.segments.size() == 2);
  CHECK(c.segments[0].force.size() == 512);
  CHECK(c.segments[1].force.size() == 512);
  // Deflection LSB -27 (extend, first in time) and 537 (last), x 0.000375 V/LSB x 72.76923 nm/V x k.
  check_close(c.segments[0].force.front(), -7.3678845375e-10 * 90.0);
  check_close(c.segments[0].force.back(), 1.465390369125e-08 * 90.0);
  // Height Sensor LSB 766 -> 2411 on extend: the sensor grows towards the sample; height = -that.
  check_close(c.segments[0].height.front(), -2.7580906230000003e-07);
  check_close(c.segments[0].height.back(), -8.681144245500001e-07);
  // Ramp size (lower-case s in 8.15) 16.72241 V over Forward vel. 34.38 V/s.
  check_close(c.segments[0].duration, 16.72241 / 34.38);
}

TEST_CASE("public files: AFM Workshop exports - Z-Sense and Force, or T-B volts with the gain", "[io][public][csv]") {
  const std::string force_file = kDir + "fmt-afm-workshop-fd_single_2020-02-14_13.41.25.csv";
  // No spring constant in the file: the tip's position needs one.
  CHECK_THROWS_WITH(read_curve_csv(force_file), Catch::Contains("no spring constant") && Catch::Contains("--spring-constant"));
  CsvOptions o;
  o.spring_constant = 40.0;
  const CurveData d = read_curve_csv(force_file, o);
  REQUIRE(d.size() == 2030);  // afmformats asserts 2030 samples and force[0] = 1276.4373e-9
  CHECK(std::count(d.segment.begin(), d.segment.end(), 0) == 1015);
  check_close(d.P[0], 1276.4373e-9);
  check_close(d.delta[0], 15072.4571e-9 - 1276.4373e-9 / 40.0);  // Z-Sense grows towards the sample
  check_close(d.P[1015], 3809.6950e-9);                          // the first retract row
  CHECK(d.spring_constant == 40.0);
  // T-B volts need the Light Lever Gain: refused without it; with the gain of afmformats' own test
  // (100 mV/nm, its sensitivity 1e-8 m/V) and k = 20, force[0] = 0.6861 x 1e-8 x 20, as afmformats asserts.
  const std::string volts_file = kDir + "fmt-afm-workshop-fd_single_2018-08-01_13.06.09.csv";
  CHECK_THROWS_WITH(read_curve_csv(volts_file, o), Catch::Contains("T-B(V)") && Catch::Contains("Light Lever Gain"));
  std::string text;
  {
    std::ifstream in(volts_file, std::ios::binary);
    text.assign(std::istreambuf_iterator<char>(in), {});
  }
  text.insert(text.find("\r\nExtend Z-Sense"), "\r\nLight Lever Gain, mV/nm:\t100\r\nForce Constant, nN/nm:\t20.0");
  const CurveData v = parse_curve_csv(text, "gain.csv");
  check_close(v.P[0], 0.6861 * 1e-8 * 20.0);
  CHECK(v.spring_constant == 20.0);
}
