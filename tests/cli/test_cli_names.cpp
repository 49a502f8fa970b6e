// Names of any bytes: fit-map keys --resume by the file (canonical path and SHA-256), not by how
// a path was spelled; a file name with a line break, escape sequences or bytes that are not
// UTF-8 is written to the table and the record reversibly and read back exactly; and no message
// echoes a control character raw (a downloaded file cannot drive the terminal).
#include <catch2/catch.hpp>

#include <filesystem>

#include <nlohmann/json.hpp>

#include "io/jpk_builder.hpp"
#include "layerjkr/text.hpp"
#include "support/cli_support.hpp"

using namespace test::cli;
namespace fs = std::filesystem;

namespace {
const std::string kCli = cli_path();
const std::string kCurve = sample_curve();
const std::string kFree = sample_fit_flags();

std::size_t data_rows(const std::string& table) {  // rows, a quoted cell with a line break counted once
  std::size_t rows = 0;
  bool quoted = false;
  for (char c : table) {
    if (c == '"') quoted = !quoted;
    if (c == '\n' && !quoted) ++rows;
  }
  return rows - 1;  // the header
}

bool has_control(const std::string& s) {
  for (char c : s)
    if ((static_cast<unsigned char>(c) < 0x20 && c != '\n') || c == 0x7f) return true;
  return false;
}
}  // namespace

TEST_CASE("fit-map --resume matches earlier rows by the file, however its path is spelled", "[cli][fit-map][names]") {
  const fs::path root = fresh_dir("spelling");
  fs::create_directories(root / "m");
  for (const char* n : {"a.csv", "b.csv", "c.csv"}) fs::copy_file(kCurve, root / "m" / n);
  fs::create_directory_symlink(root / "m", root / "link");
  const std::string table = (root / "t.csv").string();
  const auto in_root = [&](const std::string& args) {
    return run("bash -c 'cd " + root.string() + " && exec " + kCli + " " + args + "'", true);
  };
  REQUIRE(in_root("fit-map m" + kFree + " --out t.csv").code == 0);
  const std::string first = slurp(table);
  for (const std::string& spelling : std::vector<std::string>{"./m", "m/", (root / "m").string(), "link", "./link/../m"}) {
    const Run r = in_root("fit-map " + spelling + kFree + " --out t.csv --resume");
    INFO(spelling << "\n" << r.err);
    CHECK(r.code == 0);
    CHECK(r.err.find("(3 rows kept from the earlier run)") != std::string::npos);
    CHECK(r.err.find("kept at the end") == std::string::npos);  // no row left over: none doubled
    CHECK(data_rows(slurp(table)) == 3);
  }
  CHECK(slurp(table) == first);  // the rows as the first run wrote them
  // A changed file is one the rows were not made from: refused, as before.
  std::ofstream(root / "m" / "b.csv", std::ios::app) << "3.1e-6,2e-9,1\n";
  const Run changed = in_root("fit-map ./m" + kFree + " --out t.csv --resume");
  CHECK(changed.code == 2);
  CHECK(changed.err.find("changed since the earlier table was made") != std::string::npos);
}

TEST_CASE("file names with a line break, escapes or bytes that are not UTF-8 are written and read back exactly",
          "[cli][fit-map][names]") {
  const fs::path dir = fresh_dir("odd_names");
  const std::vector<std::string> names{"b\nc.csv", "M\xfcller.csv", "esc\x1b]0;owned\x07.csv", "back\\slash.csv",
                                       "caf\xc3\xa9.csv"};
  for (const std::string& n : names) fs::copy_file(kCurve, dir / n);
  const std::string table = unique("names.csv"), record = unique("names.json");
  const Run r = run("fit-map " + dir.string() + kFree + " --out " + table);
  INFO(r.err);
  REQUIRE(r.code == 0);
  CHECK_FALSE(has_control(r.err));
  CHECK(data_rows(slurp(table)) == names.size());
  // Every file cell, unescaped, is a name in the directory; the record is JSON (UTF-8) naming each.
  const std::string text = slurp(table);
  for (const std::string& n : names) {
    const std::string cell = layerjkr::escape_bytes((dir / n).string());
    INFO(cell);
    CHECK(text.find(cell) != std::string::npos);
    CHECK(layerjkr::unescape_bytes(cell) == (dir / n).string());
    CHECK(layerjkr::is_utf8(cell));
  }
  CHECK(text.find("M\\xfcller.csv") != std::string::npos);
  CHECK(text.find("caf\xc3\xa9.csv") != std::string::npos);  // valid UTF-8 stays as it is
  CHECK(text.find("\"" + (dir / "b\nc.csv").string() + "\"") != std::string::npos);  // a quoted cell over two lines
  const nlohmann::json j = nlohmann::json::parse(slurp(record));
  std::vector<std::string> named;
  for (const auto& in : j["inputs"]) named.push_back(layerjkr::unescape_bytes(in["named"].get<std::string>()));
  for (const std::string& n : names) CHECK(std::count(named.begin(), named.end(), (dir / n).string()) == 1);
  // --resume finds each row again (no duplicate), and --from-report names the very files.
  const Run resumed = run("fit-map " + dir.string() + kFree + " --out " + table + " --resume");
  INFO(resumed.err);
  CHECK(resumed.code == 0);
  CHECK(resumed.err.find("(5 rows kept from the earlier run)") != std::string::npos);
  CHECK(data_rows(slurp(table)) == names.size());
  const std::string again = unique("again.csv");
  const Run rerun = run("fit-map --from-report " + record + " --out " + again);
  INFO(rerun.err);
  CHECK(rerun.code == 0);
  CHECK(slurp(again) == slurp(table));
}

TEST_CASE("messages print control characters escaped: a scene, a CSV header, a file name", "[cli][names][errors]") {
  const std::string osc = "\x1b]0;owned\x07", clear = "\x1b[2J";
  const std::string scene = write_file("evil_scene.json", "{\"indenter\": {\"shape\": \"" + std::string("\\u001b]0;owned\\u0007") +
                                                              "\", \"R\": 1e-5}, \"medium\": {\"type\": \"half_space\", "
                                                              "\"E\": 1e6, \"nu\": 0.5}}");
  const std::string header = write_file("evil_header.csv", "delta,P" + clear + "\n0,0\n1,1\n2,2\n");
  const std::string name = unique("evil" + osc + ".csv");
  const std::string archive = unique("evil.jpk-force");
  test::write_zip(archive, test::jpk_members(8, "", "force-segment-header.duration=1.0" + clear + "\n"));
  struct Case { std::string args, shown; };
  const std::vector<Case> cases{
      {"export " + archive + " --out " + unique("never.csv"), "1.0\\x1b[2J"},
      {"summary " + scene, "\\x1b]0;owned\\x07"},
      {"fit " + header + " --scene " + sample_scene() + " --free E", "\\x1b[2J"},
      {"fit '" + name + "' --scene " + sample_scene() + " --free E", "evil\\x1b]0;owned\\x07.csv"},
  };
  for (const Case& c : cases) {
    const Run r = run(c.args);
    INFO(layerjkr::printable(c.args) << "\n" << layerjkr::printable(r.err));
    CHECK(r.code == 2);
    CHECK_FALSE(has_control(r.err));
    CHECK(r.err.find(c.shown) != std::string::npos);
  }
}
