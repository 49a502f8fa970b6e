// FEM-like synthetic data for the two-model approach (discrete.hpp): the validation's truth.
#include <algorithm>
#include <cmath>
#include <random>

#include <boost/math/tools/roots.hpp>

#include "layerjkr/discrete.hpp"
#include "layerjkr/error.hpp"

namespace layerjkr {

void SyntheticSampling::validate() const {
  if (load_steps < 2 || load_steps > 100000) throw DomainError("SyntheticSampling", "load_steps", load_steps, "2 .. 100000");
  if (!(delta_max > 0.0) || !std::isfinite(delta_max))
    throw DomainError("SyntheticSampling", "delta_max", delta_max, "finite and > 0 [m]");
  if (!(noise >= 0.0 && noise <= 0.5)) throw DomainError("SyntheticSampling", "noise", noise, "0 .. 0.5 (relative)");
  if (!(radius_resolution >= 0.0) || !std::isfinite(radius_resolution))
    throw DomainError("SyntheticSampling", "radius_resolution", radius_resolution, "finite and >= 0 [m]");
}

namespace {

class ForceNoise {
 public:
  ForceNoise(double level, unsigned seed) : level_(level), rng_(seed) {}
  double operator()(double P) { return P * (1.0 + level_ * gauss_(rng_)); }

 private:
  double level_;
  std::mt19937 rng_;
  std::normal_distribution<double> gauss_{0.0, 1.0};
};

// The contact radius where the model's non-adhesive approach is delta (delta_H grows with a).
double radius_at_approach(const ContactModel& model, double delta) {
  auto excess = [&](double a) { return model.state(a).delta_H - delta; };
  double lo = model.typical_radius(), hi = lo;
  while (excess(lo) > 0.0 && lo > model.min_radius() * 2.0) lo *= 0.5;
  while (excess(hi) < 0.0) {
    if (hi >= model.max_radius())
      throw DomainError("sample_convex", "delta_max", delta, "approaches the model reaches below its largest radius " +
                                                                  format_double(model.max_radius()) + " m");
    hi = std::min(2.0 * hi, model.max_radius());
  }
  std::uintmax_t iters = 200;
  const auto r = boost::math::tools::toms748_solve(excess, lo, hi, boost::math::tools::eps_tolerance<double>(50), iters);
  return 0.5 * (r.first + r.second);
}

}  // namespace

FlatPunchData sample_flat_punch(const ContactModel& model, const std::vector<double>& radii, const SyntheticSampling& sampling) {
  sampling.validate();
  FlatPunchData d;
  d.source = "flat punch sampled from " + model.name();
  ForceNoise noisy(sampling.noise, sampling.seed);
  for (double a : radii) {
    const double S = model.state(a).S;
    for (int i = 1; i <= sampling.load_steps; ++i) {
      const double delta = sampling.delta_max * i / sampling.load_steps;
      d.a.push_back(a);
      d.delta.push_back(delta);
      d.P.push_back(noisy(S * delta));
    }
  }
  return d;
}

ConvexData sample_convex(const ContactModel& model, const SyntheticSampling& sampling) {
  sampling.validate();
  ConvexData c;
  c.source = "convex indenter sampled from " + model.name();
  ForceNoise noisy(sampling.noise, sampling.seed);
  for (int i = 1; i <= sampling.load_steps; ++i) {
    const double delta = sampling.delta_max * i / sampling.load_steps;
    const NonAdhesiveState s = model.state(radius_at_approach(model, delta));
    c.delta.push_back(delta);
    c.P.push_back(noisy(s.P_H));
    const double node = sampling.radius_resolution;
    c.a.push_back(node > 0.0 ? node * std::max(1.0, std::round(s.a / node)) : s.a);
  }
  return c;
}

}  // namespace layerjkr
