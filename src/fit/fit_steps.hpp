// Internal: the steps of fit() - data selection, the data-driven start, and the error
// bars with the identifiability verdict.
#pragma once

#include <string>
#include <vector>

#include <ceres/problem.h>

#include "curve_evaluator.hpp"
#include "layerjkr/fit.hpp"

namespace layerjkr::detail {

double median(std::vector<double> v);

/// Gaussian sigma from the median absolute deviation: 1 / Phi^-1(3/4).
constexpr double kMadToSigma = 1.4826;
/// A force feature (the contact region, an adhesive dip) is taken as real when it exceeds
/// this many noise sigmas: for Gaussian noise a false alarm has probability < 1e-6.
constexpr double kSignificantSigmas = 5.0;
/// ...or, for noiseless data, this fraction of the force span.
constexpr double kSignificantForceFraction = 1e-6;

/// The samples of options.branch, with their scales. Throws InputError for fewer samples
/// than parameters, constant delta or P, or no contact region.
FitData select_fit_data(const CurveData& curve, const FitOptions& options, double* span,
                        double* force_span);

/// The contact-region rule for retract data without a baseline (tension-only unloading, a
/// necking tail): see fit_data.cpp. On success sets data.noise and data.unloading_only.
bool unloading_contact_region(FitData& data, double force_span);

/// Data-driven start: baseline, a contact-point scan with the stiffness solved linearly,
/// and w from the retract dip. Sets map's references and s_scale, x's w slot, and
/// data.contact (retract samples up to the observed pull-off). `source` names the curve.
void find_start(FitData& data, ParameterMap& map, const CurveEvaluator& ev, std::vector<double>& x,
                const std::string& source);

class FitRun;

/// Standard errors, correlations and the identifiability verdict at the run's solution x (the
/// summary already recorded). A w without adhesive signal (at 0, or indistinguishable from it
/// when the covariance fails) is held at 0 and the fit redone and re-recorded; its upper bound
/// comes from the profile likelihood (fit.hpp, ParameterEstimate).
void assess_uncertainty(FitRun& run, CurveEvaluator& ev, const ParameterMap& map, std::vector<double>& x,
                        const FitOptions& options, const FitData& data, FitSummary* out);

/// FitSummary::no_move_reason when the first solve did not move from the start.
void explain_no_move(const FitRun& run, const FitData& data, const ParameterMap& map, FitSummary* out);

}  // namespace layerjkr::detail
