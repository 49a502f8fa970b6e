// JKR rigs on bonded films: the thin-layer corrections of Shull and co-workers (as they are
// commonly quoted from Shull, Mater. Sci. Eng. R 36 (2002) 1) against layerjkr's exact layer on
// the same scenes. Prints the two Markdown tables of docs/fitting.md ("JKR rigs"):
//   build/bin/rig_corrections_study
// 1. The non-adhesive state of a paraboloid on an incompressible layer bonded to a rigid base,
//    as the corrections write it - P_H = (4 E* a^3 / 3R) f_p, delta_H = (a^2/R) f_delta,
//    S = 2 E* a / f_C - with the exact layer's f_p, f_delta and f_C beside the quoted fits:
//    f_p = 1 + beta (a/h)^3 (beta = 0.15 and 0.33), f_delta = 0.4 + 0.6 exp(-1.8 a/h),
//    f_C = 1 / (1 + 1.33 a/h + 1.33 (a/h)^3).
// 2. What a corrected JKR analysis returns from exact (P, a) data: the JKR law of any medium
//    (the paper's transform) with S = 2 E* a / f_C gives
//      P = E* (4 a^3 / 3R) f_p - sqrt(E* w) sqrt(8 pi a^3 / (f_C - x f_C')),  x = a/h,
//    linear in E* and sqrt(E* w): fitted by least squares to the exact layer's JKR curve (no
//    noise) from a quarter of the largest radius to the largest, for several largest a/h.
//    "Hertz" is the same analysis without corrections (every f = 1).
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <Eigen/Dense>
#include <boost/math/constants/constants.hpp>

#include "layerjkr/layerjkr.hpp"

using namespace layerjkr;

namespace {

constexpr double kPi = boost::math::constants::pi<double>();
constexpr double kR = 5e-3, kE = 1e6, kNu = 0.5, kW = 0.05;
const double kEstar = kE / (1.0 - kNu * kNu);

Scene film(double h) {
  char json[256];
  std::snprintf(json, sizeof json,
                R"({"indenter": {"shape": "paraboloid", "R": %.17g}, "medium": {"type": "layer", "E": %.17g,
                    "nu": %.17g, "h": %.17g, "base": "bonded"}, "model": "exact", "w": %.17g})",
                kR, kE, kNu, h, kW);
  return parse_scene(json, "rig film");
}

struct Corrections {
  double beta;  // f_p = 1 + beta x^3
  bool thin;    // false: every f = 1 (Hertz and JKR on a half-space)
  double f_p(double x) const { return thin ? 1.0 + beta * x * x * x : 1.0; }
  double f_C(double x) const { return thin ? 1.0 / (1.0 + 1.33 * x + 1.33 * x * x * x) : 1.0; }
  // f_C - x f_C'(x), the factor the energy release rate carries.
  double g(double x) const {
    if (!thin) return 1.0;
    const double d = 1.0 + 1.33 * x + 1.33 * x * x * x;
    return 1.0 / d + x * (1.33 + 3.99 * x * x) / (d * d);
  }
};

double f_delta(double x) { return 0.4 + 0.6 * std::exp(-1.8 * x); }

void state_table() {
  const double h = 1e-4;
  std::vector<double> ratios = {0.1, 0.3, 0.5, 1.0, 2.0, 3.0, 5.0};
  std::vector<double> radii;
  for (double x : ratios) radii.push_back(x * h);
  const CurveAnswer c = solve_curve(film(h), radii);
  std::printf("| a/h | f_p exact | 1 + 0.15 (a/h)^3 | 1 + 0.33 (a/h)^3 | f_delta exact | 0.4 + 0.6 exp(-1.8 a/h) | "
              "f_C exact | 1/(1 + 1.33 a/h + 1.33 (a/h)^3) |\n|---|---|---|---|---|---|---|---|\n");
  for (std::size_t k = 0; k < ratios.size(); ++k) {
    const double x = ratios[k], a = radii[k];
    const NonAdhesiveState& s = c.states[k].hertz;
    const double fp = s.P_H / (4.0 * kEstar * a * a * a / (3.0 * kR));
    const double fd = s.delta_H / (a * a / kR);
    const double fc = 2.0 * kEstar * a / s.S;
    std::printf("| %.1f | %.4g | %.4g | %.4g | %.4g | %.4g | %.4g | %.4g |\n", x, fp, 1.0 + 0.15 * x * x * x,
                1.0 + 0.33 * x * x * x, fd, f_delta(x), fc, Corrections{0.0, true}.f_C(x));
  }
}

// E and w from a linear least-squares fit of P = E* A(a) - sqrt(E* w) B(a) to (a_i, P_i).
std::pair<double, double> corrected_jkr_fit(const std::vector<double>& a, const std::vector<double>& P, double h,
                                            const Corrections& c) {
  Eigen::MatrixXd M(a.size(), 2);
  Eigen::VectorXd y(a.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    const double x = a[i] / h;
    M(i, 0) = 4.0 * a[i] * a[i] * a[i] / (3.0 * kR) * c.f_p(x) * 1e-6;  // columns of similar size
    M(i, 1) = -std::sqrt(8.0 * kPi * a[i] * a[i] * a[i] / c.g(x)) * 1e-3;
    y(i) = P[i];
  }
  const Eigen::Vector2d sol = M.colPivHouseholderQr().solve(y);
  const double E_star = sol(0) * 1e-6, root = sol(1) * 1e-3;
  return {E_star * (1.0 - kNu * kNu), root * root / E_star};
}

void fit_table() {
  const double a_max = 4e-4;
  std::printf("\n| largest a/h | analysis | E error | w error |\n|---|---|---|---|\n");
  for (double x_max : {0.3, 1.0, 2.0, 3.0, 5.0}) {
    const double h = a_max / x_max;
    std::vector<double> radii;
    for (int k = 0; k <= 60; ++k) radii.push_back(a_max * (0.25 + 0.75 * k / 60.0));
    const CurveAnswer c = solve_curve(film(h), radii);
    std::vector<double> P;
    for (const AdhesiveState& s : c.states) P.push_back(s.P);
    const struct {
      const char* name;
      Corrections c;
    } analyses[] = {{"Hertz (no correction)", {0.0, false}},
                    {"corrected, beta = 0.15", {0.15, true}},
                    {"corrected, beta = 0.33", {0.33, true}}};
    for (const auto& an : analyses) {
      const auto [E, w] = corrected_jkr_fit(radii, P, h, an.c);
      std::printf("| %.1f | %s | %+.1f %% | %+.1f %% |\n", x_max, an.name, 100.0 * (E / kE - 1.0), 100.0 * (w / kW - 1.0));
    }
  }
}

}  // namespace

int main() {
  try {
    state_table();
    fit_table();
  } catch (const std::exception& e) {
    std::fprintf(stderr, "rig_corrections_study: %s\n", e.what());
    return 1;
  }
  return 0;
}
