// layerjkr simulate (a synthetic curve as CSV the fit reads back) and summary's rate-dependent
// pull-off (--retract-speed, --load-rate): what they write, and their input errors (exit 2, one
// line, nothing written).
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "layerjkr/curve_data.hpp"
#include "layerjkr/scene.hpp"
#include "layerjkr/simulate.hpp"
#include "support/cli_support.hpp"

using namespace test::cli;

namespace {

const char* kCell = R"({"indenter": {"shape": "paraboloid", "R": 5e-6}, "medium": {"type": "layer", "E": 2000, "nu": 0.49,
    "h": 3e-6, "base": "bonded", "viscoelastic": {"law": "sls", "E_inf": 800, "tau": 0.2}}, "model": "exact"})";
const char* kElastomer = R"({"indenter": {"shape": "paraboloid", "R": 1e-3}, "medium": {"type": "half_space", "E": 1e6,
    "nu": 0.5}, "w": 0.05, "adhesion": {"kinetics": {"law": "maugis_barquins", "v_star": 1e-6, "n": 0.6}}})";

}  // namespace

TEST_CASE("simulate writes t,delta,P[,a],segment that fit reads back, the library's own curve", "[cli][simulate]") {
  const std::string scene = write_file("cell.json", kCell), out = unique("cell.csv");
  const Run r = run("simulate " + scene + " --max-indentation 2e-6 --speed 2e-6 --dwell 0.3 --points 150 --with-radius "
                    "--noise 1e-11 --seed 7 --out " + out);
  INFO(r.err);
  REQUIRE(r.code == 0);
  CHECK(r.out.empty());
  const std::vector<std::string> rows = lines(slurp(out));
  CHECK(rows[0].rfind("# layerjkr simulate ", 0) == 0);
  CHECK(rows[1].rfind("# note: the relaxing medium's force is integrated on a grid ", 0) == 0);  // its accuracy
  CHECK(r.err.find("simulate: note: the relaxing medium's force") != std::string::npos);
  CHECK(rows[2] == "t,delta,P,a,segment");
  const layerjkr::CurveData c = layerjkr::read_curve_csv(out);
  layerjkr::SimulationOptions o;
  o.max_indentation = 2e-6;
  o.speed = 2e-6;
  o.dwell = 0.3;
  o.points_per_branch = 150;
  o.with_radius = true;
  o.noise = 1e-11;
  o.seed = 7;
  const layerjkr::CurveData lib = layerjkr::simulate_curve(layerjkr::parse_scene(kCell), o);
  REQUIRE(c.size() == lib.size());
  for (std::size_t i = 0; i < c.size(); ++i) {  // written in round-trip precision
    REQUIRE(c.t[i] == lib.t[i]);
    REQUIRE(c.P[i] == lib.P[i]);
    REQUIRE(c.a[i] == lib.a[i]);
    REQUIRE(c.segment[i] == lib.segment[i]);
  }
  CHECK(c.dwell_count() > 0);
  // To standard output without a file, and without time when no speed is given.
  const Run plain = run("simulate " + write_file("hertz.json", R"({"indenter": {"shape": "paraboloid", "R": 5e-6},
      "medium": {"type": "half_space", "E": 2000, "nu": 0.5}})") + " --max-indentation 1e-6 --points 10 --branch approach");
  REQUIRE(plain.code == 0);
  CHECK(lines(plain.out).at(1) == "delta,P,segment");
  CHECK(lines(plain.out).size() == 12);
}

TEST_CASE("simulate: bad input exits 2 with one line and writes nothing", "[cli][simulate]") {
  const std::string cell = write_file("cell2.json", kCell), out = unique("never.csv");
  const auto refused = [&](const std::string& args, const std::string& says) {
    const Run r = run("simulate " + args + " --out " + out);
    INFO(args << "\n" << r.err);
    CHECK(r.code == 2);
    CHECK(count_lines(r.err) == 1);
    CHECK(r.err.find(says) != std::string::npos);
    CHECK_FALSE(std::filesystem::exists(out));
  };
  refused(cell + " --max-indentation 2e-6", "give the indenter's speed");
  refused(cell + " --max-indentation 2e-6 --speed -1", "--speed = -1");
  refused(cell + " --max-indentation 0 --speed 1e-6", "--max-indentation = 0");
  refused(cell + " --max-indentation 2e-6 --dwell 1", "--dwell = 1");
  refused(cell + " --max-indentation 2e-6 --speed 1e-6 --branch sideways", "--branch = \"sideways\" is unknown");
  refused(cell + " --max-indentation 2e-6 --speed 1e-6 --points 1", "--points");
  refused(write_file("k.json", kElastomer) + " --max-indentation 1e-6 --speed 1e-6 --control cantilever",
          "--control cantilever needs the lever's --stiffness");
  refused(cell + " --max-indentation 2e-6 --speed 1e-6 --control cantilever --stiffness 1",
          "cantilever-controlled retract is modelled with crack kinetics");
  refused(unique("missing.json") + " --max-indentation 2e-6 --speed 1e-6", "missing.json");
  // Issue 43: an option that cannot apply is refused, not ignored.
  refused(cell + " --max-indentation 2e-6 --speed 1e-6 --stiffness 1", "--stiffness applies to --control cantilever only");
  refused(cell + " --max-indentation 2e-6 --speed 1e-6 --seed 3", "--seed applies to --noise only");
  // Issue 41: bounds before the work - a dwell of 1e7 s ended in bad_alloc, a noise of 1e308
  // printed inf forces and a speed of 1e-316 nan times, all with exit 0.
  refused(cell + " --max-indentation 2e-6 --speed 2e-6 --dwell 1e7", "--dwell = 10000000");
  refused(cell + " --max-indentation 2e-6 --speed 2e-6 --dwell 1e7", "more than 1000000 samples");
  refused(cell + " --max-indentation 2e-6 --speed 2e-6 --noise 1e308", "--noise = 1e+308");
  refused(cell + " --max-indentation 2e-6 --speed 1e-316", "--speed = 1e-316");
  refused(cell + " --max-indentation 2e-6 --speed 1e-6 --retract-speed 1e9", "--retract-speed = 1000000000");
  refused(cell + " --max-indentation 2e-6 --speed 1e-6 --points 100001", "--points = 100001");
  refused(write_file("h2.json", R"({"indenter": {"shape": "paraboloid", "R": 5e-6},
      "medium": {"type": "half_space", "E": 2000, "nu": 0.5}})") + " --max-indentation 1e-6 --P0 1.7976931348623e308 --noise 1e298",
          "is not finite");
}

TEST_CASE("simulate never overwrites its scene, not even through a link", "[cli][simulate]") {
  const std::string scene = write_file("keep.json", kCell);
  const std::string before = slurp(scene);
  const std::filesystem::path link = unique("keep_link.json");
  std::filesystem::create_symlink(scene, link);
  for (const std::string& out : {scene, link.string()}) {
    const Run r = run("simulate " + scene + " --max-indentation 2e-6 --speed 1e-6 --out " + out);
    INFO(r.err);
    CHECK(r.code == 2);
    CHECK(count_lines(r.err) == 1);
    CHECK(r.err.find("would destroy the input") != std::string::npos);
  }
  CHECK(slurp(scene) == before);
}

TEST_CASE("simulate --free-fraction 0 starts a relaxing medium's history at the contact", "[cli][simulate]") {
  // Refused before by its own history check: "delta[0] = 1e-24 m is in contact" (rounding).
  const std::string out = unique("ff0.csv");
  const Run r = run("simulate " + write_file("cell_ff0.json", kCell) +
                    " --max-indentation 2e-6 --speed 2e-6 --points 50 --free-fraction 0 --out " + out);
  INFO(r.err);
  REQUIRE(r.code == 0);
  const layerjkr::CurveData c = layerjkr::read_curve_csv(out);
  CHECK(c.delta.front() == 0.0);
  CHECK(c.P.front() == 0.0);
  CHECK(c.P[10] > 0.0);
}

TEST_CASE("summary --retract-speed: the rate-dependent pull-off and its sweep, refused without kinetics", "[cli][simulate]") {
  const std::string scene = write_file("elastomer.json", kElastomer);
  const Run r = run("summary " + scene + " --retract-speed 1e-6");
  INFO(r.err);
  REQUIRE(r.code == 0);
  const nlohmann::json j = nlohmann::json::parse(r.out);
  const nlohmann::json& k = j.at("kinetic_pull_off");
  CHECK(k.at("drive") == "fixed grips at 1e-06 m/s");
  CHECK(k.at("pull_off_force").get<double>() < j.at("pull_off_force").get<double>());
  CHECK(k.at("equilibrium_pull_off_force").get<double>() == Approx(j.at("pull_off_force").get<double>()));
  REQUIRE(k.at("rate_dependence").size() == 5);
  for (std::size_t i = 1; i < 5; ++i)
    CHECK(k["rate_dependence"][i]["pull_off_force"].get<double>() < k["rate_dependence"][i - 1]["pull_off_force"].get<double>());
  const Run lever = run("summary " + scene + " --retract-speed 1e-6 --stiffness 20");
  REQUIRE(lever.code == 0);
  CHECK(nlohmann::json::parse(lever.out)["kinetic_pull_off"]["control"] == "cantilever");
  const Run load = run("summary " + scene + " --load-rate 1e-3");
  REQUIRE(load.code == 0);
  CHECK(nlohmann::json::parse(load.out)["kinetic_pull_off"]["rate_unit"] == "N/s");
  const Run none = run("summary " + scene);
  REQUIRE(none.code == 0);
  CHECK(none.err.find("note: the adhesion has kinetics") != std::string::npos);
  CHECK_FALSE(nlohmann::json::parse(none.out).contains("kinetic_pull_off"));
  const Run elastic = run("summary " + write_file("plain.json", R"({"indenter": {"shape": "paraboloid", "R": 1e-3},
      "medium": {"type": "half_space", "E": 1e6, "nu": 0.5}, "w": 0.05})") + " --retract-speed 1e-6");
  CHECK(elastic.code == 2);
  CHECK(elastic.err.find("changes nothing without adhesion.kinetics") != std::string::npos);
  const Run bad = run("summary " + scene + " --retract-speed 0");
  CHECK(bad.code == 2);
  CHECK(bad.err.find("--retract-speed = 0") != std::string::npos);
  const Run both = run("summary " + scene + " --retract-speed 1e-6 --load-rate 1");
  CHECK(both.code == 2);
}

TEST_CASE("fit --joint: curves at three speeds fitted together, the report with each alone", "[cli][simulate]") {
  const std::string scene = write_file("cell3.json", kCell);
  std::vector<std::string> files;
  for (const char* v : {"0.5e-6", "2e-6", "8e-6"}) {
    files.push_back(unique(std::string("speed_") + v + ".csv"));
    const Run s = run("simulate " + scene + " --max-indentation 2e-6 --speed " + v + " --points 150 --noise 5e-11 "
                      "--delta0 1e-6 --out " + files.back());
    REQUIRE(s.code == 0);
  }
  const std::string all = files[0] + " " + files[1] + " " + files[2], report = unique("joint.json");
  const Run r = run("fit " + all + " --joint --scene " + scene + " --free E,E_inf,tau,delta0 --branch all --out " + report);
  INFO(r.err << r.out);
  REQUIRE(r.code == 0);
  CHECK(r.out.find("delta0 (curve 3) = ") != std::string::npos);
  CHECK(r.out.find("curve 2: " + files[1]) != std::string::npos);
  const nlohmann::json j = nlohmann::json::parse(slurp(report));
  CHECK(j["joint"]["family"] == "hereditary");
  CHECK(j["joint"]["parameters"].contains("delta0[2]"));
  CHECK(j["joint"]["parameters"]["tau"]["unit"] == "s");
  CHECK(j["joint"]["parameters"]["tau"]["value"].get<double>() == Approx(0.2).epsilon(0.01));
  REQUIRE(j["curves"].size() == 3);
  CHECK(j["curves"][1]["alone"]["parameters"].contains("E_inf"));
  CHECK(j["provenance"]["inputs"].size() == 3);
  // Rerun from the report: the same numbers.
  const Run again = run("fit --from-report " + report + " --out " + unique("joint2.json"));
  INFO(again.err);
  REQUIRE(again.code == 0);
  CHECK(nlohmann::json::parse(slurp(unique("joint2.json")))["joint"]["parameters"]["tau"]["value"] ==
        j["joint"]["parameters"]["tau"]["value"]);
  const Run several = run("fit " + all + " --scene " + scene + " --free E");
  CHECK(several.code == 2);
  CHECK(several.err.find("give --joint") != std::string::npos);
  const Run one = run("fit " + files[0] + " --joint --scene " + scene + " --free E");
  CHECK(one.code == 2);
  CHECK(one.err.find("at least 2 curves") != std::string::npos);
  // Issue 41: the same data three times reported E with an error bar 1/sqrt(3) of one fit's and
  // "identifiable: yes"; a copy under another name is the same measurement too.
  const std::string copy = unique("speed_copy.csv");
  std::filesystem::copy_file(files[0], copy);
  for (const std::string& twice : {files[0] + " " + files[0] + " " + files[0], files[0] + " " + files[1] + " " + copy}) {
    const Run same = run("fit " + twice + " --joint --scene " + scene + " --free E,E_inf,tau,delta0 --branch all");
    INFO(same.err);
    CHECK(same.code == 2);
    CHECK(count_lines(same.err) == 1);
    CHECK(same.err.find("hold the same samples") != std::string::npos);
  }
  const Run unknown = run("fit " + files[0] + " --scene " + scene + " --free E,Einf");
  CHECK(unknown.code == 2);
  CHECK(unknown.err.find("E_inf, tau, beta, v_star, n") != std::string::npos);
}

TEST_CASE("fit-map fits relaxing curves in time: the law's columns, within their errors, and the report", "[cli][simulate]") {
  const std::string scene = write_file("cell4.json", kCell);
  const std::filesystem::path dir = fresh_dir("relaxing_map");
  for (const char* seed : {"1", "2", "3"}) {
    const Run s = run("simulate " + scene + " --max-indentation 2e-6 --speed 2e-6 --points 150 --noise 5e-11 --seed " +
                      seed + " --out " + (dir / (std::string("c") + seed + ".csv")).string());
    REQUIRE(s.code == 0);
  }
  const std::string table = unique("relaxing_map.csv"), report = unique("relaxing_report");
  const Run r = run("fit-map " + dir.string() + " --scene " + scene + " --free E,E_inf,tau,delta0 --branch all --out " +
                    table + " --report " + report);
  INFO(r.err);
  REQUIRE(r.code == 0);
  const std::vector<std::string> rows = lines(slurp(table));
  REQUIRE(rows.size() == 4);
  const auto cells = [](const std::string& row) {  // the leading cells; the quoted notices come last
    std::vector<std::string> out;
    std::string cell;
    for (char ch : row) {
      if (ch == '"') break;
      if (ch == ',') {
        out.push_back(cell);
        cell.clear();
      } else {
        cell += ch;
      }
    }
    return out;
  };
  const std::vector<std::string> head = cells(rows[0]);
  const auto column = [&](const std::string& name) {
    const auto it = std::find(head.begin(), head.end(), name);
    REQUIRE(it != head.end());
    return static_cast<std::size_t>(it - head.begin());
  };
  for (std::size_t k = 1; k < rows.size(); ++k) {
    const std::vector<std::string> row = cells(rows[k]);
    CHECK(row.at(column("status")) == "ok");
    for (const auto& [name, truth] : {std::pair<std::string, double>{"E", 2000.0}, {"E_inf", 800.0}, {"tau", 0.2}}) {
      const double value = std::stod(row.at(column(name))), error = std::stod(row.at(column(name + "_stderr")));
      CHECK(std::abs(value - truth) < 3.0 * error);
    }
  }
  CHECK(slurp(report + "/index.html").find("E_inf") != std::string::npos);
}
