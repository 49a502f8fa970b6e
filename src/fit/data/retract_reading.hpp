// Internal: what a curve's retract shows, read from the data alone before any fit - its
// baseline, the measured pull-off, which samples are in contact, where the contact was released
// and which samples are a tail the JKR model cannot describe. Nothing here depends on the
// parameters being fitted, so the fit's objective does not move under it (docs/fitting.md,
// "Rules decided from the data").
#pragma once

#include <cstddef>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "fit/evaluators/curve_evaluator.hpp"
#include "layerjkr/fit.hpp"

namespace layerjkr::detail {

/// The pull-off as an instrument's software measures it: the lowest retract force against the
/// retract's own baseline.
struct PullOffMeasure {
  bool any_retract = false;
  /// Noise of the retract's forces [N]: third differences in acquisition order (a smooth curve
  /// cancels, so a curve in contact throughout has a noise too).
  double noise = 0.0;
  /// The baseline [N]: the median of the free part - the last tenth of the retract when it is
  /// at rest, else the first tenth of the approach when that is - or the force's zero when
  /// neither part is at rest (a rig in contact throughout; tension-only data).
  double baseline = 0.0;
  bool has_baseline = false;
  std::string baseline_source;  ///< e.g. "the median of the last 30 retract samples (at rest)"
  std::size_t minimum = 0;      ///< index (into the data) of the lowest retract force
  /// The lowest retract force minus the baseline [N] (NaN without retract samples).
  double pull_off = std::numeric_limits<double>::quiet_NaN();
  /// pull_off is below the baseline by more than kSignificantSigmas x noise (and 1e-6 of the
  /// force span): the data show adhesion.
  bool adhesive = false;
};

PullOffMeasure measure_pull_off(const FitData& data, double force_span);

/// The measure into the summary's pull_off_force, pull_off_baseline(_source, _measured).
void record_pull_off(const PullOffMeasure& m, FitSummary* out);

/// How the retract lets go of the contact, read from its samples after the force minimum.
enum class Release {
  none,            ///< no adhesion shown: the model places every retract sample
  at_end,          ///< the data end at the force minimum: every retract sample in contact
  at_minimum,      ///< a jump back towards the baseline right after the minimum (load control)
  held_then_jump,  ///< the force rises past the minimum in contact, then jumps (grips, a lever)
  held_to_end,     ///< the force rises past the minimum and ends far below the baseline (a rig)
  gradual,         ///< the force returns to the baseline without a jump: a tail, excluded
  held_gradual     ///< the same return read as the branch held in contact (hold_gradual_rise)
};

/// The release in a few words, FitSummary::retract_release.
const char* to_string(Release r);

struct RetractReading {
  PullOffMeasure pull_off;
  Release release = Release::none;
  std::size_t held_past_minimum = 0;  ///< retract samples in contact after the minimum
  double jump = 0.0;                  ///< the release's rise in one sample [N] (0 without)
  /// Per sample: 1 in contact, 0 free, -1 the model decides (approach; every sample when the
  /// retract shows no adhesion). Assigned to FitData::contact.
  std::vector<signed char> contact;
  /// Per sample: after the release and not yet back at the baseline - a tail (necking, peeling,
  /// a viscoelastic tail) excluded from the fit (FitOptions::exclusion_sigmas; 0 keeps it).
  std::vector<bool> tail;
  std::size_t tail_count = 0;
  /// One sentence: what the data show and what the rule decided (a notice of the fit).
  std::string rule;
};

/// Reads the retract of `data` (the samples a fit selected, in acquisition order). The tail is
/// back at the baseline at the first sample within exclusion_sigmas (3 when 0) noise sigmas of
/// it; a release is a rise in one sample of more than kSignificantSigmas sqrt(2) noise sigmas and
/// kReleaseStepRatio times the next one.
/// hold_gradual_rise reads a gradual return the other way: the contact's own branch, held up to
/// the first sample back at the baseline (a thin layer's branch under grips or a stiff lever may
/// return to zero force without a jump).
RetractReading read_retract(const FitData& data, const FitOptions& options, double force_span,
                            bool hold_gradual_rise = false);

/// A release is a rise in one sample at least this many times the next one: after it the force
/// sits at the baseline or relaxes far more slowly, while a tail's steps shrink gradually (0.78
/// of the previous step for one relaxing at 4 samples per e-fold) and the branch's own steps grow
/// towards the grips limit. A rise at the last sample is no release (nothing follows it).
constexpr double kReleaseStepRatio = 3.0;
/// A rise that ends further below the baseline than this fraction of the pull-off has not
/// returned: the contact held to the end (a rig unloading under displacement control).
constexpr double kHeldToEndFraction = 0.25;

/// A gradual return read as the branch (Release::held_gradual) is held only as far as the model's
/// branch reaches under its control: the samples from the first one the fit at x places beyond
/// it (CurveEvaluator::clamped) become the tail, and the fit is redone, until no held sample lies
/// beyond (at most 4 passes). Between the solves, never within one, so each objective is fixed.
/// `weights` are the samples' weights before any tail was excluded.
void trim_held_to_model(RetractReading& reading, const FitOptions& options, const std::vector<double>& weights,
                        FitData& data, CurveEvaluator& ev, const std::vector<double>& x,
                        const std::function<bool()>& resolve);

/// Applies a reading: the contact flags, weight 0 for the tail (unless exclusion_sigmas is 0),
/// and the measured pull-off into data.dip and data.adhesive.
void apply_reading(const RetractReading& reading, const FitOptions& options, FitData& data);

}  // namespace layerjkr::detail
