// The ODE route (solver "ode") answers every foundation scene the closed form answers -
// summary, curve and fit - and agrees with it. The ode variants are generated here from
// every bundled scene that accepts the solver and from foundation media of every kind.
// Before, summary of the bundled two-term scenes failed: the critical-point scan reached
// radii (a = 1.8e-12) where QAGP's relative tolerance sits below the integrand's roundoff.
#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "layerjkr/layerjkr.hpp"

using namespace layerjkr;

namespace {

// Closed form and ODE agree to this relative tolerance (the ODE route's default rel_tol is
// 1e-10; the critical-point searches converge to ~1e-12).
constexpr double kTol = 1e-7;

double rel(double x, double ref) { return std::abs(x - ref) / std::max(std::abs(ref), 1e-300); }

std::string read(const std::string& path) {
  std::ifstream f(path);
  return std::string(std::istreambuf_iterator<char>(f), {});
}

// The scene text with "solver": "ode" added as its first key.
std::string with_ode(const std::string& text) {
  const auto brace = text.find('{');
  return text.substr(0, brace + 1) + R"("solver": "ode", )" + text.substr(brace + 1);
}

struct Variant {
  std::string name, text;
};

std::vector<Variant> variants() {
  std::vector<Variant> out;
  for (const auto& e : std::filesystem::directory_iterator(std::string(LAYERJKR_SOURCE_DIR) + "/data/scenes")) {
    const std::string text = read(e.path().string());
    try {
      parse_scene(with_ode(text));
    } catch (const InputError& err) {  // exact, auto: closed form only, refused by name
      CHECK_THAT(err.what(), Catch::Contains("solver"));
      continue;
    }
    out.push_back({e.path().filename().string(), text});
  }
  const std::string sphere = R"({"indenter": {"shape": "sphere", "R": 1e-3}, )";
  for (const std::string medium :
       {R"("medium": {"type": "winkler", "K": 1e12}, "w": 0.05})",
        R"("medium": {"type": "pasternak", "K": 1e12, "G": 30}, "model": "full", "w": 0.05})",
        R"("medium": {"type": "pasternak", "K": 1e12, "G": 30}, "model": "asymptotic", "w": 0.05})",
        R"("medium": {"type": "pasternak", "K": 1e12, "G": -30}, "model": "asymptotic", "w": 0.05})",
        R"("medium": {"type": "filonenko_borodich", "K": 1e12, "T": 5}, "model": "full", "w": 0.05})"})
    out.push_back({"foundation " + medium.substr(0, 50), sphere + medium});
  out.push_back({"power law d = 3 on a two-term layer",
                 R"({"indenter": {"shape": "power_law", "B": 1e8, "d": 3}, "medium": {"type": "layer", "E": 3e6, "nu": 0.3, "h": 1e-4, "base": "bonded"}, "model": "two_term", "w": 0.05})"});
  return out;
}

}  // namespace

TEST_CASE("ODE route: summary and curve of every foundation scene agree with the closed form", "[models][ode]") {
  const std::vector<Variant> all = variants();
  REQUIRE(all.size() >= 8);  // 2 bundled two-term scenes, 6 generated
  for (const Variant& v : all) {
    INFO(v.name);
    const SummaryAnswer closed = solve_summary(parse_scene(v.text));
    const SummaryAnswer ode = solve_summary(parse_scene(with_ode(v.text)));
    REQUIRE(closed.contact.pull_off.has_value() == ode.contact.pull_off.has_value());
    REQUIRE(closed.contact.zero_load_radius.has_value());
    REQUIRE(ode.contact.zero_load_radius.has_value());
    CHECK(rel(*ode.contact.zero_load_radius, *closed.contact.zero_load_radius) < kTol);
    if (closed.contact.pull_off) {
      CHECK(rel(ode.contact.pull_off->P, closed.contact.pull_off->P) < kTol);
      CHECK(rel(ode.contact.pull_off->a, closed.contact.pull_off->a) < 1e-5);  // flat in a
    }
    const double a0 = *closed.contact.zero_load_radius;
    const std::vector<double> radii{1e-6 * a0, 1e-3 * a0, 0.1 * a0, a0, 2.0 * a0};
    const CurveAnswer c = solve_curve(parse_scene(v.text), radii);
    const CurveAnswer o = solve_curve(parse_scene(with_ode(v.text)), radii);
    for (std::size_t i = 0; i < radii.size(); ++i) {
      INFO("a = " << radii[i]);
      // Relative to the state's size: P crosses 0 at a0, so relative to |P_H| + |P|.
      const AdhesiveState& s = c.states[i];
      CHECK(std::abs(o.states[i].P - s.P) / (std::abs(s.hertz.P_H) + std::abs(s.P)) < kTol);
      CHECK(std::abs(o.states[i].delta - s.delta) / (std::abs(s.hertz.delta_H) + std::abs(s.delta)) < kTol);
    }
  }
}

TEST_CASE("ODE route: a fit of the bundled hydrogel curve agrees with the closed form", "[models][ode][fit]") {
  const std::string dir = std::string(LAYERJKR_SOURCE_DIR) + "/data/";
  const std::string text = read(dir + "scenes/hydrogel_film_two_term.json");
  const CurveData data = read_curve_csv(dir + "curves/hydrogel_film_two_term.csv");
  FitOptions options;
  options.free = {FitParameter::E, FitParameter::w, FitParameter::delta0};
  const FitSummary closed = fit(data, parse_scene(text), options);
  const FitSummary ode = fit(data, parse_scene(with_ode(text)), options);
  REQUIRE(closed.converged);
  REQUIRE(ode.converged);
  for (FitParameter p : options.free) CHECK(rel(ode[p].value, closed[p].value) < 1e-5);
}
