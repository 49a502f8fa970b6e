// Every stack solvable (issue 35): a seeded random matrix of 2-5 layer stacks - neighbours'
// thickness ratios 1e-3..1e3 and modulus ratios 1e-4..1e4 in any order, nu in [0, 0.5], on
// bonded, frictionless and elastic half-space bases - and the issues' hand-picked stacks, against
// the independent solution of tools/stack_random_reference.py (Papkovich-Neuber symbol in
// mpmath, direct u-quadrature of the kernel, one Gauss-Legendre Nystrom rule). Each state's
// stiffness S = 2 E1* a x (the flat-punch factor) must agree with the reference, and the
// state's own error estimate must bound the difference.
#include <catch2/catch.hpp>

#include <cmath>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "layerjkr/exact_layer.hpp"
#include "layerjkr/layered_medium.hpp"
#include "support/test_support.hpp"

using namespace layerjkr;

namespace {

struct Row {
  std::string name;
  LayeredMedium medium;
  double alpha = 0.0, factor = 0.0, error = 0.0;
};

std::vector<std::string> split(const std::string& s, char sep) {
  std::vector<std::string> out;
  std::stringstream in(s);
  std::string part;
  while (std::getline(in, part, sep)) out.push_back(part);
  return out;
}

// "E:nu:h|E:nu:h|..." and "bonded" | "frictionless" | "half_space:Es:nus" (units of the top layer).
LayeredMedium medium_of(const std::string& layers, const std::string& base) {
  LayeredMedium m;
  for (const std::string& l : split(layers, '|')) {
    const std::vector<std::string> v = split(l, ':');
    m.layers.push_back({std::stod(v.at(0)), std::stod(v.at(1)), std::stod(v.at(2))});
  }
  if (base == "frictionless") m.base = Base::frictionless;
  else if (base.rfind("half_space:", 0) == 0) {
    const std::vector<std::string> v = split(base, ':');
    m.substrate = Substrate{std::stod(v.at(1)), std::stod(v.at(2))};
  }
  return m;
}

std::vector<Row> read_rows() {
  std::ifstream in(std::string(LAYERJKR_SOURCE_DIR) + "/data/stack/random_matrix_reference.csv");
  std::vector<Row> rows;
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#' || line.rfind("case,", 0) == 0) continue;
    const std::vector<std::string> c = split(line, ',');
    Row r;
    r.name = c.at(0);
    r.medium = medium_of(c.at(1), c.at(2));
    r.alpha = std::stod(c.at(3));
    r.factor = std::stod(c.at(4));
    r.error = std::stod(c.at(5));
    rows.push_back(r);
  }
  return rows;
}

}  // namespace

TEST_CASE("stack matrix: every stack solves, S within the reference's tolerance and within its own estimate",
          "[exact][stack][matrix]") {
  const std::vector<Row> rows = read_rows();
  REQUIRE(rows.size() >= 80);
  int solved = 0;
  for (const Row& r : rows) {
    ExactLayerOptions o;
    o.max_a_over_h = 10.0;
    const ExactLayerKernel kernel(r.medium, o);
    const auto paraboloid = make_paraboloid(10.0);
    const ExactLayerState s = kernel.solve(*paraboloid, r.alpha);
    const double factor = s.state.S / (2.0 * kernel.effective_modulus() * r.alpha);
    const double error = std::abs(factor - r.factor) / r.factor;
    INFO(r.name << " a/h1 = " << r.alpha << ": " << factor << " against " << r.factor << " (reference error "
                << r.error << "), relative " << error << ", estimate " << s.S_error);
    CHECK(error < 1e-5 + r.error / r.factor);
    CHECK(error <= s.S_error + r.error / r.factor);
    CHECK(s.S_error < 1e-3);  // an estimate that says something
    ++solved;
  }
  CHECK(solved == static_cast<int>(rows.size()));
}
