// The layerjkr executable: output formats, exit codes, and error messages.
#include <catch2/catch.hpp>

#include <sys/wait.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "layerjkr/built_scene.hpp"
#include "layerjkr/contact.hpp"
#include "layerjkr/scene.hpp"
#include "support/cli_support.hpp"

namespace {

using namespace test::cli;

const std::string kScene = std::string(LAYERJKR_SOURCE_DIR) + "/data/scenes/sphere_pdms_film_two_term.json";


}  // namespace

TEST_CASE("curve --at prints the CSV contract at full precision", "[cli]") {
  const Run r = run("curve " + kScene + " --at 1e-4,4e-4");
  REQUIRE(r.code == 0);
  const auto rows = lines(r.out);
  REQUIRE(rows.size() == 3);
  CHECK(rows[0] == "a,P,delta,P_H,delta_H,S,error_est,c");
  // Values round-trip: parse and compare with the library.
  const layerjkr::Scene s = layerjkr::load_scene(kScene);
  const layerjkr::BuiltScene built = layerjkr::build_scene(s);
  const layerjkr::JkrSolution jkr(built.model, s.w);
  const layerjkr::AdhesiveState st = jkr.at(4e-4);
  std::vector<double> v;
  std::stringstream row(rows[2]);
  for (std::string cell; std::getline(row, cell, ',');) v.push_back(std::stod(cell));
  REQUIRE(v.size() == 8);
  CHECK(v[0] == 4e-4);
  CHECK(v[1] == st.P);
  CHECK(v[2] == st.delta);
  CHECK(v[3] == st.hertz.P_H);
  CHECK(v[4] == st.hertz.delta_H);
  CHECK(v[5] == st.hertz.S);
  CHECK(v[6] == layerjkr::error_estimator(s, built).at(4e-4));
  CHECK(v[7] == st.c);  // JKR: the adhesive zone ends at the contact edge
  CHECK(st.c == 4e-4);
  // a/h = 4 with the two-term model: several per cent off the exact layer, so it warns.
  CHECK(v[6] > 0.05);
  CHECK(r.err.find("column error_est") != std::string::npos);
}

TEST_CASE("curve --a-max --points gives an even grid", "[cli]") {
  const Run r = run("curve " + kScene + " --a-max 1e-3 --points 4");
  REQUIRE(r.code == 0);
  const auto rows = lines(r.out);
  REQUIRE(rows.size() == 5);
  CHECK(std::stod(rows[1]) == 1e-3 * 1 / 4);
  CHECK(std::stod(rows[4]) == 1e-3);
}

TEST_CASE("summary prints the documented JSON keys", "[cli]") {
  const Run r = run("summary " + kScene);
  REQUIRE(r.code == 0);
  const auto j = nlohmann::json::parse(r.out);
  for (const char* key : {"pull_off_force", "pull_off_radius", "pull_off_delta",
                          "zero_load_radius", "model_error_estimate", "K", "G", "model", "warnings"})
    CHECK(j.contains(key));
  // The two-term model at a/h = 1.8: the estimate says how far off it is, and it warns.
  CHECK(j["model_error_estimate"]["reference"] == "exact");
  CHECK(j["model_error_estimate"]["pull_off_force"].get<double>() > 0.05);
  REQUIRE(j["warnings"].size() == 1);
  CHECK(j["warnings"][0].get<std::string>().find("pull-off force") != std::string::npos);
  CHECK(r.err.find("layerjkr: warning: model 'two_term' is estimated") != std::string::npos);
  CHECK(j["pull_off_force"].get<double>() == Approx(-2 * M_PI * 0.05 * 0.01).epsilon(1e-10));
  CHECK(j["fixed_grips_critical"].is_null());  // Winkler-like: delta(a) is monotone
}

TEST_CASE("a pyramid's cone equivalence is a note, not a warning", "[cli]") {
  const std::string scene = unique("pyramid.json");
  std::ofstream(scene) << R"({"indenter": {"shape": "pyramid", "semi_angle_deg": 35, "sides": 4},
                             "medium": {"type": "half_space", "E": 1500, "nu": 0.5}, "w": 0})";
  const Run r = run("summary " + scene);
  REQUIRE(r.code == 0);
  const auto j = nlohmann::json::parse(r.out);
  CHECK(j["warnings"].empty());
  REQUIRE(j["notices"].size() == 1);
  CHECK(j["notices"][0].get<std::string>().find("equivalent cone") != std::string::npos);
  CHECK(r.err.find("layerjkr: note: the 4-sided pyramid") != std::string::npos);
  CHECK(r.err.find("warning") == std::string::npos);
}

TEST_CASE("help exits 0 and lists the commands", "[cli]") {
  Run r = run("--help");
  CHECK(r.code == 0);
  CHECK(r.out.find("curve") != std::string::npos);
  CHECK(r.out.find("summary") != std::string::npos);
  r = run("curve --help");
  CHECK(r.code == 0);
  CHECK(r.out.find("--a-max") != std::string::npos);
}

TEST_CASE("bad arguments and scenes exit 2 with one message and no output", "[cli][errors]") {
  const std::string bad_nu = write_file("bad_nu.json",
      R"({"indenter": {"shape": "paraboloid", "R": 0.01},
          "medium": {"type": "layer", "E": 3e6, "nu": 0.5, "h": 1e-4}, "model": "two_term"})");
  const std::string sphere = write_file("small_sphere.json",
      R"({"indenter": {"shape": "sphere", "R": 1e-3}, "medium": {"type": "winkler", "K": 1e10}, "w": 0.1})");
  struct Case { std::string args, expected; };
  const std::vector<Case> cases{
      {"", "A subcommand is required"},
      {"frobnicate", "unknown command 'frobnicate'"},
      {"curve", "scene is required"},
      {"curve " + kScene, "curve needs --at or --a-max"},
      {"curve " + kScene + " --at abc", "'abc' is not a finite number"},
      {"curve " + kScene + " --at 1e-4,,2e-4", "'' is not a finite number"},
      {"curve " + kScene + " --at -1e-4", "must be > 0"},
      {"curve " + kScene + " --at nan", "'nan' is not a finite number"},
      {"curve " + kScene + " --a-max 1e-3", "--points"},
      {"curve " + kScene + " --a-max 1e-3 --points 0", "--points = 0"},
      {"curve " + kScene + " --a-max -1 --points 3", "--a-max = -1"},
      {"curve " + kScene + " --at 1e-4 --a-max 1e-3 --points 3", "excludes"},
      {"summary /nonexistent.json", "cannot open"},
      {"summary " + bad_nu, "nu = 0.5"},
      {"curve " + sphere + " --at 5e-4,1e-3", "contact radius a = 0.001"},
  };
  for (const auto& c : cases) {
    const Run r = run(c.args);
    INFO(c.args << "\nstderr: " << r.err);
    CHECK(r.code == 2);
    CHECK(r.out.empty());  // never partial output
    CHECK(r.err.find(c.expected) != std::string::npos);
  }
}

TEST_CASE("near-incompressible layers warn on stderr and in the summary", "[cli]") {
  const std::string path = write_file("nu049.json",
      R"({"indenter": {"shape": "paraboloid", "R": 0.01},
          "medium": {"type": "layer", "E": 3e6, "nu": 0.49, "h": 1e-4}, "model": "two_term", "w": 0.01})");
  const Run r = run("summary " + path);
  REQUIRE(r.code == 0);
  CHECK(r.err.find("warning") != std::string::npos);
  const auto warnings = nlohmann::json::parse(r.out)["warnings"];
  REQUIRE(warnings.size() == 2);  // the non-uniform expansion, and its estimated error
  CHECK(warnings[1].get<std::string>().find("is estimated") != std::string::npos);
}

TEST_CASE("auto on a nu = 0.49 hydrogel: uniform where it is within 1 %, exact elsewhere", "[cli][auto]") {
  const std::string scene = std::string(LAYERJKR_SOURCE_DIR) + "/data/scenes/hydrogel_film_auto.json";
  const Run summary = run("summary " + scene);
  REQUIRE(summary.code == 0);
  const auto j = nlohmann::json::parse(summary.out);
  CHECK(j["model"] == "uniform");  // pull-off at a/h = 18
  CHECK(j["model_choice"]["estimated_error"].get<double>() < 0.01);
  CHECK(j["model_error_estimate"]["pull_off_force"].get<double>() == j["model_choice"]["estimated_error"].get<double>());
  CHECK(j["warnings"].empty());
  CHECK(summary.err.find("auto chose model 'uniform'") != std::string::npos);
  const Run near = run("curve " + scene + " --at 2e-5,1e-4");  // a/h = 2: no reduced model within 1 %
  REQUIRE(near.code == 0);
  CHECK(near.err.find("auto chose model 'exact'") != std::string::npos);
  const Run far = run("curve " + scene + " --at 1e-4,1e-3");
  REQUIRE(far.code == 0);
  CHECK(far.err.find("auto chose model 'uniform'") != std::string::npos);
}
