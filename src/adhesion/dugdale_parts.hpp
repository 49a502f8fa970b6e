// Internal to adhesion/dugdale_solver*.cpp: the solver's intermediate states, shared by the
// state and gap code (dugdale_solver.cpp) and the pressure (dugdale_pressure.cpp).
#pragma once

#include <cmath>

#include <Eigen/Dense>

#include "adhesion/dugdale_solver.hpp"
#include "models/exact_layer_solver.hpp"

namespace layerjkr::detail {

// The factorised system on [0, a] and its flat-punch and profile columns.
struct DugdaleSolver::Inner {
  double a = 0.0, rho = 0.0;  // rho = a/h
  int nodes = 0;              // Gauss-Legendre nodes a panel, inner and outer rules alike
  Grid grid;                  // empty for a = 0 and for the half-space
  Eigen::LLT<Eigen::MatrixXd> llt;
  Eigen::MatrixXd psi;  // W^1/2 phi0, W^1/2 phi_f
  Eigen::VectorXd row;  // the interpolant's row at rho
  ExactMoments mo;      // int0, intf [units of h, m h], end0, endf
  bool system() const { return grid.t.size() > 0; }
};

// One adhesive configuration: the Dugdale zone [a, c] under s0 = sigma0/E* (none for DMT's
// non-adhesive state) and the resulting q = (pi/E*) g on the inner nodes.
struct DugdaleSolver::Zone {
  double c = 0.0, gamma = 0.0, s0 = 0.0;  // c [m], c/h, sigma0/E*
  double delta = 0.0;                     // [m]
  double delta_H = 0.0;                   // its non-adhesive part, endf/end0 [m]
  double gap_profile = 0.0;               // the gap at c of the non-adhesive state (s0 = 0) [m]
  double intD = 0.0;                      // int_0^a phi_D dt/h [m]
  double gap_c = 0.0;                     // the gap at c [m]
  Eigen::VectorXd psi_q;                  // W^1/2 q on the inner nodes [m]
  Grid theta;                             // Gauss-Legendre in theta on [0, acos(a/c)]
  Eigen::VectorXd t_out, wt_out, q_out;   // t/h, weight in t/h, q = -2 s0 sqrt(c^2 - t^2) [m]
  double q_outer(double t_over_h, double h) const {
    return t_over_h < gamma ? -2.0 * s0 * h * std::sqrt((gamma - t_over_h) * (gamma + t_over_h)) : 0.0;
  }
};

}  // namespace layerjkr::detail
