// Every file the CLI writes: a failed write (missing directory, RLIMIT_FSIZE mid-write) exits 2
// with one line and leaves neither the output nor a temporary file; a symlink planted at any
// name the old code used is never followed; an output naming an input is refused before any work.
#include <catch2/catch.hpp>

#include <unistd.h>

#include <filesystem>

#include "support/cli_support.hpp"

using namespace test::cli;
namespace fs = std::filesystem;

namespace {
const std::string kCli = cli_path();
const std::string kCurve = sample_curve();
const std::string kScene = sample_scene();
const std::string kFree = sample_fit_flags();
bool have_gnuplot() { return std::system("gnuplot --version >/dev/null 2>&1") == 0; }


std::vector<std::string> entries(const fs::path& dir) {
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(dir)) names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

// A directory of `n` curves (symlinks to the bundled one).
fs::path curve_dir(const std::string& name, int n) {
  const fs::path dir = unique(name);
  fs::create_directories(dir);
  for (int i = 0; i < n; ++i) fs::create_symlink(kCurve, dir / ("c" + std::to_string(100 + i) + ".csv"));
  return dir;
}
}  // namespace

TEST_CASE("outputs: a directory that takes no files fails before the work, one line, nothing left", "[cli][output]") {
  const fs::path dir = unique("outputs_missing");
  fs::create_directories(dir);
  const std::string missing = (dir / "no" / "such" / "dir").string();
  for (const std::string& cmd :
       {"fit " + kCurve + kFree + " --out " + missing + "/r.json", "fit-map " + curve_dir("in_a", 3).string() + kFree +
                                                                       " --out " + missing + "/x.csv",
        "export " + kCurve + " --out " + missing + "/e.csv"}) {
    const Run r = run(cmd);
    INFO(cmd << "\n" << r.err);
    CHECK(r.code == 2);
    CHECK(count_lines(r.err) == 1);
    CHECK(r.err.find("cannot create a file in") != std::string::npos);
    CHECK(r.err.find("fit-map [") == std::string::npos);  // no curve was fitted first
  }
  CHECK(entries(dir).empty());
  if (::geteuid() != 0) {  // root ignores permission bits
    const fs::path ro = dir / "read_only";
    fs::create_directories(ro);
    fs::permissions(ro, fs::perms::owner_read | fs::perms::owner_exec);
    const Run r = run("fit " + kCurve + kFree + " --out " + (ro / "r.json").string());
    CHECK(r.code == 2);
    CHECK(r.err.find("Permission denied") != std::string::npos);
    CHECK(entries(ro).empty());
    fs::permissions(ro, fs::perms::owner_all);
  }
}

TEST_CASE("outputs: a write cut short (RLIMIT_FSIZE) exits 2 and leaves no file at all", "[cli][output]") {
  const fs::path dir = unique("outputs_short");
  fs::create_directories(dir);
  const fs::path in = curve_dir("in_short", 12);
  // ulimit -f counts 1024-byte blocks in bash: every output below is larger than 1 KiB.
  const std::string limited = "bash -c 'ulimit -f 1; exec " + kCli + " ";
  for (const std::string& cmd : {"fit " + kCurve + kFree + " --out " + (dir / "r.json").string(),
                                 "fit-map " + in.string() + kFree + " --jobs 2 --out " + (dir / "m.csv").string()}) {
    const Run r = run(limited + cmd + "'", true);
    INFO(cmd << "\n" << r.err);
    CHECK(r.code == 2);
    CHECK(r.err.substr(r.err.rfind("layerjkr:")).find("File too large") != std::string::npos);
    CHECK(entries(dir).empty());
  }
}

TEST_CASE("outputs: a planted symlink at any predictable name is never followed", "[cli][output]") {
  const fs::path dir = unique("outputs_links");
  fs::create_directories(dir);
  const fs::path victim = dir / "victim.txt";
  std::ofstream(victim) << "precious\n";
  const std::string out = (dir / "r.json").string(), png = (dir / "p.png").string();
  std::vector<std::string> planted;
  for (const std::string& name : {out + ".tmp", png + ".tmp", png + ".tmp.png", png + ".dat.tmp", out + ".dat.tmp",
                                  (dir / ".r.json.tmp").string()}) {
    fs::create_symlink(victim, name);
    planted.push_back(fs::path(name).filename().string());
  }
  const bool plot = have_gnuplot();
  const Run r = run("fit " + kCurve + kFree + " --out " + out + (plot ? " --plot " + png : std::string()));
  INFO(r.err);
  REQUIRE(r.code == 0);
  CHECK(slurp(victim.string()) == "precious\n");
  std::vector<std::string> expected = planted;
  expected.insert(expected.end(), {"r.json", "victim.txt"});
  if (plot) expected.push_back("p.png");
  std::sort(expected.begin(), expected.end());
  CHECK(entries(dir) == expected);  // the outputs, and no temporary file left
  CHECK(slurp(out).find("\"converged\"") != std::string::npos);
}

TEST_CASE("outputs: naming an input, by any name, is refused before any work", "[cli][output]") {
  const fs::path dir = unique("outputs_inputs");
  fs::create_directories(dir);
  const std::string data = (dir / "data.csv").string(), scene = (dir / "scene.json").string();
  fs::copy_file(kCurve, data);
  fs::copy_file(kScene, scene);
  fs::create_hard_link(data, dir / "hard.csv");
  fs::create_symlink(data, dir / "soft.json");
  const std::string original = slurp(data), original_scene = slurp(scene);
  const std::string fit = "fit " + data + " --scene " + scene + " --branch all --free E,w,delta0,P0";
  struct Case { std::string args, flag; };
  const std::vector<Case> cases{
      {fit + " --out " + data, "--out"},
      {fit + " --out " + (dir / "hard.csv").string(), "--out"},
      {fit + " --out " + (dir / "soft.json").string(), "--out"},
      {fit + " --out " + scene, "--out"},
      {fit + " --plot " + data, "--plot"},
      {"fit-map " + dir.string() + " --scene " + scene + " --free E --out " + data, "--out"},
      {"export " + data + " --out " + (dir / "hard.csv").string(), "--out"},
  };
  for (const auto& c : cases) {
    const Run r = run(c.args);
    INFO(c.args << "\n" << r.err);
    CHECK(r.code == 2);
    CHECK(count_lines(r.err) == 1);
    CHECK(r.err.find(c.flag + " ") != std::string::npos);
    CHECK(r.err.find("would destroy the input") != std::string::npos);
  }
  CHECK(slurp(data) == original);
  CHECK(slurp(scene) == original_scene);
}
