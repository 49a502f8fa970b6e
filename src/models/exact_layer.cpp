// Exact elastic layer: kernel table (GSL QAWF + spline) and Nystrom solve (Eigen).
#include "layerjkr/exact_layer.hpp"
#include "layerjkr/model_spec.hpp"

#include <gsl/gsl_errno.h>
#include <gsl/gsl_integration.h>
#include <gsl/gsl_spline.h>

#include <cmath>
#include <exception>
#include <limits>

#include <Eigen/Dense>
#include <boost/math/differentiation/finite_difference.hpp>
#include <boost/math/quadrature/tanh_sinh.hpp>
#include <boost/math/constants/constants.hpp>

#include "core/gsl_support.hpp"
#include "layerjkr/error.hpp"

namespace layerjkr {
namespace {

constexpr double kPi = boost::math::constants::pi<double>();
constexpr double kBeta = 2.0;  // decay rate of the subtracted model e^{-beta u}(1 + gamma u)

// q(u) = 1 - L(u), written with E = exp(-2u): no overflow and no cancellation.
double one_minus_L(double u, double kappa, bool bonded) {
  const double E = std::exp(-2.0 * u);
  if (bonded) {
    const double s = 1.0 + 2.0 * u;
    return E * (2.0 * kappa * E + s * s + kappa * kappa) /
           (kappa * (1.0 + E * E) + (4.0 * u * u + 1.0 + kappa * kappa) * E);
  }
  const double one_minus_E = -std::expm1(-2.0 * u);
  return 2.0 * E * (one_minus_E + 2.0 * u) / (-std::expm1(-4.0 * u) + 4.0 * u * E);
}

// q'(0) = -L'(0): bonded -4(kappa-1)/(kappa+1)^2 (0 when incompressible), frictionless -1/2.
double slope_at_zero(double kappa, bool bonded) {
  return bonded ? -4.0 * (kappa - 1.0) / ((kappa + 1.0) * (kappa + 1.0)) : -0.5;
}

struct Remainder {
  double kappa, gamma;
  bool bonded;
};

double remainder(double u, void* p) {
  const auto* r = static_cast<const Remainder*>(p);
  return one_minus_L(u, r->kappa, r->bonded) - std::exp(-kBeta * u) * (1.0 + r->gamma * u);
}

struct SplineFree {
  void operator()(gsl_spline* s) const { gsl_spline_free(s); }
};
struct GlFree {
  void operator()(gsl_integration_glfixed_table* t) const { gsl_integration_glfixed_table_free(t); }
};

}  // namespace

struct ExactLayerKernel::Table {
  double gamma = 0.0, sigma_max = 0.0;
  std::unique_ptr<gsl_spline, SplineFree> spline;
};

void ExactLayerOptions::Validate() const {
  const char* fn = "ExactLayerOptions::Validate";
  if (!(max_a_over_h > 0.0 && max_a_over_h <= 1000.0))
    throw DomainError(fn, "max_a_over_h", max_a_over_h, "(0, 1000]");
  if (points_per_panel < 4 || points_per_panel > 20)
    throw DomainError(fn, "points_per_panel", points_per_panel, "[4, 20]");
  if (!(panel_width > 0.0 && panel_width <= 2.0))
    throw DomainError(fn, "panel_width", panel_width, "(0, 2]");
  if (min_panels < 2) throw DomainError(fn, "min_panels", min_panels, ">= 2");
  if (!(table_spacing >= 1e-4 && table_spacing <= 0.2))
    throw DomainError(fn, "table_spacing", table_spacing, "[1e-4, 0.2]");
}

ExactLayerKernel::ExactLayerKernel(const ElasticLayer& layer, ExactLayerOptions options)
    : layer_(layer), options_(options), table_(std::make_unique<Table>()) {
  detail::silence_gsl_errors();
  options_.Validate();
  detail::require_positive("ExactLayerKernel", "h", layer.h);
  E_star_ = layerjkr::effective_modulus(layer.E, layer.nu);  // validates E, nu in (-1, 0.5]
  const bool bonded = layer.base == Base::bonded;
  const double kappa = 3.0 - 4.0 * layer.nu;
  Remainder rem{kappa, slope_at_zero(kappa, bonded) + kBeta, bonded};
  table_->gamma = rem.gamma;
  table_->sigma_max = 2.0 * options_.max_a_over_h + 1.0;

  // Graded grid: spacing table_spacing up to sigma = 10, then growing like sigma (the remainder
  // varies on an O(1) scale and decays like sigma^-4).
  std::vector<double> sigma{0.0}, value;
  while (sigma.back() < table_->sigma_max)
    sigma.push_back(sigma.back() + options_.table_spacing * std::max(1.0, sigma.back() / 10.0));
  constexpr std::size_t kLimit = 2000;
  gsl_integration_workspace* ws = gsl_integration_workspace_alloc(kLimit);
  gsl_integration_workspace* cycles = gsl_integration_workspace_alloc(kLimit);
  gsl_function fn{&remainder, &rem};
  int status = GSL_SUCCESS;
  for (double s : sigma) {
    double result = 0.0, abserr = 0.0;
    if (s == 0.0) {
      status = gsl_integration_qagiu(&fn, 0.0, 1e-15, 1e-12, kLimit, ws, &result, &abserr);
    } else {
      gsl_integration_qawo_table* wf =
          gsl_integration_qawo_table_alloc(s, 1.0, GSL_INTEG_COSINE, 50);
      status = gsl_integration_qawf(&fn, 0.0, 1e-15, kLimit, ws, cycles, wf, &result, &abserr);
      gsl_integration_qawo_table_free(wf);
    }
    if (status != GSL_SUCCESS) break;
    value.push_back(result);
  }
  gsl_integration_workspace_free(ws);
  gsl_integration_workspace_free(cycles);
  if (status != GSL_SUCCESS)
    throw NumericalError(std::string("layerjkr::ExactLayerKernel: kernel transform failed (") +
                         gsl_strerror(status) + ")");
  // Ft is even in sigma: mirror the table so the spline sees that (a natural spline
  // on [0, ...] would force Ft''(0) = 0 and lose two orders near the origin).
  std::vector<double> x(2 * sigma.size() - 1), y(2 * sigma.size() - 1);
  const std::size_t n = sigma.size();
  for (std::size_t i = 0; i < n; ++i) {
    x[n - 1 - i] = -sigma[i];
    x[n - 1 + i] = sigma[i];
    y[n - 1 - i] = value[i];
    y[n - 1 + i] = value[i];
  }
  table_->spline.reset(gsl_spline_alloc(gsl_interp_cspline, x.size()));
  gsl_spline_init(table_->spline.get(), x.data(), y.data(), x.size());
}

ExactLayerKernel::~ExactLayerKernel() = default;

double ExactLayerKernel::kernel(double sigma) const {
  sigma = std::abs(sigma);
  if (!(sigma <= table_->sigma_max))
    throw DomainError("ExactLayerKernel::kernel", "sigma", sigma,
                      "[0, " + format_double(table_->sigma_max) +
                          "]; raise ExactLayerOptions::max_a_over_h");
  const double b2 = kBeta * kBeta, s2 = sigma * sigma, d = b2 + s2;
  const double model = kBeta / d + table_->gamma * (b2 - s2) / (d * d);
  return model + gsl_spline_eval(table_->spline.get(), sigma, nullptr);
}

double ExactLayerKernel::kernel_derivative(double sigma) const {
  const double x = std::abs(sigma);
  if (!(x <= table_->sigma_max))
    throw DomainError("ExactLayerKernel::kernel_derivative", "sigma", sigma,
                      "[0, " + format_double(table_->sigma_max) + "]");
  const double b2 = kBeta * kBeta, s2 = x * x, d = b2 + s2;
  const double model = -2.0 * kBeta * x / (d * d) +
                       table_->gamma * (-2.0 * x / (d * d) - 4.0 * x * (b2 - s2) / (d * d * d));
  const double value = model + gsl_spline_eval_deriv(table_->spline.get(), x, nullptr);
  return sigma < 0.0 ? -value : value;
}

namespace {

// phi0 (flat punch) and phi_f (profile) on the Nystrom nodes, in xi = x/a in [0, 1].
struct Nystrom {
  Eigen::VectorXd xi, w;
  Eigen::MatrixXd phi;  // columns: phi0, phi_f
  double rho = 0.0, end0 = 0.0, endf = 0.0;
};

Nystrom nystrom_solve(const ExactLayerKernel& k, const Profile& profile, double a, int panels,
                      int m) {
  Nystrom out;
  const double rho = a / k.layer().h;
  out.rho = rho;
  const int n = panels * m;
  std::unique_ptr<gsl_integration_glfixed_table, GlFree> gl(
      gsl_integration_glfixed_table_alloc(static_cast<std::size_t>(m)));
  out.xi.resize(n);
  out.w.resize(n);
  for (int p = 0; p < panels; ++p)
    for (int q = 0; q < m; ++q) {
      double x = 0.0, wq = 0.0;
      gsl_integration_glfixed_point(double(p) / panels, double(p + 1) / panels,
                                    static_cast<std::size_t>(q), &x, &wq, gl.get());
      out.xi(p * m + q) = x;
      out.w(p * m + q) = wq;
    }
  // Dimensionless x = a xi: A = I - (rho/pi) W [Ft(rho|xi-tau|) + Ft(rho(xi+tau))].
  auto row = [&](double x, int j) {
    return (rho / kPi) * out.w(j) * (k.kernel(rho * (x - out.xi(j))) + k.kernel(rho * (x + out.xi(j))));
  };
  Eigen::MatrixXd A(n, n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) A(i, j) = (i == j ? 1.0 : 0.0) - row(out.xi(i), j);
  Eigen::MatrixXd rhs(n, 2);
  for (int i = 0; i < n; ++i) {
    const double x = a * out.xi(i);
    rhs(i, 0) = 1.0;
    rhs(i, 1) = x * profile.sneddon(x).I0;  // x int_0^x f'(r)/sqrt(x^2 - r^2) dr
  }
  out.phi = A.partialPivLu().solve(rhs);
  // Nystrom interpolation to the edge xi = 1.
  out.end0 = 1.0;
  out.endf = a * profile.sneddon(a).I0;
  for (int j = 0; j < n; ++j) {
    const double kj = row(1.0, j);
    out.end0 += kj * out.phi(j, 0);
    out.endf += kj * out.phi(j, 1);
  }
  return out;
}

// a/h for a query at contact radius a, after checking a against the profile and the
// kernel table's range (ExactLayerOptions::max_a_over_h).
double checked_a_over_h(const ExactLayerKernel& k, const char* function, const Profile& profile,
                        double a) {
  profile.require_contact_radius(function, a);
  const double rho = a / k.layer().h;
  if (!(rho <= k.options().max_a_over_h))
    throw DomainError(function, "a/h", rho,
                      "(0, " + format_double(k.options().max_a_over_h) +
                          "] (ExactLayerOptions::max_a_over_h)");
  return rho;
}

int panel_count(const ExactLayerOptions& o, double rho) {
  return std::max(o.min_panels, static_cast<int>(std::ceil(rho / o.panel_width)));
}

}  // namespace

ExactLayerState ExactLayerKernel::solve(const Profile& profile, double a) const {
  const double rho = checked_a_over_h(*this, "exact_layer", profile, a);
  const int n_fine = panel_count(options_, rho);
  auto to_state = [&](const Nystrom& r) {
    const double int0 = r.w.dot(r.phi.col(0)), intf = r.w.dot(r.phi.col(1));
    HertzState s;
    s.a = a;
    s.delta_H = r.endf / r.end0;
    s.S = 2.0 * E_star_ * a * int0;
    s.P_H = 2.0 * E_star_ * a * (s.delta_H * int0 - intf);
    s.dS_da = 2.0 * E_star_ * r.end0 * r.end0;
    return s;
  };
  const int m = options_.points_per_panel;
  const Nystrom fine = nystrom_solve(*this, profile, a, n_fine, m);
  ExactLayerState out;
  out.state = to_state(fine);
  out.unknowns = static_cast<int>(fine.xi.size());
  out.P_H_error = out.delta_H_error = std::numeric_limits<double>::quiet_NaN();
  if (options_.estimate_error) {
    const HertzState c = to_state(nystrom_solve(*this, profile, a, std::max(2, n_fine / 2), m));
    out.P_H_error = std::abs(out.state.P_H - c.P_H) / std::abs(out.state.P_H);
    out.delta_H_error = std::abs(out.state.delta_H - c.delta_H) / std::abs(out.state.delta_H);
  }
  if (!std::isfinite(out.state.P_H) || !std::isfinite(out.state.delta_H))
    throw NumericalError("layerjkr::exact_layer: the Nystrom solve is not finite at a = " +
                         format_double(a));
  return out;
}

std::vector<double> ExactLayerKernel::pressure(const Profile& profile, double a,
                                               const std::vector<double>& radii) const {
  const double rho = checked_a_over_h(*this, "ExactLayerKernel::pressure", profile, a);
  const Nystrom ny = nystrom_solve(*this, profile, a, panel_count(options_, rho),
                                   options_.points_per_panel);
  const double delta = ny.endf / ny.end0;
  // d/dt [t I0(t)] for the profile column, by 6th-order differences in ln t.
  auto rhs_f_slope = [&](double t) {
    auto g = [&](double x) {
      const double r = std::exp(x);
      return r * profile.sneddon(r).I0;
    };
    return boost::math::differentiation::finite_difference_derivative<decltype(g), double, 6>(
               g, std::log(t)) / t;
  };
  // g'(t) = (E*/pi) [delta phi0'(t) - phi_f'(t)] from the Nystrom interpolant.
  auto g_slope = [&](double t) {
    const double x = t / a;
    double d0 = 0.0, df = rhs_f_slope(t);
    for (Eigen::Index j = 0; j < ny.xi.size(); ++j) {
      const double kj = (ny.rho / kPi) * ny.w(j) * (ny.rho / a) *
                        (kernel_derivative(ny.rho * (x - ny.xi(j))) +
                         kernel_derivative(ny.rho * (x + ny.xi(j))));
      d0 += kj * ny.phi(j, 0);
      df += kj * ny.phi(j, 1);
    }
    return (E_star_ / kPi) * (delta * d0 - df);
  };
  static thread_local boost::math::quadrature::tanh_sinh<double> rule;
  std::vector<double> out;
  for (double r : radii) {
    if (!(r >= 0.0 && r < a))
      throw DomainError("ExactLayerKernel::pressure", "r", r, "[0, a) with a = " + format_double(a));
    // t^2 = r^2 + s^2 removes the inverse square root; s = u sqrt(a^2 - r^2), u in [0, 1].
    const double smax = std::sqrt((a - r) * (a + r));
    const double integral = rule.integrate(
        [&](double u) {
          // g' is odd and smooth, so g'(t)/t -> g''(0): below t0 = 1e-3 a its value at t0
          // is used (error O(1e-6) on a 1e-3 sliver), which keeps ln t finite.
          const double s = u * smax, t = std::max(std::sqrt(r * r + s * s), 1e-3 * a);
          return g_slope(t) / t * smax;
        },
        0.0, 1.0, 1e-10);
    out.push_back(-integral);
  }
  return out;
}

double ExactLayerKernel::flat_punch_factor(double a_over_h) const {
  detail::require_positive("ExactLayerKernel::flat_punch_factor", "a_over_h", a_over_h);
  const auto flat = make_paraboloid(1.0);  // any profile: only phi0 enters S
  const double a = a_over_h * layer_.h;
  return solve(*flat, a).state.S / (2.0 * E_star_ * a);
}

namespace {

class ExactLayerModel final : public ContactModel {
 public:
  ExactLayerModel(ProfilePtr p, const ElasticLayer& layer, ExactLayerOptions o)
      : ContactModel(std::move(p)), kernel_(layer, o) {}
  HertzState state(double a) const override { return kernel_.solve(profile(), a).state; }
  std::string name() const override { return model_name(ModelKind::exact); }
  double max_radius() const override {
    return std::min(profile().max_radius(),
                    kernel_.options().max_a_over_h * kernel_.layer().h);
  }

 private:
  ExactLayerKernel kernel_;
};

class EdgeCorrected final : public ContactModel {
 public:
  EdgeCorrected(ProfilePtr p, double K, double shift)
      : ContactModel(p), winkler_(make_winkler(std::move(p), K)), shift_(shift) {}
  HertzState state(double a) const override {
    if (!(a + shift_ > 0.0))
      throw DomainError("edge_corrected", "contact radius a", a,
                        "> -beta h = " + format_double(-shift_) +
                            " (the effective radius a + beta h must be positive)");
    HertzState s = winkler_->state(a + shift_);
    s.a = a;  // the JKR energy term uses the true contact radius
    return s;
  }
  std::string name() const override { return model_name(ModelKind::edge_corrected); }
  double min_radius() const override { return std::max(0.0, -shift_); }

 private:
  ContactModelPtr winkler_;
  double shift_;
};

}  // namespace

double edge_correction_beta(const ElasticLayer& layer) {
  if (!(layer.nu < 0.5))
    throw DomainError("edge_correction_beta", "nu", layer.nu,
                      "(-1, 0.5): the Winkler constant of an incompressible bonded layer is infinite");
  ExactLayerOptions o;
  o.max_a_over_h = 50.0;
  o.estimate_error = false;
  const ExactLayerKernel kernel({1.0, layer.nu, 1.0, layer.base}, o);  // dimensionless
  const double R = 1e4, a = 50.0;
  const auto paraboloid = make_paraboloid(R);
  // Winkler on a paraboloid: delta = (a + beta h)^2 / (2R).
  const double delta = kernel.solve(*paraboloid, a).state.delta_H;
  return std::sqrt(2.0 * R * delta) - a;
}

ContactModelPtr make_edge_corrected(ProfilePtr profile, const ElasticLayer& layer) {
  const ThinLayerConstants c = thin_layer_constants(layer);  // validates the layer
  return std::make_shared<EdgeCorrected>(std::move(profile), c.K,
                                         edge_correction_beta(layer) * layer.h);
}

ContactModelPtr make_exact_layer(ProfilePtr profile, const ElasticLayer& layer,
                                 ExactLayerOptions options) {
  return std::make_shared<ExactLayerModel>(std::move(profile), layer, options);
}

}  // namespace layerjkr
