// The adhesive laws (adhesion.hpp): JKR on every model, the classical DMT on every model with a
// tip radius, and the dispatch that builds the law a scene's "adhesion" asks for.
#include "layerjkr/adhesion.hpp"

#include <cmath>
#include <limits>
#include <utility>

#include "adhesion/dmt_formula.hpp"
#include "adhesion/dugdale_solver.hpp"
#include "layerjkr/error.hpp"
#include "layerjkr/maugis_dugdale.hpp"

namespace layerjkr {
namespace {

// The states of `contact` at `radii` (one call, so a model sharing work across radii does),
// each turned adhesive by `transform`.
template <class Transform>
std::vector<AdhesiveState> transformed_states(const ContactModel& contact, const std::vector<double>& radii,
                                              Transform transform) {
  std::vector<AdhesiveState> out;
  out.reserve(radii.size());
  for (const NonAdhesiveState& h : contact.states(radii)) out.push_back(transform(h));
  return out;
}

class JkrLaw final : public AdhesiveLaw {
 public:
  JkrLaw(ContactModelPtr model, double w) : AdhesiveLaw(std::move(model), w) {}
  AdhesiveState at(double a) const override { return jkr_transform(contact()->state(a), w()); }
  std::vector<AdhesiveState> curve(const std::vector<double>& radii) const override {
    return transformed_states(*contact(), radii, [this](const NonAdhesiveState& h) { return jkr_transform(h, w()); });
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
    return transformed_states(*contact(), radii,
                              [this](const NonAdhesiveState& h) { return dmt_transform(h, w(), R_); });
  }
  AdhesionModel model() const override { return AdhesionModel::dmt; }
  bool has_zero_radius_state() const override { return true; }
  std::string name() const override { return "dmt on " + contact()->name(); }

 private:
  double R_;
};

// Maugis-Dugdale of a paraboloid on a half-space: Maugis' closed form (maugis_dugdale.hpp).
class ClosedFormMaugisLaw final : public AdhesiveLaw {
 public:
  ClosedFormMaugisLaw(ContactModelPtr model, double w, double R, double E_star, double sigma0)
      : AdhesiveLaw(std::move(model), w), R_(R), E_star_(E_star), sigma0_(sigma0) {}
  AdhesiveState at(double a) const override { return maugis_dugdale_half_space(R_, E_star_, w(), sigma0_, a); }
  AdhesionModel model() const override { return AdhesionModel::maugis_dugdale; }
  bool has_zero_radius_state() const override { return true; }
  std::string name() const override {
    return "maugis_dugdale (sigma0 = " + format_double(sigma0_) + " Pa) on " + contact()->name();
  }

 private:
  double R_, E_star_, sigma0_;
};

// A Dugdale law solved on the medium (detail::DugdaleSolver): Maugis-Dugdale, or DMT over
// the non-adhesive state's gap. The non-adhesive state at a fills hertz, so every answer
// prints P_H, delta_H and S (the solver's own Maugis-Dugdale states carry only a).
class DugdaleLaw final : public AdhesiveLaw {
 public:
  DugdaleLaw(ContactModelPtr model, double w, double sigma0, AdhesionModel kind,
             std::shared_ptr<const detail::DugdaleSolver> solver)
      : AdhesiveLaw(std::move(model), w), sigma0_(sigma0), kind_(kind), solver_(std::move(solver)) {}
  AdhesiveState at(double a) const override {
    if (w() == 0.0) return jkr_transform(contact()->state(a), 0.0);
    if (kind_ == AdhesionModel::dmt) return solver_->dmt(a, w(), sigma0_);
    AdhesiveState s = solver_->maugis_dugdale(a, w(), sigma0_);
    s.hertz = a > 0.0 ? contact()->state(a) : NonAdhesiveState{};
    return s;
  }
  AdhesionModel model() const override { return kind_; }
  bool has_zero_radius_state() const override { return w() > 0.0; }
  std::string name() const override {
    return std::string(to_string(kind_)) + " (sigma0 = " + format_double(sigma0_) + " Pa) on " + contact()->name();
  }
  std::size_t max_curve_radii() const override { return solver_->on_half_space() ? 0 : kMaxDugdaleLayerRadii; }
  std::string radius_cost() const override { return solver_->on_half_space() ? "" : "5-13 ms"; }

 private:
  double sigma0_;
  AdhesionModel kind_;
  std::shared_ptr<const detail::DugdaleSolver> solver_;
};

// The medium's Dugdale solver: the half-space or the exact layer / stack of `spec`.

// The tip's radius of curvature, where the profile has one.
double tip_radius(const ContactModel& model, const char* what) {
  if (!model.has_profile())
    throw InputError(std::string(what) + " needs an indenter profile; this model was built from data");
  return detail::dmt_tip_radius(model.profile(), what, ": give adhesion.sigma0 (or z0) for a Dugdale law on its gap");
}

}  // namespace

double detail::dmt_tip_radius(const Profile& p, const std::string& who, const std::string& remedy) {
  const double curvature = p.derivatives(0.0).d2f;
  if (!(curvature > 0.0) || !std::isfinite(curvature))
    throw InputError(who + " needs a tip with a radius of curvature (f''(0) > 0); " + p.describe() +
                     " has f''(0) = " + format_double(curvature) + remedy);
  return 1.0 / curvature;
}

void CrackKinetics::validate() const {
  if (!(v_star > 0.0 && std::isfinite(v_star))) throw DomainError("CrackKinetics", "v_star", v_star, "finite and > 0 [m/s]");
  if (!(n > 0.0 && n <= 10.0)) throw DomainError("CrackKinetics", "n", n, "(0, 10]");
}

double CrackKinetics::crack_speed(double G, double w0) const {
  const double excess = G / w0 - 1.0;
  return excess > 0.0 ? v_star * std::pow(excess, 1.0 / n) : 0.0;
}

std::string CrackKinetics::describe() const {
  return "maugis_barquins(v_star = " + format_double(v_star) + " m/s, n = " + format_double(n) + ")";
}

void AdhesionSpec::validate() const {
  if (kinetics) {
    kinetics->validate();
    if (model != AdhesionModel::jkr)
      throw DomainError("AdhesionSpec", std::string("kinetics with adhesion model ") + to_string(model), kinetics->v_star,
                        "kinetics only with model jkr (they act on JKR's edge crack)");
  }
  if (sigma0) detail::require_positive("AdhesionSpec", "sigma0", *sigma0);
  if (z0) detail::require_positive("AdhesionSpec", "z0", *z0);
  if (sigma0 && z0)
    throw DomainError("AdhesionSpec", "z0", *z0, "absent when sigma0 is given (sigma0 = " + format_double(*sigma0) + " Pa)");
}

double AdhesionSpec::dugdale_stress(double w) const {
  validate();
  detail::require_positive("AdhesionSpec::dugdale_stress", "w", w);
  if (sigma0) return *sigma0;
  return lennard_jones_dugdale_stress(w, z0 ? *z0 : kAssumedSpacing);
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
  adhesion.validate();
  if (!model) throw Error("layerjkr::make_adhesive_law: the contact model is null");
  if (adhesion.model == AdhesionModel::jkr) return make_jkr_law(std::move(model), w);
  if (adhesion.model == AdhesionModel::dmt && adhesion.stress_assumed()) {
    const double R = tip_radius(*model, "adhesion model \"dmt\" without sigma0");
    return std::make_shared<ClassicalDmtLaw>(std::move(model), w, R);
  }
  if (adhesion.model == AdhesionModel::maugis_dugdale && adhesion.stress_assumed())
    throw InputError("adhesion model \"maugis_dugdale\" needs sigma0 [Pa] (the Dugdale stress) or z0 [m]");
  const double sigma0 = w > 0.0 ? adhesion.dugdale_stress(w) : adhesion.sigma0.value_or(0.0);
  const std::string what = "adhesion model \"" + std::string(to_string(adhesion.model)) + "\" with sigma0";
  if (adhesion.model == AdhesionModel::maugis_dugdale && w > 0.0 && spec.kind == ModelKind::half_space &&
      model->has_profile() && model->profile().is_paraboloid())
    return std::make_shared<ClosedFormMaugisLaw>(model, w, tip_radius(*model, what.c_str()),
                                                 effective_modulus(spec.layer.E, spec.layer.nu), sigma0);
  auto solver = detail::make_dugdale_solver(*model, spec, what.c_str());
  return std::make_shared<DugdaleLaw>(std::move(model), w, sigma0, adhesion.model, std::move(solver));
}

std::shared_ptr<const detail::DugdaleSolver> detail::make_dugdale_solver(const ContactModel& model, const ModelSpec& spec,
                                                            const char* what) {
  if (!model.has_profile())
    throw InputError(std::string(what) + " needs an indenter profile; this model was built from data");
  ProfilePtr profile = model.profile_ptr();
  if (spec.kind == ModelKind::half_space)
    return std::make_shared<detail::DugdaleSolver>(std::move(profile),
                                                   effective_modulus(spec.layer.E, spec.layer.nu));
  if (spec.kind == ModelKind::exact) {
    auto kernel = spec.stack ? std::make_shared<ExactLayerKernel>(*spec.stack, spec.exact)
                             : std::make_shared<ExactLayerKernel>(spec.layer, spec.exact);
    return std::make_shared<detail::DugdaleSolver>(std::move(profile), std::move(kernel), /*tabulate=*/true);
  }
  throw InputError(std::string(what) + " is solved on the half-space and on the exact layer or stack (model \"exact\"), not on model \"" +
                   std::string(to_string(spec.kind)) + "\": the thin-layer and foundation laws do not give the gap outside the contact");
}

}  // namespace layerjkr
