// Asylum force maps as users export them: one 1-D Igor wave per channel per point
// (LineLLLL/LineLLLLPointPPPP<Chan>.ibw, notes holding only XLVDT, YLVDT and Indexes) and the map's
// image beside them (MapHeight/MapAdhesion layers; its note the calibration and the scan), built
// here as SOFA's public test data lay them out. Read as one map: a curve per point, pixel from the
// name, edges-inclusive positions, Defl x k; without the image the points' own LVDTs and no k.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>

#include "io/instrument_readers.hpp"
#include "io/jpk_builder.hpp"
#include "layerjkr/curve_data.hpp"
#include "layerjkr/error.hpp"
#include "layerjkr/instrument.hpp"
#include "support/temp_dir.hpp"
#include "support/test_support.hpp"

using namespace layerjkr;
namespace fs = std::filesystem;

namespace {

constexpr int kPoints = 3, kLines = 2;

fs::path make_export(const std::string& name, bool with_image, bool folders = true) {
  const fs::path root = test::scratch().path() / name;
  test::write_asylum_map_export(root.string(), with_image, folders);
  return root;
}

}  // namespace

TEST_CASE("Asylum map exports: a folder of per-channel waves is one map, calibrated by its image", "[io][asylum]") {
  const fs::path root = make_export("map", true);
  REQUIRE(is_asylum_map_export(root.string()));
  const InstrumentReader r(root.string());
  CHECK(r.header().format == InstrumentFormat::ibw_map);
  CHECK(r.header().grid_shape_x == kPoints);
  CHECK(r.header().grid_shape_y == kLines);
  CHECK(r.header().grid_size_x == Approx(4e-6 * 3 / 2));  // 3 pixels of pitch 4 um / (3 - 1)
  REQUIRE(r.size() == 6);
  const InstrumentCurve c = r.curve(4);  // line 1, point 1 (row-major by line)
  CHECK(c.grid_x == 1);
  CHECK(c.grid_y == 1);
  CHECK(c.spring_constant == 0.5);
  CHECK(c.sensitivity == 3.5e-08);
  // Points on the scan's edges: x = XOffset + (1/2 - 1/2) 4 um, y = YOffset + (1 - 1/2) 2 um.
  CHECK(c.x == Approx(1e-6));
  CHECK(c.y == Approx(-1e-6 + 1e-6));
  CHECK(r.curve(0).x == Approx(1e-6 - 2e-6));
  // Indexes 0,3,6,8 without Direction: extend [0, 3], retract (3, 6], a dwell (6, 8].
  REQUIRE(c.segments.size() == 3);
  CHECK(c.segments[0].style == SegmentStyle::extend);
  CHECK(c.segments[1].style == SegmentStyle::retract);
  CHECK(c.segments[2].style == SegmentStyle::pause);
  CHECK(c.segments[0].force.size() == 4);
  CHECK(c.segments[0].force[0] == Approx(0.5 * 2e-9));   // Defl x k, row 0 of line 1
  CHECK(c.segments[0].height[0] == Approx(-101e-9));     // -ZSnsr of point 1
  CHECK(c.segments[0].duration == Approx(4 * 5e-4));
  CHECK(c.segments[0].piezo_height.empty());  // no Raw channel exported
}

TEST_CASE("Asylum map exports: without the image, each point's LVDTs and a spring constant given", "[io][asylum]") {
  const fs::path root = make_export("bare", false, false);
  const InstrumentReader r(root.string());
  REQUIRE(r.size() == 6);
  const InstrumentCurve c = r.curve(5);  // line 1, point 2
  CHECK(std::isnan(c.spring_constant));
  CHECK(c.x == Approx(2e-6));  // XLVDT
  CHECK(c.y == Approx(2e-6));  // YLVDT
  CHECK_THAT(c.notes.front(), Catch::Contains("no map image"));
  CHECK_THAT(test::input_error([&] { to_curve_data(c, "bare#5"); }),
             Catch::Contains("bare#5") && Catch::Contains("no spring constant") && Catch::Contains("--spring-constant"));
  const CurveData d = to_curve_data(c, "bare#5", 0.2);  // force = k x deflection
  CHECK(d.P[0] == Approx(0.2 * 2e-9));
  CHECK(d.delta[0] == Approx(-(-102e-9 + 2e-9)));
}

TEST_CASE("Asylum map exports: a glob of the waves, a lone channel and the image say what they are", "[io][asylum]") {
  const fs::path root = make_export("globbed", true);
  const std::string pattern = (root / "Line0001" / "Line0001Point*.ibw").string();
  REQUIRE(is_asylum_map_export(pattern));
  const InstrumentReader r(pattern);
  REQUIRE(r.size() == 3);  // line 1 only
  CHECK(r.curve(0).grid_y == 1);
  CHECK(r.curve(0).spring_constant == 0.5);  // the image two folders up fits the files' grid
  CHECK_FALSE(is_asylum_map_export((root / "*.ibw").string()));  // matches the image too
  CHECK_THAT(test::input_error([&] { read_instrument_file((root / "Line0000" / "Line0000Point0000Defl.ibw").string()); }),
             Catch::Contains("one channel (Defl) of one point") && Catch::Contains("fit-map on the folder"));
  CHECK_THAT(test::input_error([&] { read_instrument_file((root / "ForceMap01.ibw").string()); }),
             Catch::Contains("is an image (3 x 2 x 2, layers MapHeight") && Catch::Contains("not force curves"));
  // A point without its ZSnsr fails alone.
  fs::remove(root / "Line0000" / "Line0000Point0002ZSnsr.ibw");
  const InstrumentReader partial(root.string());
  CHECK_THAT(test::input_error([&] { partial.curve(2); }), Catch::Contains("line 0 point 2 has no ZSnsr file"));
  CHECK_NOTHROW(partial.curve(1));
}

TEST_CASE("Asylum map exports: a point given twice is two curves, with a note, none dropped", "[io][asylum]") {
  // Issue 41: point (0,0) present as a flat copy beside the LineLLLL folders gave 6 rows for 7
  // curves - one measurement dropped without a word.
  const fs::path root = make_export("twice", true);
  for (const char* chan : {"Defl", "ZSnsr"})
    fs::copy_file(root / "Line0000" / (std::string("Line0000Point0000") + chan + ".ibw"),
                  root / (std::string("Line0000Point0000") + chan + ".ibw"));
  const InstrumentReader r(root.string());
  REQUIRE(r.size() == 7);
  CHECK(r.curve(0).grid_x == 0);
  CHECK(r.curve(1).grid_x == 0);  // the second set of the same point
  CHECK(r.curve(1).grid_y == 0);
  CHECK(r.curve(2).grid_x == 1);
  bool said = false;
  for (const std::string& n : r.curve(1).notes) said = said || n.find("line 0 point 0 is given by 2 sets of files") != std::string::npos;
  CHECK(said);
  CHECK(r.curve(0).segments[0].force == r.curve(1).segments[0].force);  // the same data, both kept
}

TEST_CASE("Asylum point names: LineLLLLPointPPPP<channel>, from the end of a wave's or a file's name", "[io][asylum]") {
  using detail::asylum_point_name;
  const auto full = asylum_point_name("Line0012Point0345Defl", true);
  REQUIRE(full);
  CHECK(full->line == 12);
  CHECK(full->point == 345);
  CHECK(full->channel == "Defl");
  const auto in_wave = asylum_point_name("PAAm_Line0001Point0002");  // a wave name with a prefix
  REQUIRE(in_wave);
  CHECK(in_wave->line == 1);
  CHECK(in_wave->point == 2);
  CHECK(in_wave->channel.empty());
  CHECK_FALSE(asylum_point_name("PAAm_Line0001Point0002", true));  // whole: must start with Line
  CHECK_FALSE(asylum_point_name("Line0001Point0002Defl.ibw"));      // '.' is not a channel's
  CHECK_FALSE(asylum_point_name("Line1234567Point0002"));            // 7 digits
  CHECK_FALSE(asylum_point_name("LinePoint0002"));
  CHECK_FALSE(asylum_point_name("Line0001Point"));
  CHECK_FALSE(asylum_point_name("Line0001Pt0002"));
  const auto later = asylum_point_name("Line0001Point0002_Line0003Point0004Raw");  // the last one counts
  REQUIRE(later);
  CHECK(later->line == 3);
  CHECK(later->channel == "Raw");
}

TEST_CASE("Asylum ARDF and HDF5 maps are refused saying what to export instead", "[io][asylum]") {
  for (const std::string name : {"map.ARDF", "map.ardf", "map.h5"}) {
    const fs::path path = test::scratch().path() / name;
    std::ofstream(path, std::ios::binary) << std::string("ARDF\0\0\0\0binary", 14);
    // (Catch2's combined matchers hold references to their parts: written out in each check.)
    CHECK_THROWS_WITH(InstrumentReader(path.string()),  // export, fit-map's instrument path
                      Catch::Contains("not read") && Catch::Contains("LineLLLLPointPPPP<Channel>.ibw") &&
                          Catch::Contains(name));
    CHECK_THROWS_WITH(read_curve_csv(path.string()),  // fit's fallback for unknown names
                      Catch::Contains("not read") && Catch::Contains("LineLLLLPointPPPP<Channel>.ibw") &&
                          Catch::Contains(name));
  }
}
