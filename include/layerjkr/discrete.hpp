// layerjkr: JKR from discrete data (paper, section 5 and Appendix A) - the two-model approach
// for FEM results and measurements without a closed-form non-adhesive solution.
//
// Model A, the flat punch: load steps (delta, P) at several fixed radii a_k give the
// stiffness S_k = dP/d delta at each radius (Condition 2 of the paper: P is linear in delta
// for a flat punch), hence S(a) and, by one differentiation, S'(a). Model B, the convex
// indenter, gives P(delta). This file holds stage A; the mapping to the non-adhesive curve
// and the transform (19) follow (issue #14, work in progress on this branch).
#pragma once

#include <string>
#include <vector>

namespace layerjkr {

/// Flat-punch load steps: several (delta, P) samples for each of at least 4 radii a [m].
struct FlatPunchData {
  std::vector<double> a;      ///< punch radius of each sample [m], > 0
  std::vector<double> delta;  ///< approach [m]
  std::vector<double> P;      ///< force [N]
  std::string source = "flat punch data";
};

/// Reads a CSV with the header a,delta,P (columns in any order, SI). Throws InputError naming
/// the file, line and column for anything else.
FlatPunchData read_flat_punch_csv(const std::string& path);
FlatPunchData parse_flat_punch_csv(const std::string& text, const std::string& source);

/// The stiffness at each radius, from a least-squares line P = S delta + c through its steps.
struct FlatPunchStiffness {
  std::vector<double> a;             ///< the distinct radii, increasing [m]
  std::vector<double> S;             ///< slope [N/m]
  std::vector<double> S_stderr;      ///< its standard error [N/m] (0 with exactly 2 steps)
  std::vector<double> nonlinearity;  ///< rms residual / (S x delta span): 0 for a perfect line
};

/// Fits every radius. Throws InputError (naming the radius) for fewer than 4 radii, fewer than
/// 2 load steps at a radius, a non-positive slope, steps whose nonlinearity exceeds
/// `linearity_tolerance` (Condition 2 fails) or S_k that does not grow with a.
FlatPunchStiffness fit_flat_punch(const FlatPunchData& data, double linearity_tolerance = 0.01);

}  // namespace layerjkr
