// The CLI on a stack of layers (issue 24): the paper's Appendix A bi-layer, and bad stacks
// exit 2 with one line naming the layer and the key.
#include <catch2/catch.hpp>

#include <string>

#include "support/cli_support.hpp"

using namespace test::cli;

namespace {
std::string stack_scene(const std::string& layers, const std::string& base = R"("bonded")") {
  return R"({"indenter": {"shape": "sphere", "R": 0.01}, "medium": {"type": "layers", "layers": )" + layers +
         R"(, "base": )" + base + R"(}, "model": "exact", "w": 0.05})";
}
const std::string kBilayer = R"([{"E": 3e6, "nu": 0.3, "h": 1e-4}, {"E": 3e8, "nu": 0.3, "h": 1.9e-3}])";
}  // namespace

TEST_CASE("layerjkr curve solves the paper's bi-layer", "[cli][stack]") {
  const Run r = run("curve " + write_file("bilayer.json", stack_scene(kBilayer)) + " --at 4e-4");
  INFO(r.err);
  REQUIRE(r.code == 0);
  const auto rows = lines(r.out);
  REQUIRE(rows.size() == 2);
  // a,P,delta,P_H,delta_H,S,error_est: S = 20278.27 N/m (the FEM's 20276.4 + 0.009 %)
  CHECK(rows[1].find(",20278.27") != std::string::npos);
}

TEST_CASE("bad stacks exit 2 with one line naming the layer and the key", "[cli][stack][errors]") {
  struct Case {
    std::string layers, base, expected;
  };
  const Case cases[] = {
      {"[]", R"("bonded")", "medium.layers must be a non-empty array"},
      {R"([{"E": 3e6, "nu": 0.3, "h": 1e-4}, {"E": 3e8, "nu": 0.3, "h": -1}])", R"("bonded")", "medium.layers[1].h = -1"},
      {R"([{"E": 3e6, "nu": 0.7, "h": 1e-4}])", R"("bonded")", "medium.layers[0].nu"},
      {R"([{"E": 3e6, "nu": 0.3, "h": 1e-4, "mu": 1}])", R"("bonded")", "medium.layers[0].mu is not a known key"},
      {kBilayer, R"({"E": 0, "nu": 0.3})", "medium.base.E = 0"},
  };
  for (const Case& c : cases) {
    const Run r = run("summary " + write_file("bad_stack.json", stack_scene(c.layers, c.base)));
    INFO(c.expected << "\nstderr: " << r.err);
    CHECK(r.code == 2);
    CHECK(r.out.empty());
    CHECK(lines(r.err).size() == 1);
    CHECK(r.err.find(c.expected) != std::string::npos);
  }
}
