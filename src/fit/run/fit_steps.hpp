// Internal: the steps of fit() - data selection, the data-driven start, and the error
// bars with the identifiability verdict.
#pragma once

#include <string>
#include <vector>

#include <ceres/problem.h>

#include "core/short_number.hpp"
#include "fit/evaluators/curve_evaluator.hpp"
#include "layerjkr/fit.hpp"

namespace layerjkr::detail {

double median(std::vector<double> v);

/// Where each free parameter sits in x, and the scales that make x dimensionless (fit.cpp): the
/// references are the scene's values (`fixed`), which the start then refines.
ParameterMap make_parameter_map(const FitOptions& options, const ResolvedModel& resolved, SceneParameters fixed,
                                double span, double force_span);

/// Gaussian sigma from the median absolute deviation: 1 / Phi^-1(3/4).
constexpr double kMadToSigma = 1.4826;
/// A force feature (the contact region, an adhesive dip) is taken as real when it exceeds
/// this many noise sigmas: for Gaussian noise a false alarm has probability < 1e-6.
constexpr double kSignificantSigmas = 5.0;
/// ...or, for noiseless data, this fraction of the force span.
constexpr double kSignificantForceFraction = 1e-6;

/// A contact slope d(deflection)/dz at or above this is a tip that does not indent measurably:
/// the lever takes 90 % or more of the piezo's motion, and the indentation is within the
/// deflection's calibration error (InvOLS is known to a few %).
constexpr double kRigidContactSlope = 0.9;

/// FitData::contact_slope of the selected samples (fit_data.cpp), from data.spring_constant,
/// data.baseline and data.noise.
double contact_slope(const FitData& data);
/// What a refusal for "no contact region" adds: the tip not indenting (contact slope >= 0.9),
/// else the sign conventions and a baseline offset to check.
std::string no_contact_hint(const FitData& data);

/// The change [N] of the least-squares line of P against delta through the samples idx, over
/// their span of delta (0 where delta does not vary): how far a part that should be at rest trends.
double linear_trend(const FitData& data, const std::vector<std::size_t>& idx);

/// Noise [N] of samples on a smooth curve, from the MAD of their second differences in
/// acquisition order (samples idx of P): a trend (a necking tail, the unloading curve itself)
/// cancels, white noise of sigma gives differences of sigma sqrt(6). 0 for fewer than 3 samples.
double second_difference_noise(const std::vector<double>& P, const std::vector<std::size_t>& idx);

/// A tip that does not indent measurably (data.contact_slope >= kRigidContactSlope): a warning
/// with the slope and the lever, and the fit is not called identifiable - E cannot be told from
/// a rigid sample within the deflection's calibration error.
void diagnose_indentation(const FitData& data, FitSummary* out);

/// The model's build notes (CurveModel::notes): notices where its measured interpolation error
/// is far below what the data resolve - at most kNegligibleModelError, or a force error
/// (error x the data's force span) under a tenth of their noise - else warnings that give the
/// force error against the noise.
void record_model_notes(const CurveModel& model, const FitData& data, double force_span, FitSummary* out);

/// With measured contact radii (not (P, a) data): each column's noise, given or estimated from
/// its second differences, into out->force_noise / radius_noise, and data.a_scale set so that
/// the radius residuals, like the force's, are in units of their own noise.
void weigh_columns(const FitOptions& options, double force_span, FitData& data, FitSummary* out);

/// Noise [N or m] of samples on a smooth curve from the MAD of their third differences in
/// acquisition order (idx of v): a quadratic trend - curvature, unevenly spaced samples -
/// cancels, white noise of sigma gives differences of sigma sqrt(20). 0 for fewer than 4 samples.
/// The scale the fit's diagnosis and its column weights judge residuals against.
double third_difference_noise(const std::vector<double>& v, const std::vector<std::size_t>& idx);

/// Whether the fit's residuals look like noise (fit_diagnosis.cpp): a runs test of their signs in
/// acquisition order and their rms against the data's own second-difference noise, into
/// out->runs_z and out->noise. Residuals with structure (far fewer runs than noise gives, and an
/// rms well above the noise) mean the model does not describe the data: a warning saying so, and
/// the fit is not called identifiable.
void diagnose_residuals(const FitData& data, double force_span, FitSummary* out);

/// Moduli (E, K, G, E_inf, E_2) a fit may return [Pa]: beyond them no material is meant, whatever the
/// solver's tolerances say.
constexpr double kPlausibleModulus[2] = {1e-3, 1e15};
/// The largest work of adhesion a fit may return [J/m^2] (covalent bonds are a few J/m^2).
constexpr double kPlausibleWork = 1e3;
/// Residuals this many times the data's noise, and ...
constexpr double kFailedRmsOverNoise = 100.0;
/// ... this share of the data's own spread about their mean (the model explains less than 3/4 of
/// the force's variance), are no description of them. Both: a high-SNR curve a model follows to
/// 2 % of its span is hundreds of noise sigmas off and still described (SOFA's Asylum maps).
constexpr double kFailedShareOfSpread = 0.5;

/// Honest convergence (fit_diagnosis.cpp): a fit whose parameters leave every physical range
/// (kPlausibleModulus, kPlausibleWork, a non-finite value) or whose rms residual is
/// kFailedRmsOverNoise times the data's noise (out->noise; above rounding) and kFailedShareOfSpread
/// of the fitted samples' spread about their mean has failed: converged
/// false, FitSummary::failure says why, a warning says so and nothing is called identifiable.
void judge_plausibility(FitSummary* out);

/// The samples of options.branch, with their scales. Throws InputError for fewer samples
/// than parameters, constant delta or P, or no contact region.
FitData select_fit_data(const CurveData& curve, const FitOptions& options, double* span,
                        double* force_span);

/// Robust losses are usable for scales from kLossScaleRange[0] to kLossScaleRange[1] times the
/// force span: far below it every residual is an outlier (the fit follows no sample), far above
/// it the loss is least squares everywhere, and beyond either the loss itself overflows (Ceres'
/// Cauchy loss takes the scale squared).
constexpr double kLossScaleRange[2] = {1e-6, 1e6};

/// Throws InputError naming `source`, the scale, its usable range in newtons and why, for a
/// robust loss whose scale lies outside kLossScaleRange x `force_span`.
void require_usable_loss_scale(const FitOptions& options, double force_span, const std::string& source);

/// The contact-region rule for retract data without a baseline (tension-only unloading, a
/// necking tail): see fit_data.cpp. On success sets data.noise and data.unloading_only.
bool unloading_contact_region(FitData& data, double force_span);

/// Data-driven start: baseline, a contact-point scan with the stiffness solved linearly,
/// and w from the retract dip. Sets map's references and s_scale, x's w slot, and
/// data.contact (retract samples up to the observed pull-off). `source` names the curve.
void find_start(FitData& data, ParameterMap& map, const CurveEvaluator& ev, std::vector<double>& x,
                const std::string& source);

/// The start for (P, a) data (FitData::radius_driven): the JKR force at a radius is linear in
/// the stiffness factor k and in sqrt(k w), P(a) = k P_H(a) - sqrt(k w) g(a) with g the adhesive
/// term at w = 1 J/m^2 (and + P0 when free), so a linear least-squares solve over the samples gives
/// both - no guess, no scan. Sets map's stiffness reference, s_scale, P0's reference and x's w slot.
void find_radius_start(FitData& data, ParameterMap& map, const CurveEvaluator& ev, std::vector<double>& x);

class FitRun;

/// The unscaled covariance (J^T J)^-1 of the free parameters [x units^2, row-major p x p] from the
/// Jacobian at the last evaluation of `ev`, as ceres::Covariance's DENSE_SVD gives it: singular
/// values of J whose ratio to the largest is below sqrt(min_reciprocal_condition) are dropped
/// (`truncate`: a pseudo-inverse) or make it fail (false). held_slot (>= p: none) gets a zero row
/// and column, as a SubsetManifold does. Accuracy: that of a Householder QR and a Jacobi SVD of its
/// p x p triangle, a few ulps times the condition number.
bool svd_covariance(const ResidualModel& ev, std::size_t held_slot, bool truncate, double min_reciprocal_condition,
                    std::vector<double>* C);

/// Standard errors, correlations and the identifiability verdict at the run's solution x (the
/// summary already recorded). A w without adhesive signal (at 0, or indistinguishable from it
/// when the covariance fails) is held at 0 and the fit redone and re-recorded; its upper bound
/// comes from the profile likelihood (fit.hpp, ParameterEstimate).
void assess_uncertainty(FitRun& run, ResidualModel& ev, const ParameterMap& map, std::vector<double>& x,
                        const FitOptions& options, const FitData& data, FitSummary* out);

/// The one-sided 95 % point of the deviance 2 delta cost / s^2 (chi^2(1) at 90 %, 1.6449^2): w's
/// upper bound and the limits of a free sigma0 are where the profile rises by it.
constexpr double kUpperBoundDeviance = 2.705543454095404;
/// A cost (dimensionless residuals, force / force span) per degree of freedom below this is
/// rounding: residuals of 1e-12 of the force span.
constexpr double kNoiselessCost = 1e-24;

/// Maugis' lambda of the parameters at x (fit_sigma0.cpp; NaN at w = 0).
double maugis_lambda_at(const ParameterMap& map, const std::vector<double>& x);
/// A free sigma0 beyond lambda 1e3 (JKR) or below 1e-3 (DMT) is held where it stopped; returns
/// that limit's name, or nullptr (sigma0 not free, inside the limits, or the hold failed).
const char* hold_sigma0_at_limit(FitRun& run, const ParameterMap& map, const std::vector<double>& x);
/// Reports a sigma0 held at `limit` (lambda there) as not separable from it, with a warning.
void report_sigma0_at_limit(const char* limit, double lambda, FitSummary* out);
/// A free sigma0 with an error bar stays identifiable only when holding it at lambda 1e3 and at
/// 1e-3, the others refitted, raises the deviance beyond kUpperBoundDeviance (noisy data only).
void check_sigma0_limits(FitRun& run, ResidualModel& ev, const ParameterMap& map, const std::vector<double>& x,
                         std::size_t residuals, FitSummary* out);

/// FitSummary::no_move_reason when the first solve did not move from the start.
void explain_no_move(const FitRun& run, const FitData& data, const ParameterMap& map, FitSummary* out);

/// A free parameter that ended at an end of its range (FitOptions::bounds), and that end.
struct BoundHit {
  ParameterBound bound;
  double end = 0.0;
};
/// The free parameters at an end of their ranges at x (fit_bounds.cpp).
std::vector<BoundHit> at_user_bounds(const ParameterMap& map, const FitOptions& options, const std::vector<double>& x);
/// Marks each at its bound (no error bar, not identifiable, why) and warns.
void report_user_bounds(const std::vector<BoundHit>& hits, FitSummary* out);

}  // namespace layerjkr::detail
