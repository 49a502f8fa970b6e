// Thin bonded layer, uniform in nu (docs/theory.md s.2a): the two-term expansion of the
// layer's compliance, w = eps p - D lap p, which stays finite up to nu = 1/2 where the
// stiffness expansion (K, G) blows up. Where D < 0 (0 < nu < 1/4) that pressure form is
// ill-posed and the same two terms are used in stiffness form, the full Pasternak model;
// where D = 0 both are Winkler. Either is evaluated at the edge-corrected radius a + beta h.
#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

#include <boost/math/constants/constants.hpp>
#include <boost/math/tools/roots.hpp>
#include <gsl/gsl_errno.h>
#include <gsl/gsl_sf_bessel.h>

#include "core/context_caches.hpp"
#include "core/gsl_support.hpp"
#include "layerjkr/error.hpp"
#include "layerjkr/exact_layer.hpp"
#include "layerjkr/model.hpp"
#include "layerjkr/model_spec.hpp"
#include "profiles/profile_quadrature.hpp"

namespace layerjkr {
namespace {

constexpr double kPi = boost::math::constants::pi<double>();
constexpr const char* kName = "uniform";
// Up to x = k a = 2 the Bessel combinations that vanish like x^2 are summed as power series
// with the cancelling leading terms removed; beyond it the closed forms cancel little
// (2 I1/(x I0) < 0.7).
constexpr double kSeriesMax = 2.0;

struct ScaledI {
  double i0, i1;  // e^{-x} I0(x), e^{-x} I1(x)
};

ScaledI scaled_bessel_i(double x) {
  detail::silence_gsl_errors();
  gsl_sf_result i0, i1;
  if (gsl_sf_bessel_I0_scaled_e(x, &i0) != GSL_SUCCESS || gsl_sf_bessel_I1_scaled_e(x, &i1) != GSL_SUCCESS)
    throw NumericalError("layerjkr: GSL failed to evaluate I0, I1 at x = " + format_double(x));
  return {i0.val, i1.val};
}

// sum_{j>=0} (x^2/4)^j c_j(t) until the terms stop mattering; x <= kSeriesMax.
template <class Coefficient>
double bessel_series(double x, Coefficient c) {
  const double q = 0.25 * x * x;
  double sum = 0.0, power = 1.0, fact = 1.0;  // fact = j!
  for (int j = 0; j < 40; ++j) {
    if (j > 0) fact *= j;
    const double term = power * c(j, fact);
    sum += term;
    if (j > 2 && std::abs(term) <= 1e-17 * std::abs(sum)) break;
    power *= q;
  }
  return sum;
}

// phi(x) = (1 - 2 I1(x)/(x I0(x))) / x^2, -> 1/8 at x = 0: the flat punch S = pi a^4 phi / D.
double flat_punch_factor(double x) {
  if (x > kSeriesMax) {
    const ScaledI b = scaled_bessel_i(x);
    return (1.0 - 2.0 * b.i1 / (x * b.i0)) / (x * x);
  }
  // x I0 - 2 I1 = x sum_{j>=1} (x^2/4)^j j / ((j+1) (j!)^2): positive terms only.
  const double numerator = 0.25 * bessel_series(x, [](int j, double f) { return 1.0 / ((j + 2.0) * (j + 1.0) * f * f); });
  const double i0 = bessel_series(x, [](int, double f) { return 1.0 / (f * f); });
  return numerator / i0;
}

// I1(x) / (x I0(x)), -> 1/2 at x = 0: S' = 2 pi a^3 (I1/(x I0))^2 / D.
double edge_ratio(double x) {
  if (x < 1e-8) return 0.5 - x * x / 16.0;
  const ScaledI b = scaled_bessel_i(x);
  return b.i1 / (x * b.i0);
}

// Weight of delta_H = int_0^1 f(a t) t W(t) dt, with W = x I0(x t) / I1(x) (2 at x = 0);
// x_over_i1 = x e^x / I1(x), computed once per state.
double delta_weight(double x, double x_over_i1, double t) {
  if (x < 1e-8) return 2.0;
  return x_over_i1 * scaled_bessel_i(x * t).i0 * std::exp(x * (t - 1.0));
}

// Weight of P_H = (2 pi a^4 / D) int_0^1 f(a t) t chi(t) dt, chi = (W/2 - 1)/x^2,
// -> (2 t^2 - 1)/8 at x = 0.
double force_weight(double x, double x_over_i1, double t) {
  if (x > kSeriesMax) return (0.5 * delta_weight(x, x_over_i1, t) - 1.0) / (x * x);
  // x I0(x t) - 2 I1(x) = x sum_{j>=1} (x^2/4)^j [t^2j/(j!)^2 - 1/(j!(j+1)!)]; divide by
  // 2 I1(x) x^2 = x^3 sum_j (x^2/4)^j / (j!(j+1)!).
  const double t2 = t * t;
  double t2j = 1.0;
  const double top = bessel_series(x, [&](int j, double f) {
    // coefficient of (x^2/4)^j for j + 1, divided by 4 to pull out one power.
    t2j *= t2;
    const double f1 = f * (j + 1.0);  // (j+1)!
    return 0.25 * (t2j / (f1 * f1) - 1.0 / (f1 * f1 * (j + 2.0)));
  });
  const double bottom = bessel_series(x, [](int j, double f) { return 1.0 / (f * f * (j + 1.0)); });
  return top / bottom;
}

class PressureFormLayer final : public ContactModel {
 public:
  PressureFormLayer(ProfilePtr p, double eps, double D) : ContactModel(std::move(p)), eps_(eps), D_(D) {}

  NonAdhesiveState state(double a) const override {
    profile().require_contact_radius(kName, a);
    const double x = a * std::sqrt(eps_ / D_);
    std::vector<double> cuts;
    for (double b : profile().breakpoints(a)) cuts.push_back(b / a);
    const Profile& f = profile();
    const double x_over_i1 = x < 1e-8 ? 2.0 : x / scaled_bessel_i(x).i1;
    const double delta = detail::integrate_split(
        [&](double t) { return f.f(a * t) * t * delta_weight(x, x_over_i1, t); }, 0.0, 1.0, cuts, kName);
    const double force_integral = detail::integrate_split(
        [&](double t) { return f.f(a * t) * t * force_weight(x, x_over_i1, t); }, 0.0, 1.0, cuts, kName);
    const double a3 = a * a * a, a4 = a3 * a;
    const double q = edge_ratio(x);
    return {a, 2.0 * kPi * a4 * force_integral / D_, delta, kPi * a4 * flat_punch_factor(x) / D_,
            2.0 * kPi * a3 * q * q / D_};
  }
  std::string name() const override { return kName; }

 private:
  double eps_;  // compliance per unit pressure [m^3/N]: 1/K
  double D_;    // [m^5/N], > 0
};

// The two-term model evaluated at the effective radius a + beta h (as edge_corrected does
// for Winkler): the exact layer's edge region of width ~h acts, to first order in h/a, as a
// shift of the contact edge, which no local law captures.
class EdgeShifted final : public ContactModel {
 public:
  EdgeShifted(ContactModelPtr inner, double shift)
      : ContactModel(inner->profile_ptr()), inner_(std::move(inner)), shift_(shift) {}
  NonAdhesiveState state(double a) const override {
    if (!(a + shift_ > 0.0))
      throw DomainError(kName, "contact radius a", a,
                        "> -beta h = " + format_double(-shift_) + " (a + beta h must be positive)");
    NonAdhesiveState s = inner_->state(a + shift_);
    s.a = a;  // the JKR energy term uses the true contact radius
    return s;
  }
  std::string name() const override { return kName; }
  double min_radius() const override { return std::max(0.0, -shift_); }
  double max_radius() const override { return inner_->max_radius() - shift_; }

 private:
  ContactModelPtr inner_;
  double shift_;
};

ContactModelPtr two_term_form(ProfilePtr profile, const UniformLayerConstants& c) {
  if (c.D > 0.0) return std::make_shared<PressureFormLayer>(std::move(profile), c.eps, c.D);
  const double K = 1.0 / c.eps;
  if (c.D == 0.0) return make_winkler(std::move(profile), K);
  return make_full_foundation(std::move(profile), K, -c.D * K * K);
}

// beta at which a paraboloid's approach matches the exact layer's at a/h = 50 (unit layer).
double fit_beta(double nu, const std::shared_ptr<Context>& context) {
  const ElasticLayer unit{1.0, nu, 1.0, Base::bonded};
  ExactLayerOptions o;
  o.max_a_over_h = 50.0;
  o.estimate_error = false;
  o.context = context;
  const ExactLayerKernel kernel(unit, o);
  const double R = 1e4, a = 50.0;
  const auto paraboloid = make_paraboloid(R);
  const double target = kernel.solve(*paraboloid, a).state.delta_H;
  const ContactModelPtr model = two_term_form(paraboloid, uniform_layer_constants(unit));
  boost::uintmax_t iterations = 100;
  // |beta| < 2 for every nu measured (docs/models.md): the bracket is wide.
  const auto root = boost::math::tools::toms748_solve(
      [&](double b) { return model->state(a + b).delta_H - target; }, -20.0, 20.0,
      boost::math::tools::eps_tolerance<double>(45), iterations);
  if (iterations >= 100) throw NumericalError("layerjkr: uniform_layer_beta did not converge for nu = " + format_double(nu));
  return 0.5 * (root.first + root.second);
}

}  // namespace

UniformLayerConstants uniform_layer_constants(const ElasticLayer& layer) {
  const char* fn = "uniform_layer_constants";
  detail::require_positive(fn, "E", layer.E);
  detail::require_positive(fn, "h", layer.h);
  if (!(layer.nu > -1.0 && layer.nu <= 0.5)) throw DomainError(fn, "nu", layer.nu, "(-1, 0.5]");
  if (layer.base != Base::bonded)
    throw DomainError(fn, "base (frictionless)", 0.0,
                      "bonded (a frictionless layer's expansion is uniform already: use edge_corrected)");
  const double nu = layer.nu, h = layer.h, E = layer.E;
  UniformLayerConstants c;
  c.eps = h * (1.0 + nu) * (1.0 - 2.0 * nu) / (E * (1.0 - nu));
  c.D = h * h * h * nu * (4.0 * nu - 1.0) * (1.0 + nu) / (3.0 * E * (1.0 - nu) * (1.0 - nu));
  return c;
}

double uniform_layer_beta(const ElasticLayer& layer, const std::shared_ptr<Context>& context) {
  (void)uniform_layer_constants(layer);  // validates
  return *detail::context_caches(context).uniform_betas.get(
      layer.nu, [&] { return std::make_shared<const double>(fit_beta(layer.nu, context)); });  // ~0.1 s
}

ContactModelPtr make_uniform_layer(ProfilePtr profile, const ElasticLayer& layer, bool edge_correction,
                                   const std::shared_ptr<Context>& context) {
  const UniformLayerConstants c = uniform_layer_constants(layer);
  const double shift = edge_correction ? uniform_layer_beta(layer, context) * layer.h : 0.0;
  return std::make_shared<EdgeShifted>(two_term_form(std::move(profile), c), shift);
}

}  // namespace layerjkr
