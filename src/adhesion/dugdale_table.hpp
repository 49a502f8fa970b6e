// Internal: the Dugdale states of a power-law profile on a layer or stack, tabulated once per
// (medium, d) so that a Maugis-Dugdale or DMT state costs microseconds instead of the
// milliseconds of a Nystrom solve (issue 35; docs/theory.md s.4b, "Tables").
//
// A state is linear in the tension and in the profile (DugdaleParts): at contact radius a and
// zone radius c, in units of the top layer (h1 = 1) and the unit profile r^d,
//   delta = delta_H + s0 D,  P = P_H + sigma0 P,  gap(c) = s0 G + F   (s0 = sigma0/E*),
// where D, P, G, F depend on (a/h, c/h) alone. They are tabulated in x = ln(c/h) and
// theta = acos(a/c) in [0, pi/2] (theta = pi/2 is a = 0, the adhesive disc alone), each divided
// by its half-space value (s.5a's closed forms), which makes them ratios that tend to 1 as
// c/h -> 0 and are smooth in theta to both ends:
//   D: -2 c sin(theta),   P: -2 c^2 (sin(theta) cos(theta) + theta),
//   G: (4 c/pi)(theta sin(theta) - 1 + cos(theta)),   F: (2 c^d/pi)(sin(theta) cos(theta) - theta cos(2 theta))
// (F's for d = 2; other d keep the same shape in theta). Each piece of x holds a tensor
// Chebyshev series of the four ratios, built from direct solves (DugdaleSolver::parts) at its
// Chebyshev points the first time a query falls in it, and checked there against direct
// solves at points between them: the largest difference is the piece's measured error, which
// every answer from the table carries. Pieces come from and go to the Context's disk cache.
#pragma once

#include <array>
#include <memory>
#include <mutex>
#include <vector>

#include "adhesion/dugdale_solver.hpp"
#include "layerjkr/exact_layer.hpp"
#include "layerjkr/layered_medium.hpp"

namespace layerjkr::detail {

class DiskCache;

class DugdaleTable {
 public:
  /// The table of r^d on `unit_medium` (E1 = h1 = 1), solved with `options`' discretisation;
  /// pieces from `disk` under `disk_key` (may be null or disabled).
  DugdaleTable(const LayeredMedium& unit_medium, double d, const ExactLayerOptions& options,
               std::shared_ptr<const DiskCache> disk, std::vector<double> disk_key);
  ~DugdaleTable();
  DugdaleTable(const DugdaleTable&) = delete;
  DugdaleTable& operator=(const DugdaleTable&) = delete;

  /// The range of c/h it covers: below, the half-space's closed forms are within min_c() of it.
  static double min_c();  ///< 1e-6
  static double max_c();  ///< 100

  struct Parts {
    double D = 0.0, P = 0.0, G = 0.0, F = 0.0;  ///< DugdaleParts' four, unit medium and profile
    double error = 0.0;  ///< the piece's measured error, relative to the larger of each part and its half-space size
  };
  /// The parts at 0 <= a <= c, c in [min_c(), max_c()] (units of h1). Thread-safe.
  Parts at(double a, double c) const;

  /// The half-space's parts (the ratios' denominators) at (a, c), for d: D, P, G, F.
  static Parts half_space(double a, double c, double d);

  /// The largest measured error of the pieces built so far (0 if none).
  double measured_error() const;

 private:
  struct Piece;
  const Piece& piece(int k) const;
  void build(int k, Piece& p) const;
  const DugdaleSolver& solver() const;

  double d_;
  LayeredMedium unit_medium_;
  ExactLayerOptions options_;
  std::shared_ptr<const DiskCache> disk_;
  std::vector<double> disk_key_;
  std::unique_ptr<std::array<std::once_flag, 16>> built_;
  std::unique_ptr<std::array<std::unique_ptr<Piece>, 16>> pieces_;
  mutable std::once_flag solver_made_;
  mutable std::unique_ptr<DugdaleSolver> solver_;
};

/// The table of (medium, d) for `options` from the Context's cache (options.context; null:
/// the global one) and its disk cache; any E1, h1 (the medium's ratios key it).
std::shared_ptr<const DugdaleTable> shared_dugdale_table(const LayeredMedium& medium, double d,
                                                         const ExactLayerOptions& options);

}  // namespace layerjkr::detail
