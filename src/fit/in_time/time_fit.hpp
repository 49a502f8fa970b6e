// Internal: fit() in time (time_fit.cpp, time_start.cpp) - a relaxing medium or crack kinetics
// fitted to every sample of a curve with its time.
#pragma once

#include <vector>

#include "fit/evaluators/curve_evaluator.hpp"
#include "layerjkr/fit.hpp"
#include "fit/evaluators/residual_model.hpp"

namespace layerjkr::detail {

/// The fit of a scene whose medium relaxes or whose adhesion has kinetics (fit.hpp).
FitSummary fit_in_time(const CurveData& curve, const Scene& scene, const FitOptions& options);

/// E_inf, tau, beta, v_star, n: the parameters of a law in time; drag, the lever's in liquid.
bool time_parameter(FitParameter q);
/// What a fit in time refuses, before any work (InputError naming the curve): a curve without
/// time, (P, a) data, the options only an equilibrium curve has (contact-point methods, ranges, a
/// retract window, a tilted baseline), parameters the scene's law does not have.
void check_request(const CurveData& curve, const Scene& scene, const FitOptions& options);
/// True where a fit in time models the scene's adhesion on its relaxing medium: a half-space with
/// w > 0 and a Maugis-Dugdale zone (RelaxingAdhesionEvaluator).
bool relaxing_adhesion(const Scene& scene);
/// Every sample in acquisition order, weighted where options.branch is (an approach fit ends with
/// the approach: nothing later changes it), with baseline, noise and offset from the elastic
/// selection of the approach; span and force span [m], [N] of the data.
FitData select_time_data(const CurveData& curve, const FitOptions& options, double* span, double* force_span);
/// The scene without its time: what the elastic start and the curve model are built from.
Scene elastic_scene(const Scene& scene);
/// The law's fixed values (the references of the free ones) into `fixed`.
void law_values(const Scene& scene, SceneParameters* fixed);

/// The start: an elastic fit of `elastic` (the scene without its time) on the approach (a relaxing
/// medium) or the chosen branch (kinetics) gives E (or K, G), delta0, P0 and w, into map's
/// references; a relaxing medium's E is then raised from the elastic fit's (a modulus averaged over
/// the loading) to the instantaneous one the law implies. Then a few values of the law's time
/// scale (tau, and E_inf/E where free; beta; v_star) are scanned with `ev` and the cheapest kept
/// in x. A notice says what the start was.
void start_in_time(const CurveData& curve, const Scene& elastic, const Scene& scene, const FitOptions& options,
                   const FitData& data, ResidualModel& ev, ParameterMap& map, std::vector<double>& x, FitSummary* out);

/// What the fitted law says of itself: a relaxed modulus above the instantaneous one (the data
/// stiffen), a relaxation time beyond the data's time scales, a power law without relaxation.
void judge_law(const ParameterMap& map, const std::vector<double>& x, const Scene& scene, const FitData& data,
               FitSummary* out);

/// Where a fit in time whose residuals are not noise misses, named and measured, as one warning:
/// each piece of the history (the pause before the approach, the approach, the dwell, the retract,
/// a pause after it) by its share of the residuals' sum of squares and its rms against the noise;
/// the relaxation the dwell shows beyond the law's (and the time scale of one exponential that
/// takes most of it); a retract below the fit's lowest force (adhesion); a baseline step between
/// the curve's ends off contact (drift). `drag` [N s/m] is the fitted lever's drag.
void name_misfit_in_time(const FitData& data, double drag, FitSummary* out);

}  // namespace layerjkr::detail
