// The Maugis-Dugdale contact pressure of DugdaleSolver (docs/theory.md s.4b).
#include <algorithm>
#include <cmath>
#include <vector>

#include <Eigen/Dense>
#include <boost/math/constants/constants.hpp>
#include <boost/math/differentiation/finite_difference.hpp>
#include <boost/math/quadrature/tanh_sinh.hpp>

#include "adhesion/dugdale_parts.hpp"
#include "adhesion/dugdale_solver.hpp"
#include "layerjkr/error.hpp"
#include "models/exact_layer_solver.hpp"

namespace layerjkr::detail {

std::vector<double> DugdaleSolver::maugis_dugdale_pressure(double a, double w, double sigma0,
                                                           const std::vector<double>& radii) const {
  const char* fn = "DugdaleSolver::maugis_dugdale_pressure";
  constexpr double pi = boost::math::constants::pi<double>();
  check(fn, a, w, sigma0);
  for (double r : radii)
    if (!std::isfinite(r) || r < 0.0) throw DomainError(fn, "r", r, "finite and >= 0");
  const AdhesiveState s = solve_md(a, w, sigma0, options_.points_per_panel);
  const Inner in = inner(a, options_.points_per_panel);
  const Zone z = zone(in, s.c, sigma0);
  const double c = s.c;
  // q'(t) [1] on [0, a]: -(t I0)' (6th-order differences in ln t) plus the kernel's action on q.
  auto q_slope = [&](double t) {
    auto term = [&](double x) { return profile_term(*profile_, std::exp(x)); };
    double slope = -boost::math::differentiation::finite_difference_derivative<decltype(term), double, 6>(
                       term, std::log(t)) / t;
    if (kernel_) {
      const double x = t / h_;
      double sum = 0.0;
      for (Eigen::Index j = 0; j < in.grid.t.size(); ++j)
        sum += in.grid.sqrt_w(j) * z.psi_q(j) *
               (kernel_->kernel_derivative(x - in.grid.t(j)) + kernel_->kernel_derivative(x + in.grid.t(j)));
      for (Eigen::Index k = 0; k < z.t_out.size(); ++k)
        sum += z.wt_out(k) * z.q_out(k) *
               (kernel_->kernel_derivative(x - z.t_out(k)) + kernel_->kernel_derivative(x + z.t_out(k)));
      slope += sum / (pi * h_);
    }
    return slope;
  };
  static thread_local boost::math::quadrature::tanh_sinh<double> rule;
  std::vector<double> out;
  out.reserve(radii.size());
  for (double r : radii) {
    if (r >= a) {
      out.push_back(r < c ? -sigma0 : 0.0);
      continue;
    }
    // t^2 = r^2 + s^2 removes the inverse square root; q' is odd, so q'(t)/t is regular at 0
    // (below t = 1e-3 a its value there is used, as ExactLayerKernel::pressure does).
    const double smax = std::sqrt((a - r) * (a + r));
    const double inner_part = rule.integrate(
        [&](double u) {
          const double t = std::max(std::sqrt(r * r + u * u * smax * smax), 1e-3 * a);
          return q_slope(t) / t * smax;
        },
        0.0, 1.0, 1e-10);
    const double zone_part = std::acos(std::max(-1.0, (2 * a * a - c * c - r * r) / ((c - r) * (c + r))));
    out.push_back(-(E_star_ / pi) * inner_part - (sigma0 / pi) * zone_part);
  }
  return out;
}

}  // namespace layerjkr::detail
