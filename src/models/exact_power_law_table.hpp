// Internal: the exact layer's state for a power-law profile f = B r^d as functions of a/h.
//
// In units of h the flat-punch solution and the solution for the right-hand side t^d depend
// only on nu, the base, d and rho = a/h, so their integrals and edge values (ExactMoments of
// the unit profile r^d on a unit layer) are tabulated once and scaled: the profile's moments
// are B h^d times the unit ones. Every state of a paraboloid, cone or power law on that layer
// (any E, h, B, radius, curve or fit step) is then four Chebyshev sums (~0.2 us).
//
// Representation: Chebyshev series (GSL cheb) in x = ln rho on pieces of x (unit width above a/h = 0.01), of the
// normalised moments int0/rho, end0, intf/(C rho^(d+1)) and endf/(C rho^d) (C = I0 of r^d
// at 1), which tend to constants as rho -> 0 and grow like powers of rho beyond 1. A piece is
// built the first time a query falls in it (13 solves), so a scene pays only for the radii
// it reaches. Measured against direct solves: see tests/models/test_exact_power_law_table.cpp
// and docs/exact-layer.md.
#pragma once

#include <memory>
#include <vector>

#include "layerjkr/layered_medium.hpp"
#include "models/exact_layer_solver.hpp"

namespace layerjkr::detail {

class DiskCache;

class ExactPowerLawTable {
 public:
  /// The table for r^d (d >= 1) on a layer of Poisson's ratio nu and `base`, solved with
  /// `options` (their discretisation sets the table's accuracy).
  ExactPowerLawTable(double nu, Base base, double d, const ExactLayerOptions& options);
  /// The same for a stack, in units of its top layer (a/h1; h1 = E1 = 1 in `unit_medium`).
  /// With `disk` (enabled), each piece is loaded from it under `disk_key` and its index, or
  /// built and stored there.
  ExactPowerLawTable(const LayeredMedium& unit_medium, double d, const ExactLayerOptions& options,
                     std::shared_ptr<const DiskCache> disk = nullptr, std::vector<double> disk_key = {});
  ~ExactPowerLawTable();
  ExactPowerLawTable(const ExactPowerLawTable&) = delete;
  ExactPowerLawTable& operator=(const ExactPowerLawTable&) = delete;

  /// Range of rho = a/h the table covers; outside it the caller solves directly.
  static double min_rho();  ///< 1e-6
  static double max_rho();  ///< 220
  bool covers(double rho) const { return rho >= min_rho() && rho <= max_rho(); }

  /// Moments of the unit profile r^d at rho on the unit layer (h = 1). Thread-safe.
  ExactMoments at(double rho) const;

 private:
  struct Pieces;
  void build_piece(int k) const;
  void solve_piece(int k) const;
  const ExactLayerKernel& unit_kernel() const;  // made on the first piece solved
  double d_, C_;
  ProfilePtr unit_profile_;
  LayeredMedium unit_medium_;
  ExactLayerOptions options_;           // its context reset: the table lives in that Context's cache
  std::weak_ptr<Context> context_;      // the Context the kernel comes from, while it lives
  std::shared_ptr<const DiskCache> disk_;
  std::vector<double> disk_key_;
  std::unique_ptr<Pieces> pieces_;
};

/// The table for (nu, base, d, discretisation) from the cache of options.context (null:
/// Context::global()), built on first request, once, thread-safely.
std::shared_ptr<const ExactPowerLawTable> shared_power_law_table(double nu, Base base, double d,
                                                                 const ExactLayerOptions& options);
/// The table of a stack (any E1, h1: it is keyed by the stack's ratios), a/h1 in the range.
std::shared_ptr<const ExactPowerLawTable> shared_power_law_table(const LayeredMedium& medium, double d,
                                                                 const ExactLayerOptions& options);

}  // namespace layerjkr::detail
