// Internal: what the exact layer's Nystrom solve yields, shared by the solver
// (exact_layer_solver.cpp), the ContactModel "exact" (exact_layer_model.cpp) and the
// per-(nu, base, d) power-law tables (exact_power_law_table.cpp).
#pragma once

#include <vector>

#include <Eigen/Dense>

#include "layerjkr/exact_layer.hpp"
#include "layerjkr/profile.hpp"

namespace layerjkr::detail {

// The flat-punch solution phi0 and the profile's phi_f: their integrals over [0, a/h] (in
// units of h) and their values at the edge. A state is a closed form in these.
struct ExactMoments {
  double int0 = 0.0, intf = 0.0, end0 = 0.0, endf = 0.0;
};

// delta_H = phi_f(a)/phi0(a), S = 2E* h int phi0, P_H = 2E* h (delta_H int phi0 - int phi_f),
// S' = 2E* phi0(a)^2 (docs/theory.md s.4): no differentiation anywhere.
inline NonAdhesiveState exact_state_from(const ExactMoments& mo, double a, double h, double E_star) {
  NonAdhesiveState s;
  s.a = a;
  s.delta_H = mo.endf / mo.end0;
  s.S = 2.0 * E_star * h * mo.int0;
  s.P_H = 2.0 * E_star * h * (s.delta_H * mo.int0 - mo.intf);
  s.dS_da = 2.0 * E_star * mo.end0 * mo.end0;
  return s;
}

// Composite Gauss-Legendre grid in units of h on [0, rho]: `panels` equal panels of width
// b = rho / panels, p nodes each; node k p + q sits at b (k + s_q) with weight b v_q.
struct Grid {
  int panels = 0, p = 0;
  double b = 0.0;
  std::vector<double> s, v;  // the rule's nodes and weights on [0, 1]
  Eigen::VectorXd t, w;      // nodes and weights [h]
  Eigen::VectorXd sqrt_w;
};
Grid make_grid(double rho, int panels, int p);

// The distinct p x p blocks of the kernel matrix on an equal-panel grid:
// toeplitz[d](i, j) = Ft(b (d + s_i - s_j)), d = 0..m-1 (offset -d is the transpose), and
// hankel[e](i, j) = Ft(b (e + s_i + s_j)), e = 0..2m-2.
struct KernelBlocks {
  std::vector<Eigen::MatrixXd> toeplitz, hankel;
};
KernelBlocks kernel_blocks(const ExactLayerKernel& kernel, const Grid& grid);

// The symmetrised Nystrom matrix B = I - (1/pi) W^1/2 [Ft(t_i - t_j) + Ft(t_i + t_j)] W^1/2 on
// the grid (symmetric positive definite: the operator's symbol L(u) is a compliance).
void fill_symmetric_matrix(const ExactLayerKernel& kernel, const Grid& grid, Eigen::MatrixXd& B);

// The Nystrom interpolant's kernel row at t = rho (units of h) over the first n nodes,
// premultiplied by W^1/2, so that phi(rho) = rhs(rho) + row . psi for psi = W^1/2 phi.
Eigen::VectorXd edge_row(const ExactLayerKernel& kernel, const Grid& grid, double rho, Eigen::Index n);

// The profile's right-hand side x I0(x) = x int_0^x f'(r)/sqrt(x^2 - r^2) dr [m] at x [m].
double profile_term(const Profile& profile, double x);

// One Nystrom solve at a/h = rho with the kernel's options (no range checks).
ExactMoments exact_moments(const ExactLayerKernel& kernel, const Profile& profile, double rho);

// a/h for a query at contact radius a, after checking a against the profile and the
// kernel table's range (ExactLayerOptions::max_a_over_h); `function` names the caller.
double checked_a_over_h(const ExactLayerKernel& kernel, const char* function, const Profile& profile,
                        double a);

// The grid of one radius rho = a/h: `panels` panels of `nodes` Gauss-Legendre nodes.
struct Discretisation {
  int panels, nodes;
};
Discretisation discretise(const ExactLayerOptions& options, double rho);

// A sweep over count steps of [0, rho] uses a whole number of panels per step, each at most
// panel_width h wide, and at least min_panels in all.
int sweep_panels_per_step(const ExactLayerOptions& options, double rho, int count);

}  // namespace layerjkr::detail
