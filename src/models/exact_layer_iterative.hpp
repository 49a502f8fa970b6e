// Internal: the exact layer's symmetrised Nystrom system B psi = rhs solved without forming
// B, for large a/h (docs/exact-layer.md).
//
// * Products: with equal panels B = I - (1/pi) S (T + H) S, T block Toeplitz and H block
//   Hankel (S = W^1/2 is the same on every panel). For every node pair (i, j) of a panel,
//   T and H act on the panel index as scalar convolutions, so B x costs 2p real FFTs
//   forward, p back and 2p^2 spectral products (Eigen's FFT): O(p^2 m log m) for m panels,
//   against (m p)^2 for a dense product and (m p)^3 / 3 for a Cholesky factor.
// * Preconditioner: B's symbol is L(u), which vanishes like (2/3) u^3 at low frequency for an
//   incompressible bonded layer (condition number ~0.2 (a/h)^3) and tends to 1 at high
//   frequency. So the badly conditioned modes are the smooth ones, and a two-level
//   preconditioner removes them: the coarse space Z is the Legendre polynomials of degree <
//   q on every panel (orthonormal in the quadrature's inner product), the coarse operator
//   is the Galerkin projection E = Z^T B Z of the fine operator (assembled from the same
//   Toeplitz and Hankel blocks; re-discretising the equation on a coarse grid instead is
//   indefinite at nu = 0.5), and M^-1 = Z E^-1 Z^T + (I - Z Z^T).
// * Conjugate gradients on both right-hand sides until the residual is 1e-14 of the
//   right-hand side's norm.
#pragma once

#include <Eigen/Dense>

#include "models/exact_layer_solver.hpp"

namespace layerjkr::detail {

struct IterativeSolve {
  Eigen::MatrixXd psi;  // the solutions, one column per right-hand side
  int iterations = 0;   // the most CG iterations any column took
};

/// Solves B psi = rhs on `grid` by preconditioned CG; throws NumericalError if it does not
/// converge in 1000 iterations.
IterativeSolve solve_iteratively(const ExactLayerKernel& kernel, const Grid& grid, const Eigen::MatrixXd& rhs);

}  // namespace layerjkr::detail
