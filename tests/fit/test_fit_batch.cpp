// Batches keep what they finish: on_item in input order, cancellation between curves (the items
// that ran are a prefix, each reported), skipping, a throwing hook, and paths that are not
// regular files (FIFO, directory, dangling link, link loop) as failed items, never a hang.
#include <catch2/catch.hpp>

#include <sys/stat.h>

#include <atomic>
#include <filesystem>
#include <stdexcept>

#include "layerjkr/fit.hpp"
#include "support/temp_dir.hpp"

using namespace layerjkr;
namespace fs = std::filesystem;

namespace {

const std::string kCurve = std::string(LAYERJKR_SOURCE_DIR) + "/data/curves/hydrogel_film_two_term.csv";
const std::string kScene = std::string(LAYERJKR_SOURCE_DIR) + "/data/scenes/hydrogel_film_two_term.json";

FitOptions fit_options() {
  FitOptions o;
  o.free = {FitParameter::E, FitParameter::w, FitParameter::delta0, FitParameter::P0};
  o.branch = Branch::all;
  o.compute_covariance = false;
  return o;
}

std::vector<std::string> copies(std::size_t n) { return std::vector<std::string>(n, kCurve); }

}  // namespace

TEST_CASE("fit batch: on_item sees every item once, in input order, from several threads", "[fit][batch]") {
  const Scene scene = load_scene(kScene);
  BatchOptions b;
  b.jobs = 4;
  std::vector<std::size_t> seen;
  b.on_item = [&](std::size_t i, const BatchItem& it) {
    CHECK(it.ok);
    seen.push_back(i);
  };
  const std::vector<BatchItem> items = fit_files(copies(12), scene, fit_options(), CsvOptions{}, b);
  REQUIRE(seen.size() == 12);
  for (std::size_t i = 0; i < seen.size(); ++i) CHECK(seen[i] == i);
  for (const auto& it : items) CHECK((it.ok && !it.cancelled && !it.skipped));
}

TEST_CASE("fit batch: cancelled stops between curves, what ran is a reported prefix", "[fit][batch]") {
  const Scene scene = load_scene(kScene);
  std::atomic<std::size_t> reported{0}, started{0};
  BatchOptions b;
  b.jobs = 3;
  b.cancelled = [&] { return started.fetch_add(1) >= 5; };  // polled before each start
  b.on_item = [&](std::size_t i, const BatchItem& it) {
    CHECK(i == reported);
    CHECK_FALSE(it.cancelled);
    ++reported;
  };
  const std::vector<CurveData> curves(20, read_curve_csv(kCurve, CsvOptions{}));
  const std::vector<BatchItem> items = fit_batch(curves, scene, fit_options(), b);
  REQUIRE(items.size() == 20);
  std::size_t ran = 0;
  while (ran < items.size() && !items[ran].cancelled) ++ran;
  CHECK(ran == reported);
  CHECK(ran == 5);  // the five polls that said "go" each started a fit; none started after
  for (std::size_t i = 0; i < items.size(); ++i) {
    CHECK(items[i].cancelled == (i >= ran));
    CHECK(items[i].ok == (i < ran));
  }
}

TEST_CASE("fit batch: skip leaves an item unread, and a throwing hook is rethrown", "[fit][batch]") {
  const Scene scene = load_scene(kScene);
  std::vector<CurveData> curves(4);  // empty curves: fitting any of them fails
  for (std::size_t i = 0; i < curves.size(); ++i) curves[i].source = "c" + std::to_string(i);
  BatchOptions b;
  b.skip = [](const BatchItem& it) { return it.source == "c1" || it.source == "c2"; };
  const std::vector<BatchItem> items = fit_batch(curves, scene, fit_options(), b);
  CHECK((!items[0].skipped && !items[0].ok && !items[0].error.empty()));
  CHECK((items[1].skipped && items[1].error.empty()));
  CHECK(items[2].skipped);
  CHECK_FALSE(items[3].skipped);

  BatchOptions thrower;
  thrower.jobs = 2;
  thrower.on_item = [](std::size_t i, const BatchItem&) {
    if (i == 1) throw std::runtime_error("disk full");
  };
  CHECK_THROWS_WITH(fit_batch(curves, scene, fit_options(), thrower), "disk full");
}

TEST_CASE("fit_files: paths that are not regular files are failed items, never opened", "[fit][batch]") {
  const test::TempDir dir;
  const fs::path d = dir.path();
  fs::create_symlink(d / "loop.csv", d / "loop.csv");
  fs::create_symlink(d / "missing", d / "dangling.csv");
  fs::create_directory(d / "dir.csv");
  REQUIRE(::mkfifo((d / "fifo.csv").c_str(), 0600) == 0);
  fs::create_symlink(kCurve, d / "link.csv");
  const std::vector<std::string> paths{(d / "loop.csv").string(), (d / "dangling.csv").string(),
                                       (d / "dir.csv").string(),  (d / "fifo.csv").string(),
                                       (d / "link.csv").string(), (d / "fifo.jpk-force").string()};
  REQUIRE(::mkfifo(paths.back().c_str(), 0600) == 0);
  const std::vector<BatchItem> items = fit_files(paths, load_scene(kScene), fit_options(), CsvOptions{});
  REQUIRE(items.size() == paths.size());
  const std::vector<std::string> why{"symbolic link loop", "dangling symbolic link", "is a directory", "is a FIFO",
                                     "", "is a FIFO"};
  for (std::size_t i = 0; i < items.size(); ++i) {
    INFO(paths[i] << ": " << items[i].error);
    CHECK(items[i].source == paths[i]);
    CHECK(items[i].ok == why[i].empty());
    CHECK(items[i].error.find(why[i]) != std::string::npos);
    if (!items[i].ok) CHECK(items[i].error.find(paths[i]) == 0);
  }
}
