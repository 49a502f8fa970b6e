// Scene JSON reader: every shape and medium, and every kind of bad input.
#include <catch2/catch.hpp>

#include <cmath>
#include <string>

#include "layerjkr/built_scene.hpp"
#include "layerjkr/contact.hpp"
#include "layerjkr/error.hpp"
#include "layerjkr/model_spec.hpp"
#include "layerjkr/scene.hpp"

using namespace layerjkr;

namespace {
std::string scene(const std::string& indenter, const std::string& medium,
                  const std::string& extra = "") {
  return R"({"indenter": )" + indenter + R"(, "medium": )" + medium + extra + "}";
}
const std::string kPara = R"({"shape": "paraboloid", "R": 0.01})";
const std::string kLayer = R"({"type": "layer", "E": 3e6, "nu": 0.3, "h": 1e-4, "base": "bonded"})";
}  // namespace

TEST_CASE("valid scenes build the expected models", "[scene]") {
  struct Case { std::string indenter, medium, extra, model; };
  const std::vector<Case> cases{
      {kPara, kLayer, R"(, "model": "two_term", "w": 0.05)", "two_term"},
      {kPara, kLayer, R"(, "model": "leading")", "winkler"},
      {R"({"shape": "sphere", "R": 0.01})", R"({"type": "winkler", "K": 1e10})", "", "winkler"},
      {R"({"shape": "cone", "semi_angle_deg": 70})", R"({"type": "half_space", "E": 1e6, "nu": 0.5})", "", "half_space"},
      {R"({"shape": "power_law", "B": 10, "d": 2.5})", R"({"type": "pasternak", "K": 1e10, "G": 5})", R"(, "model": "full")", "full_foundation"},
      {kPara, R"({"type": "pasternak", "K": 1e10, "G": -5})", R"(, "model": "asymptotic")", "two_term"},
      {kPara, R"({"type": "layer", "E": 1e6, "nu": 0.5, "h": 1e-3})", R"(, "model": "exact")", "exact"},
      {kPara, kLayer, R"(, "model": "edge_corrected")", "edge_corrected"},
      {kPara, R"({"type": "filonenko_borodich", "K": 1e10, "T": 5})", R"(, "model": "full", "solver": "ode")", "ode(full_foundation)"},
      {R"({"shape": "table", "r": [0, 1e-4, 2e-4, 3e-4], "z": [0, 5e-7, 2e-6, 4.5e-6]})",
       R"({"type": "layer", "E": 1e6, "nu": 0.49, "h": 1e-5, "base": "frictionless"})", R"(, "model": "two_term")", "winkler"},
  };
  for (const auto& c : cases) {
    const Scene s = parse_scene(scene(c.indenter, c.medium, c.extra));
    const BuiltScene b = build_scene(s);
    INFO(c.medium << c.extra);
    CHECK(b.model->name() == c.model);
  }
  const Scene s = parse_scene(scene(kPara, kLayer, R"(, "model": "two_term", "w": 0.05)"));
  CHECK(s.w == 0.05);
  const BuiltScene b = build_scene(s);
  REQUIRE(b.resolved.K);
  CHECK(*b.resolved.K == Approx(3e6 * 0.7 / (1e-4 * 1.3 * 0.4)).epsilon(1e-14));
  CHECK(b.resolved.G.value() < 0.0);
  CHECK(b.resolved.E_star.value() == Approx(3e6 / 0.91).epsilon(1e-14));
  CHECK(build_scene(parse_scene(scene(kPara, R"({"type": "layer", "E": 3e6, "nu": 0.49, "h": 1e-4})", R"(, "model": "two_term")"))).resolved.warnings.size() == 1);
}

TEST_CASE("invalid scenes name the key and the value", "[scene][errors]") {
  struct Case { std::string text, expected; };
  const std::vector<Case> cases{
      {"{", "not valid JSON"},
      {"[1, 2]", "must be a JSON object"},
      {"", "not valid JSON"},
      {R"({"medium": )" + kLayer + R"(, "model": "two_term"})", "indenter is missing"},
      {scene(kPara, kLayer, R"(, "model": "two_term", "colour": "red")"), "scene.colour is not a known key"},
      {scene(R"({"shape": "paraboloid", "R": 0.01, "Rr": 1})", kLayer, R"(, "model": "two_term")"), "indenter.Rr is not a known key"},
      {scene(R"({"shape": "paraboloid", "R": "big"})", kLayer, R"(, "model": "two_term")"), "indenter.R must be a number, got \"big\""},
      {scene(R"({"shape": "paraboloid"})", kLayer, R"(, "model": "two_term")"), "indenter.R is missing"},
      {scene(R"({"shape": "paraboloid", "R": -0.01})", kLayer, R"(, "model": "two_term")"), "R = -0.01"},
      {scene(R"({"shape": "ellipsoid", "R": 1})", kLayer, R"(, "model": "two_term")"), "indenter.shape = \"ellipsoid\" is unknown"},
      {scene(R"({"shape": 3})", kLayer), "indenter.shape must be a string, got 3"},
      {scene(R"({"shape": "cone", "semi_angle_deg": 90})", kLayer, R"(, "model": "two_term")"), "semi_angle_deg = 90"},
      {scene(R"({"shape": "power_law", "B": 1, "d": 0.5})", kLayer, R"(, "model": "two_term")"), "d = 0.5"},
      {scene(R"({"shape": "table", "r": [0, 2, 1], "z": [0, 1, 2]})", kLayer, R"(, "model": "two_term")"), "r[2] = 1"},
      {scene(R"({"shape": "table", "r": [0, 1, "x"], "z": [0, 1, 2]})", kLayer, R"(, "model": "two_term")"), "indenter.r[2] must be a number"},
      {scene(R"({"shape": "table", "r": 5, "z": [0, 1, 2]})", kLayer, R"(, "model": "two_term")"), "indenter.r must be an array"},
      {scene(kPara, R"({"type": "layer", "E": 3e6, "nu": 0.5, "h": 1e-4})", R"(, "model": "two_term")"), "nu = 0.5"},
      {scene(kPara, R"({"type": "layer", "E": 3e6, "nu": 0.3, "h": 0})", R"(, "model": "two_term")"), "h = 0"},
      {scene(kPara, R"({"type": "layer", "E": -3e6, "nu": 0.3, "h": 1e-4})", R"(, "model": "two_term")"), "E = -3000000"},
      {scene(kPara, R"({"type": "layer", "E": 3e6, "nu": 0.3, "h": 1e-4, "base": "glued"})", R"(, "model": "two_term")"), "medium.base = \"glued\""},
      {scene(kPara, kLayer), "model is missing; medium 'layer' needs one of: leading, two_term"},
      {scene(kPara, kLayer, R"(, "model": "full")"), "model = \"full\" is not available for medium 'layer' (available: leading, two_term, edge_corrected, exact, incompressible, uniform, auto)"},
      {scene(kPara, R"({"type": "layer", "E": 3e6, "nu": 0.6, "h": 1e-4})", R"(, "model": "exact")"), "nu = 0.6"},
      {scene(kPara, R"({"type": "pasternak", "K": 1e10, "G": -5})", R"(, "model": "full")"), "G (or tension T) = -5"},
      {scene(kPara, R"({"type": "pasternak", "K": 1e10})", R"(, "model": "full")"), "medium.G is missing"},
      {scene(kPara, R"({"type": "winkler", "K": 0})"), "K = 0"},
      {scene(kPara, R"({"type": "elastic", "K": 1})"), "medium.type = \"elastic\" is unknown"},
      {scene(kPara, R"({"type": "half_space", "E": 1e6, "nu": 0.7})"), "nu = 0.7"},
      {scene(kPara, R"({"type": "half_space", "E": 1e6, "nu": 0.3})", R"(, "solver": "ode")"), "foundation models only"},
      {scene(kPara, kLayer, R"(, "model": "two_term", "solver": "fast")"), "solver = \"fast\""},
      {scene(kPara, kLayer, R"(, "model": "two_term", "w": -0.1)"), "w = -0.1"},
      {scene(kPara, kLayer, R"(, "model": "two_term", "w": "0.1")"), "w must be a number"},
      {scene(kPara, kLayer, R"(, "model": "two_term", "w": 1e999)"), "not valid JSON"},
      {scene(kPara, R"({"type": "layers", "layers": []})", R"(, "model": "exact")"), "medium.layers must be a non-empty array"},
      {scene(kPara, R"({"type": "layers"})", R"(, "model": "exact")"), "medium.layers is missing"},
      {scene(kPara, R"({"type": "layers", "layers": [{"E": 1e6, "nu": 0.3, "h": 1e-4}, {"E": 1e6, "nu": 0.3, "h": 0}]})", R"(, "model": "exact")"), "medium.layers[1].h = 0"},
      {scene(kPara, R"({"type": "layers", "layers": [{"E": 1e6, "nu": 0.51, "h": 1e-4}]})", R"(, "model": "exact")"), "medium.layers[0].nu = 0.51"},
      {scene(kPara, R"({"type": "layers", "layers": [{"E": -1, "nu": 0.3, "h": 1e-4}]})", R"(, "model": "exact")"), "medium.layers[0].E = -1"},
      {scene(kPara, R"({"type": "layers", "layers": [{"E": 1e6, "nu": 0.3, "h": 1e-4, "G": 1}]})", R"(, "model": "exact")"), "medium.layers[0].G is not a known key"},
      {scene(kPara, R"({"type": "layers", "layers": [{"E": 1e6, "nu": 0.3}]})", R"(, "model": "exact")"), "medium.layers[0].h is missing"},
      {scene(kPara, R"({"type": "layers", "layers": [{"E": 1e6, "nu": 0.3, "h": 1e-4}], "base": {"E": 1e6, "nu": 0.7}})", R"(, "model": "exact")"), "medium.base.nu = 0.7"},
      {scene(kPara, R"({"type": "layers", "layers": [{"E": 1e6, "nu": 0.3, "h": 1e-4}], "base": {"E": 1e6}})", R"(, "model": "exact")"), "medium.base.nu is missing"},
      {scene(kPara, R"({"type": "layers", "layers": [{"E": 1e6, "nu": 0.3, "h": 1e-4}], "base": "glued"})", R"(, "model": "exact")"), "medium.base = \"glued\""},
      {scene(kPara, R"({"type": "layers", "layers": [{"E": 1e6, "nu": 0.3, "h": 1e-4}], "base": 3})", R"(, "model": "exact")"), "medium.base must be"},
      {scene(kPara, R"({"type": "layers", "layers": [{"E": 1e6, "nu": 0.3, "h": 1e-4}]})", R"(, "model": "uniform")"), "available: exact, leading, two_term, incompressible, auto"},
      {scene(kPara, R"({"type": "layers", "layers": [{"E": 1e6, "nu": 0.3, "h": 1e-4}], "base": {"E": 1e6, "nu": 0.3}})", R"(, "model": "leading")"), "no thin-layer law"},
      {scene(kPara, R"({"type": "layers", "layers": [{"E": 1e6, "nu": 0.3, "h": 1e-4}], "base": "frictionless"})", R"(, "model": "two_term")"), "bonded for model 'two_term'"},
      {scene(kPara, R"({"type": "layers", "layers": [{"E": 1e6, "nu": 0.5, "h": 1e-4}, {"E": 1e7, "nu": 0.5, "h": 1e-4}]})", R"(, "model": "leading")"), "every layer is incompressible"},
      {scene(kPara, R"({"type": "layers", "layers": [{"E": 1e6, "nu": 0.5, "h": 1e-4}, {"E": 1e7, "nu": 0.4, "h": 1e-4}]})", R"(, "model": "incompressible")"), "layers[1].nu = 0.4"},
      {scene(kPara, R"({"type": "layers", "layers": [{"E": 1e6, "nu": 0.3, "h": 1e-4}]})"), "model is missing; medium 'layers' needs one of: exact, leading, two_term, incompressible, auto"},
  };
  for (const auto& c : cases) {
    INFO(c.text);
    CHECK_THROWS_AS(parse_scene(c.text), InputError);
    CHECK_THROWS_WITH(parse_scene(c.text), Catch::Contains(c.expected));
  }
  CHECK_THROWS_WITH(load_scene("/nonexistent/scene.json"), Catch::Contains("cannot open"));
}

TEST_CASE("a stack of layers builds the exact solver of the stack", "[scene][stack]") {
  const std::string stack = R"({"type": "layers", "layers": [{"E": 3e6, "nu": 0.3, "h": 1e-4},
      {"E": 3e8, "nu": 0.3, "h": 1.9e-3}], "base": "bonded"})";
  const Scene s = parse_scene(scene(R"({"shape": "sphere", "R": 0.01})", stack, R"(, "model": "exact")"));
  CHECK(s.medium.type == MediumType::layers);
  REQUIRE(s.medium.stack.layers.size() == 2);
  CHECK(s.medium.stack.layers[1].E == 3e8);
  CHECK_FALSE(s.medium.stack.substrate);
  const ResolvedModel r = resolve_model(s);
  CHECK(r.spec.kind == ModelKind::exact);
  REQUIRE(r.spec.stack);
  CHECK(r.spec.layer.h == 1e-4);  // the top layer
  CHECK(*r.E_star == Approx(3e6 / 0.91).epsilon(1e-15));
  CHECK_FALSE(r.reference);
  // the paper's Appendix A at a* = 0.4 mm (tests/models/test_exact_stack.cpp has the FEM check)
  CHECK(build_scene(s).model->state(0.4e-3).S == Approx(20278.274363).epsilon(1e-9));
  const Scene h = parse_scene(scene(kPara, R"({"type": "layers", "layers": [{"E": 1e6, "nu": 0.5, "h": 1e-4}],
      "base": {"E": 1e6, "nu": 0.5}})", R"(, "model": "exact")"));
  REQUIRE(h.medium.stack.substrate);
  CHECK(h.medium.stack.substrate->nu == 0.5);
  // a layer on a half-space of its own material is Hertz
  const double a = 1e-4, Es = 1e6 / 0.75;
  CHECK(build_scene(h).model->state(a).P_H == Approx(4.0 * Es * a * a * a / (3.0 * 0.01)).epsilon(1e-9));
  // the thin-stack laws: springs in series (and the k^2 term), judged against the exact stack
  const Scene t = parse_scene(scene(R"({"shape": "sphere", "R": 0.01})", stack, R"(, "model": "two_term")"));
  const ResolvedModel rt = resolve_model(t);
  const ThinStackConstants c = thin_stack_constants(t.medium.stack);
  CHECK(rt.spec.kind == ModelKind::two_term);
  CHECK(*rt.K == c.K);
  CHECK(*rt.G == c.G);
  CHECK(c.K == Approx(1.0 / (1e-4 * 1.3 * 0.4 / (3e6 * 0.7) + 1.9e-3 * 1.3 * 0.4 / (3e8 * 0.7))).epsilon(1e-14));
  REQUIRE(rt.reference);
  CHECK(rt.reference->stack);
  const BuiltScene bt = build_scene(t);
  REQUIRE(bt.reference);
  CHECK(bt.reference->state(0.4e-3).S == Approx(20278.274363).epsilon(1e-9));
  CHECK(bt.model->state(0.4e-3).S == Approx(M_PI * c.K * 0.16e-6).epsilon(1e-12));  // 17058 N/m: -16 %
}

TEST_CASE("model auto on a stack: the thin-stack law where it is within tolerance, else exact", "[scene][stack]") {
  // 3 um of coating on a 10 mm sphere: a >> H, Winkler's springs in series are within 2 %
  const std::string thin = R"({"type": "layers", "layers": [{"E": 3e6, "nu": 0.3, "h": 1e-6},
      {"E": 1e7, "nu": 0.3, "h": 2e-6}], "base": "bonded"})";
  const Scene s = parse_scene(scene(kPara, thin, R"(, "model": "auto", "tolerance": 0.02, "w": 0.05)"));
  const BuiltScene b = build_scene_for_summary(s);
  REQUIRE(b.choice);
  CHECK(b.choice->model == ModelKind::winkler);
  CHECK(b.choice->estimated_error < 0.02);
  // the choice's estimate against the exact stack's own pull-off
  ModelSpec exact = *resolve_model(s).reference;
  const double P_exact = summarize(JkrSolution(make_contact_model(s.profile, exact), 0.05)).pull_off->P;
  const double P_chosen = summarize(JkrSolution(b.model, 0.05)).pull_off->P;
  CHECK(std::abs(P_chosen / P_exact - 1.0) < 0.02);
  CHECK(std::abs(P_chosen / P_exact - 1.0) == Approx(b.choice->estimated_error).epsilon(0.05));
  // the paper's bi-layer at a/H ~ 0.1: no thin law is within 5 %
  const std::string paper = R"({"type": "layers", "layers": [{"E": 3e6, "nu": 0.3, "h": 1e-4},
      {"E": 3e8, "nu": 0.3, "h": 1.9e-3}]})";
  const BuiltScene p = build_scene_for_summary(parse_scene(scene(kPara, paper, R"(, "model": "auto", "tolerance": 0.05, "w": 0.05)")));
  CHECK(p.choice->model == ModelKind::exact);
  // an incompressible stack (a cell on a gel): the squeeze film
  const std::string cell = R"({"type": "layers", "layers": [{"E": 1e3, "nu": 0.5, "h": 1e-6}, {"E": 1e4, "nu": 0.5, "h": 2e-6}]})";
  const BuiltScene c = build_scene_for_summary(parse_scene(scene(kPara, cell, R"(, "model": "auto", "tolerance": 0.1, "w": 1e-4)")));
  CHECK(c.choice->model == ModelKind::incompressible);
  CHECK(c.choice->estimated_error < 0.1);  // 6 % at a/H ~ 15
  // on a half-space there is no candidate
  const std::string hs = R"({"type": "layers", "layers": [{"E": 3e6, "nu": 0.3, "h": 1e-6}], "base": {"E": 1e7, "nu": 0.3}})";
  CHECK(build_scene_for_summary(parse_scene(scene(kPara, hs, R"(, "model": "auto", "tolerance": 0.5, "w": 0.05)"))).choice->model ==
        ModelKind::exact);
}

TEST_CASE("deep nesting is refused while parsing, naming the limit", "[scene][errors][limits]") {
  // 100 000 '[' crashed the reader (a recursive dump for the error snippet overflowed the stack).
  const std::string deep = std::string(100000, '[') + std::string(100000, ']');
  CHECK_THROWS_WITH(parse_scene(deep, "deep.json"),
                    Catch::Contains("deep.json") && Catch::Contains("deeper than 32 levels"));
  std::string objects;
  for (int i = 0; i < 40; ++i) objects += R"({"indenter": )";
  objects += "1" + std::string(40, '}');
  CHECK_THROWS_WITH(parse_scene(objects), Catch::Contains("deeper than 32 levels"));
  // Just inside the limit: an ordinary error, its snippet bounded.
  const std::string nested = std::string(31, '[') + std::string(31, ']');
  CHECK_THROWS_WITH(parse_scene(nested), Catch::Contains("must be a JSON object, got [[[["));
  std::string wide = "[";
  for (int i = 0; i < 100000; ++i) wide += "12345,";
  wide += "1]";
  const std::string message = [&] {
    try {
      parse_scene(wide);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string();
  }();
  CHECK(message.size() < 200);
  CHECK_THAT(message, Catch::Contains("..."));
}

TEST_CASE("a key given twice is an error naming the key, not the last one winning", "[scene][errors]") {
  // "model": "two_term", "model": "exact" used to run the exact model.
  CHECK_THROWS_WITH(parse_scene(scene(kPara, kLayer, R"(, "model": "two_term", "model": "exact")")),
                    Catch::Contains("model is given twice"));
  CHECK_THROWS_WITH(
      parse_scene(scene(R"({"shape": "paraboloid", "R": 0.01, "R": 0.02})", kLayer, R"(, "model": "two_term")")),
      Catch::Contains("indenter.R is given twice"));
  // The same key in different objects is fine.
  CHECK_NOTHROW(parse_scene(R"({"indenter": {"shape": "paraboloid", "R": 0.01}, "medium": {"type": "winkler", "K": 1e9}})"));
}

TEST_CASE("a scene with a UTF-8 byte-order mark is read, as CSV files are", "[scene]") {
  CHECK(parse_scene("\xEF\xBB\xBF" + scene(kPara, kLayer, R"(, "model": "two_term")")).model == SceneModel::two_term);
}

TEST_CASE("scene files: devices and oversized files are refused, naming the path", "[scene][errors][limits]") {
  CHECK_THROWS_WITH(load_scene("/dev/urandom"), Catch::Contains("/dev/urandom") && Catch::Contains("not a regular file"));
}

TEST_CASE("a bundled scene file loads and solves", "[scene]") {
  const Scene s = load_scene(std::string(LAYERJKR_SOURCE_DIR) + "/data/scenes/sphere_pdms_film_two_term.json");
  const JkrSolution jkr(build_scene(s).model, s.w);
  REQUIRE(jkr.pull_off());
  CHECK(jkr.pull_off()->P == Approx(-2 * M_PI * 0.05 * 0.01).epsilon(1e-10));
}
