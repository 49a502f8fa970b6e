// Results that reproduce themselves: a fit report's provenance reruns to the same numbers bit for
// bit (a CSV curve and one curve of an instrument map), a changed or missing input is refused
// naming both hashes, another version only warns; fit-map's record beside its table holds every
// input's SHA-256 and stops --resume from mixing rows of other options, scenes or inputs.
#include <catch2/catch.hpp>

#include <filesystem>

#include <nlohmann/json.hpp>

#include "layerjkr/provenance.hpp"
#include "support/cli_support.hpp"

using namespace test::cli;
namespace fs = std::filesystem;
using json = nlohmann::json;

namespace {
const std::string kCurve = sample_curve();
const std::string kScene = sample_scene();
const std::string kFree = sample_fit_flags();
const std::string kMap = std::string(LAYERJKR_SOURCE_DIR) + "/../shared/data/instrument/fmt-jpk-fd_map2x2_extracted.jpk-force-map";


std::string file_sha256(const std::string& path) {
  const std::string bytes = slurp(path);
  return layerjkr::sha256_hex(bytes.data(), bytes.size());
}

// Every key of the two reports but "provenance" equal, numbers compared exactly (json's ==
// compares doubles with ==; both parse the shortest round-trip text), and their provenance equal
// but for the command line and what the rerun adds.
void check_same_report(const std::string& first, const std::string& second) {
  json a = json::parse(slurp(first)), b = json::parse(slurp(second));
  REQUIRE(a.contains("provenance"));
  REQUIRE(b.contains("provenance"));
  json pa = a["provenance"], pb = b["provenance"];
  a.erase("provenance");
  b.erase("provenance");
  CHECK(a.dump() == b.dump());  // the text too: same digits, same order
  CHECK(a == b);
  CHECK(b["provenance"].is_null());
  CHECK(pb["rerun_of"]["sha256"] == file_sha256(first));
  for (const char* key : {"layerjkr_version", "scene", "options", "csv", "inputs"}) {
    INFO(key);
    CHECK(pa[key] == pb[key]);
  }
  CHECK(pa["command_line"] != pb["command_line"]);
}
}  // namespace

TEST_CASE("fit --from-report reruns a CSV fit to the same numbers bit for bit", "[cli][provenance]") {
  const std::string data = unique("curve.csv");
  fs::copy_file(kCurve, data);
  const std::string first = unique("first.json"), second = unique("second.json");
  const Run r = run("fit " + data + kFree + " --starts 2 --loss huber:1e-10 --out " + first);
  INFO(r.err);
  REQUIRE(r.code == 0);
  const json p = json::parse(slurp(first))["provenance"];
  CHECK(p["layerjkr_version"] == layerjkr::version());
  CHECK(p["inputs"][0]["path"] == fs::canonical(data).string());
  CHECK(p["inputs"][0]["size"] == fs::file_size(data));
  CHECK(p["inputs"][0]["sha256"] == file_sha256(data));
  CHECK(p["scene"]["sha256"] == file_sha256(kScene));
  CHECK(p["scene"]["json"] == json::parse(slurp(kScene)));
  CHECK(p["options"]["extra_starts"] == 2);
  CHECK(p["options"]["loss"] == "huber");
  CHECK(p["options"]["loss_scale"] == 1e-10);
  CHECK(p["command_line"][1] == "fit");
  const Run again = run("fit --from-report " + first + " --out " + second);
  INFO(again.err);
  REQUIRE(again.code == 0);
  CHECK(again.err.empty());
  CHECK(again.out == r.out);  // the printed summary too
  check_same_report(first, second);
}

TEST_CASE("fit --from-report reruns one curve of an instrument map bit for bit", "[cli][provenance][instrument]") {
  if (!fs::exists(kMap)) {
    test::report_skip(kMap + " is absent (the shared data beside the repository)");
    return;
  }
  const std::string scene = write_file("hertz.json", R"({"indenter": {"shape": "paraboloid", "R": 4e-8},
      "medium": {"type": "half_space", "E": 3e5, "nu": 0.5}})");
  const std::string first = unique("map_first.json"), second = unique("map_second.json");
  const Run r = run("fit " + kMap + " --curve 2 --scene " + scene + " --free E,delta0,P0 --out " + first);
  INFO(r.err);
  REQUIRE(r.code == 0);
  CHECK(json::parse(slurp(first))["provenance"]["csv"]["curve"] == 2);
  const Run again = run("fit --from-report " + first + " --out " + second);
  INFO(again.err);
  REQUIRE(again.code == 0);
  check_same_report(first, second);
  // A found contact point and an indentation range are recorded and rerun too.
  const std::string third = unique("map_rov.json"), fourth = unique("map_rov_again.json");
  const Run rov = run("fit " + kMap + " --curve 2 --scene " + scene +
                      " --free E --contact-point rov --indentation-range -1e-7:5e-7 --out " + third);
  INFO(rov.err);
  REQUIRE(rov.code == 0);
  const json o = json::parse(slurp(third))["provenance"]["options"];
  CHECK(o["contact_point"] == "rov");
  CHECK(o["indentation_range"] == json::array({-1e-7, 5e-7}));
  REQUIRE(run("fit --from-report " + third + " --out " + fourth).code == 0);
  check_same_report(third, fourth);
}

TEST_CASE("fit --from-report refuses a changed or missing input in one line naming both hashes", "[cli][provenance]") {
  const std::string data = unique("changing.csv");
  fs::copy_file(kCurve, data);
  const std::string report = unique("changing.json");
  REQUIRE(run("fit " + data + kFree + " --out " + report).code == 0);
  const std::string before = file_sha256(data);
  std::ofstream(data, std::ios::app) << "3e-6,1e-9\n";
  const Run changed = run("fit --from-report " + report + " --out " + unique("never.json"));
  CHECK(changed.code == 2);
  CHECK(count_lines(changed.err) == 1);
  CHECK(changed.err.find(fs::canonical(data).string()) != std::string::npos);
  CHECK(changed.err.find(before) != std::string::npos);
  CHECK(changed.err.find(file_sha256(data)) != std::string::npos);
  CHECK_FALSE(fs::exists(unique("never.json")));
  fs::remove(data);
  const Run missing = run("fit --from-report " + report);
  CHECK(missing.code == 2);
  CHECK(count_lines(missing.err) == 1);
  CHECK(missing.err.find("missing") != std::string::npos);
  CHECK(missing.err.find(before) != std::string::npos);
}

TEST_CASE("fit --from-report: another version warns and reruns, flags beside it and bad reports are refused",
          "[cli][provenance]") {
  const std::string report = unique("old.json"), rerun = unique("old_rerun.json");
  REQUIRE(run("fit " + kCurve + kFree + " --out " + report).code == 0);
  json j = json::parse(slurp(report));
  j["provenance"]["layerjkr_version"] = "0.0.1";
  const std::string old = write_file("old_version.json", j.dump(2));
  const Run r = run("fit --from-report " + old + " --out " + rerun);
  INFO(r.err);
  CHECK(r.code == 0);
  CHECK(r.err.find("warning: " + old + " was written by layerjkr 0.0.1, this is " + layerjkr::version()) !=
        std::string::npos);
  json a = json::parse(slurp(report)), b = json::parse(slurp(rerun));
  a.erase("provenance");
  b.erase("provenance");
  CHECK(a == b);

  json unknown = json::parse(slurp(report));
  unknown["provenance"]["options"]["colour_map"] = "viridis";
  j = json::parse(slurp(report));
  j["provenance"]["scene"]["json"] = nullptr;
  j["provenance"]["scene"]["note"] = "built in code";
  struct Case { std::string args, expected; };
  const std::vector<Case> cases{
      {"fit --from-report " + report + " --scene " + kScene, "not --scene"},
      {"fit --from-report " + report + " --starts 3", "not --starts"},
      {"fit --from-report " + report + " " + kCurve, "not data"},
      {"fit --from-report " + write_file("nothing.json", "{\"converged\": true}"), "has no \"provenance\""},
      {"fit --from-report " + write_file("unknown.json", unknown.dump()), "unknown option 'colour_map'"},
      {"fit --from-report " + write_file("coded.json", j.dump()), "cannot be rerun: its scene was built in code"},
      {"fit --from-report " + unique("absent.json"), "cannot open"},
      {"fit " + kCurve + " --free E", "--scene is required"},
      {"fit --scene " + kScene + " --free E", "data is required"},
  };
  for (const auto& c : cases) {
    const Run e = run(c.args);
    INFO(c.args << "\n" << e.err);
    CHECK(e.code == 2);
    CHECK(count_lines(e.err) == 1);
    CHECK(e.err.find(c.expected) != std::string::npos);
  }
}

TEST_CASE("fit-map writes its record beside the table: every input's size and SHA-256", "[cli][fit-map][provenance]") {
  const fs::path dir = unique("map_in");
  fs::create_directories(dir);
  fs::copy_file(kCurve, dir / "a.csv");
  std::ofstream(dir / "b.csv") << "delta,P\n1,abc\n";
  const std::string out = unique("results.csv");
  const Run r = run("fit-map " + dir.string() + kFree + " --jobs 2 --out " + out);
  INFO(r.err);
  REQUIRE(r.code == 3);  // b.csv failed
  const std::string sidecar = unique("results.json");
  REQUIRE(fs::exists(sidecar));
  const json p = json::parse(slurp(sidecar));
  CHECK(p["layerjkr_version"] == layerjkr::version());
  CHECK(p["table"] == out);
  CHECK(p["curves"].is_null());
  CHECK(p["options"]["free"] == json({"E", "w", "delta0", "P0"}));
  CHECK(p["scene"]["sha256"] == file_sha256(kScene));
  REQUIRE(p["inputs"].size() == 2);
  for (int k = 0; k < 2; ++k) {
    const std::string path = (dir / (k == 0 ? "a.csv" : "b.csv")).string();
    CHECK(p["inputs"][k]["path"] == path);
    CHECK(p["inputs"][k]["size"] == fs::file_size(path));
    CHECK(p["inputs"][k]["sha256"] == file_sha256(path));
  }
  // The name rule: .csv becomes .json, anything else gets .json appended.
  const std::string txt = unique("results.txt");
  REQUIRE(run("fit-map " + (dir / "a.csv").string() + kFree + " --out " + txt).code == 0);
  CHECK(fs::exists(txt + ".json"));
  const Run help = run("fit-map --help");
  CHECK(help.out.find("OUT.json") != std::string::npos);
}

TEST_CASE("fit-map --resume refuses rows made from other options, another scene, changed inputs or no record",
          "[cli][fit-map][provenance]") {
  const fs::path dir = unique("resume_in");
  fs::create_directories(dir);
  for (int i = 0; i < 3; ++i) fs::copy_file(kCurve, dir / ("c" + std::to_string(i) + ".csv"));
  const std::string out = unique("resume.csv"), sidecar = unique("resume.json");
  REQUIRE(run("fit-map " + dir.string() + kFree + " --out " + out).code == 0);
  const std::string table = slurp(out), record = slurp(sidecar);
  const std::string other_scene = write_file("other_scene.json", R"({"indenter": {"shape": "paraboloid", "R": 1e-5},
      "medium": {"type": "layer", "E": 60000, "nu": 0.3, "h": 2e-7, "base": "bonded"}, "model": "two_term", "w": 0.001})");
  struct Case { std::string args, expected; };
  const std::vector<Case> cases{
      {"fit-map " + dir.string() + kFree + " --starts 1 --resume --out " + out, "other fit options"},
      {"fit-map " + dir.string() + kFree + " --units nm,nN --resume --out " + out, "other fit options"},
      {"fit-map " + dir.string() + " --scene " + other_scene + " --branch all --free E,w,delta0,P0 --resume --out " + out,
       "another scene"},
  };
  for (const auto& c : cases) {
    const Run r = run(c.args);
    INFO(c.args << "\n" << r.err);
    CHECK(r.code == 2);
    CHECK(count_lines(r.err) == 1);
    CHECK(r.err.find(c.expected) != std::string::npos);
    CHECK(slurp(out) == table);
    CHECK(slurp(sidecar) == record);
  }
  // A changed input: named with both hashes.
  const std::string c1 = (dir / "c1.csv").string(), before = file_sha256(c1);
  std::ofstream(c1, std::ios::app) << "3e-6,1e-9\n";
  const Run changed = run("fit-map " + dir.string() + kFree + " --resume --out " + out);
  CHECK(changed.code == 2);
  CHECK(count_lines(changed.err) == 1);
  CHECK(changed.err.find(c1 + " changed") != std::string::npos);
  CHECK(changed.err.find(before) != std::string::npos);
  CHECK(changed.err.find(file_sha256(c1)) != std::string::npos);
  fs::copy_file(kCurve, c1, fs::copy_options::overwrite_existing);
  // The same run resumes; an input of the earlier run not named now keeps its row and its record.
  const Run same = run("fit-map " + (dir / "c0.csv").string() + " " + (dir / "c1.csv").string() + kFree +
                       " --resume --out " + out);
  INFO(same.err);
  CHECK(same.code == 0);
  CHECK(json::parse(slurp(sidecar))["inputs"].size() == 3);
  CHECK(lines(slurp(out)).size() == 4);
  // No record: nothing to check the rows against.
  fs::remove(sidecar);
  const Run bare = run("fit-map " + dir.string() + kFree + " --resume --out " + out);
  CHECK(bare.code == 2);
  CHECK(count_lines(bare.err) == 1);
  CHECK(bare.err.find("is missing") != std::string::npos);
}

TEST_CASE("fit-map --from-report reruns a map to the same table byte for byte", "[cli][fit-map][provenance]") {
  const fs::path dir = unique("rerun_in");
  fs::create_directories(dir);
  for (int i = 0; i < 3; ++i) fs::copy_file(kCurve, dir / ("c" + std::to_string(i) + ".csv"));
  std::ofstream(dir / "c1.csv", std::ios::app) << "3.1e-6,2e-9,1\n";  // one curve not like the others
  std::ofstream(dir / "bad.csv") << "delta,P\n1,abc\n";              // a failed row, rerun as failed
  const std::string out = unique("first_map.csv"), again = unique("second_map.csv");
  const Run r = run("fit-map " + dir.string() + kFree + " --starts 1 --jobs 2 --out " + out);
  INFO(r.err);
  REQUIRE(r.code == 3);  // bad.csv failed
  const std::string page = unique("rerun_report");
  const Run rerun =
      run("fit-map --from-report " + unique("first_map.json") + " --jobs 1 --out " + again + " --report " + page);
  INFO(rerun.err);
  REQUIRE(rerun.code == 3);
  CHECK(slurp(again) == slurp(out));  // every cell, every digit
  CHECK(slurp(page + "/index.html").find("window.layerjkr") != std::string::npos);  // the rerun's report
  const json a = json::parse(slurp(unique("first_map.json"))), b = json::parse(slurp(unique("second_map.json")));
  for (const char* key : {"layerjkr_version", "scene", "options", "csv", "inputs", "curves"}) {
    INFO(key);
    CHECK(a[key] == b[key]);
  }
  CHECK(b["rerun_of"]["sha256"] == file_sha256(unique("first_map.json")));
  // A changed input is refused before anything is written; flags beside --from-report too.
  std::ofstream(dir / "c2.csv", std::ios::app) << "3.2e-6,2e-9,1\n";
  const Run changed = run("fit-map --from-report " + unique("first_map.json") + " --out " + unique("never_map.csv"));
  CHECK(changed.code == 2);
  CHECK(count_lines(changed.err) == 1);
  CHECK(changed.err.find((dir / "c2.csv").string()) != std::string::npos);
  CHECK_FALSE(fs::exists(unique("never_map.csv")));
  const Run flags = run("fit-map --from-report " + unique("first_map.json") + " --starts 2 --out " + unique("never_map.csv"));
  CHECK(flags.code == 2);
  CHECK(flags.err.find("give only --out, --jobs, --plot-dir, --report, --tiff, --force with it, not --starts") != std::string::npos);
  const Run report = run("fit-map --from-report " + write_file("fit_report.json", "{\"provenance\": {}}") + " --out " +
                         unique("never_map.csv"));
  CHECK(report.code == 2);
  CHECK(report.err.find("is not a fit-map record") != std::string::npos);
}
