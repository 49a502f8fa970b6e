// layerjkr: JKR from discrete data (paper, section 5 and Appendix A) - the two-model approach
// for FEM results and measurements without a closed-form non-adhesive solution.
//
// Model A, the flat punch: load steps (delta, P) at several fixed radii a_k give the
// stiffness S_k = dP/d delta at each radius (Condition 2 of the paper: P is linear in delta
// for a flat punch), hence S(a) and, by one differentiation, S'(a). Model B, the convex
// indenter, gives P(delta); each S maps to the delta where dP/d delta = S, and the transform
// (19) then needs S' only (issue #14, work in progress on this branch: the smoothing is not yet
// chosen by a measured study, the single-model comparison and the CLI are missing).
#pragma once

#include <cmath>
#include <string>
#include <vector>

#include "layerjkr/model.hpp"

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

/// The convex indenter's non-adhesive curve P(delta), delta from first contact [m], P [N].
struct ConvexData {
  std::vector<double> delta, P;
  std::vector<double> a;  ///< contact radius [m] when the model reports it (empty if not)
  std::string source = "convex-indenter data";
};
/// Reads a CSV with the header delta,P or delta,P,a (SI, any order).
ConvexData read_convex_csv(const std::string& path);
ConvexData parse_convex_csv(const std::string& text, const std::string& source);

/// y(x) = exp(polynomial in ln x) through positive samples by least squares, its degree
/// (1 .. max_degree, and below the sample count) chosen by leave-one-out cross-validation:
/// power laws (Winkler, Hertz) are exact at degree 1, and the smooth departures of a layer
/// cost a degree or two.
class LogPolynomialFit {
 public:
  LogPolynomialFit(const std::vector<double>& x, const std::vector<double>& y, int max_degree, const std::string& what);
  double value(double x) const;
  /// d ln y / d ln x.
  double log_slope(double x) const;
  /// d^2 ln y / d (ln x)^2.
  double log_curvature(double x) const;
  int degree() const { return static_cast<int>(c_.size()) - 1; }
  double cv_rms() const { return cv_; }  ///< leave-one-out rms of ln y at the chosen degree

 private:
  double u(double x) const { return (std::log(x) - center_) / scale_; }
  std::vector<double> c_;  // coefficients in u, lowest first
  double center_ = 0.0, scale_ = 1.0, cv_ = 0.0;
};

struct DiscreteOptions {
  double linearity_tolerance = 0.01;  ///< flat-punch Condition 2 (fit_flat_punch)
  int max_degree = 3;                  ///< of both log-log fits, 1 .. 6
};

/// The two-model non-adhesive curve (paper, section 5): S(a) through the flat-punch S_k and
/// S'(a) = S d ln S / d ln a / a (one differentiation), P(delta) through the convex data, and
/// delta_H(a) where dP/d delta = S(a), P_H = P(delta_H). The radii are those of the flat-punch
/// data whose stiffness the convex data reach; outside them state() throws DomainError.
ContactModelPtr make_discrete_model(const FlatPunchData& flat, const ConvexData& convex,
                                    const DiscreteOptions& options = {});

/// The single-model alternative the paper argues against: P, delta and a all from the convex
/// data (which must carry a), S = dP/d delta and S' = dS/da by differentiating the data twice.
/// For comparison with make_discrete_model.
ContactModelPtr make_single_model(const ConvexData& convex, const DiscreteOptions& options = {});

}  // namespace layerjkr
