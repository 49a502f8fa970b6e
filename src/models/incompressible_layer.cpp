// Thin incompressible bonded layer: the lubrication-type law w = -(h^3/(3 mu)) lap p
// (docs/theory.md s.2), solved for any profile in closed form.
#include <cmath>
#include <vector>

#include <boost/math/constants/constants.hpp>

#include "layerjkr/error.hpp"
#include "layerjkr/model.hpp"
#include "layerjkr/model_spec.hpp"
#include "profiles/profile_quadrature.hpp"

namespace layerjkr {
namespace {

constexpr double kPi = boost::math::constants::pi<double>();

// The profile's moment M(a) = int_0^a f r dr and I(a) = int_0^a f r (2 r^2 - a^2) dr:
// closed forms for B r^d, else tanh-sinh quadrature split at the profile's knots.
struct Moments {
  double M, I;
};

Moments profile_moments(const Profile& profile, double a) {
  if (const auto form = profile.power_law_form()) {
    const double d = form->d, ad2 = form->B * std::pow(a, d + 2.0);
    return {ad2 / (d + 2.0), ad2 * a * a * d / ((d + 4.0) * (d + 2.0))};
  }
  std::vector<double> cuts;
  for (double b : profile.breakpoints(a)) cuts.push_back(b / a);
  // t = r / a, as Profile::moment does: tanh-sinh's thresholds are absolute.
  const double I = a * a * a * a *
                   detail::integrate_split([&](double t) { return profile.f(a * t) * t * (2.0 * t * t - 1.0); },
                                           0.0, 1.0, cuts, "incompressible_layer");
  return {profile.moment(a), I};
}

class IncompressibleLayer final : public ContactModel {
 public:
  IncompressibleLayer(ProfilePtr p, double E, double h) : ContactModel(std::move(p)), c_(E / (h * h * h)) {}

  // With c = 3 mu / h^3 = E / h^3: lap p = -c (delta - f), p(a) = 0. Integrating twice,
  // p'(r) = -c (delta r/2 - M(r)/r). The non-adhesive edge has no pressure gradient,
  // p'(a) = 0, so delta_H = 2 M(a)/a^2; then P = pi c (delta a^4/8 - int_0^a r M dr)
  // gives P_H = (pi c / 4) I(a), S = pi c a^4 / 8 and S' = pi c a^3 / 2.
  NonAdhesiveState state(double a) const override {
    profile().require_contact_radius(to_string(ModelKind::incompressible), a);
    const Moments m = profile_moments(profile(), a);
    const double a2 = a * a;
    return {a, 0.25 * kPi * c_ * m.I, 2.0 * m.M / a2, kPi * c_ * a2 * a2 / 8.0, 0.5 * kPi * c_ * a2 * a};
  }
  std::string name() const override { return to_string(ModelKind::incompressible); }

 private:
  double c_;  // E / h^3 [N/m^5]
};

}  // namespace

ContactModelPtr make_incompressible_layer(ProfilePtr profile, const ElasticLayer& layer) {
  const char* fn = "make_incompressible_layer";
  detail::require_positive(fn, "E", layer.E);
  detail::require_positive(fn, "h", layer.h);
  if (layer.nu != 0.5)
    throw DomainError(fn, "nu", layer.nu, "0.5 exactly (the incompressible law; use \"exact\" for nu < 0.5)");
  if (layer.base != Base::bonded)
    throw DomainError(fn, "base (frictionless)", 0.0,
                      "bonded (a frictionless incompressible layer has no lubrication-type limit)");
  return std::make_shared<IncompressibleLayer>(std::move(profile), layer.E, layer.h);
}

}  // namespace layerjkr
