// The CLI on instrument files: fit straight from a JPK archive (JPK's own E), export and
// read back, fit-map over a force map and a QI map with positions, a corrupt archive
// failing only its own row. Skipped, not failed, when ../shared is absent.
#include <catch2/catch.hpp>

#include <algorithm>
#include <filesystem>
#include <fstream>

#include "support/cli_support.hpp"
#include "support/test_support.hpp"
#include "io/jpk_builder.hpp"

using namespace test::cli;
namespace fs = std::filesystem;

namespace {
const std::string kDir = std::string(LAYERJKR_SOURCE_DIR) + "/../shared/data/instrument/";
const std::string kSpot3 = kDir + "fmt-jpk-fd_spot3-0192.jpk-force";
bool have_data() { return fs::exists(kSpot3); }
std::string kSource() { return std::string(LAYERJKR_SOURCE_DIR) + "/../shared/data/real/jpk_spot3_0192_approach.csv"; }
// nanite's test_app_ret: R = 40 nm, nu = 0.5, Hertz paraboloid.
std::string hertz_scene() {
  return write_file("hertz.json", R"({"indenter": {"shape": "paraboloid", "R": 4e-8},
      "medium": {"type": "half_space", "E": 3e5, "nu": 0.5}})");
}
double value_after(const std::string& text, const std::string& key) {
  const std::size_t at = text.find(key);
  REQUIRE(at != std::string::npos);
  return std::stod(text.substr(at + key.size()));
}
}  // namespace

TEST_CASE("fit reads a JPK archive directly and reproduces JPK's E = 233.1 kPa within 0.2 %", "[cli][instrument]") {
  if (!have_data()) {
    test::report_skip(kDir + " is absent (the shared data beside the repository)");
    return;
  }
  const Run r = run("fit " + kSpot3 + " --scene " + hertz_scene() + " --free E,delta0,P0");
  INFO(r.err << r.out);
  REQUIRE(r.code == 0);
  const double E = value_after(r.out, "E = ");
  CHECK(test::rel_err(E, 233.1e3) < 2e-3);
  // Exported and read back, the same curve gives the same fit.
  const std::string csv = unique("spot3.csv");
  REQUIRE(run("export " + kSpot3 + " --out " + csv).code == 0);
  CHECK(lines(slurp(csv))[0] == "curve,segment,t,force,height,tip_position");
  CHECK(lines(slurp(csv)).size() == 4001);
  const Run back = run("fit " + csv + " --scene " + hertz_scene() + " --free E,delta0,P0");
  REQUIRE(back.code == 0);
  CHECK(value_after(back.out, "E = ") == E);
}

TEST_CASE("a map: fit needs --curve, fit-map gives every curve its row with index and position", "[cli][instrument]") {
  if (!have_data()) {
    test::report_skip(kDir + " is absent (the shared data beside the repository)");
    return;
  }
  const std::string map = kDir + "fmt-jpk-fd_map2x2_extracted.jpk-force-map";
  const std::string qi = kDir + "fmt-jpk-fd_2020.02.07-16.29.05.036.jpk-qi-data";
  const Run need = run("fit " + map + " --scene " + hertz_scene() + " --free E,delta0,P0");
  CHECK(need.code == 2);
  CHECK(need.err.find("holds 4 curves; select one with --curve N") != std::string::npos);
  const std::string exported = unique("map.csv");
  REQUIRE(run("export " + map + " --out " + exported).code == 0);
  CHECK(run("fit " + exported + " --scene " + hertz_scene() + " --free E,delta0,P0").err.find("select one") !=
        std::string::npos);
  const Run one = run("fit " + exported + " --curve 2 --scene " + hertz_scene() + " --free E,delta0,P0");
  INFO(one.err);
  CHECK(one.code == 0);
  // A broken archive among the inputs fails only its own row.
  const std::string broken = write_file("broken.jpk-force", "not a zip");
  const std::string out = unique("results.csv");
  const Run r = run("fit-map " + map + " " + qi + " " + broken + " --scene " + hertz_scene() +
                    " --free E,delta0,P0 --jobs 2 --out " + out);
  INFO(r.err);
  REQUIRE(r.code == 3);  // the broken file and a curve failed, the others fitted
  const auto rows = lines(slurp(out));
  REQUIRE(rows.size() == 10);  // header, 4 + 4 curves, 1 broken file
  CHECK(rows[1].rfind(map + "#0,0,", 0) == 0);
  CHECK(rows[3].find("#2,2,0.0005718359375000001,-0.00021373046875000003,9,9,") != std::string::npos);
  CHECK(rows[6].find("#1,1,") != std::string::npos);
  CHECK(rows[6].find(",1,0,") != std::string::npos);  // QI pixel (1, 0)
  CHECK(rows[9].find("broken.jpk-force,,,,,,error,") != std::string::npos);
  CHECK(rows[9].find("zip") != std::string::npos);
}

TEST_CASE("fit-map refuses --curve on an instrument map instead of ignoring it", "[cli][instrument][errors]") {
  // Issue 43: --curve picks one curve of a CSV export for fit; fit-map fits every curve of an
  // instrument file, and accepted --curve there only to ignore it. The bundled QI map.
  const std::string qi = std::string(LAYERJKR_SOURCE_DIR) + "/data/instrument/fmt-jpk-fd_2020.02.07-16.29.05.036.jpk-qi-data";
  const std::string table = unique("curve_refused.csv");
  const Run r = run("fit-map " + qi + " --scene " + hertz_scene() + " --free E,delta0,P0 --curve 2 --out " + table);
  CHECK(r.code == 2);
  CHECK(count_lines(r.err) == 1);
  CHECK(r.err.find("--curve 2 does not apply to") != std::string::npos);
  CHECK(r.err.find("--curves A:B") != std::string::npos);
  CHECK_FALSE(fs::exists(table));
}

TEST_CASE("export rejects files that are not instrument files, with exit 2", "[cli][instrument][errors]") {
  const Run r = run("export " + write_file("x.csv", "delta,P\n1,2\n") + " --out " + unique("o.csv"));
  CHECK(r.code == 2);
  CHECK(r.err.find("not an instrument file") != std::string::npos);
  CHECK(r.out.empty());
}

TEST_CASE("export says what the reader noted, as fit does: a spring constant given twice", "[cli][instrument]") {
  // Issue 41: export wrote the forces from one of two different SpringConstant values and said
  // nothing (fit says which it used).
  const std::string ibw = unique("twice.ibw");
  {
    const std::string bytes = test::igor_wave("Version:16.11.212\rSpringConstant: 1.1841\rSpringConstant: 0.5\r"
                                              "InvOLS: 4.499e-08\rIndexes: 0,2,5\rDirection: NaN,1,-1,\r");
    std::ofstream(ibw, std::ios::binary) << bytes;
  }
  const Run r = run("export " + ibw + " --out " + unique("twice.csv"));
  INFO(r.err);
  REQUIRE(r.code == 0);
  CHECK(r.err.find("export: note: the wave note gives SpringConstant 2 times with different values") != std::string::npos);
}

TEST_CASE("fit-map --plot-dir draws every fitted field over the map grid", "[cli][instrument][plot]") {
  if (!have_data() || std::system("gnuplot --version >/dev/null 2>&1") != 0) {
    test::report_skip("needs ../shared/data/instrument and gnuplot");
    return;
  }
  const std::string dir = unique("maps");
  const Run r = run("fit-map " + kDir + "fmt-jpk-fd_map2x2_extracted.jpk-force-map --scene " + hertz_scene() +
                    " --free E,delta0,P0 --out " + unique("m.csv") + " --plot-dir " + dir);
  INFO(r.err);
  REQUIRE(r.code == 0);
  for (const char* field : {"E", "delta0", "P0", "pull_off", "rms_residual", "status"}) {
    const fs::path png = fs::path(dir) / (std::string(field) + ".png");
    INFO(png);
    CHECK(fs::file_size(png) > 1000);
    std::ifstream in(png, std::ios::binary);
    char magic[4] = {};
    in.read(magic, 4);
    CHECK(std::string(magic + 1, 3) == "PNG");
  }
  for (const auto& e : fs::directory_iterator(dir)) CHECK(e.path().extension() == ".png");  // no leftovers
  // Issue 43: refused before the work - nothing written, no table, no record, no folder.
  const Run csv_only = run("fit-map " + kSource() + " --scene " + hertz_scene() + " --free E,delta0 --out " +
                           unique("c.csv") + " --plot-dir " + unique("none"));
  CHECK(csv_only.code == 2);
  CHECK(count_lines(csv_only.err) == 1);
  CHECK(csv_only.err.find("no input carries map positions") != std::string::npos);
  CHECK_FALSE(fs::exists(unique("c.csv")));
  CHECK_FALSE(fs::exists(unique("c.json")));
  CHECK_FALSE(fs::exists(unique("none")));
  // A single curve from an instrument file has no map position: the table stands, and the maps
  // are said to be impossible (exit 0), not an exit 2 after the work.
  const Run single = run("fit-map " + kDir + "fmt-jpk-fd_spot3-0192.jpk-force --scene " + hertz_scene() +
                         " --free E,delta0,P0 --out " + unique("single.csv") + " --plot-dir " + unique("single_plots") +
                         " --tiff " + unique("single_tiffs"));
  INFO(single.err);
  CHECK(single.code == 0);
  CHECK(single.err.find("no fitted curve carries a map position") != std::string::npos);
  CHECK(fs::exists(unique("single.csv")));
}

TEST_CASE("a Bruker curve fits from the file as spot3 does - a force volume maps, whole or by --curves",
          "[cli][instrument][nanoscope]") {
  const std::string single = kDir + "bruker/20200904_Egel4-Z1.0_00025.spm";
  const std::string volume = kDir + "bruker/20200903_Egel2.0_00023.spm";
  if (!fs::exists(single) || !fs::exists(volume)) {
    test::report_skip(kDir + "bruker is absent (the shared data beside the repository)");
    return;
  }
  // The header's tip: \Tip Radius: 20 (nm).
  const std::string scene = write_file("bruker_hertz.json", R"({"indenter": {"shape": "paraboloid", "R": 2e-8},
      "medium": {"type": "half_space", "E": 1e4, "nu": 0.5}})");
  const Run r = run("fit " + single + " --scene " + scene + " --free E,delta0,P0");
  INFO(r.err << r.out);
  REQUIRE(r.code == 0);
  CHECK(r.out.find("converged") != std::string::npos);
  const double E = value_after(r.out, "E = ");
  CHECK(E > 1e3);  // a soft gel ("Egel"): kPa, not MPa or Pa
  CHECK(E < 1e5);
  const std::string csv = unique("bruker.csv");
  REQUIRE(run("export " + single + " --out " + csv).code == 0);
  CHECK(lines(slurp(csv)).size() == 2049);
  const Run back = run("fit " + csv + " --scene " + scene + " --free E,delta0,P0");
  REQUIRE(back.code == 0);
  CHECK(value_after(back.out, "E = ") == E);

  const std::string flags = " --scene " + scene + " --free E,delta0,P0 --jobs 2 --out ";
  const std::string all = unique("volume.csv"), part = unique("volume_part.csv");
  REQUIRE(run("fit-map " + volume + flags + all).code == 0);
  const auto rows = lines(slurp(all));
  REQUIRE(rows.size() == 257);
  CHECK(rows[1].rfind(volume + "#0,0,", 0) == 0);
  CHECK(rows[256].find(",15,15,") != std::string::npos);  // the grid's last pixel
  // A range is read on its own and gives the very rows of the whole map.
  REQUIRE(run("fit-map " + volume + flags + part + " --curves 16:32").code == 0);
  const auto some = lines(slurp(part));
  REQUIRE(some.size() == 17);
  for (std::size_t i = 1; i < some.size(); ++i) CHECK(some[i] == rows[16 + i]);
  const Run none = run("fit-map " + volume + flags + unique("none.csv") + " --curves 300:");
  CHECK(none.code == 4);  // no curve fitted
  CHECK(none.err.find("0 of 1 curves fitted") != std::string::npos);
  CHECK(slurp(unique("none.csv")).find("selects none of its 256 curves") != std::string::npos);
  const std::string two = unique("two.csv");
  REQUIRE(run("export " + volume + " --out " + two + " --curves 254:").code == 0);
  CHECK(lines(slurp(two)).size() == 1 + 2 * 2048);
  CHECK(run("fit-map " + volume + flags + part + " --curves 5:2").code == 2);
}

TEST_CASE("fit on a binary file of no known format names the known formats", "[cli][instrument][errors]") {
  const std::string bin = write_file("mystery.dat", std::string("\x7f" "ELF\0\0\0", 7));
  const Run r = run("fit " + bin + " --scene " + hertz_scene() + " --free E,delta0,P0");
  CHECK(r.code == 2);
  CHECK(r.err.find("mystery.dat") != std::string::npos);
  CHECK(r.err.find("NUL bytes") != std::string::npos);
  CHECK(r.err.find("Bruker NanoScope") != std::string::npos);
  CHECK(lines(r.err).size() == 1);
  const std::string pfc = write_file("capture.pfc", "\\*Force file list\r\n");
  const Run p = run("export " + pfc + " --out " + unique("pfc.csv"));
  CHECK(p.code == 2);
  CHECK(p.err.find("PeakForce Capture") != std::string::npos);
}

TEST_CASE("export, fit and fit-map take --spring-constant and --sensitivity for a file without them", "[cli][instrument]") {
  std::vector<test::Member> members = test::jpk_members();
  std::string& seg = members[1].bytes;
  const std::string key = "channel.vDeflection.conversion-set.conversion.force.base-calibration-slot=distance";
  seg.replace(seg.find(key), key.size(), "channel.vDeflection.conversion-set.conversion.force.defined=false");
  const std::string jpk = unique("no_k.jpk-force");
  test::write_zip(jpk, members);
  const Run refused = run("export " + jpk + " --out " + unique("no_k.csv"));
  CHECK(refused.code == 2);
  CHECK(count_lines(refused.err) == 1);
  CHECK(refused.err.find("the file gives no spring constant") != std::string::npos);
  const Run given = run("export " + jpk + " --spring-constant 12 --sensitivity 1e-7 --out " + unique("k.csv"));
  INFO(given.err);
  CHECK(given.code == 0);
  const Run bad = run("export " + jpk + " --spring-constant -1 --out " + unique("k2.csv"));
  CHECK(bad.code == 2);
  CHECK(bad.err.find("--spring-constant = -1 is invalid") != std::string::npos);
  for (const char* command : {"fit", "fit-map"}) {
    const Run r = run(std::string(command) + " " + jpk + " --scene " + write_file("h.json", R"({"indenter": {"shape":
        "paraboloid", "R": 4e-8}, "medium": {"type": "half_space", "E": 3e5, "nu": 0.5}})") +
                      " --free E --spring-constant 12 --sensitivity 1e-7 --out " + unique(std::string(command) + ".out"));
    INFO(command << ": " << r.err);
    CHECK(r.err.find("no spring constant") == std::string::npos);  // read; the tiny curve may not fit
  }
}

TEST_CASE("export takes the vendors' text exports fit reads: AFM Workshop's CSV", "[cli][instrument]") {
  // Issue 41: export refused the AFM Workshop CSV that fit reads. Its spring constant is the
  // header's or --spring-constant's; the height is the tip's position less F/k.
  const std::string aw = std::string(LAYERJKR_SOURCE_DIR) + "/tests/data/instrument/fmt-afm-workshop-fd_single_2020-02-14_13.41.25.csv";
  const Run refused = run("export " + aw + " --out " + unique("aw0.csv"));
  CHECK(refused.code == 2);
  CHECK(refused.err.find("--spring-constant") != std::string::npos);
  const std::string out = unique("aw.csv");
  const Run r = run("export " + aw + " --spring-constant 0.2 --out " + out);
  INFO(r.err);
  REQUIRE(r.code == 0);
  const std::string text = slurp(out);
  CHECK(text.rfind("curve,segment,force,height,tip_position\n", 0) == 0);
  CHECK(std::count(text.begin(), text.end(), '\n') > 100);
  const Run sens = run("export " + aw + " --spring-constant 0.2 --sensitivity 1e-7 --out " + unique("aw2.csv"));
  CHECK(sens.code == 2);
  CHECK(sens.err.find("a sensitivity (--sensitivity 1e-07 m/V) does not apply") != std::string::npos);
}

TEST_CASE("export takes NT-MDT's and Chiaro's text exports and AFM Workshop's maps, with their calibration",
          "[cli][instrument]") {
  // Issue 41: afmformats reads these; layerjkr did not. NT-MDT's file holds no calibration: both
  // options are required and named; AFM Workshop's map of T-B volts needs the sensitivity.
  const std::string dir = std::string(LAYERJKR_SOURCE_DIR) + "/tests/data/instrument/";
  const std::string nt = dir + "fmt-ntmdt-txt-fd_2015_01_17_gel4-0,1_mQ_adh_6B_Curve_DFL_Height_51.txt";
  const Run bare = run("export '" + nt + "' --out " + unique("nt0.csv"));
  CHECK(bare.code == 2);
  CHECK(bare.err.find("--spring-constant") != std::string::npos);
  CHECK(bare.err.find("--sensitivity") != std::string::npos);
  const std::string out = unique("nt.csv");
  const Run r = run("export '" + nt + "' --spring-constant 0.055 --sensitivity 61 --out " + out);
  INFO(r.err);
  REQUIRE(r.code == 0);
  CHECK(lines(slurp(out)).size() == 1645);  // a header and afmformats' 1644 samples
  CHECK(r.err.find("note: dropped 178 approach and 178 retract rows of constant padding") != std::string::npos);
  const std::string map = dir + "fmt-afm-workshop-fd_mapping_16_2018-08-01_13.07.zip";
  const Run no_sens = run("export " + map + " --spring-constant 20 --out " + unique("ws0.csv"));
  CHECK(no_sens.code == 2);
  CHECK(no_sens.err.find("--sensitivity") != std::string::npos);
  const Run ws = run("export " + map + " --spring-constant 20 --sensitivity 1e-8 --out " + unique("ws.csv"));
  INFO(ws.err);
  CHECK(ws.code == 0);
  CHECK(ws.err.find("16 curve(s)") != std::string::npos);
  // afmformats' HDF5 export: the CLI links libhdf5 (the library and the wheel do not).
  const std::string h5 = unique("h5.csv");
  const Run hd = run("export " + dir + "fmt-hdf5-fd_version_0.13.3.h5 --out " + h5);
  INFO(hd.err);
  CHECK(hd.code == 0);
  CHECK(lines(slurp(h5)).size() == 7797);
  CHECK(lines(slurp(h5))[2001].find(",-7.038311459845539e-10,") != std::string::npos);  // afmformats' force[2000]
}
