// Synthetic curves: the fit's forward model, evaluated with the contact module's lookups.
#include "layerjkr/simulate.hpp"

#include <cmath>
#include <random>

#include "layerjkr/adhesion.hpp"
#include "layerjkr/built_scene.hpp"
#include "layerjkr/contact.hpp"
#include "layerjkr/error.hpp"

namespace layerjkr {

void SimulationOptions::validate() const {
  const char* fn = "SimulationOptions";
  if (points_per_branch < 2)
    throw DomainError(fn, "points_per_branch", static_cast<double>(points_per_branch), ">= 2");
  detail::require_positive(fn, "max_indentation", max_indentation);
  detail::require_non_negative(fn, "free_fraction", free_fraction);
  detail::require_finite(fn, "delta0", delta0);
  detail::require_finite(fn, "P0", P0);
  detail::require_non_negative(fn, "noise", noise);
}

CurveData simulate_curve(const Scene& scene, const SimulationOptions& o) {
  o.validate();
  // Where contact starts without adhesion sets the radius scale for "auto".
  const double a_scale = std::sqrt(o.max_indentation * scene.profile->length_scale());
  const BuiltScene built = build_scene(scene, 0.1 * a_scale);
  // The scene's adhesion model (JKR unless its "adhesion" key says otherwise), as the fit's.
  const AdhesiveSolution sol(make_adhesive_law(built.model, built.resolved.spec, scene.w, scene.adhesion));
  const double a_floor = 1e-9 * a_scale;
  const double a_zero = scene.w > 0.0 ? sol.zero_load_radius().value_or(a_floor) : a_floor;
  const double d_contact = sol.at(a_zero).delta;
  double d_release = d_contact;
  if (scene.w > 0.0)
    if (const auto po = sol.pull_off()) d_release = po->delta;
  const double d_max = d_contact + o.max_indentation;

  CurveData c;
  c.source = "simulated(" + built.model->name() + ")";
  std::mt19937_64 rng(o.seed);
  std::normal_distribution<double> gauss(0.0, 1.0);
  auto add = [&](double delta, double start, int segment) {
    const bool contact = delta >= start;
    const double P = contact ? sol.force_at_delta(delta) : 0.0;
    c.delta.push_back(delta + o.delta0);
    c.P.push_back(P + o.P0 + (o.noise > 0.0 ? o.noise * gauss(rng) : 0.0));
    c.segment.push_back(segment);
    if (o.with_radius) c.a.push_back(contact ? sol.contact_radius_at_delta(delta) : 0.0);
  };
  const std::size_t n = o.points_per_branch;
  if (o.branch != Branch::retract) {
    const double lo = d_contact - o.free_fraction * o.max_indentation;
    for (std::size_t i = 0; i < n; ++i) add(lo + (d_max - lo) * i / (n - 1.0), d_contact, 0);
  }
  if (o.branch != Branch::approach) {
    const double lo = d_release - o.free_fraction * (d_max - d_release);
    for (std::size_t i = 0; i < n; ++i) add(d_max - (d_max - lo) * i / (n - 1.0), d_release, 1);
  }
  return c;
}

}  // namespace layerjkr
