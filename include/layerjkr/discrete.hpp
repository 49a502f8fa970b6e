// layerjkr: JKR from discrete data (paper, section 5 and Appendix A) - the two-model approach
// for FEM results and measurements without a closed-form non-adhesive solution.
//
// Model A, the flat punch: load steps (delta, P) at several fixed radii a_k give the
// stiffness S_k = dP/d delta at each radius (Condition 2 of the paper: P is linear in delta
// for a flat punch), hence S(a) and, by one differentiation, S'(a). Model B, the convex
// indenter, gives P(delta); each S maps to the delta where dP/d delta = S, and the transform
// (19) then needs S' only. The single-model alternative, a bootstrap of the reconstruction's
// error, and synthetic FEM-like data from any model (to validate the workflow) sit beside it.
#pragma once

#include <array>
#include <cmath>
#include <memory>
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

/// A smooth positive curve y(x) through positive samples, fitted in log-log coordinates, where
/// the power laws of the thin-layer and Hertz limits are straight lines. Non-positive samples
/// (the zero row FEM output starts with) are skipped. Accuracy: that of the data - the fit
/// only smooths; docs/discrete-data.md has the measured reconstruction errors.
class LogLogFit {
 public:
  virtual ~LogLogFit() = default;
  virtual double value(double x) const = 0;
  /// d ln y / d ln x.
  virtual double log_slope(double x) const = 0;
  /// d^2 ln y / d (ln x)^2.
  virtual double log_curvature(double x) const = 0;
  /// Leave-one-out rms of ln y at the chosen complexity (the cross-validation score).
  double cv_rms() const { return cv_; }
  /// The chosen complexity, e.g. "degree 2" or "5 cubic B-splines".
  virtual std::string complexity() const = 0;
  /// The number of fitted coefficients (for residual degrees of freedom).
  virtual int parameters() const = 0;

 protected:
  double cv_ = 0.0;
};

/// ln y as a polynomial in ln x, its degree (1 .. max_degree, below the sample count - 1)
/// chosen by leave-one-out cross-validation: power laws (Winkler, Hertz) are exact at degree 1,
/// and the smooth departures of a layer cost a degree or two.
class LogPolynomialFit final : public LogLogFit {
 public:
  LogPolynomialFit(const std::vector<double>& x, const std::vector<double>& y, int max_degree, const std::string& what);
  double value(double x) const override;
  double log_slope(double x) const override;
  double log_curvature(double x) const override;
  std::string complexity() const override;
  int parameters() const override { return static_cast<int>(c_.size()); }
  int degree() const { return static_cast<int>(c_.size()) - 1; }

 private:
  double u(double x) const { return (std::log(x) - center_) / scale_; }
  std::vector<double> c_;  // coefficients in u, lowest first
  double center_ = 0.0, scale_ = 1.0;
};

/// ln y as a least-squares cubic B-spline in ln x (GSL basis, uniform breakpoints; the paper's
/// Appendix A used Matlab's spap2 B-splines), the number of basis functions (4 .. n - 2) chosen
/// by leave-one-out cross-validation; with 4 or 5 samples one piece of order n - 2. Outside the
/// samples it continues the end piece.
class LogSplineFit final : public LogLogFit {
 public:
  LogSplineFit(const std::vector<double>& x, const std::vector<double>& y, const std::string& what);
  double value(double x) const override;
  double log_slope(double x) const override;
  double log_curvature(double x) const override;
  std::string complexity() const override;
  int parameters() const override { return basis_; }

 private:
  // The spline as one cubic per interval, c[0] + c[1] t + c[2] t^2 + c[3] t^3, t = u - breaks_[j].
  std::size_t interval(double u) const;
  std::vector<double> breaks_;
  std::vector<std::array<double, 4>> cubic_;
  int basis_ = 0;
  std::size_t order_ = 4;
};

/// Fits `y(x)` with the chosen smoothing; `what` names the data in error messages.
std::shared_ptr<const LogLogFit> fit_log_log(const std::vector<double>& x, const std::vector<double>& y,
                                             Smoothing smoothing, int max_degree, const std::string& what);

struct DiscreteOptions {
  double linearity_tolerance = 0.01;  ///< flat-punch Condition 2 (fit_flat_punch)
  Smoothing smoothing = Smoothing::log_polynomial;
  int max_degree = 3;                  ///< of log_polynomial fits, 1 .. 6
  /// Throws DomainError naming the option outside its range.
  void validate() const;
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

/// FEM-like synthetic data from any model, to validate the workflow against a known truth.
/// Forces carry relative Gaussian noise of standard deviation `noise` (0 for none); `seed`
/// makes the noise reproducible.
struct SyntheticSampling {
  int load_steps = 20;       ///< equal delta substeps up to delta_max, as an FEM run (>= 2)
  double delta_max = 0.0;    ///< largest approach [m], > 0
  double noise = 0.0;        ///< relative force noise, 0 .. 0.5
  unsigned seed = 1;
  /// The convex run reports a rounded to this mesh spacing [m], as an FEM run that reads the
  /// contact radius off its outermost node in contact; 0 reports the exact radius.
  double radius_resolution = 0.0;
  void validate() const;
};
/// Flat punch of each radius on the model's body: P = S(a) delta at every substep.
FlatPunchData sample_flat_punch(const ContactModel& model, const std::vector<double>& radii,
                                const SyntheticSampling& sampling);
/// The model's convex indenter under displacement control: P and a at every substep (delta
/// beyond the model's largest radius throws DomainError).
ConvexData sample_convex(const ContactModel& model, const SyntheticSampling& sampling);

/// The most replicates x radii one bootstrap_discrete evaluates (InputError beyond, before any
/// replicate): 200 replicates of 100 000 radii, measured at 14 s (docs/development.md, Limits).
inline constexpr double kMaxBootstrapEvaluations = 2e7;

struct BootstrapOptions {
  int replicates = 200;  ///< 20 .. 100000; replicates x radii <= kMaxBootstrapEvaluations
  unsigned seed = 1;
  void validate() const;
};

/// The spread of the JKR reconstruction under the data's own noise: a residual bootstrap.
/// Each replicate puts the residuals of every flat-punch line (resampled within its radius)
/// and of the convex fit (resampled in ln P, and ln a for the single model) back on the fitted
/// curves, rebuilds the model and the JKR solution; the errors are the replicates' standard
/// deviations. They measure the noise, not a bias the smoothing may have. A radius at the edge
/// of the data can fall outside some replicates' range; `used` counts the replicates behind each
/// error, which is NaN below 2.
struct DiscreteUncertainty {
  std::vector<double> a;          ///< the radii asked for [m]
  std::vector<double> P_err;      ///< std of the adhesive force at each radius [N]
  std::vector<double> delta_err;  ///< std of the adhesive approach [m]
  std::vector<int> used;          ///< replicates whose range held the radius (the rest skip it)
  double pull_off_force_err = NAN;    ///< [N]; NaN if no replicate found a pull-off
  double zero_load_radius_err = NAN;  ///< [m]
  int replicates = 0;   ///< asked for
  int failed = 0;       ///< replicates whose data no longer made a model (counted, not used)
};
DiscreteUncertainty bootstrap_discrete(const FlatPunchData& flat, const ConvexData& convex, double w,
                                       const std::vector<double>& radii, DiscreteApproach approach,
                                       const DiscreteOptions& options = {}, const BootstrapOptions& bootstrap = {});

}  // namespace layerjkr
