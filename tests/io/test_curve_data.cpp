// The CSV reader: every form, units, branch selection, and one clear error per defect.
#include <catch2/catch.hpp>

#include <fstream>

#include "layerjkr/curve_data.hpp"
#include "layerjkr/error.hpp"
#include "support/temp_dir.hpp"

using namespace layerjkr;

TEST_CASE("delta,P with optional columns, comments and CRLF", "[csv]") {
  const CurveData c = parse_curve_csv(
      "# made by hand\r\ndelta,P,a,weight,segment\r\n1e-6,2e-9,3e-6,1,0\r\n2e-6,5e-9,4e-6,2,1\r\n\r\n", "t");
  REQUIRE(c.size() == 2);
  CHECK(c.delta[1] == 2e-6);
  CHECK(c.P[1] == 5e-9);
  CHECK(c.a[0] == 3e-6);
  CHECK(c.weight[1] == 2.0);
  CHECK(c.segment[1] == 1);
}

TEST_CASE("units scale lengths and forces", "[csv]") {
  CsvOptions o;
  parse_units("nm,nN", o);
  const CurveData c = parse_curve_csv("P,delta\n2,100\n", "t", o);
  CHECK(c.delta[0] == Approx(1e-7).epsilon(1e-15));
  CHECK(c.P[0] == Approx(2e-9).epsilon(1e-15));
  CHECK_THROWS_WITH(parse_units("nm", o), Catch::Contains("LENGTH,FORCE"));
  CHECK_THROWS_WITH(parse_units("furlong,N", o), Catch::Contains("furlong"));
  CHECK_THROWS_WITH(parse_curve_csv("delta_m,P\n1,2\n", "t", o), Catch::Contains("SI"));
}

TEST_CASE("JPK tip_position,force and raw z,deflection forms", "[csv]") {
  const CurveData j = parse_curve_csv("tip_position_m,force_N\n1.8e-5,1e-10\n", "t");
  CHECK(j.delta[0] == -1.8e-5);
  CHECK(j.P[0] == 1e-10);
  CsvOptions o;
  o.spring_constant = 0.05;
  const CurveData r = parse_curve_csv("z,deflection\n1e-6,2e-8\n", "t", o);
  CHECK(r.delta[0] == Approx(1e-6 - 2e-8).epsilon(1e-15));
  CHECK(r.P[0] == Approx(0.05 * 2e-8).epsilon(1e-15));
  o.z_sign = -1.0;
  o.deflection_sign = -1.0;
  const CurveData f = parse_curve_csv("z,deflection\n1e-6,2e-8\n", "t", o);
  CHECK(f.delta[0] == Approx(-1e-6 + 2e-8).epsilon(1e-15));
  CHECK(f.P[0] == Approx(-0.05 * 2e-8).epsilon(1e-15));
  CHECK_THROWS_WITH(parse_curve_csv("z,deflection\n1,2\n", "t"), Catch::Contains("spring constant k [N/m]"));
}

TEST_CASE("P,a: a rig's load and contact radius without a displacement", "[csv]") {
  CsvOptions o;
  parse_units("um,mN", o);
  const CurveData d = parse_curve_csv("P,a,segment\n0.5,200,0\n1.5,300,0\n-0.5,150,1\n", "rig", o);
  CHECK(d.radius_only());
  CHECK(d.size() == 3);
  CHECK(d.delta.empty());
  CHECK(d.a[1] == Approx(300e-6));
  CHECK(d.P[2] == Approx(-0.5e-3));
  CHECK(d.retract_mask() == std::vector<bool>{false, false, true});
  CHECK_THROWS_WITH(parse_curve_csv("P,weight\n1,1\n", "t"), Catch::Contains("or P with a"));
}

TEST_CASE("z,force: the piezo and the force, the deflection force / k (AFM Workshop, lab scripts)", "[csv]") {
  CsvOptions o;
  o.spring_constant = 0.05;
  // The same sample as z,deflection 1e-6,2e-8 above: force = k x deflection = 1e-9 N.
  const CurveData r = parse_curve_csv("z,force\n1e-6,1e-9\n", "t", o);
  CHECK(r.delta[0] == Approx(1e-6 - 2e-8).epsilon(1e-15));
  CHECK(r.P[0] == 1e-9);
  parse_units("nm,nN", o);  // AFM Workshop writes Z-Sense in nm and Force in nN
  const CurveData n = parse_curve_csv("z,force,segment\n1000,1,0\n", "t", o);
  CHECK(n.delta[0] == Approx(1e-6 - 2e-8).epsilon(1e-15));
  CHECK(n.P[0] == Approx(1e-9).epsilon(1e-15));
  CHECK_THROWS_WITH(parse_curve_csv("z,force\n1,2\n", "t"),
                    Catch::Contains("z,force data need the cantilever spring constant") && Catch::Contains("force / k"));
  CHECK_THROWS_WITH(parse_curve_csv("z,force,deflection\n1,2,3\n", "t", o), Catch::Contains("not both"));
}

TEST_CASE("branches: segment column or a split at the deepest point", "[csv]") {
  CurveData c;
  c.delta = {0, 1, 2, 3, 2, 1};
  c.P = {0, 0, 0, 0, 0, 0};
  CHECK(c.select(Branch::approach) == std::vector<std::size_t>{0, 1, 2, 3});
  CHECK(c.select(Branch::retract) == std::vector<std::size_t>{4, 5});
  CHECK(c.select(Branch::all).size() == 6);
  c.segment = {0, 0, 1, 1, 1, 1};
  CHECK(c.select(Branch::approach) == std::vector<std::size_t>{0, 1});
  CHECK(parse_enum<Branch>("retract", "branch") == Branch::retract);
  CHECK_THROWS_WITH(parse_enum<Branch>("down", "branch"), Catch::Contains("down") && Catch::Contains("approach"));
}

TEST_CASE("every defect names the line and the column", "[csv][errors]") {
  auto err = [](const std::string& text) {
    try {
      parse_curve_csv(text, "data.csv");
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  CHECK_THAT(err(""), Catch::Contains("data.csv") && Catch::Contains("empty"));
  CHECK_THAT(err("delta,P\n"), Catch::Contains("no data rows"));
  CHECK_THAT(err("delta,F\n1,2\n"), Catch::Contains("'F' is unknown"));
  CHECK_THAT(err("delta,P\n1,abc\n"), Catch::Contains("line 2") && Catch::Contains("'P'") && Catch::Contains("abc"));
  CHECK_THAT(err("delta,P\n1,nan\n"), Catch::Contains("not a finite number"));
  CHECK_THAT(err("delta,P\n1,1e999\n"), Catch::Contains("not a finite number"));
  CHECK_THAT(err("delta,P\n1,2,3\n"), Catch::Contains("line 2 has 3 cells"));
  CHECK_THAT(err("delta,P\n1\n"), Catch::Contains("line 2 has 1 cells"));
  CHECK_THAT(err("delta,P,weight\n1,2,0\n"), Catch::Contains("weight = 0"));
  CHECK_THAT(err("delta,P,segment\n1,2,3\n"), Catch::Contains("segment") && Catch::Contains("2 (dwell)"));
  CHECK_THAT(err("delta,P,segment\n1,2,1\n2,3,0\n"), Catch::Contains("returns to segment 0 after retract rows"));
  CHECK_THAT(err("delta,P,t\n1,2,0.5\n2,3,0.5\n"), Catch::Contains("t = 0.5 s in row 2 does not increase"));
  CHECK_THAT(err("delta,P,t\n1,2,inf\n"), Catch::Contains("not a finite number"));
  CHECK_THAT(err("delta,P,a\n1,2,-1\n"), Catch::Contains("a = -1"));
  CHECK_THAT(err("delta,P,P\n1,2,3\n"), Catch::Contains("twice"));
  CHECK_THAT(err("P\n1\n"), Catch::Contains("delta, tip_position, z"));
  CHECK_THAT(err(std::string("delta,P\n1,\0\n", 11)), Catch::Contains("not a text file"));
  CHECK_THAT(err("delta,P,segment\n1,2,0\n2,3,1\n3,4,0\n"), Catch::Contains("row 3 returns to segment 0"));
  CHECK(parse_curve_csv("delta,P\n1,2\n2,3\n2,3\n", "t").size() == 3);  // repeats are samples
  CHECK_THROWS_WITH(read_curve_csv("/nonexistent/x.csv"), Catch::Contains("cannot open"));
}

TEST_CASE("a leading UTF-8 byte-order mark is ignored, as in scene files", "[csv]") {
  const CurveData d = parse_curve_csv("\xEF\xBB\xBF" "delta,P\n1,2\n2,3\n", "bom.csv");
  CHECK(d.size() == 2);
  CHECK(d.P[1] == 3.0);
}

TEST_CASE("input limits: rows, bytes, devices, each naming the limit", "[csv][errors][limits]") {
  CsvOptions few;
  few.max_rows = 2;
  CHECK(parse_curve_csv("delta,P\n1,2\n2,3\n", "t", few).size() == 2);
  CHECK_THROWS_WITH(parse_curve_csv("delta,P\n1,2\n2,3\n3,4\n", "t", few),
                    Catch::Contains("more than 2 data rows") && Catch::Contains("max_rows"));
  const std::string path = test::scratch().file("limits.csv");
  std::ofstream(path) << "delta,P\n1,2\n2,3\n";
  CsvOptions small;
  small.max_bytes = 10;
  CHECK_THROWS_WITH(read_curve_csv(path, small),
                    Catch::Contains("limits.csv") && Catch::Contains("10 bytes") && Catch::Contains("max_bytes"));
  CHECK(read_curve_csv(path).size() == 2);
  // A device would be read forever (summary /dev/urandom ate all memory); a directory is no file.
  CHECK_THROWS_WITH(read_curve_csv("/dev/urandom"), Catch::Contains("not a regular file"));
  CHECK_THROWS_WITH(read_curve_csv(test::scratch().path().string()), Catch::Contains("not a regular file"));
  CsvOptions zero;
  zero.max_rows = 0;
  CHECK_THROWS_AS(parse_curve_csv("delta,P\n1,2\n", "t", zero), DomainError);
}

TEST_CASE("the curve column of many curves is read in linear time", "[csv]") {
  // 200 000 distinct ids: a linear search per row (the old reader) took ~10 s here.
  std::string text = "curve,segment,force,height,tip_position\n";
  for (int i = 0; i < 200000; ++i) text += std::to_string(i) + ",0,1,0,-" + std::to_string(i % 7) + "\n";
  CsvOptions one;
  one.curve = 123456;
  const CurveData d = parse_curve_csv(text, "many.csv", one);
  CHECK(d.size() == 1);
  CHECK_THROWS_WITH(parse_curve_csv(text, "many.csv"), Catch::Contains("holds 200000 curves"));
}
