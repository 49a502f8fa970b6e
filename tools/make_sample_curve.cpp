// What this teaches: how to make a synthetic force curve with known answers
// (simulate_curve) - the bundled samples README fits, and the way to test a fitting set-up
// before trusting it with measured data.
//
// How the data are made:
//   film: data/scenes/hydrogel_film_two_term.json (a 10 um colloidal probe on a 200 nm bonded
//     hydrogel film, E = 50 kPa, nu = 0.3, w = 0.001 J/m^2, the two-term model), one approach and
//     one retract of 500 samples each to 100 nm past first contact, shifted by a contact point
//     delta0 = 2.5 um and a force baseline P0 = 40 pN, plus Gaussian force noise of 200 pN (a soft
//     AFM cantilever), seed 2026. README's main job fits it.
//   cell_dwell: a 5 um sphere on a cell-like half-space (nu = 0.49) relaxing as a fractional
//     standard linear solid, E = 2 kPa, beta = 0.4, tau = 0.5 s, E_inf = 500 Pa: approach at
//     2 um/s to 1 um past first contact, a 3 s dwell at constant height, the retract at 2 um/s;
//     200 samples a branch, delta0 = 1 um, P0 = 10 pN, 2 pN noise (seed 2026). README's
//     viscoelastic example fits it from data/scenes/cell_fractional_sls.json (every law value 2x off).
//
// Run: build/bin/make_sample_curve film data/curves/hydrogel_film_two_term.csv, or cell_dwell
// data/curves/cell_dwell_fractional_sls.csv (targets regenerate_sample_curve*); the tests
// generated_sample_curve* fail when a committed copy is stale.
#include <fstream>
#include <iostream>
#include <string>

#include "layerjkr/layerjkr.hpp"

namespace {

const char* kCell = R"({"indenter": {"shape": "paraboloid", "R": 5e-6}, "medium": {"type": "half_space", "E": 2000,
    "nu": 0.49, "viscoelastic": {"law": "fractional_sls", "beta": 0.4, "tau": 0.5, "E_inf": 500}}})";

layerjkr::CurveData film(std::string* header) {
  const layerjkr::Scene scene = layerjkr::load_scene(LAYERJKR_SOURCE_DIR "/data/scenes/hydrogel_film_two_term.json");
  layerjkr::SimulationOptions o;
  o.branch = layerjkr::Branch::all;
  o.points_per_branch = 500;
  o.max_indentation = 1e-7;
  o.free_fraction = 0.5;
  o.delta0 = 2.5e-6;
  o.P0 = 40e-12;
  o.noise = 200e-12;
  o.seed = 2026;
  *header = "# synthetic: data/scenes/hydrogel_film_two_term.json, delta0 = 2.5e-6 m, P0 = 4e-11 N,\n"
            "# noise 2e-10 N (seed 2026); made by tools/make_sample_curve.cpp\n";
  return layerjkr::simulate_curve(scene, o);
}

layerjkr::CurveData cell_dwell(std::string* header) {
  layerjkr::SimulationOptions o;
  o.max_indentation = 1e-6;
  o.speed = 2e-6;
  o.dwell = 3.0;
  o.points_per_branch = 200;
  o.delta0 = 1e-6;
  o.P0 = 1e-11;
  o.noise = 2e-12;
  o.seed = 2026;
  *header = "# synthetic: a 5 um sphere on a half-space (nu = 0.49), fractional SLS E = 2000 Pa, beta = 0.4,\n"
            "# tau = 0.5 s, E_inf = 500 Pa; 2 um/s, 1 um, 3 s dwell; delta0 = 1e-6 m, P0 = 1e-11 N,\n"
            "# noise 2e-12 N (seed 2026); made by tools/make_sample_curve.cpp\n";
  return layerjkr::simulate_curve(layerjkr::parse_scene(kCell), o);
}

}  // namespace

int main(int argc, char** argv) {
  const std::string which = argc == 3 ? argv[1] : "";
  if (which != "film" && which != "cell_dwell") {
    std::cerr << "usage: make_sample_curve film|cell_dwell OUT.csv\n";
    return 2;
  }
  try {
    std::string header;
    const layerjkr::CurveData c = which == "film" ? film(&header) : cell_dwell(&header);
    const bool timed = !c.t.empty();
    std::ofstream out(argv[2]);
    out << header << (timed ? "t,delta,P,segment\n" : "delta,P,segment\n");
    for (std::size_t i = 0; i < c.size(); ++i) {
      if (timed) out << layerjkr::format_double(c.t[i]) << ",";
      out << layerjkr::format_double(c.delta[i]) << "," << layerjkr::format_double(c.P[i]) << "," << c.segment[i] << "\n";
    }
    if (!out) throw layerjkr::InputError(std::string(argv[2]) + ": cannot write");
    std::cout << "wrote " << c.size() << " samples to " << argv[2] << "\n";
  } catch (const layerjkr::Error& e) {
    std::cerr << "make_sample_curve: " << e.what() << "\n";
    return 2;
  }
  return 0;
}
