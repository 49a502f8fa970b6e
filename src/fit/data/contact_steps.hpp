// Internal: the contact-point methods inside fit() - option checks, the baseline of a window,
// and the fit that finds the contact point or selects a range before it solves.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "layerjkr/contact_point.hpp"
#include "layerjkr/fit.hpp"

namespace layerjkr::detail {

/// Throws DomainError naming the first invalid contact-point field of FitOptions.
void validate_contact_options(const FitOptions& options);

/// The brief report's line on the contact point ("" for method fit without a range).
std::string contact_point_line(const ContactPointReport& report);

/// Median and MAD sigma of the samples with delta in `window` (nullopt: the shallowest
/// quarter by delta). Throws InputError naming `source` and the window if it holds < 3.
void baseline_of(const std::vector<double>& delta, const std::vector<double>& P,
                 const std::optional<Interval>& window, const std::string& source, double* baseline,
                 double* noise);

/// True when fit() must find a contact point or select a range before it solves.
bool steered_contact(const FitOptions& options);

/// Fills s->contact_point for a plain fit (method fit, no range): delta0 and its error.
void report_fitted_contact(const CurveData& curve, const FitOptions& options, FitSummary* s);

/// fit() with the contact point found by options.contact_point and the ranges applied.
FitSummary fit_steered(const CurveData& curve, const Scene& scene, const FitOptions& options,
                       bool hold_gradual_rise = false);

/// fit() itself. contact_given: the data were shifted so that the found contact point and
/// baseline (or a first fit's delta0 and P0) are 0; a free delta0 and P0 start there instead
/// of at the data-driven scan. hold_gradual_rise: a retract that returns to the baseline without
/// a release is held in contact up to it instead of excluded as a tail (read_retract), the other
/// reading fit() weighs against the first.
FitSummary fit_core(const CurveData& curve, const Scene& scene, const FitOptions& options, bool contact_given,
                    bool hold_gradual_rise = false);

/// fit() of an elastic curve without its dwell: fit_steered or fit_core, and the contact point
/// reported (fit_second_readings.cpp).
FitSummary fit_once(const CurveData& curve, const Scene& scene, const FitOptions& options, bool hold_gradual_rise);

/// A retract that returns to the baseline without a jump, fitted again with the return held in
/// contact; the reading whose residuals are noise and follow every sample better is returned,
/// with a notice giving both rms values.
FitSummary weigh_gradual_rise(const CurveData& data, const Scene& scene, const FitOptions& options, FitSummary tail);

/// With P0 fixed: a warning, and no identifiability, where the data put P0 elsewhere (kSignificantSigmas)
/// and freeing it moves a parameter by more than 3 error bars.
void check_fixed_baseline(const CurveData& data, const Scene& scene, const FitOptions& options, FitSummary* out);

/// With P0 and w free and no sample at rest: a warning, and no identifiability, where P0 held at
/// the force's zero fits as well or better (P0 trading with the adhesion).
void check_baseline_trade(const CurveData& data, const Scene& scene, const FitOptions& options, FitSummary* out);

}  // namespace layerjkr::detail
