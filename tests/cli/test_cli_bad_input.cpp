// Bad input through every command: malformed, mistyped, missing, unknown, negative,
// non-finite, empty, huge and binary scenes and curves. Each must give exit code 2, one
// message line on stderr naming the problem, nothing on stdout and no output file -
// within a time limit (no hang).
#include <catch2/catch.hpp>

#include <filesystem>

#include "support/cli_support.hpp"

using namespace test::cli;
namespace fs = std::filesystem;

namespace {

const std::string kCurve = std::string(LAYERJKR_SOURCE_DIR) + "/data/curves/hydrogel_film_two_term.csv";
const std::string kScene = std::string(LAYERJKR_SOURCE_DIR) + "/data/scenes/hydrogel_film_two_term.json";

// Runs `args` under a 30 s timeout and checks the rejection contract.
void check_rejected(const std::string& what, const std::string& args, const std::string& expected,
                    const std::string& out) {
  const Run r = run("timeout 30 " + std::string(LAYERJKR_CLI_PATH) + " " + args, true);
  INFO(what << "\nstderr: " << r.err.substr(0, 300));
  CHECK(r.code == 2);
  CHECK(r.out.empty());
  CHECK(count_lines(r.err) == 1);
  CHECK(r.err.find(expected) != std::string::npos);
  CHECK_FALSE(fs::exists(out));
}


}  // namespace

TEST_CASE("every command rejects bad scenes with one message and exit 2", "[cli][bad-input]") {
  const std::string huge(8 << 20, ' ');
  struct Case {
    std::string name, text, expected;
  };
  const std::vector<Case> scenes{
      {"truncated", "{\"indenter\": {\"shape\": \"sphere\"", "not valid JSON"},
      {"not an object", "[1, 2, 3]", "must be a JSON object"},
      {"empty", "", "not valid JSON"},
      {"huge whitespace", huge + "{", "not valid JSON"},
      {"binary", std::string("\x7f" "ELF\x02\x01\x01\0\0\0", 10), "not valid JSON"},
      {"wrong type", R"({"indenter": {"shape": "sphere", "R": "1e-3"}, "medium": {"type": "winkler", "K": 1e9}})",
       "must be a number"},
      {"missing medium", R"({"indenter": {"shape": "sphere", "R": 1e-3}})", "medium is missing"},
      {"missing R", R"({"indenter": {"shape": "sphere"}, "medium": {"type": "winkler", "K": 1e9}})", "R is missing"},
      {"unknown shape", R"({"indenter": {"shape": "hexagon"}, "medium": {"type": "winkler", "K": 1e9}})",
       "\"hexagon\" is unknown"},
      {"unknown key", R"({"indenter": {"shape": "sphere", "R": 1e-3, "colour": 1}, "medium": {"type": "winkler", "K": 1e9}})",
       "colour is not a known key"},
      {"negative R", R"({"indenter": {"shape": "sphere", "R": -1e-3}, "medium": {"type": "winkler", "K": 1e9}})",
       "R = -0.001"},
      {"zero K", R"({"indenter": {"shape": "sphere", "R": 1e-3}, "medium": {"type": "winkler", "K": 0}})", "K = 0"},
      {"overflowing number", R"({"indenter": {"shape": "sphere", "R": 1e999}, "medium": {"type": "winkler", "K": 1e9}})",
       "not valid JSON"},
      {"negative w", R"({"indenter": {"shape": "sphere", "R": 1e-3}, "medium": {"type": "winkler", "K": 1e9}, "w": -1})",
       "w = -1"},
      {"nu out of range", R"({"indenter": {"shape": "sphere", "R": 1e-3}, "medium": {"type": "half_space", "E": 1e6, "nu": 0.7}})",
       "nu = 0.7 is invalid"},
      {"table not monotone", R"({"indenter": {"shape": "table", "r": [0, 1, 2], "z": [0, 2, 1]}, "medium": {"type": "winkler", "K": 1e9}})",
       "z"},
      {"deeply nested", std::string(100000, '[') + std::string(100000, ']'), "deeper than 32 levels"},
      {"duplicate key", R"({"indenter": {"shape": "sphere", "R": 1e-3}, "medium": {"type": "winkler", "K": 1e9}, "w": 1, "w": 2})",
       "w is given twice"},
  };
  for (const auto& c : scenes) {
    const std::string path = write_file("bad_scene.json", c.text);
    const std::string out = unique("never_written.json");
    for (const std::string& cmd : {"summary " + path, "curve " + path + " --at 1e-4",
                                   "fit " + kCurve + " --scene " + path + " --free E --out " + out}) {
      check_rejected(c.name + ": " + cmd.substr(0, 60), cmd, c.expected, out);
    }
    std::remove(path.c_str());
  }
}

TEST_CASE("fit rejects bad curves and arguments with one message and exit 2", "[cli][bad-input]") {
  const std::string huge_rows = [] {
    std::string s = "delta,P\n";
    for (int i = 0; i < 200000; ++i) s += "1e-7,abc\n";
    return s;
  }();
  struct Case {
    std::string name, text, args, expected;
  };
  const std::vector<Case> cases{
      {"bad header", "depth,load\n1,2\n", "--free E", "'depth' is unknown"},
      {"no header", "1e-7,1e-9\n2e-7,2e-9\n", "--free E", "'1e-7' is unknown"},
      {"binary", std::string("\x89PNG\r\n\x1a\n\0\0\0\x0dIHDR", 16), "--free E", "not a text file"},
      {"huge, bad cells", huge_rows, "--free E", "line 2, column 'P': 'abc'"},
      {"infinite cell", "delta,P\n1e-7,inf\n", "--free E", "not a finite number"},
      {"ragged", "delta,P\n1e-7,1e-9,3\n", "--free E", "has 3 cells"},
      {"segments out of order", "delta,P,segment\n1,2,1\n2,3,0\n", "--free E", "acquisition order"},
      {"negative spring constant", "z,deflection\n1,2\n", "--free E --spring-constant -1", "spring_constant"},
      {"bad z sign", "z,deflection\n1,2\n", "--free E --spring-constant 0.1 --z-sign 2", "z_sign"},
      {"zero iterations", "delta,P\n1,2\n", "--free E --max-iterations 0", "max_iterations"},
      // Issue 43: options that cannot apply are refused, not ignored.
      {"z sign without z", "delta,P\n1,2\n", "--free E --z-sign -1", "has no z column: a z sign"},
      {"deflection sign on z,force", "z,force\n1,2\n", "--free E --spring-constant 0.1 --deflection-sign -1",
       "has no z,deflection columns: a deflection sign"},
      {"bounds without a range", "delta,P\n1,2\n", "--free E --bounds E", "--bounds: \"E\" is invalid; use NAME=MIN:MAX"},
      {"bounds of a fixed parameter", "delta,P\n1,2\n", "--free E --bounds w=0:1", "bounds of w: the parameter is not free"},
      {"bounds reversed", "delta,P\n1,2\n", "--free E --bounds E=2:1", "bounds of E (lower end)"},
      {"noise of radii without radii", "delta,P\n1e-7,1e-9\n2e-7,2e-9\n3e-7,4e-9\n4e-7,6e-9\n5e-7,9e-9\n",
       "--free E --radius-noise 1e-9", "these data have no contact radii"},
      {"displacement noise not a number", "delta,P\n1,2\n", "--free E --displacement-noise x",
       "--displacement-noise = \"x\" is invalid; give the noise, a finite number > 0"},
      {"force noise without radii or displacement noise",
       "delta,P\n1e-7,1e-9\n2e-7,2e-9\n3e-7,4e-9\n4e-7,6e-9\n5e-7,9e-9\n", "--free E --force-noise 1e-9",
       "no contact radii and delta is taken as exact"},
      {"unknown contact point", "delta,P\n1,2\n", "--free E --contact-point poc", "--contact-point = \"poc\" is unknown (known: fit, threshold, rov, gof)"},
      {"indentation range reversed", "delta,P\n1,2\n", "--free E --indentation-range 1e-6:0",
       "--indentation-range = \"1e-6:0\" is invalid; use MIN:MAX with MIN < MAX"},
      {"indentation range one number", "delta,P\n1,2\n", "--free E --indentation-range 1e-6",
       "--indentation-range = \"1e-6\" is invalid"},
      {"force range above 1", "delta,P\n1,2\n", "--free E --force-range 0:1.5",
       "--force-range = \"0:1.5\" is invalid; use MIN:MAX with 0 <= MIN < MAX <= 1"},
      {"baseline window not a number", "delta,P\n1,2\n", "--free E --baseline-window a:b",
       "--baseline-window = \"a:b\" is invalid"},
      {"contact point on retract", "delta,P\n1e-7,1e-9\n2e-7,2e-9\n3e-7,4e-9\n4e-7,6e-9\n5e-7,9e-9\n",
       "--free E --branch retract --contact-point rov", "contact point 'rov' needs approach samples"},
  };
  for (const auto& c : cases) {
    const std::string path = write_file("bad_curve.csv", c.text);
    const std::string out = unique("never_written.json");
    check_rejected(c.name, "fit " + path + " --scene " + kScene + " " + c.args + " --out " + out, c.expected, out);
    std::remove(path.c_str());
  }
}

TEST_CASE("CSV-only options on an instrument file are refused, not ignored", "[cli][bad-input]") {
  // Issue 43: --units and the signs were accepted and ignored for a JPK file.
  const std::string jpk = std::string(LAYERJKR_SOURCE_DIR) + "/data/instrument/fmt-jpk-fd_spot3-0192.jpk-force";
  const std::string hertz = std::string(LAYERJKR_SOURCE_DIR) + "/data/scenes/hertz_R40nm.json";
  for (const char* option : {"--units nm,nN", "--z-sign -1", "--deflection-sign -1"}) {
    const std::string out = unique("never_written.json");
    check_rejected(option, "fit " + jpk + " --scene " + hertz + " --free E,delta0,P0 " + option + " --out " + out,
                   "--units, --z-sign and --deflection-sign apply to CSV files only", out);
  }
}

TEST_CASE("devices are refused instead of read forever", "[cli][bad-input][limits]") {
  const std::string out = unique("never_written.json");
  check_rejected("summary /dev/urandom", "summary /dev/urandom", "not a regular file", out);
  check_rejected("fit /dev/urandom", "fit /dev/urandom --scene " + kScene + " --free E --out " + out,
                 "not a regular file", out);
}
