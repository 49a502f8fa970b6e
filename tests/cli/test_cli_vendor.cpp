// Vendors' files as they are written, through the CLI: an Asylum map exported per channel fitted
// from its folder (a row per point, with its pixel), a curve of piezo and force with its spring
// constant, and fit-map saying what a folder held besides curves.
#include <catch2/catch.hpp>

#include <filesystem>

#include "io/jpk_builder.hpp"
#include "support/cli_support.hpp"

using namespace test::cli;
namespace fs = std::filesystem;

namespace {
const std::string kFree = sample_fit_flags();
const std::string kHertz = R"({"indenter": {"shape": "paraboloid", "R": 1e-6},
    "medium": {"type": "half_space", "E": 1e6, "nu": 0.5}})";
}  // namespace

TEST_CASE("vendor files: fit-map reads an Asylum map exported per channel from its folder", "[cli][vendor][asylum]") {
  const std::string root = unique("ar_export");
  test::write_asylum_map_export(root, true);
  const std::string table = unique("ar.csv");
  const Run r = run("fit-map " + root + " --scene " + write_file("hertz.json", kHertz) + " --free E,delta0 --out " + table);
  INFO(r.err);
  // The builder's 9-row curves are too short to fit: every point is a row that says why.
  CHECK(r.code == 4);
  const auto rows = lines(slurp(table));
  REQUIRE(rows.size() == 7);  // header and one row per point
  CHECK(rows[1].rfind(root + "#0,0,", 0) == 0);
  CHECK(rows[6].find(",2,1,error,") != std::string::npos);  // point 2 of line 1: its pixel
  // The export of one point, read back: Defl x k (0.5 N/m, from the map image).
  const Run e = run("export " + root + " --curves 0:1 --out " + unique("one.csv"));
  INFO(e.err);
  REQUIRE(e.code == 0);
  const std::vector<std::string> exported = lines(slurp(unique("one.csv")));
  CHECK(exported.at(0) == "curve,segment,t,force,height,tip_position");
  const std::string& first = exported.at(1);
  const std::size_t t_end = first.find(',', 4);  // after "0,0,": t, then force
  const double force = std::stod(first.substr(t_end + 1, first.find(',', t_end + 1) - t_end - 1));
  CHECK(force == Approx(0.5 * 1e-9).epsilon(1e-6));  // Defl 1 nm (float32) x k
}

TEST_CASE("vendor files: z,force curves with --spring-constant, and what a folder held besides curves", "[cli][vendor]") {
  // The bundled sample as piezo and force: z = delta + P / k.
  std::ifstream in(sample_curve());
  std::string text = "z,force,segment\n";
  const double k = 0.1;
  for (std::string line; std::getline(in, line);) {
    if (line.empty() || line[0] == '#' || line[0] == 'd') continue;
    const std::size_t a = line.find(','), b = line.find(',', a + 1);
    const double delta = std::stod(line.substr(0, a)), P = std::stod(line.substr(a + 1, b - a - 1));
    char row[128];
    std::snprintf(row, sizeof row, "%.17g,%.17g,%s\n", delta + P / k, P, line.substr(b + 1).c_str());
    text += row;
  }
  const fs::path dir = fresh_dir("zforce");
  std::ofstream(dir / "zf.csv") << text;
  const Run without = run("fit " + (dir / "zf.csv").string() + kFree);
  CHECK(without.code == 2);
  CHECK(without.err.find("z,force data need the cantilever spring constant") != std::string::npos);
  const Run with = run("fit " + (dir / "zf.csv").string() + kFree + " --spring-constant 0.1");
  INFO(with.err);
  CHECK(with.code == 0);
  // The same as the delta,P curve with that spring constant (which also sets the retract's control).
  const Run plain = run("fit " + sample_curve() + kFree + " --spring-constant 0.1");
  CHECK(with.out.substr(with.out.find("E = "), 12) == plain.out.substr(plain.out.find("E = "), 12));
  // fit-map on the folder: the curve, and a line for what it did not read.
  fs::create_directories(dir / "bruker");
  std::ofstream(dir / "notes.txt") << "a lab note\n";
  const Run map = run("fit-map " + dir.string() + kFree + " --spring-constant 0.1 --out " + unique("zf_map.csv"));
  INFO(map.err);
  CHECK(map.code == 0);
  CHECK(map.err.find("not read: 1 folder(s) (bruker/; a folder's own files are read: name a sub-folder") != std::string::npos);
  CHECK(map.err.find("1 other file(s) (notes.txt; not .csv or an instrument file)") != std::string::npos);
}
