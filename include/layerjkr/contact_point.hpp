// layerjkr: where contact begins on an approach curve, found from the data alone, and the
// report of the contact point a fit used (FitSummary::contact_point).
//
//   ContactPoint c = find_contact_point(delta, P, ContactPointMethod::rov);
//   // c.delta [m] in the data's delta coordinate, c.uncertainty [m], c.baseline [N]
//
// fit() calls it when FitOptions::contact_point is not `fit`; docs/fitting.md defines the
// methods, their uncertainties and the study of how the modulus moves with them.
//
// Every method works on the approach samples sorted by delta (delta grows towards the sample)
// and first measures the baseline: the median force P_b and the noise sigma (1.4826 x the
// median absolute deviation) of the baseline samples - those with delta inside the baseline
// window, by default the quarter of the samples with the smallest delta (fit()'s own rule).
//   threshold: the curve leaves the noise band for good at the first sample after which every
//     force exceeds P_b + 5 sigma; from there it walks back to the last sample at or below
//     P_b, and the contact point is where the straight line through that sample and the next
//     crosses P_b. Uncertainty: the distance from that crossing to the exit sample (how long
//     the curve takes to emerge from the noise).
//   rov: ratio of variances (Gavara 2016, Sci. Rep. 6:21267), RoV_i = var(P[i+1..i+N]) /
//     var(P[i-N..i]); the contact point is the sample of the largest RoV. N = max(5, min(n/10,
//     m/2)) samples, m the number of samples above half the largest force over the baseline
//     (so the window scales with the contact region, not with a long baseline). Uncertainty:
//     the half-width of the RoV peak at half its height above 1.
//   gof: goodness-of-fit scan. For each candidate sample c the model
//     P = P0 + k max(delta - delta_c, 0)^m is fitted to all samples by linear least squares
//     in (P0, k); the contact point is the candidate of least chi^2, P0 its fitted baseline.
//     m is the Hertz exponent of the indenter: 1 + 1/d for a profile r^d (paraboloid 3/2,
//     cone 2), 3/2 for any other profile (a sphere or a rounded tip at small depth).
//     The point is refined to the vertex of the parabola through chi^2 at the best sample and
//     its neighbours. Uncertainty: the profile-likelihood 1-sigma half-width, Delta chi^2 = s^2
//     with s^2 = chi^2_min / (n - 3) the residual variance: the larger of the parabola's
//     sqrt(2 s^2 / chi'') and half the extent of the samples with chi^2 - chi^2_min <= s^2.
// Uncertainties are at least half the median sample spacing.
#pragma once

#include <cstddef>
#include <limits>
#include <optional>
#include <utility>
#include <vector>

#include "layerjkr/types.hpp"

namespace layerjkr {

/// A range [first, second] of a quantity (units where it is used); first < second.
using Interval = std::pair<double, double>;

/// A contact point found from the data.
struct ContactPoint {
  ContactPointMethod method = ContactPointMethod::threshold;
  double delta = std::numeric_limits<double>::quiet_NaN();        ///< [m], the data's delta coordinate
  double uncertainty = std::numeric_limits<double>::quiet_NaN();  ///< [m], as defined above per method
  double baseline = std::numeric_limits<double>::quiet_NaN();     ///< P0 the method used [N]
  double noise = std::numeric_limits<double>::quiet_NaN();        ///< baseline noise sigma [N]
};

/// The contact point of approach samples (delta_i [m], P_i [N], any order, same length >= 10,
/// finite). `exponent` is gof's power m (> 0; see above), `baseline_window` a delta range [m]
/// holding the baseline samples (nullopt: the shallowest quarter). Throws InputError when the
/// data show no contact (threshold: the force never leaves the noise band for good) or the
/// window holds fewer than 3 samples, DomainError for method `fit` (it needs a model: fit()).
ContactPoint find_contact_point(const std::vector<double>& delta, const std::vector<double>& P,
                                ContactPointMethod method, double exponent = 1.5,
                                const std::optional<Interval>& baseline_window = std::nullopt);

/// The contact point a fit used and the samples its range kept (FitSummary::contact_point).
struct ContactPointReport {
  ContactPointMethod method = ContactPointMethod::fit;
  /// The contact point [m]: method fit, the fitted delta0 (0, the fixed value, when delta0 is
  /// not free); otherwise the method's point (the start of delta0 when delta0 is free).
  double value = std::numeric_limits<double>::quiet_NaN();
  /// [m]: fit, delta0's standard error (NaN when delta0 is not free); otherwise the method's
  /// uncertainty.
  double standard_error = std::numeric_limits<double>::quiet_NaN();
  /// The baseline [N] the method found (P0, fixed there unless P0 is free); NaN for fit.
  double baseline = std::numeric_limits<double>::quiet_NaN();
  /// The point the indentation and force ranges are measured from [m]: the method's point,
  /// or for fit the delta0 of the first fit (fit, select, refit); NaN without a range.
  double range_reference = std::numeric_limits<double>::quiet_NaN();
  /// Approach samples of the curve, and of them those the ranges kept (all without a range).
  std::size_t approach_samples = 0, samples_in_range = 0;
};

}  // namespace layerjkr
