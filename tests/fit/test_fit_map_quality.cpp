// A map's quality layer says where to look: 64 x 64 clean synthetic approach curves (a sphere
// and a four-sided pyramid on a cell-like half-space, E varying over the map, force noise of a
// real cantilever) fit with no warning pixel - the model's stated approximations and
// interpolation errors are notices - and every pixel's E is within its error bar.
#include <catch2/catch.hpp>

#include <cmath>
#include <map>
#include <string>
#include <tuple>
#include <vector>

#include "layerjkr/fit.hpp"
#include "layerjkr/scene.hpp"
#include "layerjkr/simulate.hpp"

using namespace layerjkr;

namespace {

constexpr int kSide = 64;

std::string cell_scene(const std::string& indenter, double E) {
  return R"({"indenter": )" + indenter + R"(, "medium": {"type": "half_space", "E": )" + std::to_string(E) +
         R"(, "nu": 0.5}, "w": 0})";
}

struct MapCounts {
  std::map<std::string, int> quality;
  int notices = 0, outside_error_bar = 0;
};

// Each pixel its own E (1-3 kPa), contact point and seed; approach only, as a QI map's.
MapCounts fit_map(const std::string& indenter, double max_indentation, double noise) {
  std::vector<CurveData> curves;
  std::vector<double> truth;
  for (int k = 0; k < kSide * kSide; ++k) {
    const double E = 1000.0 + 2000.0 * ((k * 37) % 101) / 100.0;
    SimulationOptions s;
    s.branch = Branch::approach;
    s.points_per_branch = 300;
    s.max_indentation = max_indentation;
    s.free_fraction = 1.0;
    s.delta0 = 1e-7 * ((k * 13) % 7);
    s.noise = noise;
    s.seed = static_cast<std::uint64_t>(k) + 1;
    curves.push_back(simulate_curve(parse_scene(cell_scene(indenter, E)), s));
    curves.back().source = "pixel " + std::to_string(k);
    truth.push_back(E);
  }
  FitOptions o;
  o.free = {FitParameter::E, FitParameter::delta0, FitParameter::P0};
  o.branch = Branch::approach;
  BatchOptions b;
  b.jobs = 2;
  const std::vector<BatchItem> items = fit_batch(curves, parse_scene(cell_scene(indenter, 2000.0)), o, b);
  MapCounts counts;
  for (std::size_t k = 0; k < items.size(); ++k) {
    ++counts.quality[batch_quality(items[k])];
    if (!items[k].ok) continue;
    counts.notices += items[k].summary.notices.empty() ? 0 : 1;
    const ParameterEstimate& e = items[k].summary[FitParameter::E];
    if (!(std::abs(e.value - truth[k]) < 4.0 * e.standard_error)) ++counts.outside_error_bar;
  }
  return counts;
}

}  // namespace

TEST_CASE("a 64 x 64 map of clean sphere and pyramid curves has no warning pixel", "[fit][batch][quality]") {
  for (const auto& [name, indenter, depth, noise] :
       {std::make_tuple("sphere", std::string(R"({"shape": "sphere", "R": 5e-6})"), 1e-6, 2e-11),
        std::make_tuple("pyramid", std::string(R"({"shape": "pyramid", "semi_angle_deg": 35, "sides": 4})"), 1e-6,
                        2e-11)}) {
    INFO(name);
    MapCounts c = fit_map(indenter, depth, noise);
    std::string tally;
    for (const auto& [q, n] : c.quality) tally += q + ": " + std::to_string(n) + "; ";
    INFO(tally);
    CHECK(c.quality["warning"] == 0);
    CHECK(c.quality["failed"] == 0);
    CHECK(c.quality["ok"] == kSide * kSide);
    // What the fits state about themselves is kept, as notices.
    CHECK(c.notices == kSide * kSide);
    // 4 standard errors: about 0.3 of 4 096 pixels expected outside by chance.
    CHECK(c.outside_error_bar <= 2);
  }
}
