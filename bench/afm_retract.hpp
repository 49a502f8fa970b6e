// The AFM retract the Maugis-Dugdale benchmarks and study fit (bench/dugdale_fit_cost,
// bench/dugdale_map, tools/adhesion_fit_study): the scene's adhesive law at 60 radii from its
// load-controlled pull-off to 15 nm beyond, then 30 samples off contact, with Gaussian noise of
// standard deviation `noise` [N] on every force (the benchmarks: 0.5 % of a 5.3 nN pull-off).
#pragma once

#include <optional>
#include <random>

#include "layerjkr/layerjkr.hpp"

namespace layerjkr::bench {

constexpr double kAfmRetractNoise = 0.005 * 5.3e-9;  ///< [N]

inline CurveData afm_retract(const Scene& truth, std::mt19937_64& rng, double noise = kAfmRetractNoise) {
  const BuiltScene built = build_scene(truth, 0.0, false);
  const AdhesiveLawPtr law = make_adhesive_law(built.model, resolve_model(truth).spec, truth.w, truth.adhesion);
  const std::optional<CriticalPoint> po = AdhesiveSolution(law).pull_off();
  const double a0 = po ? po->a : 0.0;
  std::normal_distribution<double> g(0.0, 1.0);
  CurveData c;
  for (int i = 0; i < 60; ++i) {
    const AdhesiveState s = law->at(a0 + 15e-9 * (59 - i) / 59.0);
    c.delta.push_back(s.delta);
    c.P.push_back(s.P + noise * g(rng));
    c.segment.push_back(1);
  }
  const double d_release = c.delta.back(), span = c.delta.front() - d_release;
  for (int i = 1; i <= 30; ++i) {
    c.delta.push_back(d_release - span * i / 60.0);
    c.P.push_back(noise * g(rng));
    c.segment.push_back(1);
  }
  return c;
}

}  // namespace layerjkr::bench
