// layerjkr: the options of a fit (fit.hpp, which includes this header): what is free, which
// branch, the retract's control, the baseline, the loss, the contact point and the ranges, every
// one validated (FitOptions::validate) with the option's name, its value and the valid range.
#pragma once

#include <limits>
#include <optional>
#include <vector>

#include "layerjkr/contact_point.hpp"
#include "layerjkr/types.hpp"

namespace layerjkr {

/// A free parameter's allowed range, in its reported unit (E in Pa, w in J/m^2, tau in s;
/// FitOptions::bounds). Either end may be infinite; lower < upper.
struct ParameterBound {
  FitParameter parameter = FitParameter::E;
  double lower = -std::numeric_limits<double>::infinity();
  double upper = std::numeric_limits<double>::infinity();
};

struct FitOptions {
  /// Parameters to identify (at least one, no duplicates). Others come from the scene
  /// (delta0 = 0 and P0 = 0 unless freed).
  std::vector<FitParameter> free;
  Branch branch = Branch::approach;
  /// What controls the retract. Under a cantilever of stiffness k the tip follows the adhesive
  /// branch beyond the load-controlled pull-off until dP/d delta = -k, then jumps free; under
  /// load control it jumps at the pull-off, under fixed grips at the minimum of delta.
  /// `automatic` uses a cantilever where its stiffness is known, else follows the data: fixed
  /// grips where the retract holds the contact past its force minimum (the release read from the
  /// samples before the fit, docs/fitting.md "Rules decided from the data"), else load control; a
  /// return to the baseline without a jump is fitted both as a tail and as the held branch, and
  /// the reading whose residuals are noise and follow every sample better is kept; a notice says
  /// which and why;
  /// `cantilever` requires the stiffness (the fit throws InputError naming the curve without it).
  RetractControl retract_control = RetractControl::automatic;
  /// The cantilever's stiffness [N/m], finite and > 0; nullopt: the curve's own
  /// CurveData::spring_constant (an instrument file's; 0 there means unknown).
  std::optional<double> cantilever_stiffness;
  /// Retract samples after the release (read from the data before the fit) that have not yet
  /// returned to the retract's measured baseline (|P - baseline| > exclusion_sigmas x the
  /// retract's noise) are not JKR: they are excluded from the fit, counted and reported
  /// (FitSummary::excluded). 0 keeps every sample.
  double exclusion_sigmas = 3.0;
  /// The noise of each fitted column when a curve carries measured contact radii (delta,P,a):
  /// force [N] and radius [m], finite and > 0; unset: estimated from the data (the second
  /// differences in acquisition order). Each column's residuals are divided by its own noise, so
  /// the two weigh what they measure, whatever their units or spans.
  std::optional<double> force_noise, radius_noise;
  /// Errors in both variables for (delta, P) data whose displacement is measured with noise of its
  /// own, independent of the force's - a JKR rig's displacement sensor, not an AFM's delta = z - P/k,
  /// whose noise is the force's. Each contact sample's residual is then its distance to the curve
  /// (orthogonal distance regression, as ODRPACK and scipy.odr), in the metric where force and
  /// displacement are measured in their own noises: the model's point at the radius a_i that is
  /// nearest the sample, found per sample. Least squares in the force alone reads displacement noise
  /// on a curved branch as force noise that grows with the slope, and biases E (docs/fitting.md).
  /// Only the ratio of the two noises changes the estimate; the error bars scale by the residuals.
  bool errors_in_displacement = false;
  /// The displacement's noise [m] under errors_in_displacement, finite and > 0; unset: estimated,
  /// like force_noise, from the third differences of the column in acquisition order.
  std::optional<double> displacement_noise;
  /// Baseline::tilt also fits a linear tilt of the baseline, P0 + slope * delta, with the slope
  /// taken by least squares from the samples the fitted model puts off contact (never from
  /// excluded ones); the data are detilted and refitted once (FitSummary::baseline_slope).
  Baseline baseline = Baseline::constant;
  /// With P0 not free: the force's offset - the median of the samples at rest (the shallowest
  /// quarter, or baseline_window) - is subtracted before the fit where it exceeds 3 of its own
  /// standard errors, as JPK's software and nanite do (FitSummary::baseline_offset says how much);
  /// false keeps the forces as they are, their zero the baseline.
  bool remove_offset = true;
  /// Which unloading samples a retract fit uses: every one (all); from the largest force
  /// down to the observed pull-off, the force minimum (to_pull_off); or from the largest force
  /// down to P_max - window_fraction (P_max - P_min) (force_fraction), as linearised-JKR and
  /// two-point analyses use. Approach samples are not affected.
  RetractWindow retract_window = RetractWindow::all;
  double window_fraction = 0.5;  ///< in (0, 1], for force_fraction
  /// How an approach fit finds the contact point (contact_point.hpp). `fit`: delta0 is a
  /// fitted parameter (free) or 0. Any other method finds it from the approach samples first;
  /// delta0 and P0 are then fixed at the found point and baseline, unless freed, in which case
  /// the found values are their start. Needs approach samples (branch approach or all).
  ContactPointMethod contact_point = ContactPointMethod::fit;
  /// Approach samples whose indentation delta - delta_c [m] from the contact point lies in
  /// [first, second] (first may be negative: it keeps that much baseline; second > first);
  /// nullopt keeps all. delta_c is the method's point, or for `fit` the fitted delta0 of a first
  /// fit on all samples, after which the kept ones are fitted again from its delta0 and P0.
  std::optional<Interval> indentation_range;
  /// Approach samples by force, as fractions of the approach's largest force above the baseline,
  /// 0 <= first < second <= 1: the kept window of delta begins at the first sample past the
  /// contact point whose force reaches `first` (0: the baseline stays) and ends before the first
  /// one beyond `second` (1: no end). Combined with indentation_range, a sample needs both.
  std::optional<Interval> force_range;
  /// Delta range [m] of the baseline samples (baseline and noise of the start and of the
  /// contact-point methods); nullopt: the quarter of the samples with the smallest delta. With
  /// a range it serves before the selection (the method, or the first fit of `fit`).
  std::optional<Interval> baseline_window;
  /// Ranges the free parameters must stay in (at most one per parameter, each free): every
  /// solve keeps them, starts included. A parameter that ends at an end of its range is reported
  /// there with no error bar (`at_bound`, the data would put it beyond) and the others' error
  /// bars come from the fit with it held there; a warning says so. Not in joint fits.
  std::vector<ParameterBound> bounds;
  /// Robust loss on force residuals; loss_scale [N] > 0 is where it departs from
  /// least squares (required for huber and cauchy).
  LossType loss = LossType::none;
  double loss_scale = 0.0;
  /// Ceres trust-region limits (>= 1, > 0), each relative: function_tolerance to the cost,
  /// parameter_tolerance to the (dimensionless) parameters, gradient_tolerance to the problem's
  /// own scale, the cost of the best constant force (so that no rescaling of the data or of the
  /// weights meets it by itself; 1e-15 of it is ~3e-14 on 1 000 samples, Ceres' old absolute 1e-14).
  int max_iterations = 200;
  double function_tolerance = 1e-9;
  double parameter_tolerance = 1e-10;
  double gradient_tolerance = 1e-15;
  /// Extra starts (>= 0) with delta0 and the stiffness perturbed around the data-driven
  /// guess; the lowest cost wins.
  int extra_starts = 0;
  /// Standard errors and correlations (ceres::Covariance).
  bool compute_covariance = true;
  /// |correlation| above this marks a pair as not separable, in (0, 1).
  double correlation_limit = 0.99;
  /// Grid density of the tabulated family, >= 8.
  int table_points_per_decade = 40;
  /// Print Ceres' progress per iteration (stdout) and its full report (stderr).
  bool trace = false;
  /// Throws DomainError naming the first invalid field.
  void validate() const;
};

}  // namespace layerjkr
