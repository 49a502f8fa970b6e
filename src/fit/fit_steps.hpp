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

/// Data-driven start: baseline, a contact-point scan with the stiffness solved linearly,
/// and w from the retract dip. Sets map's references and s_scale, x's w slot, and
/// data.contact (retract samples up to the observed pull-off). `source` names the curve.
void find_start(FitData& data, ParameterMap& map, const CurveEvaluator& ev, std::vector<double>& x,
                const std::string& source);

/// Standard errors, correlations and the identifiability verdict at the solution x
/// (ev must hold the Jacobian there). `problem` is the solved Ceres problem.
void assess_uncertainty(const CurveEvaluator& ev, ceres::Problem* problem, double final_cost,
                        const ParameterMap& map, std::vector<double>& x, const FitOptions& options,
                        std::size_t residuals, FitSummary* out);

}  // namespace layerjkr::detail
