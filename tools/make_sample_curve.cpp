// What this teaches: how to make a synthetic force curve with known answers
// (simulate_curve) - the bundled sample that README's main job fits, and the way to
// test a fitting set-up before trusting it with measured data.
//
// How the data is made: data/scenes/hydrogel_film_two_term.json (a 10 um colloidal
// probe on a 200 nm bonded hydrogel film, E = 50 kPa, nu = 0.3, w = 0.001 J/m^2, the
// two-term model), one approach and one retract of 500 samples each to 100 nm past
// first contact, shifted by a contact point delta0 = 2.5 um and a force baseline
// P0 = 40 pN, plus Gaussian force noise of 200 pN (a soft AFM cantilever), seed 2026.
//
// Run: build/bin/make_sample_curve data/curves/hydrogel_film_two_term.csv
// (target regenerate_sample_curve); the test generated_sample_curve fails when the
// committed copy is stale.
#include <cstdio>
#include <fstream>
#include <iostream>

#include "layerjkr/layerjkr.hpp"

int main(int argc, char** argv) {
  if (argc != 2) {
    std::cerr << "usage: make_sample_curve OUT.csv\n";
    return 2;
  }
  try {
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
    const layerjkr::CurveData c = layerjkr::simulate_curve(scene, o);
    std::ofstream out(argv[1]);
    out << "# synthetic: data/scenes/hydrogel_film_two_term.json, delta0 = 2.5e-6 m, P0 = 4e-11 N,\n"
           "# noise 2e-10 N (seed 2026); made by examples/make_sample_curve.cpp\n"
           "delta,P,segment\n";
    for (std::size_t i = 0; i < c.size(); ++i)
      out << layerjkr::format_double(c.delta[i]) << "," << layerjkr::format_double(c.P[i]) << ","
          << c.segment[i] << "\n";
    if (!out) throw layerjkr::InputError(std::string(argv[1]) + ": cannot write");
    std::cout << "wrote " << c.size() << " samples to " << argv[1] << "\n";
  } catch (const layerjkr::Error& e) {
    std::cerr << "make_sample_curve: " << e.what() << "\n";
    return 2;
  }
  return 0;
}
