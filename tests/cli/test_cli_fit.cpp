// layerjkr fit and fit-map: report contract, plot, batches with failures, bad data.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>

#include "layerjkr/error.hpp"
#include "layerjkr/simulate.hpp"
#include "support/cli_support.hpp"

using namespace test::cli;
namespace fs = std::filesystem;

namespace {
const std::string kSource = LAYERJKR_SOURCE_DIR;
const std::string kCurve = kSource + "/data/curves/hydrogel_film_two_term.csv";
const std::string kScene = kSource + "/data/scenes/hydrogel_film_two_term.json";
const std::string kFit = "fit " + kCurve + " --scene " + kScene + " --branch all ";
bool have_gnuplot() { return std::system("gnuplot --version >/dev/null 2>&1") == 0; }
}  // namespace

TEST_CASE("fit recovers the bundled sample and writes the documented report", "[cli][fit]") {
  const std::string report = unique("report.json");
  const Run r = run(kFit + "--free E,w,delta0,P0 --out " + report);
  INFO(r.err);
  REQUIRE(r.code == 0);
  CHECK(r.out.find("converged") != std::string::npos);
  const auto j = nlohmann::json::parse(slurp(report));
  for (const char* key : {"converged", "parameters", "correlation", "rms_residual", "iterations",
                          "identifiable", "identifiability_known", "identifiability_reason", "no_move_reason",
                          "warnings"})
    CHECK(j.contains(key));
  CHECK(j["identifiability_reason"] == "");
  CHECK(j["parameters"]["E"]["reason"] == "");
  CHECK(j["parameters"]["w"]["upper_bound"].is_null());
  CHECK(j["converged"] == true);
  CHECK(j["identifiable"] == true);
  // The sample was made with E = 50 kPa, w = 1 mJ/m^2, delta0 = 2.5 um (make_sample_curve).
  const auto& p = j["parameters"];
  CHECK(std::abs(p["E"]["value"].get<double>() - 5e4) < 4 * p["E"]["stderr"].get<double>());
  CHECK(std::abs(p["w"]["value"].get<double>() - 1e-3) < 4 * p["w"]["stderr"].get<double>());
  CHECK(std::abs(p["delta0"]["value"].get<double>() - 2.5e-6) < 4 * p["delta0"]["stderr"].get<double>());
  CHECK(j["correlation"]["E"]["E"] == Approx(1.0));
  CHECK(j["correlation"]["E"]["w"] == j["correlation"]["w"]["E"]);
  std::remove(report.c_str());
}

TEST_CASE("fit reports an unidentifiable G with null error bars", "[cli][fit]") {
  const std::string scene = write_file("pasternak.json",
      R"({"indenter": {"shape": "paraboloid", "R": 1e-5}, "medium": {"type": "pasternak", "K": 3e11, "G": 1e-3}, "model": "asymptotic"})");
  const std::string report = unique("g.json");
  const Run r = run("fit " + kCurve + " --scene " + scene + " --branch all --free K,G,w,delta0,P0 --out " + report);
  INFO(r.err << r.out);
  REQUIRE(r.code == 0);
  const auto j = nlohmann::json::parse(slurp(report));
  CHECK(j["identifiable"] == false);
  CHECK(j["identifiability_known"] == true);
  CHECK(j["parameters"]["G"]["stderr"].is_null());
  CHECK(j["parameters"]["G"]["identifiable"] == false);
  CHECK(j["parameters"]["G"]["reason"].get<std::string>().find("not separable") != std::string::npos);
  CHECK(j["unidentifiable"][0].get<std::string>().find("G") != std::string::npos);
  CHECK(r.out.find("cannot separate") != std::string::npos);
  std::remove(report.c_str());
}

TEST_CASE("fit and fit-map report w without adhesion at its bound, with its upper bound and reasons", "[cli][fit]") {
  const std::string scene_json = R"({"indenter": {"shape": "paraboloid", "R": 1e-5},
      "medium": {"type": "half_space", "E": 1e6, "nu": 0.5}})";
  layerjkr::SimulationOptions so;
  so.branch = layerjkr::Branch::retract;
  so.max_indentation = 1e-6;
  so.noise = 1e-7;
  so.seed = 1;
  const layerjkr::CurveData c = layerjkr::simulate_curve(layerjkr::parse_scene(scene_json, "scene"), so);
  std::string csv = "delta,P,segment\n";
  for (std::size_t i = 0; i < c.size(); ++i)
    csv += layerjkr::format_double(c.delta[i]) + "," + layerjkr::format_double(c.P[i]) + ",1\n";
  const std::string curve = write_file("no_adhesion.csv", csv), scene = write_file("hertz.json", scene_json);
  const std::string report = unique("w0.json"), table = unique("w0_map.csv");
  const std::string args = " --scene " + scene + " --branch retract --free E,w,delta0,P0 --out ";
  const Run r = run("fit " + curve + args + report);
  INFO(r.err << r.out);
  REQUIRE(r.code == 0);
  const auto j = nlohmann::json::parse(slurp(report));
  const auto& w = j["parameters"]["w"];
  CHECK(w["at_bound"] == true);
  CHECK(w["stderr"].is_null());
  CHECK(w["upper_bound"].get<double>() > 0.0);
  CHECK(w["identifiable"] == true);
  CHECK(w["reason"].get<std::string>().find("no adhesive signal") != std::string::npos);
  CHECK_FALSE(j["parameters"]["E"]["stderr"].is_null());
  CHECK(j["identifiable"] == true);
  CHECK(r.out.find("identifiable: yes") != std::string::npos);
  const Run m = run("fit-map " + curve + args + table);
  INFO(m.err);
  REQUIRE(m.code == 0);
  const auto rows = lines(slurp(table));
  REQUIRE(rows.size() == 2);
  CHECK(rows[1].find(",1,yes,") != std::string::npos);
  CHECK(rows[1].find(",0,,") != std::string::npos);  // w = 0 with no standard error
  std::remove(report.c_str());
  std::remove(table.c_str());
  std::remove(curve.c_str());
  std::remove(scene.c_str());
}

TEST_CASE("fit --plot writes a PNG through gnuplot", "[cli][fit][plot]") {
  if (!have_gnuplot()) {
    test::report_skip("gnuplot is not installed");
    return;
  }
  const std::string png = unique("fit.png");
  const Run r = run(kFit + "--free E,w,delta0,P0 --plot " + png);
  INFO(r.err);
  REQUIRE(r.code == 0);
  const std::string bytes = slurp(png);
  REQUIRE(bytes.size() > 1000);
  CHECK(bytes.substr(1, 3) == "PNG");
  std::remove(png.c_str());
}

TEST_CASE("fit-map fits a directory in parallel and reports a bad curve without stopping", "[cli][fit-map]") {
  const fs::path dir = unique("map");
  fs::create_directories(dir);
  for (int i = 0; i < 6; ++i) fs::copy_file(kCurve, dir / ("curve" + std::to_string(i) + ".csv"));
  std::ofstream(dir / "broken.csv") << "delta,P\n1,abc\n";
  const std::string out = unique("map.csv");
  const Run r = run("fit-map " + dir.string() + " --scene " + kScene +
                    " --branch all --free E,w,delta0,P0 --jobs 2 --out " + out);
  INFO(r.err);
  REQUIRE(r.code == 3);  // some curves failed: the table has every row
  CHECK(r.err.find("6 of 7 curves fitted") != std::string::npos);
  CHECK(r.err.find("fit-map [") == std::string::npos);  // stderr is a file: no progress bar
  const auto rows = lines(slurp(out));
  REQUIRE(rows.size() == 8);
  CHECK(rows[0] == "file,curve,x,y,grid_x,grid_y,status,error,model,converged,iterations,rms_residual,identifiable,"
                   "identifiability,contact_point,contact_point_err,range_samples,E,E_stderr,w,w_stderr,delta0,"
                   "delta0_stderr,P0,P0_stderr,quality,warnings,notices");
  CHECK(rows[1].find("broken.csv,,,,,,error,") != std::string::npos);
  CHECK(rows[1].find("abc") != std::string::npos);
  for (std::size_t k = 2; k < rows.size(); ++k) CHECK(rows[k].find(",ok,,two_term,1,") != std::string::npos);
  for (std::size_t k = 2; k < rows.size(); ++k) CHECK(rows[k].find(",1,yes,") != std::string::npos);
  CHECK(rows[2].substr(rows[2].find(",two_term,")) == rows[7].substr(rows[7].find(",two_term,")));
  fs::remove_all(dir);
  std::remove(out.c_str());
}

TEST_CASE("fit and fit-map reject bad data and options with exit 2 and no output", "[cli][fit][errors]") {
  const std::string out = unique("never.json");
  const std::string text = write_file("text.csv", "delta,P\n1e-6,abc\n");
  const std::string nan = write_file("nan.csv", "delta,P\n1e-6,1e-9\n2e-6,nan\n");
  const std::string few = write_file("few.csv", "delta,P\n1e-6,1e-9\n2e-6,2e-9\n");
  const std::string falling = write_file("falling.csv", "delta,P\n1e-7,4e-9\n2e-7,3e-9\n3e-7,2e-9\n4e-7,1e-9\n5e-7,0\n");
  const std::string raw = write_file("raw.csv", "z,deflection\n1e-6,1e-9\n");
  const std::string header = write_file("header.csv", "depth,force\n1,2\n");
  const std::string empty = write_file("empty.csv", "");
  const std::string binary = write_file("binary.csv", std::string("\x89PNG\r\n\x1a\n\0\0", 10));
  struct Case { std::string args, expected; };
  const std::vector<Case> cases{
      {"fit " + text + " --scene " + kScene + " --free E", "'abc' is not a finite number"},
      {"fit " + nan + " --scene " + kScene + " --free E", "'nan' is not a finite number"},
      {"fit " + few + " --scene " + kScene + " --free E,w,delta0 --branch all", "more samples than parameters"},
      {"fit " + falling + " --scene " + kScene + " --free E,delta0 --branch all", "no contact region"},
      {"fit " + raw + " --scene " + kScene + " --free E", "spring constant k [N/m]"},
      {"fit " + header + " --scene " + kScene + " --free E", "'depth' is unknown"},
      {"fit " + empty + " --scene " + kScene + " --free E", "is empty"},
      {"fit " + binary + " --scene " + kScene + " --free E", "not a text file"},
      {"fit /nonexistent.csv --scene " + kScene + " --free E", "cannot open"},
      {kFit + "--free E,nu", "'nu' is not a fit parameter"},
      {kFit + "--free E,E", "listed twice"},
      {kFit + "--free K,E", "E and K/G"},
      {kFit + "--free E,R,w --loss huber", "huber:SCALE"},
      {kFit + "--free E --loss huber:-1", "must be a finite number > 0"},
      {"fit " + kCurve + " --scene " + kScene + " --free E --branch sideways", "sideways"},
      {kFit + "--free E --units parsec,N", "parsec"},
      {kFit + "--free E --starts -1", "extra_starts"},
      {"fit " + kCurve + " --free E", "--scene is required"},
      {"fit-map " + kCurve + " --scene " + kScene + " --free E --jobs 0", "--jobs = 0"},
      {"fit-map /nonexistent/*.csv --scene " + kScene + " --free E", "matches no files"},
      {"fit-map /nonexistent_dir --scene " + kScene + " --free E", "no such file"},
  };
  for (const auto& c : cases) {
    const Run r = run(c.args + " --out " + out);
    INFO(c.args << "\nstderr: " << r.err);
    CHECK(r.code == 2);
    CHECK(r.out.empty());
    CHECK(r.err.find(c.expected) != std::string::npos);
    CHECK_FALSE(fs::exists(out));
  }
}

TEST_CASE("fit-map draws a progress bar with curves per second and time left on a terminal", "[cli][fit-map]") {
  if (std::system("command -v script >/dev/null 2>&1") != 0) {
    test::report_skip("the program `script` (util-linux) is absent: no terminal to run fit-map on");
    return;
  }
  const std::string out = unique("tty_map.csv");
  // script(1) gives the CLI a pseudo-terminal; what it draws there arrives on script's stdout.
  const Run r = run("script -qec '" + cli_path() + " fit-map " + sample_curve() + sample_fit_flags() +
                        " --jobs 1 --out " + out + "' /dev/null",
                    true);
  INFO(r.out << r.err);
  REQUIRE(r.code == 0);
  CHECK(r.out.find("fit-map [##############################] 1/1") != std::string::npos);
  CHECK(r.out.find("curves/s") != std::string::npos);
  CHECK(r.out.find("s left") != std::string::npos);
}

TEST_CASE("fit and fit-map take a contact-point method and an indentation range and report them",
          "[cli][fit][contact]") {
  // A Hertz approach (paraboloid R = 5 um, E* = 2 kPa / 0.75, contact at 100 nm, a deterministic
  // wobble of 0.5 % of the largest force as noise): the report's point and kept samples.
  const fs::path dir = unique("contact");
  fs::create_directories(dir);
  std::string csv = "delta,P,segment\n";
  std::vector<double> delta;
  for (int i = 0; i < 400; ++i) {
    const double d = -1e-6 + 2e-6 * i / 399.0, t = std::max(d - 1e-7, 0.0);
    const double P = 4.0 / 3.0 * 2e3 / 0.75 * std::sqrt(5e-6) * std::pow(t, 1.5) + 2.5e-11 * std::sin(1.3 * i);
    delta.push_back(d);
    char line[96];
    std::snprintf(line, sizeof line, "%.17g,%.17g,0\n", d, P);
    csv += line;
  }
  std::ofstream(dir / "a.csv") << csv;
  std::ofstream(dir / "b.csv") << csv;
  const std::string scene = write_file("hertz.json", R"({"indenter": {"shape": "paraboloid", "R": 5e-6},
      "medium": {"type": "half_space", "E": 1e3, "nu": 0.5}})");
  const std::string report = unique("contact.json");
  const Run r = run("fit " + (dir / "a.csv").string() + " --scene " + scene +
                    " --free E --contact-point gof --indentation-range -1e-7:4e-7 --out " + report);
  INFO(r.err);
  REQUIRE(r.code == 0);
  CHECK(r.out.find("contact point (gof)") != std::string::npos);
  const auto j = nlohmann::json::parse(slurp(report));
  const double point = j["contact_point"]["value"];
  CHECK(j["contact_point"]["method"] == "gof");
  CHECK(std::abs(point - 1e-7) < 4.0 * j["contact_point"]["stderr"].get<double>());
  std::size_t kept = 0;
  for (double d : delta) kept += d >= point - 1e-7 && d <= point + 4e-7 ? 1 : 0;
  CHECK(j["contact_point"]["samples_in_range"] == kept);
  CHECK(j["points"] == kept);

  const std::string table = unique("contact_map.csv");  // its record contact_map.json: not the fit's report
  const Run m = run("fit-map " + dir.string() + " --scene " + scene +
                    " --free E --contact-point gof --indentation-range -1e-7:4e-7 --out " + table);
  INFO(m.err);
  REQUIRE(m.code == 0);
  const auto rows = lines(slurp(table));
  REQUIRE(rows.size() == 3);
  CHECK(rows[0].find(",identifiable,identifiability,contact_point,contact_point_err,range_samples,E,E_stderr") != std::string::npos);
  char cells[64];
  std::snprintf(cells, sizeof cells, ",%.17g,", point);
  CHECK(rows[1].find(cells) != std::string::npos);
  CHECK(rows[1].find("," + std::to_string(kept) + ",") != std::string::npos);
  fs::remove_all(dir);
  std::remove(report.c_str());
  std::remove(table.c_str());
}

TEST_CASE("fit: a weight column's scale changes nothing, and a loss scale beyond use exits 2", "[cli][fit]") {
  // The bundled curve with a uniform weight column of 1e-20 or 1e200: the same report as without.
  std::ifstream in(kCurve);
  std::string header, plain, tiny, huge;
  for (std::string line; std::getline(in, line);) {
    if (line.empty() || line[0] == '#') continue;
    if (header.empty()) {
      header = line;
      plain += line + "\n";
      tiny += line + ",weight\n";
      huge += line + ",weight\n";
      continue;
    }
    plain += line + "\n";
    tiny += line + ",1e-20\n";
    huge += line + ",1e200\n";
  }
  const std::string free = " --scene " + kScene + " --branch all --free E,w,delta0,P0";
  const Run a = run("fit " + write_file("plain.csv", plain) + free);
  REQUIRE(a.code == 0);
  for (const std::string& text : {tiny, huge}) {
    const Run b = run("fit " + write_file("weighted.csv", text) + free);
    INFO(b.out);
    CHECK(b.code == 0);
    CHECK(b.out == a.out);  // every digit; "identifiable: yes" with the same error bars
  }
  for (const char* loss : {"cauchy:1e300", "cauchy:1e-300", "huber:1e300"}) {
    const Run r = run(kFit + "--free E,w,delta0,P0 --loss " + loss);
    INFO(loss << "\n" << r.err << r.out);
    CHECK(r.code == 2);
    CHECK(r.err.find("outside its usable range") != std::string::npos);
    CHECK(r.out.empty());
    // fit-map: the curve's row says why, never "ok"; no curve fitted is exit code 4.
    const std::string table = unique("loss_map.csv");
    const Run m = run("fit-map " + kCurve + free + " --loss " + loss + " --out " + table);
    CHECK(m.code == 4);
    CHECK(slurp(table).find(",error,") != std::string::npos);
    CHECK(slurp(table).find(",ok,") == std::string::npos);
  }
}
