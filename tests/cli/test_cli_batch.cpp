// fit-map keeps what it finished: every entry of an input directory gets a row (loops, dangling
// links, FIFOs, directories included, none blocking), SIGINT / SIGTERM leave a valid partial
// table that --resume completes to the uninterrupted run's table, and usage errors and counts
// beyond their limits are one line with exit 2.
#include <catch2/catch.hpp>

#include <signal.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <thread>

#include "support/cli_support.hpp"

using namespace test::cli;
namespace fs = std::filesystem;

namespace {
const std::string kCli = cli_path();
const std::string kCurve = sample_curve();
const std::string kScene = sample_scene();
const std::string kFree = sample_fit_flags();


fs::path curve_dir(const std::string& name, int n) {
  const fs::path dir = unique(name);
  fs::create_directories(dir);
  for (int i = 0; i < n; ++i) fs::create_symlink(kCurve, dir / ("c" + std::to_string(1000 + i) + ".csv"));
  return dir;
}

// The cells of a CSV row, less one: commas outside double quotes (a message cell is quoted where
// it holds a comma).
std::size_t unquoted_commas(const std::string& row) {
  std::size_t n = 0;
  bool quoted = false;
  for (char c : row) {
    if (c == '"') quoted = !quoted;
    n += c == ',' && !quoted ? 1 : 0;
  }
  return n;
}

// The temporary file fit-map writes for `target` in `dir` (hidden, random name: .TARGET.XXXXXX),
// or "". The table's record (map.json) has its own beside the table's.
std::string temporary_file(const fs::path& dir, const std::string& target = "map.csv") {
  for (const auto& e : fs::directory_iterator(dir))
    if (e.path().filename().string().rfind("." + target + ".", 0) == 0) return e.path().string();
  return "";
}

// Runs the CLI in the background with `args`, sends `sig` once the table holds a row, waits.
int interrupt(const std::vector<std::string>& args, const fs::path& out_dir, int sig, const std::string& err) {
  const pid_t pid = ::fork();
  if (pid == 0) {
    std::vector<char*> argv{const_cast<char*>(kCli.c_str())};
    for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    if (!std::freopen(err.c_str(), "w", stderr) || !std::freopen("/dev/null", "w", stdout)) ::_exit(99);
    ::execv(kCli.c_str(), argv.data());
    ::_exit(98);
  }
  for (int tries = 0; tries < 60000; ++tries) {  // at most 60 s
    const std::string tmp = temporary_file(out_dir);
    if (!tmp.empty() && count_lines(slurp(tmp)) >= 2) break;
    int status = 0;
    if (::waitpid(pid, &status, WNOHANG) == pid) return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  ::kill(pid, sig);
  int status = 0;
  ::waitpid(pid, &status, 0);
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}
}  // namespace

TEST_CASE("fit-map: every input-like entry of a directory gets a row, none blocks", "[cli][fit-map][batch]") {
  const fs::path dir = unique("odd_entries");
  fs::create_directories(dir);
  fs::create_symlink(kCurve, dir / "a_good.csv");
  fs::create_symlink(dir / "loop.csv", dir / "loop.csv");
  fs::create_symlink(dir / "missing", dir / "dangling.csv");
  fs::create_directory(dir / "dir.csv");
  REQUIRE(::mkfifo((dir / "fifo.csv").c_str(), 0600) == 0);
  REQUIRE(::mkfifo((dir / "fifo.jpk-force").c_str(), 0600) == 0);
  std::ofstream(dir / "notes.txt") << "not an input by name\n";
  const std::string out = unique("odd.csv");
  const Run r = run("timeout 60 " + kCli + " fit-map " + dir.string() + kFree + " --out " + out, true);
  INFO(r.err);
  REQUIRE(r.code == 3);  // the odd entries failed, the curve fitted
  const auto rows = lines(slurp(out));
  REQUIRE(rows.size() == 7);
  auto row_of = [&](const std::string& name) {
    for (const auto& row : rows)
      if (row.rfind((dir / name).string() + ",", 0) == 0) return row;
    return std::string("(no row)");
  };
  CHECK(row_of("a_good.csv").find(",ok,") != std::string::npos);
  CHECK(row_of("loop.csv").find("symbolic link loop") != std::string::npos);
  CHECK(row_of("dangling.csv").find("dangling symbolic link") != std::string::npos);
  CHECK(row_of("dir.csv").find("is a directory") != std::string::npos);
  CHECK(row_of("fifo.csv").find("is a FIFO") != std::string::npos);
  CHECK(row_of("fifo.jpk-force").find("is a FIFO") != std::string::npos);
  CHECK(r.err.find("1 of 6 curves fitted; 5 failed") != std::string::npos);
}

TEST_CASE("fit-map: SIGINT and SIGTERM keep a valid partial table, --resume completes it", "[cli][fit-map][signal]") {
  // 120 curves at 20 extra starts: seconds of work, so the signal lands mid-run.
  const fs::path in = curve_dir("signal_in", 120);
  const fs::path out_dir = unique("signal_out");
  fs::create_directories(out_dir);
  const std::string out = (out_dir / "map.csv").string(), full = unique("full.csv"), err = unique("signal.err");
  const std::vector<std::string> args{"fit-map", in.string(), "--scene", kScene, "--branch", "all", "--free",
                                      "E,w,delta0,P0", "--starts", "20", "--jobs", "2", "--out", out};
  for (const int sig : {SIGINT, SIGTERM}) {
    INFO("signal " << sig);
    const int code = interrupt(args, out_dir, sig, err);
    const std::string message = slurp(err);
    INFO(message);
    REQUIRE(code == 128 + sig);
    const auto rows = lines(slurp(out));
    REQUIRE(rows.size() >= 2);
    REQUIRE(rows.size() < 121);
    const std::string last = lines(message).back();
    CHECK(last.find("fit-map: stopped by " + std::string(sig == SIGINT ? "SIGINT" : "SIGTERM") + ": " +
                    std::to_string(rows.size() - 1) + " of 120 rows written to " + out) == 0);
    for (std::size_t k = 1; k < rows.size(); ++k) {  // a prefix of the input, every row whole
      CHECK(rows[k].rfind((in / ("c" + std::to_string(999 + k) + ".csv")).string() + ",,,,,,ok,,two_term,1,", 0) == 0);
      CHECK(unquoted_commas(rows[k]) == unquoted_commas(rows[0]));
    }
    CHECK(temporary_file(out_dir).empty());
    CHECK(temporary_file(out_dir, "map.json").empty());
    CHECK(fs::exists(out_dir / "map.json"));  // the record is committed with the table
  }
  std::string resume_args, full_args;
  for (std::size_t k = 1; k + 1 < args.size(); ++k) resume_args += " " + args[k];
  const Run resumed = run("fit-map" + resume_args + " " + out + " --resume");
  INFO(resumed.err);
  REQUIRE(resumed.code == 0);
  CHECK(resumed.err.find("rows kept from the earlier run") != std::string::npos);
  const Run whole = run("fit-map" + resume_args + " " + full);
  REQUIRE(whole.code == 0);
  CHECK(slurp(out) == slurp(full));
}

TEST_CASE("fit-map --resume refuses a table of another header or a damaged one", "[cli][fit-map][batch]") {
  const fs::path in = curve_dir("resume_in", 3);
  const std::string out = unique("resume.csv");
  REQUIRE(run("fit-map " + in.string() + kFree + " --out " + out).code == 0);
  const std::string table = slurp(out);
  struct Case { std::string args, expected; };
  const std::vector<Case> cases{
      {"fit-map " + in.string() + " --scene " + kScene + " --free E --resume --out " + out, "header of"},
      {"fit-map " + in.string() + kFree + " --resume --plot-dir " + unique("plots") + " --out " + out, "--plot-dir"},
  };
  for (const auto& c : cases) {
    const Run r = run(c.args);
    INFO(c.args << "\n" << r.err);
    CHECK(r.code == 2);
    CHECK(count_lines(r.err) == 1);
    CHECK(r.err.find(c.expected) != std::string::npos);
    CHECK(slurp(out) == table);
  }
  std::ofstream(out, std::ios::app) << "a,b,c\n";
  const Run r = run("fit-map " + in.string() + kFree + " --resume --out " + out);
  CHECK(r.code == 2);
  CHECK(r.err.find("line 5 is not a row of 28 cells") != std::string::npos);
  // A last line cut off mid-write is fitted again.
  std::ofstream(out) << table << "cut,off";
  const Run again = run("fit-map " + in.string() + kFree + " --resume --out " + out);
  INFO(again.err);
  CHECK(again.code == 0);
  CHECK(slurp(out) == table);
}

TEST_CASE("usage errors and counts beyond their limits: one line, exit 2", "[cli][errors]") {
  struct Case { std::string args, expected; };
  const std::vector<Case> cases{
      {"", "A subcommand is required"},
      {"frobnicate", "unknown command 'frobnicate'"},
      {"curve", "scene is required"},
      {"curve " + kScene + " --frob", "--frob"},
      {"curve " + kScene + " --a-max 1e-3 --points abc", "abc"},
      {"fit " + kCurve + " --free E", "--scene is required"},
      {"curve " + kScene + " --a-max 1e-3 --points 2147483647", "--points = 2147483647 must be in [1, 100000] (the limit"},
      {"curve " + kScene + " --a-max 1e-3 --points 100001", "(the limit"},
      {"fit-map " + kCurve + kFree + " --jobs 1000000 --out " + unique("never.csv"), "--jobs = 1000000 must be in [1, 1024]"},
  };
  for (const auto& c : cases) {
    const Run r = run("timeout 30 " + kCli + " " + c.args, true);
    INFO(c.args << "\nstderr: " << r.err);
    CHECK(r.code == 2);
    CHECK(count_lines(r.err) == 1);
    CHECK(r.err.find(c.expected) != std::string::npos);
  }
  CHECK_FALSE(fs::exists(unique("never.csv")));
  const Run help = run("fit-map --help");
  CHECK(help.code == 0);
  CHECK(help.out.find("--resume") != std::string::npos);
}
