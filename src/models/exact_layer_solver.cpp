// Exact elastic layer: the Nystrom solver (Eigen) on the kernel of models/layer_kernel.hpp -
// grids, the dense and iterative solves, sweeps and the contact pressure.
#include "layerjkr/exact_layer.hpp"

#include <gsl/gsl_integration.h>

#include <algorithm>
#include <utility>
#include <cmath>
#include <limits>

#include <Eigen/Dense>
#include <boost/math/differentiation/finite_difference.hpp>
#include <boost/math/quadrature/tanh_sinh.hpp>
#include <boost/math/constants/constants.hpp>

#include "core/gsl_support.hpp"
#include "models/exact_layer_iterative.hpp"
#include "models/exact_layer_solver.hpp"
#include "models/layer_kernel.hpp"
#include "layerjkr/error.hpp"

namespace layerjkr {
namespace {

constexpr double kPi = boost::math::constants::pi<double>();

struct GlFree {
  void operator()(gsl_integration_glfixed_table* t) const { gsl_integration_glfixed_table_free(t); }
};

}  // namespace

void ExactLayerOptions::validate() const {
  const char* fn = "ExactLayerOptions::validate";
  if (!(max_a_over_h > 0.0 && max_a_over_h <= 1000.0))
    throw DomainError(fn, "max_a_over_h", max_a_over_h, "(0, 1000]");
  if (points_per_panel < 4 || points_per_panel > 32)
    throw DomainError(fn, "points_per_panel", points_per_panel, "[4, 32]");
  if (!(panel_width > 0.0 && panel_width <= 8.0))
    throw DomainError(fn, "panel_width", panel_width, "(0, 8]");
  if (min_panels < 2) throw DomainError(fn, "min_panels", min_panels, ">= 2");
  if (dense_max_unknowns < 1) throw DomainError(fn, "dense_max_unknowns", dense_max_unknowns, ">= 1");
}

ExactLayerKernel::ExactLayerKernel(const ElasticLayer& layer, ExactLayerOptions options)
    : layer_(layer), medium_(LayeredMedium::single(layer)), options_(std::move(options)) {
  detail::silence_gsl_errors();
  options_.validate();
  detail::require_positive("ExactLayerKernel", "h", layer.h);
  E_star_ = layerjkr::effective_modulus(layer.E, layer.nu);  // validates E, nu in (-1, 0.5]
  kernel_ = detail::shared_layer_kernel(layer.nu, layer.base == Base::bonded, options_.context);
  // Holding the Context would make a cycle for the power-law tables it caches, whose unit
  // solver is an ExactLayerKernel: a private Context would never be freed.
  options_.context.reset();
}

ExactLayerKernel::ExactLayerKernel(const LayeredMedium& medium, ExactLayerOptions options)
    : layer_(medium.top()), medium_(medium), options_(std::move(options)) {
  detail::silence_gsl_errors();
  options_.validate();
  medium.validate("ExactLayerKernel");
  E_star_ = layerjkr::effective_modulus(layer_.E, layer_.nu);
  kernel_ = detail::shared_stack_kernel(medium, options_.context);
  // Holding the Context would make a cycle for the power-law tables it caches, whose unit
  // solver is an ExactLayerKernel: a private Context would never be freed.
  options_.context.reset();
}

ExactLayerKernel::~ExactLayerKernel() = default;

double ExactLayerKernel::kernel(double sigma) const {
  if (!std::isfinite(sigma)) throw DomainError("ExactLayerKernel::kernel", "sigma", sigma, "finite");
  return kernel_->value(sigma);
}

double ExactLayerKernel::kernel_derivative(double sigma) const {
  if (!std::isfinite(sigma))
    throw DomainError("ExactLayerKernel::kernel_derivative", "sigma", sigma, "finite");
  return kernel_->derivative(sigma);
}

using detail::checked_a_over_h;
using detail::discretise;
using detail::Discretisation;
using detail::Grid;
using detail::make_grid;

Grid detail::make_grid(double rho, int panels, int p) {
  std::unique_ptr<gsl_integration_glfixed_table, GlFree> gl(
      gsl_integration_glfixed_table_alloc(static_cast<std::size_t>(p)));
  Grid g;
  g.panels = panels;
  g.p = p;
  g.b = rho / panels;
  std::vector<double>& v = g.v;
  v.resize(static_cast<std::size_t>(p));
  g.s.resize(static_cast<std::size_t>(p));
  for (int q = 0; q < p; ++q)
    gsl_integration_glfixed_point(0.0, 1.0, static_cast<std::size_t>(q), &g.s[q], &v[q], gl.get());
  const int n = panels * p;
  g.t.resize(n);
  g.w.resize(n);
  for (int k = 0; k < panels; ++k)
    for (int q = 0; q < p; ++q) {
      g.t(k * p + q) = g.b * (k + g.s[q]);
      g.w(k * p + q) = g.b * v[q];
    }
  g.sqrt_w = g.w.cwiseSqrt();
  return g;
}

detail::KernelBlocks detail::kernel_blocks(const ExactLayerKernel& k, const Grid& g) {
  const int m = g.panels, p = g.p;
  KernelBlocks out;
  out.toeplitz.assign(static_cast<std::size_t>(m), Eigen::MatrixXd(p, p));
  out.hankel.assign(static_cast<std::size_t>(2 * m - 1), Eigen::MatrixXd(p, p));
  for (int d = 0; d < m; ++d)
    for (int i = 0; i < p; ++i)
      for (int j = 0; j < p; ++j) out.toeplitz[d](i, j) = k.kernel(g.b * (d + g.s[i] - g.s[j]));
  for (int e = 0; e < 2 * m - 1; ++e)
    for (int i = 0; i < p; ++i)
      for (int j = 0; j <= i; ++j)
        out.hankel[e](i, j) = out.hankel[e](j, i) = k.kernel(g.b * (e + g.s[i] + g.s[j]));
  return out;
}

// With equal panels the first part is block Toeplitz and the second block Hankel, so only
// (2m-1) p^2 + m p^2 distinct kernel values are needed instead of (m p)^2. B is symmetric
// positive definite: the operator's symbol is L(u) > 0, a compliance (for one layer the
// kernel's 1 - L lies in (0, 1]; for a stack on a soft substrate 1 - L may be negative).
void detail::fill_symmetric_matrix(const ExactLayerKernel& k, const Grid& g, Eigen::MatrixXd& B) {
  const int m = g.panels, p = g.p, n = m * p;
  const detail::KernelBlocks blocks = detail::kernel_blocks(k, g);
  B.resize(n, n);
  for (int kb = 0; kb < m; ++kb)
    for (int lb = 0; lb <= kb; ++lb) {
      const Eigen::MatrixXd& T = blocks.toeplitz[kb - lb];
      const Eigen::MatrixXd& H = blocks.hankel[kb + lb];
      for (int i = 0; i < p; ++i)
        for (int j = 0; j < p; ++j) {
          const int r = kb * p + i, c = lb * p + j;
          const double v = -(1.0 / kPi) * g.sqrt_w(r) * g.sqrt_w(c) * (T(i, j) + H(i, j));
          B(r, c) = B(c, r) = v + (r == c ? 1.0 : 0.0);
        }
    }
}

double detail::profile_term(const Profile& profile, double x) { return x * profile.sneddon(x).I0; }

Eigen::VectorXd detail::edge_row(const ExactLayerKernel& k, const Grid& g, double rho, Eigen::Index n) {
  Eigen::VectorXd row(n);
  for (Eigen::Index j = 0; j < n; ++j)
    row(j) = (1.0 / kPi) * g.sqrt_w(j) * (k.kernel(rho - g.t(j)) + k.kernel(rho + g.t(j)));
  return row;
}

namespace {
using detail::edge_row;
using detail::fill_symmetric_matrix;
using detail::profile_term;

// Right-hand sides on the nodes: 1 (flat punch) and the profile term at x = h t.
Eigen::MatrixXd right_hand_sides(const Profile& profile, double h, const Eigen::VectorXd& t) {
  Eigen::MatrixXd rhs(t.size(), 2);
  for (Eigen::Index i = 0; i < t.size(); ++i) {
    rhs(i, 0) = 1.0;
    rhs(i, 1) = profile_term(profile, h * t(i));
  }
  return rhs;
}

using Moments = detail::ExactMoments;
using detail::exact_state_from;

// One radius: factor B (Cholesky) on `panels` panels of [0, rho] and solve both columns.
struct Solution {
  Grid grid;
  Eigen::MatrixXd phi;  // phi0, phi_f on the nodes
  Moments moments;
};

// The Cholesky factor of B, computed in place in `storage`. Small systems reuse one
// per-thread buffer: allocating and faulting in a fresh matrix for every state cost more
// than the factorisation itself (measured 3.4 ms against 0.8 ms at a/h = 50).
using Factor = Eigen::LLT<Eigen::Ref<Eigen::MatrixXd>>;
constexpr Eigen::Index kReusedUnknowns = 1024;  // 8 MB a thread at most

Eigen::MatrixXd& factor_storage(Eigen::Index n, Eigen::MatrixXd& local) {
  static thread_local Eigen::MatrixXd reused;
  return n <= kReusedUnknowns ? reused : local;
}

Factor factor(const ExactLayerKernel& k, const Grid& g, double rho, Eigen::MatrixXd& storage) {
  fill_symmetric_matrix(k, g, storage);
  Factor llt(storage);
  if (llt.info() != Eigen::Success)
    throw NumericalError("layerjkr::exact_layer: the Nystrom matrix is not positive definite at a/h = " +
                         format_double(rho));
  return llt;
}

Eigen::MatrixXd dense_solve(const ExactLayerKernel& k, const Grid& g, double rho, const Eigen::MatrixXd& rhs) {
  Eigen::MatrixXd local;
  return factor(k, g, rho, factor_storage(g.t.size(), local)).solve(rhs);
}

Solution nystrom_solve(const ExactLayerKernel& k, const Profile& profile, double rho, int panels, int p) {
  const double h = k.layer().h;
  Solution out;
  out.grid = make_grid(rho, panels, p);
  const Grid& g = out.grid;
  const Eigen::MatrixXd rhs = g.sqrt_w.asDiagonal() * right_hand_sides(profile, h, g.t);
  const Eigen::MatrixXd psi = g.t.size() > k.options().dense_max_unknowns
                                  ? detail::solve_iteratively(k, g, rhs).psi
                                  : dense_solve(k, g, rho, rhs);
  const Eigen::VectorXd row = edge_row(k, g, rho, psi.rows());
  Moments& mo = out.moments;
  mo.int0 = g.sqrt_w.dot(psi.col(0));
  mo.intf = g.sqrt_w.dot(psi.col(1));
  mo.end0 = 1.0 + row.dot(psi.col(0));
  mo.endf = profile_term(profile, h * rho) + row.dot(psi.col(1));
  out.phi = g.sqrt_w.cwiseInverse().asDiagonal() * psi;
  return out;
}

int panel_count(const ExactLayerOptions& o, double rho) {
  return std::max(o.min_panels, static_cast<int>(std::ceil(rho / o.panel_width)));
}

}  // namespace

// Every panel keeps points_per_panel nodes, however narrow: fewer on narrow panels cut
// small-a/h states 3x but cost non-smooth profiles (r^1.5, tables) an order of accuracy
// (measured: 2e-9 against 2e-10).
detail::Discretisation detail::discretise(const ExactLayerOptions& o, double rho) {
  return {panel_count(o, rho), o.points_per_panel};
}

detail::ExactMoments detail::exact_moments(const ExactLayerKernel& k, const Profile& profile, double rho) {
  const Discretisation d = discretise(k.options(), rho);
  return nystrom_solve(k, profile, rho, d.panels, d.nodes).moments;
}

namespace {

// Every radius rho_j = j b (j = 1..panels) from one factorisation on [0, rho_max]: the
// matrix for j panels is the leading block of the full one, so with B = L L^T
// psi_j = L_j^-T y_j where y = L^-1 W^1/2 rhs is shared. Integrals are running sums
// z . y (z = L^-1 W^1/2 1), and each edge value needs one triangular solve L_j^-1 row_j.
std::vector<Moments> nystrom_sweep(const ExactLayerKernel& k, const Profile& profile, double rho_max,
                                   int panels, int p) {
  const double h = k.layer().h;
  const Grid g = make_grid(rho_max, panels, p);
  Eigen::MatrixXd local;
  const Factor llt = factor(k, g, rho_max, factor_storage(g.t.size(), local));
  const auto L = llt.matrixL();
  Eigen::MatrixXd y = g.sqrt_w.asDiagonal() * right_hand_sides(profile, h, g.t);
  L.solveInPlace(y);
  Eigen::VectorXd z = g.sqrt_w;
  L.solveInPlace(z);
  const Eigen::MatrixXd& full = llt.matrixLLT();
  std::vector<Moments> out(static_cast<std::size_t>(panels));
  double int0 = 0.0, intf = 0.0;
  for (int j = 1; j <= panels; ++j) {
    const Eigen::Index n = static_cast<Eigen::Index>(j) * p;
    for (Eigen::Index i = n - p; i < n; ++i) {
      int0 += z(i) * y(i, 0);
      intf += z(i) * y(i, 1);
    }
    const double rho = j * g.b;
    Eigen::VectorXd e = edge_row(k, g, rho, n);
    full.topLeftCorner(n, n).triangularView<Eigen::Lower>().solveInPlace(e);
    Moments& mo = out[static_cast<std::size_t>(j - 1)];
    mo.int0 = int0;
    mo.intf = intf;
    mo.end0 = 1.0 + e.dot(y.col(0).head(n));
    mo.endf = profile_term(profile, h * rho) + e.dot(y.col(1).head(n));
  }
  return out;
}

}  // namespace

int detail::sweep_panels_per_step(const ExactLayerOptions& o, double rho, int count) {
  return std::max({1, static_cast<int>(std::ceil(rho / count / o.panel_width)),
                   (o.min_panels + count - 1) / count});
}

double detail::checked_a_over_h(const ExactLayerKernel& k, const char* function, const Profile& profile,
                                double a) {
  profile.require_contact_radius(function, a);
  const double rho = a / k.layer().h;
  // A few ulps of slack: a = 1 mm on h = 1 um gives a/h = 1000.0000000000001.
  if (!(rho <= k.options().max_a_over_h * (1.0 + 8.0 * std::numeric_limits<double>::epsilon())))
    throw DomainError(function, "a/h", rho,
                      "(0, " + format_double(k.options().max_a_over_h) +
                          "] (ExactLayerOptions::max_a_over_h)");
  return rho;
}

NonAdhesiveState ExactLayerKernel::state(const Profile& profile, double a) const {
  const double rho = checked_a_over_h(*this, "exact_layer", profile, a);
  const NonAdhesiveState s = exact_state_from(detail::exact_moments(*this, profile, rho), a, layer_.h, E_star_);
  if (!std::isfinite(s.P_H) || !std::isfinite(s.delta_H))
    throw NumericalError("layerjkr::exact_layer: the Nystrom solve is not finite at a = " + format_double(a));
  return s;
}

ExactLayerState ExactLayerKernel::solve(const Profile& profile, double a) const {
  ExactLayerState out;
  out.state = state(profile, a);
  const double rho = a / layer_.h;
  const Discretisation d = discretise(options_, rho);
  const int panels = d.panels, p = d.nodes;
  out.unknowns = panels * p;
  out.P_H_error = out.delta_H_error = out.S_error = std::numeric_limits<double>::quiet_NaN();
  if (options_.estimate_error) {  // the same panels with 3/4 of the nodes
    const int coarse = std::max(2, 3 * p / 4);
    const NonAdhesiveState c =
        exact_state_from(nystrom_solve(*this, profile, rho, panels, coarse).moments, a, layer_.h, E_star_);
    // Each at least the kernel's own accuracy: the transform is integrated to 1e-13 of its size
    // (layer_kernel.cpp), and the solve's rounding shows in the last digits (measured 1e-13 at
    // most on the random stack matrix, tests/models/test_stack_matrix.cpp).
    constexpr double kKernelAccuracy = 1e-12;
    out.P_H_error = std::max(kKernelAccuracy, std::abs(out.state.P_H - c.P_H) / std::abs(out.state.P_H));
    out.delta_H_error = std::max(kKernelAccuracy, std::abs(out.state.delta_H - c.delta_H) / std::abs(out.state.delta_H));
    out.S_error = std::max(kKernelAccuracy, std::abs(out.state.S - c.S) / std::abs(out.state.S));
  }
  return out;
}

std::vector<NonAdhesiveState> ExactLayerKernel::sweep(const Profile& profile, double a_max, int count) const {
  if (count < 1) throw DomainError("ExactLayerKernel::sweep", "count", count, ">= 1");
  const double rho = checked_a_over_h(*this, "ExactLayerKernel::sweep", profile, a_max);
  const int per_step = detail::sweep_panels_per_step(options_, rho, count);
  const std::vector<Moments> all =
      nystrom_sweep(*this, profile, rho, per_step * count, options_.points_per_panel);
  std::vector<NonAdhesiveState> out;
  for (int j = 1; j <= count; ++j) {
    const double a = a_max * j / count;
    NonAdhesiveState s = exact_state_from(all[static_cast<std::size_t>(j * per_step - 1)], a, layer_.h, E_star_);
    if (!std::isfinite(s.P_H) || !std::isfinite(s.delta_H))
      throw NumericalError("layerjkr::exact_layer: the Nystrom sweep is not finite at a = " + format_double(a));
    out.push_back(s);
  }
  return out;
}

std::vector<double> ExactLayerKernel::pressure(const Profile& profile, double a,
                                               const std::vector<double>& radii) const {
  const double rho = checked_a_over_h(*this, "ExactLayerKernel::pressure", profile, a);
  const Discretisation d = discretise(options_, rho);
  const Solution ny = nystrom_solve(*this, profile, rho, d.panels, d.nodes);
  const double delta = ny.moments.endf / ny.moments.end0;
  const double h = layer_.h;
  // d/dt [t I0(t)] for the profile column, by 6th-order differences in ln t.
  auto rhs_f_slope = [&](double t) {
    auto g = [&](double x) {
      const double r = std::exp(x);
      return profile_term(profile, r);
    };
    return boost::math::differentiation::finite_difference_derivative<decltype(g), double, 6>(
               g, std::log(t)) / t;
  };
  // g'(t) = (E*/pi) [delta phi0'(t) - phi_f'(t)] from the Nystrom interpolant.
  auto g_slope = [&](double t) {
    const double x = t / h;  // units of h
    double d0 = 0.0, df = rhs_f_slope(t);
    for (Eigen::Index j = 0; j < ny.grid.t.size(); ++j) {
      const double kj = ny.grid.w(j) / (kPi * h) *
                        (kernel_derivative(x - ny.grid.t(j)) + kernel_derivative(x + ny.grid.t(j)));
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

}  // namespace layerjkr
