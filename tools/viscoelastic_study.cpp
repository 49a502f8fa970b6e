// The viscoelastic study of docs/fitting.md ("Fits in time"): a cell-like layer that relaxes,
// measured at three speeds, fitted both ways - an elastic model on each branch of each curve, and
// the law in time on each curve alone and on the three jointly - and, with --kinetics, an
// elastomer's rate-dependent adhesion fitted both ways (slow: a minute). Writes markdown.
//
//   viscoelastic_study OUT.md            (regenerate_viscoelastic_study; generated_viscoelastic_study)
//   viscoelastic_study --kinetics OUT.md (by hand; its table is quoted in docs/fitting.md)
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "layerjkr/layerjkr.hpp"

using namespace layerjkr;

namespace {

std::string num(double v, int digits = 4) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*g", digits, v);
  return buf;
}

// "v +- e" and the distance to the truth in standard errors.
std::string estimate(const FitSummary& s, FitParameter q, double truth) {
  const ParameterEstimate& e = s[q];
  if (!std::isfinite(e.standard_error)) return num(e.value) + " (no error bar)";
  return num(e.value) + " +- " + num(e.standard_error, 2) + " (" + num((e.value - truth) / e.standard_error, 2) + " SE)";
}

const char* kLayer = R"({"indenter": {"shape": "paraboloid", "R": 5e-6}, "medium": {"type": "layer", "E": %s, "nu": 0.49,
    "h": 3e-6, "base": "bonded", "viscoelastic": %s}, "model": "exact"})";

Scene layer(const std::string& E, const std::string& law) {
  char buf[512];
  std::snprintf(buf, sizeof buf, kLayer, E.c_str(), law.c_str());
  return parse_scene(buf);
}

CurveData curve(const Scene& truth, double speed, std::uint64_t seed) {
  SimulationOptions o;
  o.max_indentation = 2e-6;
  o.speed = speed;
  o.points_per_branch = 300;
  o.noise = 5e-11;
  o.seed = seed;
  o.delta0 = 1e-6;
  return simulate_curve(truth, o);
}

const double kSpeeds[] = {0.5e-6, 2e-6, 8e-6};

// One law: elastic fits of each branch, the law alone per curve, and jointly, for three seeds.
void study(std::ostream& out, const std::string& title, const Scene& truth, const Scene& guess,
           const std::vector<FitParameter>& law, const std::vector<double>& values) {
  Scene elastic = truth;
  elastic.medium.relaxation = RelaxationLaw{};
  out << "### " << title << "\n\n";
  out << "| seed | speed [um/s] | elastic E, approach [Pa] | elastic E, retract [Pa] |";
  for (FitParameter q : law) out << " " << to_string(q) << ", this curve alone |";
  out << "\n|---|---|---|---|";
  for (std::size_t k = 0; k < law.size(); ++k) out << "---|";
  out << "\n";
  FitOptions e;
  e.free = {FitParameter::E, FitParameter::delta0};
  FitOptions f;
  f.free = law;
  f.free.push_back(FitParameter::delta0);
  f.branch = Branch::all;
  std::vector<std::string> joint_rows;
  for (std::uint64_t seed = 1; seed <= 3; ++seed) {
    std::vector<CurveData> curves;
    for (double v : kSpeeds) curves.push_back(curve(truth, v, 10 * seed + curves.size()));
    for (std::size_t k = 0; k < curves.size(); ++k) {
      e.branch = Branch::approach;
      const FitSummary a = fit(curves[k], elastic, e);
      e.branch = Branch::retract;
      const FitSummary r = fit(curves[k], elastic, e);
      const FitSummary alone = fit(curves[k], guess, f);
      out << "| " << seed << " | " << num(kSpeeds[k] * 1e6) << " | " << num(a[FitParameter::E].value) << " | "
          << num(r[FitParameter::E].value) << " |";
      for (std::size_t q = 0; q < law.size(); ++q) out << " " << estimate(alone, law[q], values[q]) << " |";
      out << "\n";
    }
    const JointFitSummary j = fit_joint(curves, guess, f);
    std::string row = "| " + std::to_string(seed) + " |";
    for (std::size_t q = 0; q < law.size(); ++q) row += " " + estimate(j.fit, law[q], values[q]) + " |";
    row += " " + num(j.fit.rms_residual / 5e-11, 3) + " |";
    joint_rows.push_back(row);
  }
  out << "\nThe three speeds of each seed fitted jointly (each curve its own delta0):\n\n| seed |";
  for (FitParameter q : law) out << " " << to_string(q) << " |";
  out << " rms / noise |\n|---|";
  for (std::size_t k = 0; k < law.size(); ++k) out << "---|";
  out << "---|\n";
  for (const std::string& r : joint_rows) out << r << "\n";
  out << "\n";
}

void kinetics(std::ostream& out) {
  const char* kElastomer = R"({"indenter": {"shape": "paraboloid", "R": 1e-3}, "medium": {"type": "half_space",
      "E": 1e6, "nu": 0.5}, "w": %s, "adhesion": {"kinetics": {"law": "maugis_barquins", "v_star": %s, "n": %s}}})";
  const auto scene = [&](const char* w, const char* v, const char* n) {
    char buf[512];
    std::snprintf(buf, sizeof buf, kElastomer, w, v, n);
    return parse_scene(buf);
  };
  const Scene truth = scene("0.05", "1e-6", "0.6"), guess = scene("0.03", "1e-5", "0.5");
  Scene elastic = truth;
  elastic.adhesion.kinetics.reset();
  out << "### Rate-dependent adhesion: an elastomer sphere (R = 1 mm, E = 1 MPa, w0 = 0.05 J/m^2, v_star = 1 um/s, "
         "n = 0.6), 2 um deep, 2 uN noise\n\n| speed [um/s] | elastic JKR: w [J/m^2] | E [Pa] | kinetics alone: w0 | v_star [m/s] | n |\n"
         "|---|---|---|---|---|---|\n";
  std::vector<CurveData> curves;
  FitOptions e;
  e.free = {FitParameter::E, FitParameter::w, FitParameter::delta0};
  e.branch = Branch::all;
  e.retract_control = RetractControl::fixed_grips;
  FitOptions f = e;
  f.free = {FitParameter::E, FitParameter::w, FitParameter::v_star, FitParameter::n, FitParameter::delta0};
  for (double v : {0.3e-6, 1e-6, 3e-6}) {
    SimulationOptions o;
    o.max_indentation = 2e-6;
    o.speed = v;
    o.points_per_branch = 200;
    o.noise = 2e-6;
    o.seed = curves.size() + 1;
    o.delta0 = 1e-6;
    curves.push_back(simulate_curve(truth, o));
    const FitSummary el = fit(curves.back(), elastic, e), k = fit(curves.back(), guess, f);
    out << "| " << num(v * 1e6) << " | " << estimate(el, FitParameter::w, 0.05) << " | " << estimate(el, FitParameter::E, 1e6)
        << " | " << estimate(k, FitParameter::w, 0.05) << " | " << estimate(k, FitParameter::v_star, 1e-6) << " | "
        << estimate(k, FitParameter::n, 0.6) << " |\n";
  }
  const JointFitSummary j = fit_joint(curves, guess, f);
  out << "\nJointly: E " << estimate(j.fit, FitParameter::E, 1e6) << ", w0 " << estimate(j.fit, FitParameter::w, 0.05)
      << ", v_star " << estimate(j.fit, FitParameter::v_star, 1e-6) << ", n " << estimate(j.fit, FitParameter::n, 0.6)
      << " (" << num(j.fit.solve_seconds, 2) << " s).\n";
}

}  // namespace

int main(int argc, char** argv) {
  const bool with_kinetics = argc == 3 && std::string(argv[1]) == "--kinetics";
  if (argc != 2 && !with_kinetics) {
    std::cerr << "usage: viscoelastic_study [--kinetics] OUT.md\n";
    return 2;
  }
  try {
    std::ostringstream out;
    out << "# Fits in time: a relaxing cell-like layer fitted both ways\n\n"
           "Made by `tools/viscoelastic_study.cpp` (target regenerate_viscoelastic_study; the test "
           "generated_viscoelastic_study checks it). A 5 um sphere on a 3 um bonded layer (nu = 0.49), indented 2 um "
           "(a/h about 1) at 0.5, 2 and 8 um/s and withdrawn at the same speed, 300 samples a branch, 50 pN noise, "
           "delta0 = 1 um; each law fitted from a scene 2.5x off with delta0 free; elastic fits of E and delta0 on the "
           "same medium without its law, approach and retract apart. \"SE\": the estimate's distance to the truth in "
           "its own standard errors.\n\n";
    study(out, "Standard linear solid: E = 2 kPa, E_inf = 800 Pa, tau = 0.2 s",
          layer("2000", R"({"law": "sls", "E_inf": 800, "tau": 0.2})"),
          layer("5000", R"({"law": "sls", "E_inf": 320, "tau": 0.5})"),
          {FitParameter::E, FitParameter::E_inf, FitParameter::tau}, {2000.0, 800.0, 0.2});
    study(out, "Power law: E(1 s) = 1 kPa, beta = 0.2",
          layer("1000", R"({"law": "power_law", "beta": 0.2, "t0": 1})"),
          layer("2500", R"({"law": "power_law", "beta": 0.45, "t0": 1})"),
          {FitParameter::E, FitParameter::beta}, {1000.0, 0.2});
    if (with_kinetics) kinetics(out);
    std::ofstream f(with_kinetics ? argv[2] : argv[1]);
    f << out.str();
    if (!f) throw InputError(std::string("cannot write ") + (with_kinetics ? argv[2] : argv[1]));
  } catch (const std::exception& e) {
    std::cerr << "viscoelastic_study: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
