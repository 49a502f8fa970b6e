// Bounds before work (docs/development.md, Limits): what a small input can multiply - a map
// header's grid, radii x the cost of a radius, a stack's layers, bootstrap replicates x radii -
// is bounded before the work starts, and every library failure is an Error naming its input,
// never "internal error".
#include <catch2/catch.hpp>

#include <filesystem>

#include "io/jpk_builder.hpp"
#include "support/cli_support.hpp"

using namespace test::cli;
namespace fs = std::filesystem;

namespace {
const std::string kSource = LAYERJKR_SOURCE_DIR;
const std::string kFree = sample_fit_flags();
bool have_gnuplot() { return std::system("gnuplot --version >/dev/null 2>&1") == 0; }
}  // namespace

TEST_CASE("bounds: a map header announcing 1e6 x 1e6 pixels over 4 curves is drawn from its curves", "[cli][bounds]") {
  const std::string map = unique("sparse.jpk-force-map");
  test::write_jpk_map(map, 4, 2, 1000000, 1000000);  // the 2 x 2 curves land 500 000 pixels apart
  const std::string report = unique("sparse_report"), table = unique("sparse.csv");
  std::string args = "fit-map " + map + kFree + " --out " + table + " --report " + report;
  if (have_gnuplot()) args += " --plot-dir " + unique("sparse_plots");
  const Run r = run(args);
  INFO(r.err);
  CHECK(r.code == 4);  // the builder's 8-sample curves do not fit: every row failed, every output written
  CHECK(r.err.find("internal error") == std::string::npos);
  CHECK(lines(slurp(table)).size() == 5);
  const std::string page = slurp(report + "/index.html");
  CHECK(page.find("4 on map grids too sparse to draw") != std::string::npos);
  if (have_gnuplot()) CHECK(fs::file_size(unique("sparse_plots") + "/status.png") > 1000);
}

TEST_CASE("bounds: --tiff of a map whose grid no image can hold is refused before any fit", "[cli][bounds]") {
  // Issue 41: the same 1e6 x 1e6 header with --tiff was refused only after every fit, the table
  // and its record already written.
  const std::string map = unique("tiff_sparse.jpk-force-map");
  test::write_jpk_map(map, 4, 2, 1000000, 1000000);
  const std::string table = unique("tiff_sparse.csv");
  const Run r = run("fit-map " + map + kFree + " --out " + table + " --tiff " + unique("tiff_sparse_dir"));
  CHECK(r.code == 2);
  CHECK(count_lines(r.err) == 1);
  CHECK(r.err.find("map grid of 1000000 x 1000000 pixels; an image holds at most 67108864") != std::string::npos);
  CHECK_FALSE(fs::exists(table));
  CHECK_FALSE(fs::exists(unique("tiff_sparse_dir")));
}

TEST_CASE("bounds: radii of a Dugdale law on a layer beyond 2 000 a call are refused before any is solved",
          "[cli][bounds]") {
  const std::string scene = write_file("md_film.json", R"({"indenter": {"shape": "paraboloid", "R": 2e-8},
      "medium": {"type": "layer", "E": 1e9, "nu": 0.3, "h": 1e-8, "base": "bonded"},
      "model": "exact", "w": 0.05, "adhesion": {"model": "maugis_dugdale", "sigma0": 2e8}})");
  const Run r = run("timeout 20 " + cli_path() + " curve " + scene + " --a-max 2e-8 --points 100000", true);
  CHECK(r.code == 2);
  CHECK(count_lines(r.err) == 1);
  CHECK(r.err.find("100000 radii of maugis_dugdale") != std::string::npos);
  CHECK(r.err.find("limit of 2000 radii a call") != std::string::npos);
  const Run few = run("curve " + scene + " --a-max 2e-8 --points 4");
  CHECK(few.code == 0);
  CHECK(lines(few.out).size() == 5);
}

TEST_CASE("bounds: a stack of more than 64 layers is refused before it is built", "[cli][bounds]") {
  std::string layers;
  for (int i = 0; i < 3000; ++i) layers += std::string(i ? "," : "") + R"({"E": 1e6, "nu": 0.45, "h": 1e-8})";
  const std::string scene = write_file("deep_stack.json", R"({"indenter": {"shape": "paraboloid", "R": 1e-5},
      "medium": {"type": "layers", "layers": [)" + layers + R"(], "base": "bonded"}, "w": 0.01, "model": "exact"})");
  const Run r = run("timeout 20 " + cli_path() + " summary " + scene, true);
  CHECK(r.code == 2);
  CHECK(r.err.find("medium.layers") != std::string::npos);
  CHECK(r.err.find("has 3000 layers; at most 64") != std::string::npos);
}

TEST_CASE("bounds: bootstrap replicates x radii beyond 2e7 are refused, repeated steps give an answer",
          "[cli][bounds][discrete]") {
  const std::string flat = kSource + "/data/discrete/flat_punch.csv", convex = kSource + "/data/discrete/convex.csv";
  const Run big = run("timeout 20 " + cli_path() + " discrete --flat " + flat + " --convex " + convex +
                          " --w 0.05 --points 100000 --bootstrap 1000",
                      true);
  CHECK(big.code == 2);
  CHECK(big.err.find("1000 replicates x 100000 radii exceed the limit") != std::string::npos);
  // Each flat-punch step listed twice: the radii at the data's edge met a root finder's "do not
  // bracket the root" (internal error); now the edge's slope is taken as it is.
  std::string twice;
  std::ifstream in(flat);
  std::getline(in, twice);
  twice += "\n";
  for (std::string line; std::getline(in, line);) twice += line + "\n" + line + "\n";
  const Run r = run("discrete --flat " + write_file("twice.csv", twice) + " --convex " + convex + " --w 0.05 --points 20");
  INFO(r.err);
  CHECK(r.code == 0);
  CHECK(lines(r.out).size() == 21);
  CHECK(r.err.find("internal error") == std::string::npos);
}
