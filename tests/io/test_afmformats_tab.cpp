// afmformats' tab export (src/io/afmformats_tab.cpp), read as read_curve_csv reads any curve file:
// the file afmformats' own test writes (force, tip position, segment as True/False) to the values
// that test asserts, and the 0.13.3 layout whose first row sits on the column names' line.
#include <catch2/catch.hpp>

#include <cmath>
#include <string>

#include "layerjkr/curve_data.hpp"
#include "layerjkr/error.hpp"
#include "support/test_support.hpp"

using namespace layerjkr;

TEST_CASE("afmformats tab: the file afmformats' test writes, to the values it asserts", "[io][afmformats]") {
  // tests/test_fmt_tab.py::generate_tab_file and test_open_simple (afmformats, MIT).
  std::string text = "# BEGIN METADATA\r\n# {\r\n#   \"software\": \"JPK\",\r\n#   \"spring constant\": 0.02230065831827453\r\n"
                     "# }\r\n# END METADATA\r\n# force\ttip position\tsegment\r\n";
  char row[128];
  for (int ii = 0; ii < 100; ++ii) {
    std::snprintf(row, sizeof row, "%.17g\t%.17g\t%s\r\n", ii * 1e-9, M_PI * ii * 1e-6, ii > 50 ? "True" : "False");
    text += row;
  }
  const CurveData d = parse_curve_csv(text, "gen.tab");
  REQUIRE(d.size() == 100);
  int retract = 0;
  for (int s : d.segment) retract += s;
  CHECK(retract == 49);
  CHECK(d.P[0] == 0.0);
  CHECK(d.P[1] == Approx(1e-9).epsilon(1e-15));
  CHECK(-d.delta[1] == Approx(M_PI * 1e-6).epsilon(1e-15));
  CHECK(d.spring_constant == 0.02230065831827453);
}

TEST_CASE("afmformats tab 0.13.3: heights placed by the spring constant, the glued first row kept", "[io][afmformats]") {
  // The layout of afmformats' fmt-tab-fd_version_0.13.3.tab (a JPK curve): the first row written
  // on the column names' line. afmformats skips that line, so its force[2000] (-6.7762282e-10) is
  // this reader's sample 2001.
  const std::string head = "# afmformats 0.13.3\n#\n# BEGIN METADATA\n# {\n#   \"spring constant\": 0.02,\n"
                           "#   \"software\": \"JPK\"\n# }\n# END METADATA\n#\n";
  const std::string text = head +
                           "# force\theight (measured)\theight (piezo)\tsegment\ttime-6.7744671e-10\t5.5198847e-05\t"
                           "3.7875836e-05\tFalse\t1.1245\n"
                           "-6.8435897e-10\t5.5194395e-05\t3.7871432e-05\tFalse\t1.125\n"
                           "1e-9\t5.5e-05\t3.7e-05\tTrue\t1.1255\n";
  const CurveData d = parse_curve_csv(text, "glued.tab");
  REQUIRE(d.size() == 3);
  CHECK(d.P[0] == -6.7744671e-10);
  CHECK(d.delta[0] == Approx(-(5.5198847e-05 - 6.7744671e-10 / 0.02)).epsilon(1e-15));  // -(height + F/k)
  CHECK(d.t == std::vector<double>{1.1245, 1.125, 1.1255});
  CHECK(d.segment == std::vector<int>{0, 0, 1});
  bool said = false;
  for (const std::string& n : d.notes) said = said || n.find("first sample is written on the column names' line") != std::string::npos;
  CHECK(said);
  // Heights without a spring constant cannot place the tip: refused, naming the option.
  std::string no_k = text;
  no_k.replace(no_k.find("\"spring constant\": 0.02,"), std::string("\"spring constant\": 0.02,").size(), "");
  CHECK_THAT(test::input_error([&] { parse_curve_csv(no_k, "nok.tab"); }),
             Catch::Contains("nok.tab: afmformats tab export") && Catch::Contains("--spring-constant"));
  CsvOptions given;
  given.spring_constant = 0.04;
  CHECK(parse_curve_csv(no_k, "nok.tab", given).delta[0] == Approx(-(5.5198847e-05 - 6.7744671e-10 / 0.04)));
  CHECK_THAT(test::input_error([&] { parse_curve_csv(head + "# force\tfoo\n1\t2\n", "bad.tab"); }),
             Catch::Contains("column 'foo' is not one it knows"));
}
