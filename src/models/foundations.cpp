// Closed-form foundation models: Winkler, two-term, full Pasternak; layer constants.
#include <cmath>

#include "layerjkr/error.hpp"
#include "layerjkr/model.hpp"
#include "layerjkr/model_spec.hpp"
#include "models/state_formulas.hpp"

namespace layerjkr {
namespace {

detail::ProfileAt<double> profile_at(const Profile& p, double a) {
  const ProfileDerivatives d = p.derivatives(a);
  return {d.f, d.df, d.d2f, p.moment(a)};
}

NonAdhesiveState hertz_state(double a, const detail::StateOf<double>& s) {
  return {a, s.P_H, s.delta_H, s.S, s.dS_da};
}

class TwoTerm final : public ContactModel {
 public:
  TwoTerm(ProfilePtr p, double K, double G)
      : ContactModel(std::move(p)), K_(K), G_(G), name_(to_string(G == 0.0 ? ModelKind::winkler : ModelKind::two_term)) {}
  NonAdhesiveState state(double a) const override {
    profile().require_contact_radius(name_, a);
    return hertz_state(a, detail::two_term_state(a, profile_at(profile(), a), K_, G_));
  }
  std::string name() const override { return name_; }

 private:
  double K_, G_;
  const char* name_;
};

class FullFoundation final : public ContactModel {
 public:
  FullFoundation(ProfilePtr p, double K, double G)
      : ContactModel(std::move(p)), K_(K), G_(G), lambda_(std::sqrt(K / G)) {}
  NonAdhesiveState state(double a) const override {
    profile().require_contact_radius(to_string(ModelKind::full_foundation), a);
    return hertz_state(a, detail::full_foundation_state(a, profile_at(profile(), a), K_, G_, lambda_));
  }
  std::string name() const override { return to_string(ModelKind::full_foundation); }

 private:
  double K_, G_, lambda_;
};

}  // namespace

ContactModel::ContactModel(ProfilePtr profile) : profile_(std::move(profile)) {
  if (!profile_) throw Error("layerjkr::ContactModel: the profile is null");
}

ContactModel::ContactModel(FromData) {}

const Profile& ContactModel::profile() const {
  if (!profile_) throw Error("layerjkr::ContactModel: a model built from data has no indenter profile");
  return *profile_;
}

double ContactModel::max_radius() const { return profile().max_radius(); }

double ContactModel::typical_radius() const { return profile().length_scale(); }

double ContactModel::numerical_error(double /*a*/) const { return 1e-12; }

std::vector<NonAdhesiveState> ContactModel::states(const std::vector<double>& radii) const {
  std::vector<NonAdhesiveState> out;
  out.reserve(radii.size());
  for (double a : radii) out.push_back(state(a));
  return out;
}

ContactModelPtr make_winkler(ProfilePtr profile, double K) {
  detail::require_positive("make_winkler", "K", K);
  return std::make_shared<TwoTerm>(std::move(profile), K, 0.0);
}

ContactModelPtr make_two_term(ProfilePtr profile, double K, double G) {
  detail::require_positive("make_two_term", "K", K);
  detail::require_finite("make_two_term", "G", G);
  return std::make_shared<TwoTerm>(std::move(profile), K, G);
}

ContactModelPtr make_full_foundation(ProfilePtr profile, double K, double G) {
  detail::require_positive("make_full_foundation", "K", K);
  if (!std::isfinite(G) || !(G > 0.0))
    throw DomainError("make_full_foundation", "G (or tension T)", G,
                      "finite and > 0; for G <= 0 use the asymptotic two-term model, which has "
                      "no exterior solution");
  return std::make_shared<FullFoundation>(std::move(profile), K, G);
}

double effective_modulus(double E, double nu) {
  detail::require_positive("effective_modulus", "E", E);
  if (!(nu > -1.0 && nu <= 0.5)) throw DomainError("effective_modulus", "nu", nu, "(-1, 0.5]");
  return E / ((1.0 - nu) * (1.0 + nu));
}

ThinLayerConstants thin_layer_constants(const ElasticLayer& layer) {
  const char* fn = "thin_layer_constants";
  detail::require_positive(fn, "E", layer.E);
  detail::require_positive(fn, "h", layer.h);
  const double nu = layer.nu;
  if (!(nu > -1.0 && nu < 0.5))
    throw DomainError(fn, "nu", nu,
                      "(-1, 0.5); the compressible thin-layer expansion is singular at 0.5");
  ThinLayerConstants c;
  const double E = layer.E, h = layer.h;
  if (layer.base == Base::frictionless) {
    c.K = E / (h * (1.0 - nu) * (1.0 + nu));
    c.G = 0.0;
    return c;
  }
  const double m = 1.0 - 2.0 * nu;
  c.K = E * (1.0 - nu) / (h * (1.0 + nu) * m);
  c.G = h * E * nu * (1.0 - 4.0 * nu) / (3.0 * (1.0 + nu) * m * m);
  if (nu > 0.45) {
    const double ratio = std::sqrt(nu * (4.0 * nu - 1.0) / (3.0 * m * (1.0 - nu)));
    c.warnings.push_back(
        "bonded layer with nu = " + format_double(nu) +
        " > 0.45: the compressible thin-layer expansion is non-uniform as nu -> 0.5; it needs "
        "a/h >> " + format_double(ratio) +
        " and an incompressible layer follows a different law (docs/theory.md section 2)");
  }
  return c;
}

}  // namespace layerjkr
