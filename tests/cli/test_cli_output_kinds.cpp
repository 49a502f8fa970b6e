// Outputs like a Unix tool's (output_file.hpp): `-` and /dev/stdout are standard output, FIFOs
// and devices are written through and stay what they are, a symbolic link is followed to the
// file it names, a replaced file keeps its mode and owner, a directory at any output name is
// refused before any fit, derived files (fit-map's record, --plot-dir's pictures) never replace a
// file layerjkr did not write unless --force, and fit-map's exit code says whether curves failed.
#include <catch2/catch.hpp>

#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <unistd.h>

#include <filesystem>

#include "io/jpk_builder.hpp"
#include "support/cli_support.hpp"

using namespace test::cli;
namespace fs = std::filesystem;

namespace {
const std::string kCli = cli_path();
const std::string kCurve = sample_curve();
const std::string kFree = sample_fit_flags();
bool have_gnuplot() { return std::system("gnuplot --version >/dev/null 2>&1") == 0; }

fs::path curve_dir(const std::string& name, int n) {
  const fs::path dir = fresh_dir(name);
  for (int i = 0; i < n; ++i) fs::create_symlink(kCurve, dir / ("c" + std::to_string(1000 + i) + ".csv"));
  return dir;
}

bool is_report(const std::string& text) { return text.find("\"converged\": true") != std::string::npos; }
}  // namespace

TEST_CASE("outputs: - and /dev/stdout are standard output, the summary then on stderr, no file named -",
          "[cli][output]") {
  const fs::path dir = fresh_dir("stdout_here"), links = fresh_dir("stdout_links");
  fs::create_symlink("/dev/stdout", links / "out");  // a user's link to it: the descriptor, reached
  // /dev/stdout itself only when a regression cannot replace the system's link (not as root).
  std::vector<std::string> names{"-", "/dev/fd/1", (links / "out").string()};
  if (::geteuid() != 0) names.push_back("/dev/stdout");
  for (const std::string& name : names) {
    const Run r = run("bash -c 'cd " + dir.string() + " && exec " + kCli + " fit " + kCurve + kFree + " --out " + name + "'",
                      true);
    INFO(name << "\n" << r.err);
    REQUIRE(r.code == 0);
    CHECK(is_report(r.out));
    CHECK(r.err.find("layerjkr fit: converged") != std::string::npos);  // the summary, moved to stderr
  }
  CHECK(fs::is_empty(dir));
  CHECK(fs::is_symlink(links / "out"));
  const std::string archive = unique("one.jpk-force");
  test::write_zip(archive, test::jpk_members(8));
  const Run csv = run("export " + archive + " --out -");
  INFO(csv.err);
  CHECK(csv.code == 0);
  CHECK(csv.out.rfind("curve,segment,t,force,height,tip_position\n", 0) == 0);
  CHECK(lines(csv.out).size() == 9);
  const Run map = run("bash -c 'cd " + dir.string() + " && exec " + kCli + " fit-map " + kCurve + kFree + " --out -'", true);
  INFO(map.err);
  CHECK(map.code == 0);
  CHECK(map.out.rfind("file,curve,", 0) == 0);
  CHECK(lines(map.out).size() == 2);
  CHECK(map.err.find("no record written") != std::string::npos);
  CHECK(fs::is_empty(dir));  // no "-" and no "-.json"
  const Run both = run("fit " + kCurve + kFree + " --out - --plot /dev/stdout");
  CHECK(both.code == 2);
  CHECK(both.err.find("both standard output") != std::string::npos);
  CHECK(run("fit-map " + kCurve + kFree + " --out - --resume").code == 2);
}

TEST_CASE("outputs: a FIFO is written through to its reader and stays a FIFO, with no record beside it",
          "[cli][output]") {
  const fs::path dir = fresh_dir("fifo");
  const std::string pipe = (dir / "pipe").string(), got = (dir / "got.txt").string();
  REQUIRE(::mkfifo(pipe.c_str(), 0600) == 0);
  for (const std::string& command : {"fit " + kCurve + kFree, "fit-map " + kCurve + kFree}) {
    // Bounded: a FIFO replaced by a file leaves its reader waiting (20 s, then it is stopped).
    const Run r = run("bash -c 'timeout 20 cat " + pipe + " > " + got + " & timeout 20 " + kCli + " " + command +
                          " --out " + pipe + "; code=$?; wait; exit $code'",
                      true);
    INFO(command << "\n" << r.err);
    CHECK(r.code == 0);
    CHECK(fs::is_fifo(pipe));
    const std::string text = slurp(got);
    CHECK((is_report(text) || text.rfind("file,curve,", 0) == 0));
  }
  CHECK_FALSE(fs::exists(dir / "pipe.json"));
}

TEST_CASE("outputs: a character device is written through, never replaced", "[cli][output]") {
  // A device node of its own (as root): a regression would replace it here, not /dev/null.
  const fs::path dir = fresh_dir("device");
  std::string device = (dir / "null").string();
  if (::mknod(device.c_str(), S_IFCHR | 0666, makedev(1, 3)) != 0) {
    if (::geteuid() == 0) {
      test::report_skip("cannot create a device node here (mknod: " + std::string(std::strerror(errno)) + ")");
      return;
    }
    device = "/dev/null";  // not root: renaming over /dev/null is impossible, so it is safe to try
  }
  const Run r = run("fit " + kCurve + kFree + " --out " + device);
  INFO(r.err);
  CHECK(r.code == 0);
  CHECK(fs::is_character_file(device));
  CHECK(r.out.find("layerjkr fit: converged") != std::string::npos);
}

TEST_CASE("outputs: a symbolic link is followed - its file is replaced in its own directory, the link stays",
          "[cli][output]") {
  const fs::path dir = fresh_dir("links"), real = fresh_dir("links_target");
  const fs::path file = real / "report.json";
  std::ofstream(file) << "old\n";
  fs::create_symlink(file, dir / "one");
  fs::create_symlink(dir / "one", dir / "two");      // a chain of links
  fs::create_symlink("../links_target/new.json", dir / "dangling");  // relative, to a name not yet made
  for (const char* name : {"one", "two", "dangling"}) {
    const Run r = run("fit " + kCurve + kFree + " --out " + (dir / name).string());
    INFO(name << "\n" << r.err);
    REQUIRE(r.code == 0);
    CHECK(fs::is_symlink(dir / name));
  }
  CHECK(is_report(slurp(file.string())));
  CHECK(is_report(slurp((real / "new.json").string())));
  CHECK(std::distance(fs::directory_iterator(dir), fs::directory_iterator()) == 3);   // no temporary file left
  CHECK(std::distance(fs::directory_iterator(real), fs::directory_iterator()) == 2);
}

TEST_CASE("outputs: a replaced file keeps its mode and owner, a new one gets the umask's", "[cli][output]") {
  const fs::path dir = fresh_dir("modes");
  for (const unsigned mode : {0600u, 0640u, 0604u}) {
    const std::string out = (dir / ("r" + std::to_string(mode) + ".json")).string();
    std::ofstream(out) << "private\n";
    REQUIRE(::chmod(out.c_str(), mode) == 0);
    REQUIRE(run("fit " + kCurve + kFree + " --out " + out).code == 0);
    struct stat st {};
    REQUIRE(::stat(out.c_str(), &st) == 0);
    CHECK((st.st_mode & 07777) == mode);
    CHECK(is_report(slurp(out)));
  }
  const std::string fresh = (dir / "new.json").string();
  REQUIRE(run("bash -c 'umask 027; exec " + kCli + " fit " + kCurve + kFree + " --out " + fresh + "'", true).code == 0);
  struct stat st {};
  REQUIRE(::stat(fresh.c_str(), &st) == 0);
  CHECK((st.st_mode & 07777) == 0640u);
  if (::geteuid() == 0) {  // only root can give a file away; the replacement keeps that owner
    const std::string other = (dir / "other.json").string();
    std::ofstream(other) << "theirs\n";
    REQUIRE(::chown(other.c_str(), 4242, 4343) == 0);
    REQUIRE(run("fit " + kCurve + kFree + " --out " + other).code == 0);
    REQUIRE(::stat(other.c_str(), &st) == 0);
    CHECK(st.st_uid == 4242u);
    CHECK(st.st_gid == 4343u);
  }
}

TEST_CASE("outputs: a directory at any output or derived name is refused before any fit", "[cli][output]") {
  // 2 s of CPU is far less than fitting 1000 curves: a check made after the fits dies of SIGXCPU.
  const fs::path in = curve_dir("many", 1000), dir = fresh_dir("dirs");
  fs::create_directories(dir / "taken.json");
  const std::string limited = "bash -c 'ulimit -t 2; exec " + kCli + " ";
  struct Case { std::string args, says; };
  const std::vector<Case> cases{
      {"fit " + kCurve + kFree + " --out " + dir.string(), "is a directory"},
      {"fit-map " + in.string() + kFree + " --jobs 1 --out " + dir.string(), "is a directory"},
      {"fit-map " + in.string() + kFree + " --jobs 1 --out " + (dir / "taken.csv").string(), "taken.json is a directory"},
      {"export " + kCurve + " --out " + dir.string(), "is a directory"},
  };
  for (const Case& c : cases) {
    const Run r = run(limited + c.args + "'", true);
    INFO(c.args << "\n" << r.err);
    CHECK(r.code == 2);
    CHECK(count_lines(r.err) == 1);
    CHECK(r.err.find(c.says) != std::string::npos);
  }
  CHECK_FALSE(fs::exists(dir / "taken.csv"));
}

TEST_CASE("fit-map: a file at the record's name that layerjkr did not write is not replaced unless --force",
          "[cli][output]") {
  const fs::path dir = fresh_dir("record");
  const std::string out = (dir / "results.csv").string(), record = (dir / "results.json").string();
  std::ofstream(record) << "{\"my\": \"notes\"}\n";
  const Run refused = run("fit-map " + kCurve + kFree + " --out " + out);
  CHECK(refused.code == 2);
  CHECK(refused.err.find(record + " exists and is not a fit-map record") != std::string::npos);
  CHECK(refused.err.find("--force") != std::string::npos);
  CHECK(slurp(record) == "{\"my\": \"notes\"}\n");
  CHECK_FALSE(fs::exists(out));
  REQUIRE(run("fit-map " + kCurve + kFree + " --out " + out + " --force").code == 0);
  CHECK(slurp(record).find("\"layerjkr_version\"") != std::string::npos);
  const Run again = run("fit-map " + kCurve + kFree + " --out " + out);  // its own record: replaced
  CHECK(again.code == 0);
}

TEST_CASE("fit-map --plot-dir: a picture layerjkr did not draw is not replaced unless --force", "[cli][output][plot]") {
  if (!have_gnuplot()) {
    test::report_skip("needs gnuplot");
    return;
  }
  const std::string map = unique("grid.jpk-force-map");
  test::write_jpk_map(map, 4, 2, 2, 2);
  const fs::path plots = fresh_dir("plots");
  std::ofstream(plots / "E.png") << "my own picture\n";
  const std::string args = "fit-map " + map + kFree + " --out " + unique("grid.csv") + " --plot-dir " + plots.string();
  const Run refused = run(args);
  CHECK(refused.code == 2);
  CHECK(refused.err.find("E.png exists and is not a picture layerjkr drew") != std::string::npos);
  CHECK(slurp((plots / "E.png").string()) == "my own picture\n");
  CHECK(std::distance(fs::directory_iterator(plots), fs::directory_iterator()) == 1);
  const Run forced = run(args + " --force");
  INFO(forced.err);
  CHECK(forced.code == 4);  // the builder's 8-sample curves cannot be fitted: every pixel failed, drawn as such
  CHECK(slurp((plots / "E.png").string()).find("tEXtSoftware") != std::string::npos);  // marked as layerjkr's
  const Run again = run(args);  // its own pictures are replaced
  INFO(again.err);
  CHECK(again.code == 4);
}

TEST_CASE("fit-map --tiff: a float TIFF per field and map, a TIFF layerjkr did not write not replaced unless --force",
          "[cli][output][tiff]") {
  const std::string map = unique("tiff_grid.jpk-force-map");
  test::write_jpk_map(map, 4, 2, 2, 2);
  const fs::path dir = fresh_dir("tiffs");
  const std::string args = "fit-map " + map + kFree + " --out " + unique("tiff_grid.csv") + " --tiff " + dir.string();
  const Run first = run(args);
  INFO(first.err);
  CHECK(first.code == 4);  // the builder's 8-sample curves cannot be fitted: every pixel NaN
  CHECK(first.err.find("TIFF image(s) written to") != std::string::npos);
  std::size_t files = 0;
  for (const auto& e : fs::directory_iterator(dir)) {
    CHECK(e.path().extension() == ".tiff");
    const std::string bytes = slurp(e.path().string());
    CHECK(bytes.compare(0, 4, std::string("II*\0", 4)) == 0);
    CHECK(bytes.find("layerjkr fit-map") != std::string::npos);
    ++files;
  }
  CHECK(files == 10);  // E, w, delta0, P0 (the sample flags' free parameters), each _stderr, pull_off, rms_residual
  std::ofstream(dir / "E.tiff", std::ios::trunc) << "my own image\n";
  const Run refused = run(args);
  CHECK(refused.code == 2);
  CHECK(refused.err.find("E.tiff exists and is not a TIFF layerjkr wrote") != std::string::npos);
  CHECK(slurp((dir / "E.tiff").string()) == "my own image\n");
  const Run forced = run(args + " --force");
  CHECK(forced.code == 4);
  CHECK(slurp((dir / "E.tiff").string()).find("layerjkr fit-map: E [Pa]") != std::string::npos);
  const Run again = run(args);  // its own TIFFs are replaced without --force
  INFO(again.err);
  CHECK(again.code == 4);
  // Issue 41: refused before the work - nothing written, no table, no record, no folder.
  const std::string csv_table = unique("tiff_c.csv");
  const Run csv_only = run("fit-map " + kCurve + kFree + " --out " + csv_table + " --tiff " + unique("none"));
  CHECK(csv_only.code == 2);
  CHECK(count_lines(csv_only.err) == 1);
  CHECK(csv_only.err.find("no input carries map positions") != std::string::npos);
  CHECK_FALSE(fs::exists(csv_table));
  CHECK_FALSE(fs::exists(unique("none")));
  // Two maps of the same stem in two folders: "16 TIFF image(s) written" wrote 8 before, the
  // first map's overwritten; now the second's are grid_2.*.
  const fs::path a = fresh_dir("stem_a"), b = fresh_dir("stem_b"), both = fresh_dir("tiffs_both");
  test::write_jpk_map((a / "grid.jpk-force-map").string(), 4, 2, 2, 2);
  test::write_jpk_map((b / "grid.jpk-force-map").string(), 4, 2, 2, 2);
  const Run two = run("fit-map " + (a / "grid.jpk-force-map").string() + " " + (b / "grid.jpk-force-map").string() + kFree +
                      " --out " + unique("two.csv") + " --tiff " + both.string());
  INFO(two.err);
  CHECK(two.err.find("20 TIFF image(s) written") != std::string::npos);
  std::size_t images = 0;
  for (const auto& e : fs::directory_iterator(both)) images += e.path().extension() == ".tiff" ? 1 : 0;
  CHECK(images == 20);
  CHECK(fs::exists(both / "grid.E.tiff"));
  CHECK(fs::exists(both / "grid_2.E.tiff"));
}

TEST_CASE("fit-map's exit code: 0 every curve fitted, 3 some failed, 4 none - --version and --help say so",
          "[cli][output]") {
  const fs::path dir = fresh_dir("codes");
  std::ofstream(dir / "bad.csv") << "delta,P\n1,2\n";
  fs::create_symlink(kCurve, dir / "good.csv");
  CHECK(run("fit-map " + (dir / "good.csv").string() + kFree + " --out " + unique("all.csv")).code == 0);
  CHECK(run("fit-map " + dir.string() + kFree + " --out " + unique("some.csv")).code == 3);
  const Run none = run("fit-map " + (dir / "bad.csv").string() + kFree + " --out " + unique("none.csv"));
  CHECK(none.code == 4);
  CHECK(none.err.find("0 of 1 curves fitted; 1 failed") != std::string::npos);
  const Run version = run("--version");
  CHECK(version.code == 0);
  CHECK(version.out.rfind("layerjkr ", 0) == 0);
  const Run help = run("--help");
  CHECK(help.out.find("3 some curves failed") != std::string::npos);
  CHECK(help.out.find("4 no curve was fitted") != std::string::npos);
}
