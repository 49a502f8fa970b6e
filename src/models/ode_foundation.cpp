// The ODE route: P_H(a) = int_0^a S(s) delta_H'(s) ds with GSL's adaptive QAGP.
//
// The right-hand side of dP_H/da = S delta_H' does not involve P_H, so the initial
// value problem from P_H(0) = 0 is a quadrature; QAGP's extrapolation copes with the
// integrable endpoint behaviour of cones and low power laws. The integration runs in
// the scaled variable t = s/a in [0, 1]. Nothing here uses the moment int f r dr,
// which is what makes it an independent check of the closed forms.
#include <gsl/gsl_errno.h>
#include <gsl/gsl_integration.h>

#include <cmath>
#include <algorithm>
#include <exception>
#include <limits>
#include <memory>

#include <boost/math/constants/constants.hpp>

#include "core/bessel_ratio.hpp"
#include "core/gsl_support.hpp"
#include "layerjkr/error.hpp"
#include "layerjkr/model.hpp"

namespace layerjkr {
namespace {

constexpr double kPi = boost::math::constants::pi<double>();

struct WorkspaceDeleter {
  void operator()(gsl_integration_workspace* w) const { gsl_integration_workspace_free(w); }
};

class OdeFoundation final : public ContactModel {
 public:
  OdeFoundation(ProfilePtr p, double K, double G, FoundationKind kind, double tol)
      : ContactModel(std::move(p)),
        K_(K),
        G_(G),
        full_(kind == FoundationKind::full),
        lambda_(full_ ? std::sqrt(K / G) : 0.0),
        tol_(tol) {
    detail::silence_gsl_errors();
  }

  NonAdhesiveState state(double a) const override {
    profile().require_contact_radius("ode_foundation", a);
    NonAdhesiveState s = local(a);
    s.P_H = integrate_force(a);
    return s;
  }
  std::string name() const override { return full_ ? "ode(full_foundation)" : "ode(two_term)"; }

 private:
  // Everything but P_H: the edge condition and the flat-punch stiffness.
  NonAdhesiveState local(double a) const {
    const ProfileDerivatives d = profile().derivatives(a);
    NonAdhesiveState s;
    s.a = a;
    if (full_) {
      const double q = detail::bessel_k1_over_k0(lambda_ * a);
      s.delta_H = d.f + d.df / (lambda_ * q);
      s.S = kPi * K_ * a * a + 2.0 * kPi * G_ * lambda_ * a * q;
      s.dS_da = 2.0 * kPi * K_ * a * q * q;
    } else {
      s.delta_H = d.f - (G_ / K_) * (d.d2f + d.df / a);
      s.S = kPi * K_ * a * a;
      s.dS_da = 2.0 * kPi * K_ * a;
    }
    return s;
  }

  // The size of the terms rhs(a) sums: its roundoff floor is eps times this. At tiny radii
  // the terms cancel (a paraboloid's a f'' - f' = 0) and P_H ~ a^4 falls below that floor,
  // so a relative tolerance alone cannot be met (QAGP failed at a = 1.8e-12 on the
  // bundled scenes).
  double term_size(double a) const {
    const ProfileDerivatives d = profile().derivatives(a);
    if (full_) {
      const double q = detail::bessel_k1_over_k0(lambda_ * a);
      const double rho = 1.0 / (lambda_ * q);
      const double S = kPi * K_ * a * a + 2.0 * kPi * G_ * lambda_ * a * q;
      return std::abs(S) * (std::abs(d.df) + std::abs(d.d2f * rho) +
                            std::abs(d.df) * (1.0 / (q * q) + 1.0 + std::abs(rho / a)));
    }
    return kPi * K_ * a * a * std::abs(d.df) +
           kPi * std::abs(G_) * (a * a * std::abs(d.d3f) + a * std::abs(d.d2f) + std::abs(d.df));
  }

  // dP_H/da = S(a) delta_H'(a), with delta_H' from the profile derivatives.
  double rhs(double a) const {
    const ProfileDerivatives d = profile().derivatives(a);
    if (full_) {
      const double q = detail::bessel_k1_over_k0(lambda_ * a);
      const double rho = 1.0 / (lambda_ * q);  // K0/(lam K1)
      const double drho = 1.0 / (q * q) - 1.0 + rho / a;
      const double S = kPi * K_ * a * a + 2.0 * kPi * G_ * lambda_ * a * q;
      return S * (d.df + d.d2f * rho + d.df * drho);
    }
    // S delta_H' = pi K a^2 f' - pi G (a^2 f''' + a f'' - f'), arranged without 1/a^2.
    return kPi * K_ * a * a * d.df - kPi * G_ * (a * a * d.d3f + a * d.d2f - d.df);
  }

  struct Context {
    const OdeFoundation* self;
    double a;
    std::exception_ptr error;
  };

  static double integrand(double t, void* raw) {
    auto* c = static_cast<Context*>(raw);
    if (c->error) return 0.0;
    try {
      return c->self->rhs(c->a * t) * c->a;
    } catch (...) {  // never unwind through GSL's C frames
      c->error = std::current_exception();
      return 0.0;
    }
  }

  double integrate_force(double a) const {
    constexpr std::size_t kLimit = 2000;
    std::unique_ptr<gsl_integration_workspace, WorkspaceDeleter> ws(
        gsl_integration_workspace_alloc(kLimit));
    std::vector<double> pts{0.0};
    for (double b : profile().breakpoints(a)) pts.push_back(b / a);
    pts.push_back(1.0);
    Context ctx{this, a, nullptr};
    gsl_function fn{&OdeFoundation::integrand, &ctx};
    // An absolute tolerance at the integrand's roundoff floor (terms of size term_size over
    // [0, a], 1e3 ulps): below it no quadrature resolves P_H, and an error that small is
    // below what the closed forms resolve too.
    const double floor = 1e3 * std::numeric_limits<double>::epsilon() * a *
                         std::max(term_size(a), term_size(0.5 * a));
    double result = 0.0, abserr = 0.0;
    int status = gsl_integration_qagp(&fn, pts.data(), pts.size(), floor, tol_, kLimit,
                                      ws.get(), &result, &abserr);
    if (ctx.error) std::rethrow_exception(ctx.error);
    // QAGP reports roundoff even when the achieved error meets the tolerance.
    if (status == GSL_EROUND && abserr <= std::max(floor, tol_ * std::abs(result))) status = GSL_SUCCESS;
    if (status != GSL_SUCCESS || !std::isfinite(result))
      throw NumericalError("layerjkr::ode_foundation: QAGP failed at a = " + format_double(a) +
                           " (" + gsl_strerror(status) + ", estimated error " +
                           format_double(abserr) + ")");
    return result;
  }

  double K_, G_;
  bool full_;
  double lambda_, tol_;
};

}  // namespace

ContactModelPtr make_ode_foundation(ProfilePtr profile, double K, double G, FoundationKind kind,
                                    double rel_tol) {
  const char* fn = "make_ode_foundation";
  detail::require_positive(fn, "K", K);
  detail::require_finite(fn, "G", G);
  if (kind == FoundationKind::full && !(G > 0.0))
    throw DomainError(fn, "G (or tension T)", G,
                      "> 0 for the full foundation; use FoundationKind::asymptotic for G <= 0");
  if (!(rel_tol >= 1e-14 && rel_tol <= 1e-2))
    throw DomainError(fn, "rel_tol", rel_tol, "[1e-14, 1e-2]");
  return std::make_shared<OdeFoundation>(std::move(profile), K, G, kind, rel_tol);
}

}  // namespace layerjkr
