// Maugis-Dugdale and DMT on the half-space, the exact layer and stacks (docs/theory.md s.4b): the
// numerical core - the inner solve, the zone, the gap, c from the gap - that dugdale_states.cpp
// answers states with.
#include "adhesion/dugdale_solver.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <utility>

#include <Eigen/Dense>
#include <boost/math/constants/constants.hpp>
#include <boost/math/quadrature/tanh_sinh.hpp>
#include <boost/math/tools/roots.hpp>

#include "core/gsl_support.hpp"
#include "layerjkr/error.hpp"
#include "adhesion/dugdale_parts.hpp"
#include "adhesion/dugdale_table.hpp"
#include "models/exact_layer_solver.hpp"
#include "models/exact_power_law_table.hpp"

namespace layerjkr::detail {
namespace {

constexpr double kPi = boost::math::constants::pi<double>();

// Panels on an integral in theta (t = r cos theta) whose t-extent is `arc` h: as wide as the
// inner grid's panels, since the kernel varies on the scale h; 4 at least (the half-space's
// smooth integrands need no more).
int theta_panels(const ExactLayerOptions& o, double arc_over_h, bool layer) {
  const int by_width = layer ? static_cast<int>(std::ceil(arc_over_h / o.panel_width)) : 0;
  return std::max(4, by_width);
}

}  // namespace

DugdaleSolver::DugdaleSolver(ProfilePtr profile, std::shared_ptr<const ExactLayerKernel> kernel, bool tabulate)
    : profile_(std::move(profile)), kernel_(std::move(kernel)) {
  if (!profile_) throw DomainError("DugdaleSolver", "profile", 0.0, "a profile (not null)");
  if (!kernel_) throw DomainError("DugdaleSolver", "kernel", 0.0, "an exact-layer kernel (not null)");
  E_star_ = kernel_->effective_modulus();
  h_ = kernel_->layer().h;
  options_ = kernel_->options();
  if (tabulate && options_.tabulate_power_laws)
    if (const std::optional<PowerLawForm> form = profile_->power_law_form()) {
      form_ = *form;
      table_ = shared_dugdale_table(kernel_->medium(), form->d, options_);
      moments_table_ = shared_power_law_table(kernel_->medium(), form->d, options_);
    }
}

double DugdaleSolver::table_error() const { return table_ ? table_->measured_error() : 0.0; }

ExactMoments DugdaleSolver::moments(double a) const {
  const double rho = a / h_;
  if (a == 0.0) return ExactMoments{0.0, 0.0, 1.0, 0.0};
  if (moments_table_ && moments_table_->covers(rho)) {
    ExactMoments m = moments_table_->at(rho);
    const double scale = form_.B * std::pow(h_, form_.d);
    m.intf *= scale;
    m.endf *= scale;
    return m;
  }
  return exact_moments(*kernel_, *profile_, rho);
}


DugdaleSolver::DugdaleSolver(ProfilePtr profile, double E_star) : profile_(std::move(profile)) {
  if (!profile_) throw DomainError("DugdaleSolver", "profile", 0.0, "a profile (not null)");
  require_positive("DugdaleSolver", "E_star", E_star);
  E_star_ = E_star;
}

void DugdaleSolver::check(const char* function, double a, double w, double sigma0) const {
  if (!std::isfinite(a) || a < 0.0) throw DomainError(function, "a", a, "finite and >= 0");
  if (a > 0.0) {
    if (kernel_)
      checked_a_over_h(*kernel_, function, *profile_, a);
    else
      profile_->require_contact_radius(function, a);
  }
  require_non_negative(function, "w", w);
  require_positive(function, "sigma0", sigma0);
}

DugdaleSolver::Inner DugdaleSolver::inner(double a, int nodes) const {
  Inner in;
  in.a = a;
  in.rho = a / h_;
  in.nodes = nodes;
  in.mo.end0 = 1.0;
  if (a == 0.0) return in;
  if (!kernel_) {
    // Sneddon: q = delta - t I0(t); int_0^a t I0 dt = a^2 (I0 - I2) closes P.
    const SneddonIntegrals s = profile_->sneddon(a);
    in.mo.int0 = a;
    in.mo.intf = a * a * (s.I0 - s.I2);
    in.mo.endf = a * s.I0;
    return in;
  }
  const int panels = discretise(options_, in.rho).panels;
  in.grid = make_grid(in.rho, panels, nodes);
  const Grid& g = in.grid;
  Eigen::MatrixXd B;
  fill_symmetric_matrix(*kernel_, g, B);
  in.llt.compute(B);
  if (in.llt.info() != Eigen::Success)
    throw NumericalError("layerjkr::DugdaleSolver: the Nystrom matrix is not positive definite at a/h = " +
                         format_double(in.rho));
  Eigen::MatrixXd rhs(g.t.size(), 2);
  for (Eigen::Index i = 0; i < g.t.size(); ++i) {
    rhs(i, 0) = g.sqrt_w(i);
    rhs(i, 1) = g.sqrt_w(i) * profile_term(*profile_, h_ * g.t(i));
  }
  in.psi = in.llt.solve(rhs);
  in.row = edge_row(*kernel_, g, in.rho, g.t.size());
  in.mo.int0 = g.sqrt_w.dot(in.psi.col(0));
  in.mo.intf = g.sqrt_w.dot(in.psi.col(1));
  in.mo.end0 = 1.0 + in.row.dot(in.psi.col(0));
  in.mo.endf = profile_term(*profile_, a) + in.row.dot(in.psi.col(1));
  return in;
}

DugdaleSolver::Zone DugdaleSolver::zone(const Inner& in, double c, double sigma0) const {
  Zone z;
  z.c = c;
  z.gamma = c / h_;
  z.s0 = sigma0 / E_star_;
  const double theta_a = std::acos(std::min(1.0, in.a / c));
  z.theta = make_grid(theta_a, theta_panels(options_, z.gamma * theta_a, kernel_ != nullptr), in.nodes);
  const Eigen::Index m = z.theta.t.size();
  z.t_out.resize(m);
  z.wt_out.resize(m);
  z.q_out.resize(m);
  for (Eigen::Index k = 0; k < m; ++k) {
    const double sn = std::sin(z.theta.t(k));
    z.t_out(k) = z.gamma * std::cos(z.theta.t(k));
    z.wt_out(k) = z.theta.w(k) * z.gamma * sn;  // dt/h = (c/h) sin(theta) dtheta
    z.q_out(k) = -2.0 * z.s0 * c * sn;
  }
  // The kernel between the [a, c] nodes and themselves and the inner nodes, each value once:
  // phi_D's right-hand side (1/pi) int_a^c q_D K(x, t) dt and the gap at c both use them.
  const Eigen::VectorXd wq = z.wt_out.cwiseProduct(z.q_out);
  const Eigen::Index n = in.grid.t.size();
  auto K = [&](double x, double t) { return kernel_->kernel(x - t) + kernel_->kernel(x + t); };
  Eigen::VectorXd self = Eigen::VectorXd::Zero(m);
  Eigen::MatrixXd cross(m, n);
  if (kernel_) {
    for (Eigen::Index k = 0; k < m; ++k) {
      for (Eigen::Index l = 0; l < k; ++l) {
        const double v = K(z.t_out(k), z.t_out(l));
        self(k) += wq(l) * v;
        self(l) += wq(k) * v;
      }
      self(k) += wq(k) * K(z.t_out(k), z.t_out(k));
      for (Eigen::Index j = 0; j < n; ++j) cross(k, j) = K(z.t_out(k), in.grid.t(j));
    }
  }
  auto rhs_D = [&](double x) {
    double sum = 0.0;
    for (Eigen::Index k = 0; k < m; ++k) sum += wq(k) * K(x, z.t_out(k));
    return sum / kPi;
  };
  double endD = 0.0;
  Eigen::VectorXd psiD;
  if (in.system()) {
    psiD = in.llt.solve(Eigen::VectorXd(in.grid.sqrt_w.cwiseProduct(cross.transpose() * wq) / kPi));
    endD = rhs_D(in.rho) + in.row.dot(psiD);
    z.intD = in.grid.sqrt_w.dot(psiD);
  } else if (kernel_) {
    endD = rhs_D(0.0);  // a = 0: no unknowns, the zone's own displacement at the centre
  }
  // g continuous at a: delta end0 - endf + endD = q_D(a).
  z.delta_H = in.mo.endf / in.mo.end0;
  z.delta = (z.q_outer(in.rho, h_) - endD) / in.mo.end0 + z.delta_H;
  if (in.system()) z.psi_q = z.delta * in.psi.col(0) - in.psi.col(1) + psiD;
  // The gap at c on the same theta rule: (2/pi) sum omega_k H(t_k) (see gap_at).
  Eigen::VectorXd kernel_part = self;
  if (in.system()) kernel_part += cross * in.grid.sqrt_w.cwiseProduct(z.psi_q);
  // And the non-adhesive state's (the profile's part alone; the same kernel values).
  Eigen::VectorXd kernel_H = Eigen::VectorXd::Zero(m);
  if (in.system()) kernel_H = cross * in.grid.sqrt_w.cwiseProduct(z.delta_H * in.psi.col(0) - in.psi.col(1));
  double sum = 0.0, sum_H = 0.0;
  for (Eigen::Index k = 0; k < m; ++k) {
    const double profile = profile_term(*profile_, h_ * z.t_out(k));
    sum += z.theta.w(k) * (z.q_out(k) - kernel_part(k) / kPi - z.delta + profile);
    sum_H += z.theta.w(k) * (-kernel_H(k) / kPi - z.delta_H + profile);
  }
  z.gap_c = (2.0 / kPi) * sum;
  z.gap_profile = (2.0 / kPi) * sum_H;
  return z;
}

// The gap (2/pi) int_a^r H(t) / sqrt(r^2 - t^2) dt with H = Q - D (docs/theory.md s.4b): Q the
// surface term (q on the zone, minus the kernel's action on q over [0, c]), D = delta - t I0.
double DugdaleSolver::gap_at(const Inner& in, const Zone* zp, double r) const {
  if (r <= in.a) return 0.0;
  if (zp && r == zp->c) return zp->gap_c;
  const Zone empty{};
  const Zone& z = zp ? *zp : empty;
  const double delta = zp ? z.delta : in.mo.endf / in.mo.end0;
  Eigen::VectorXd psi_q;
  if (in.system()) psi_q = zp ? z.psi_q : Eigen::VectorXd(delta * in.psi.col(0) - in.psi.col(1));
  auto H = [&](double t_over_h) {
    double Q = z.q_outer(t_over_h, h_);
    if (kernel_) {
      double sum = 0.0;
      if (in.system())
        for (Eigen::Index j = 0; j < in.grid.t.size(); ++j)
          sum += in.grid.sqrt_w(j) * psi_q(j) *
                 (kernel_->kernel(t_over_h - in.grid.t(j)) + kernel_->kernel(t_over_h + in.grid.t(j)));
      for (Eigen::Index k = 0; k < z.t_out.size(); ++k)
        sum += z.wt_out(k) * z.q_out(k) *
               (kernel_->kernel(t_over_h - z.t_out(k)) + kernel_->kernel(t_over_h + z.t_out(k)));
      Q -= sum / kPi;
    }
    return Q - delta + profile_term(*profile_, h_ * t_over_h);
  };
  const double rho_r = r / h_;
  // theta in [0, theta_a]: t = r cos(theta); sqrt(r^2 - t^2) dtheta-cancels the Abel kernel.
  auto integrand = [&](double theta) { return H(rho_r * std::cos(theta)); };
  const double theta_a = std::acos(in.a / r);
  if (!zp) {  // smooth: no q_D
    const Grid rule = make_grid(theta_a, theta_panels(options_, rho_r * theta_a, kernel_ != nullptr), in.nodes);
    double sum = 0.0;
    for (Eigen::Index k = 0; k < rule.t.size(); ++k) sum += rule.w(k) * integrand(rule.t(k));
    return (2.0 / kPi) * sum;
  }
  // Inside the zone or beyond it q_D(r cos theta) has a square root at theta_c = acos(c/r) (or a
  // near one at theta = 0): tanh-sinh, split there. (At r = c, zone() has the gap on its rule.)
  static thread_local boost::math::quadrature::tanh_sinh<double> rule;
  const double tol = 1e-12;
  if (r < z.c) return (2.0 / kPi) * rule.integrate(integrand, 0.0, theta_a, tol);
  const double theta_c = std::acos(z.c / r);
  return (2.0 / kPi) *
         (rule.integrate(integrand, 0.0, theta_c, tol) + rule.integrate(integrand, theta_c, theta_a, tol));
}

double DugdaleSolver::find_c(double a, double h0, const char* function, double sigma0,
                             const std::function<double(double)>& gap) const {
  // c ranges over (a, c_max]: the profile's domain and, on a layer, the kernel's table.
  double c_max = profile_->max_radius();
  if (kernel_) c_max = std::min(c_max, options_.max_a_over_h * h_);
  auto f = [&](double c) { return gap(c) - h0; };
  double lo = a, f_lo = -h0;
  double step = a > 0.0 ? 1e-2 * a : 1e-2 * std::sqrt(h0 * profile_->length_scale());
  double hi = a + step, f_hi = 0.0;
  for (int i = 0;; ++i) {
    if (!(hi < c_max)) {
      hi = std::nextafter(c_max, 0.0);
      if (!profile_->contains(hi)) hi = c_max * (1.0 - 1e-12);
    }
    f_hi = f(hi);
    if (!std::isfinite(f_hi))
      throw NumericalError(std::string("layerjkr::") + function + ": the gap is not finite at c = " +
                           format_double(hi));
    if (f_hi >= 0.0) break;
    if (!(hi < c_max * (1.0 - 1e-12)) || i > 200)
      throw DomainError(function, "sigma0", sigma0,
                        "large enough that the gap reaches h0 = w/sigma0 = " + format_double(h0) +
                            " m before c = " + format_double(c_max) +
                            " m (the profile's max_radius or max_a_over_h h)");
    lo = hi;
    f_lo = f_hi;
    step *= 4.0;
    hi = a + step;
  }
  if (f_hi == 0.0) return hi;
  std::uintmax_t iterations = 100;
  const auto root = boost::math::tools::toms748_solve(f, lo, hi, f_lo, f_hi,
                                                      boost::math::tools::eps_tolerance<double>(44), iterations);
  return 0.5 * (root.first + root.second);
}

DugdaleParts DugdaleSolver::parts(double a, double c, int nodes) const {
  const char* fn = "DugdaleSolver::parts";
  check(fn, a, 0.0, 1.0);
  if (!(c > a)) throw DomainError(fn, "c", c, "> a = " + format_double(a));
  check(fn, c, 0.0, 1.0);
  const Inner in = inner(a, nodes);
  const Zone z = zone(in, c, E_star_);  // s0 = 1
  DugdaleParts p;
  p.delta_H = z.delta_H;
  p.int0 = in.mo.int0;
  p.intf = in.mo.intf;
  p.D = z.delta - z.delta_H;
  p.P = 2.0 * h_ * (p.D * in.mo.int0 + z.intD) -
        2.0 * (c * c * std::acos(std::min(1.0, a / c)) - a * std::sqrt((c - a) * (c + a)));
  p.G = z.gap_c - z.gap_profile;
  p.F = z.gap_profile;
  return p;
}

}  // namespace layerjkr::detail
