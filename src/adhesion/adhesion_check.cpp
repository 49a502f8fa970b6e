// check_adhesion (adhesion_check.hpp): lambda from the contact's compliance, and the answer's
// pull-off error against Maugis-Dugdale.
#include "layerjkr/adhesion_check.hpp"

#include <cmath>
#include <cstdio>

#include <boost/math/constants/constants.hpp>

#include "layerjkr/error.hpp"
#include "layerjkr/maugis_dugdale.hpp"

namespace layerjkr {
namespace {

constexpr double kPi = boost::math::constants::pi<double>();

// kappa = lambda h0 / delta_a for a paraboloid on a half-space, where a_c^3 = 9 pi w R^2 / (8 E*)
// and S' = 2 E*: lambda = 2 sigma0 (9 R / (16 pi w E*^2))^(1/3), delta_a = sqrt(2 pi w a_c / E*).
double kappa() {
  return 2.0 * std::cbrt(9.0 / (16.0 * kPi)) / std::sqrt(2.0 * kPi * std::cbrt(9.0 * kPi / 8.0));
}

// Maugis' dimensionless pull-off force of the answer's own model: JKR -3/2, DMT -2.
double limit_pull_off(AdhesionModel m) { return m == AdhesionModel::jkr ? -1.5 : -2.0; }

std::string short_number(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g", x);
  return buf;
}

}  // namespace

double contact_lambda(const NonAdhesiveState& h, double w, double sigma0) {
  detail::require_positive("contact_lambda", "w", w);
  detail::require_positive("contact_lambda", "sigma0", sigma0);
  detail::require_positive("contact_lambda", "a", h.a);
  detail::require_positive("contact_lambda", "dS/da", h.dS_da);
  const double delta_a = std::sqrt(4.0 * kPi * w * h.a / h.dS_da);
  return kappa() * delta_a * sigma0 / w;
}

std::optional<AdhesionCheck> check_adhesion(const AdhesiveSolution& jkr, const AdhesiveSolution& answer,
                                            const AdhesionSpec& adhesion, const ModelSpec* medium) {
  if (jkr.law().model() != AdhesionModel::jkr)
    throw Error("layerjkr::check_adhesion: needs the contact's JKR solution, got a " +
                std::string(to_string(jkr.law().model())) + " one");
  const double w = jkr.w();
  if (!(w > 0.0)) return std::nullopt;
  const std::optional<CriticalPoint> jkr_pull_off = jkr.pull_off();
  if (!jkr_pull_off || !(jkr_pull_off->a > 0.0)) return std::nullopt;
  AdhesionCheck c;
  c.model = answer.law().model();
  c.sigma0 = adhesion.dugdale_stress(w);
  c.sigma0_assumed = adhesion.stress_assumed();
  c.lambda = contact_lambda(jkr.model().state(jkr_pull_off->a), w, c.sigma0);
  const ContactModel& contact = jkr.model();
  const bool closed_form = contact.name() == "half_space" && contact.has_profile() && contact.profile().is_paraboloid();
  c.basis = closed_form ? "closed form" : "half-space estimate";
  if (c.model == AdhesionModel::maugis_dugdale) return c;
  c.pull_off_error = std::abs(limit_pull_off(c.model) / maugis_pull_off_force(c.lambda) - 1.0);
  const bool solvable = medium && (medium->kind == ModelKind::half_space || medium->kind == ModelKind::exact);
  if (closed_form || !solvable || c.pull_off_error <= kAdhesionSolveAbove) return c;
  AdhesionSpec md;
  md.model = AdhesionModel::maugis_dugdale;
  md.sigma0 = c.sigma0;
  const std::optional<CriticalPoint> md_pull_off =
      AdhesiveSolution(make_adhesive_law(jkr.law().contact(), *medium, w, md)).pull_off();
  const std::optional<CriticalPoint> own = answer.pull_off();
  if (!md_pull_off || !own) return c;
  c.pull_off_error = std::abs(own->P / md_pull_off->P - 1.0);
  c.basis = "solved on the medium";
  return c;
}

std::string AdhesionCheck::brief_report() const {
  std::string s = "lambda = " + short_number(lambda) +
                  " (sigma0 = " + short_number(sigma0) + " Pa" +
                  (sigma0_assumed ? ", from z0 = " + short_number(AdhesionSpec::kAssumedSpacing * 1e9) +
                                        " nm assumed; set adhesion.sigma0 or adhesion.z0"
                                  : std::string()) +
                  ")";
  if (model == AdhesionModel::maugis_dugdale) return s;
  return s + ", pull-off force estimated " + short_number(100.0 * pull_off_error) + " % off Maugis-Dugdale (" + basis +
         ")";
}

}  // namespace layerjkr
