// The adhesive laws (adhesion.hpp): JKR on every model, the classical DMT on every model with a
// tip radius, and the dispatch that builds the law a scene's "adhesion" asks for.
#include "layerjkr/adhesion.hpp"

#include <cmath>
#include <limits>
#include <utility>

#include "adhesion/dmt_formula.hpp"
#include "layerjkr/error.hpp"

namespace layerjkr {
namespace {

class JkrLaw final : public AdhesiveLaw {
 public:
  JkrLaw(ContactModelPtr model, double w) : AdhesiveLaw(std::move(model), w) {}
  AdhesiveState at(double a) const override { return jkr_transform(contact()->state(a), w()); }
  std::vector<AdhesiveState> curve(const std::vector<double>& radii) const override {
    std::vector<AdhesiveState> out;
    out.reserve(radii.size());
    for (const NonAdhesiveState& h : contact()->states(radii)) out.push_back(jkr_transform(h, w()));
    return out;
  }
  AdhesionModel model() const override { return AdhesionModel::jkr; }
  std::string name() const override { return contact()->name(); }
};

// P = P_H - 2 pi w R: the Maugis-Dugdale limit lambda -> 0 for a tip of radius R on any medium
// (the adhesive zone grows to infinity while the contact's own deformation stays finite).
class ClassicalDmtLaw final : public AdhesiveLaw {
 public:
  ClassicalDmtLaw(ContactModelPtr model, double w, double R) : AdhesiveLaw(std::move(model), w), R_(R) {}
  AdhesiveState at(double a) const override {
    if (a == 0.0) return dmt_transform(NonAdhesiveState{}, w(), R_);
    return dmt_transform(contact()->state(a), w(), R_);
  }
  std::vector<AdhesiveState> curve(const std::vector<double>& radii) const override {
    std::vector<AdhesiveState> out;
    out.reserve(radii.size());
    for (const NonAdhesiveState& h : contact()->states(radii)) out.push_back(dmt_transform(h, w(), R_));
    return out;
  }
  AdhesionModel model() const override { return AdhesionModel::dmt; }
  bool has_zero_radius_state() const override { return true; }
  std::string name() const override { return "dmt on " + contact()->name(); }

 private:
  double R_;
};

// The tip's radius of curvature 1/f''(0), where the profile has one.
double tip_radius(const ContactModel& model, const char* what) {
  if (!model.has_profile())
    throw InputError(std::string(what) + " needs an indenter profile; this model was built from data");
  const Profile& p = model.profile();
  const double curvature = p.derivatives(0.0).d2f;
  if (!(curvature > 0.0) || !std::isfinite(curvature))
    throw InputError(std::string(what) + " needs a tip with a radius of curvature (f''(0) > 0); " + p.describe() +
                     " has f''(0) = " + format_double(curvature) +
                     ": give adhesion.sigma0 (or z0) for a Dugdale law on its gap");
  return 1.0 / curvature;
}

}  // namespace

void AdhesionSpec::validate() const {
  if (sigma0) detail::require_positive("AdhesionSpec", "sigma0", *sigma0);
  if (z0) detail::require_positive("AdhesionSpec", "z0", *z0);
  if (sigma0 && z0)
    throw DomainError("AdhesionSpec", "z0", *z0, "absent when sigma0 is given (sigma0 = " + format_double(*sigma0) + " Pa)");
}

double AdhesionSpec::dugdale_stress(double w) const {
  validate();
  detail::require_positive("AdhesionSpec::dugdale_stress", "w", w);
  if (sigma0) return *sigma0;
  return 16.0 * w / (9.0 * std::sqrt(3.0) * (z0 ? *z0 : kAssumedSpacing));
}

AdhesiveState dmt_transform(const NonAdhesiveState& hertz, double w, double R) {
  detail::require_non_negative("dmt_transform", "w", w);
  detail::require_positive("dmt_transform", "R", R);
  AdhesiveState s;
  s.a = hertz.a;
  s.c = w > 0.0 ? std::numeric_limits<double>::infinity() : hertz.a;
  s.P = detail::dmt_force(hertz.P_H, w, R);
  s.delta = hertz.delta_H;
  s.hertz = hertz;
  return s;
}

AdhesiveLaw::AdhesiveLaw(ContactModelPtr contact, double w) : contact_(std::move(contact)), w_(w) {
  if (!contact_) throw Error("layerjkr::AdhesiveLaw: the contact model is null");
  detail::require_non_negative("AdhesiveLaw", "w", w);
}

std::vector<AdhesiveState> AdhesiveLaw::curve(const std::vector<double>& radii) const {
  std::vector<AdhesiveState> out;
  out.reserve(radii.size());
  for (double a : radii) out.push_back(at(a));
  return out;
}

AdhesiveLawPtr make_jkr_law(ContactModelPtr model, double w) { return std::make_shared<JkrLaw>(std::move(model), w); }

AdhesiveLawPtr make_adhesive_law(ContactModelPtr model, const ModelSpec& spec, double w, const AdhesionSpec& adhesion) {
  (void)spec;
  adhesion.validate();
  if (!model) throw Error("layerjkr::make_adhesive_law: the contact model is null");
  switch (adhesion.model) {
    case AdhesionModel::jkr:
      return make_jkr_law(std::move(model), w);
    case AdhesionModel::dmt:
      if (!adhesion.sigma0 && !adhesion.z0) {
        const double R = tip_radius(*model, "adhesion model \"dmt\" without sigma0");
        return std::make_shared<ClassicalDmtLaw>(std::move(model), w, R);
      }
      break;
    case AdhesionModel::maugis_dugdale:
      break;
  }
  throw InputError("adhesion model \"" + std::string(to_string(adhesion.model)) + "\" with a Dugdale stress is not built yet");
}

}  // namespace layerjkr
