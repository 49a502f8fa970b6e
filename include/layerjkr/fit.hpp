// layerjkr: identification of K, G, w (or E, w) from measured adhesive curves (Ceres).
//
//   layerjkr::FitOptions options;
//   options.free = {FitParameter::E, FitParameter::w, FitParameter::delta0};
//   layerjkr::FitSummary s = layerjkr::fit(curve, scene, options);
//   std::cout << s.brief_report();
//
// The forward model. The scene fixes the indenter, the medium and the model; the free
// parameters replace the scene's values. A sample (delta_i, P_i) is predicted as
//   P0 + P(a_i)  with delta(a_i) = delta_i - delta0 on the branch's stable part, else P0,
// where P(a), delta(a) is the adhesive curve of the scene: JKR (jkr.hpp, the default), or
// what its "adhesion" key asks for (adhesion.hpp) - the classical DMT (delta = delta_H,
// P = P_H - 2 pi w R, R the tip's radius, a varying R for a paraboloid) on every family, or
// Maugis-Dugdale - Maugis' closed form on the hertz family (maugis_dugdale.hpp), the Dugdale
// solver on the medium on the dugdale family - whose Dugdale stress sigma0 is the scene's,
// follows w where the scene gives z0, or is free (FitParameter::sigma0, fitted in log like E),
// or the Dugdale DMT (DMT with sigma0 or z0; dugdale family). A free sigma0 is identifiable only
// when the data exclude both its limits: holding it at lambda = 1e3 (JKR) and at 1e-3 (DMT)
// with the others refitted must raise the deviance beyond the one-sided 95 % point. A Dugdale
// law on a model that does not solve its medium exactly (a thin-layer law, a foundation, auto)
// throws InputError naming the scene's adhesion and model. The stable part is
// a >= a_0 (zero load) on approach: a soft cantilever snaps in at zero load, so the curve
// is continuous at P0; and a >= a_po (pull-off) on retract: after pull-off the tip is
// free. Samples with measured contact radii add residuals (a_model - a_i) / a_scale.
//
// Derivatives are exact: each a_i is found by safeguarded Newton iteration, and its
// sensitivity follows by implicit differentiation, da/dx = (d target/dx - d delta/dx)/delta'(a),
// evaluated with ceres::Jet. docs/fitting.md says why this beat latent a_i blocks.
//
// Families and their free parameters:
//   foundation (winkler, pasternak / filonenko_borodich asymptotic and full, layer
//     leading / two_term): K, G (T for Filonenko-Borodich), or E for a layer (K and G
//     follow from E, nu, h), w, delta0, P0, and R for a paraboloid.
//   hertz (half_space with a paraboloid): E, w, delta0, P0, R, and sigma0 with adhesion
//     maugis_dugdale.
//   tabulated (exact, edge_corrected, auto, half_space with any other profile): E, w,
//     delta0, P0. The scene's model is evaluated once on a log grid of radii and splined
//     (FitOptions::table_points_per_decade); its stiffness scales exactly with E.
//   dugdale (a Dugdale law on exact - a layer or a stack - or on half_space with a profile
//     other than a paraboloid): E, w, delta0, P0, and sigma0 with maugis_dugdale. The curve is
//     solved per parameter vector on 31 radii and interpolated (E by exact scaling, w and
//     sigma0 by forward differences): seconds per fit, not milliseconds (docs/fitting.md).
//
// In time. A scene whose medium relaxes (medium.viscoelastic) or whose adhesion has kinetics
// (adhesion.kinetics) is fitted in time, against every sample of the curve with its time
// (CurveData::t; InputError without it) - the history the force depends on - whatever the branch,
// which chooses only the samples that are residuals:
//   hereditary (a relaxing half-space, layer or stack, w = 0): Lee-Radok up to the deepest sample,
//     Ting's rule after (viscoelastic.hpp), over the measured indentation delta_i - delta0; free
//     E (instantaneous; a power law's at t0), E_inf and tau (a one-term Prony law), beta (a power
//     law), delta0, P0. Exact Jacobians; tens of milliseconds for curves of ~1 000 samples.
//   kinetic (crack kinetics on an elastic medium): approach and dwell at equilibrium (as above),
//     the retract by the crack's ODE from the equilibrium contact at the deepest sample, driven by
//     the measured indentation (kinetics.hpp); free E (or K, G), w (w0), v_star, n, delta0, P0. The
//     retract's Jacobian by central differences of the ODE: seconds per fit.
// Both start from an elastic fit of the scene without its time and a scan of the law's time scale;
// contact-point methods, ranges, retract windows and a tilted baseline are refused there.
// fit_joint fits several such curves of one sample together.
//
// Internally parameters are dimensionless: log(K/K0), log(E/E0), log(R/R0), log(sigma0/sigma0_0),
// G/(K0 L^2), sqrt(w/w0) (so w = 0 is a regular bound), delta0/L, P0/F, with L and F
// the data's length and force scales; residuals are divided by F.
#pragma once

#include <functional>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "layerjkr/contact_point.hpp"
#include "layerjkr/curve_data.hpp"
#include "layerjkr/fit_options.hpp"
#include "layerjkr/instrument.hpp"
#include "layerjkr/scene.hpp"
#include "layerjkr/types.hpp"

namespace layerjkr {

/// One parameter of the fitted model, in SI units.
///
/// Identifiability is never claimed without evidence: `identifiable` is true only when the
/// data were shown to determine the parameter - a standard error was computed, or (w at its
/// bound) its one-sided upper bound was. Otherwise it is false and `reason` says whether the
/// data cannot separate it (a null direction of the Jacobian, a correlation above the limit)
/// or whether that is unknown (the covariance could not be computed or was not asked for), and why.
struct ParameterEstimate {
  FitParameter parameter = FitParameter::K;
  /// A joint fit's per-curve parameter (delta0, P0): the curve's position in the input (0-based);
  /// -1 for a parameter every curve shares, and in a fit of one curve.
  int curve = -1;
  double value = 0.0;
  /// Standard error scaled by the residual variance (as lmfit / nanite do); NaN when not
  /// identifiable, at its bound, or not computed (`reason` says which).
  double standard_error = 0.0;
  double initial = 0.0;   ///< the data-driven start
  /// w ended at 0 because the data show no adhesive signal (fixing w = 0 raises the cost by a
  /// deviance below 1e-6, or the solver stopped there): the other parameters and their error
  /// bars come from the fit with w held at 0; w's error bar is one-sided (upper_bound).
  bool at_bound = false;
  /// at_bound: the 95 % one-sided upper bound on w [J/m^2] from the profile likelihood (the w at
  /// which refitting the other parameters with w held there raises the deviance
  /// 2 delta cost / s^2 by 2.706, the chi^2(1) 90 % point); NaN otherwise or if it was not found.
  double upper_bound = std::numeric_limits<double>::quiet_NaN();
  bool identifiable = false;  ///< true only when shown (see above)
  /// Empty when the parameter has its error bar; else why not (not separable, at its bound, or
  /// identifiability unknown and why), one sentence.
  std::string reason;
};

struct FitSummary {
  /// The solver converged and the answer is plausible: false also where the parameters left every
  /// physical range or the residuals are orders of magnitude above the noise (`failure`).
  bool converged = false;
  std::string termination;  ///< Ceres' termination message (prefixed by "failed: ..." on a failure)
  /// Empty, or why the fit failed although the solver may have stopped normally: a modulus
  /// outside [1e-3, 1e15] Pa, w above 1e3 J/m^2, a non-finite value, or an rms residual 100 times
  /// the data's noise and half the forces' spread about their mean. fit-map reports such a curve as failed, with this reason.
  std::string failure;
  /// Trust-region iterations summed over the solves that produced the result (the solve from the
  /// start, or the winning extra start, then the refits after exclusion, detilt and holding w).
  int iterations = 0;
  /// Evaluations of the residuals (each with or without the Jacobian) over the same solves, as
  /// Ceres counts them (lmfit's nfev): what the fit cost beyond its iterations.
  int function_evaluations = 0;
  std::string model;        ///< the contact model that was fitted (e.g. "two_term")
  FitFamily family = FitFamily::foundation;  ///< how the model was evaluated
  std::vector<ParameterEstimate> parameters;  ///< the free parameters, in FitOptions order
  /// Correlation matrix of the free parameters (row-major, NaN when not computed).
  std::vector<std::vector<double>> correlation;
  double rms_residual = 0.0;  ///< root-mean-square force residual [N] (unweighted)
  /// The samples the fit minimised (weight > 0): n in the statistics below.
  std::size_t samples_fitted = 0;
  /// Goodness of fit as lmfit states it, from the unweighted force residuals r of the n fitted
  /// samples and the k = parameters.size() free parameters: chi_square = sum r^2 [N^2],
  /// reduced_chi_square = chi_square / (n - k) [N^2], aic = n ln(chi_square / n) + 2 k and
  /// bic = n ln(chi_square / n) + k ln n (dimensionless; their differences between fits of the
  /// same samples choose a model: lower is better). NaN where n <= k or chi_square = 0.
  double chi_square() const;
  double reduced_chi_square() const;
  double aic() const;
  double bic() const;
  double initial_cost = 0.0, final_cost = 0.0;  ///< Ceres costs (dimensionless)
  std::size_t points = 0;             ///< samples on the branch
  std::size_t points_in_contact = 0;  ///< of which the model puts in contact
  /// True only when every free parameter is identifiable (ParameterEstimate::identifiable) and
  /// the residuals are noise (residual_structure false).
  bool identifiable = false;
  /// False when identifiability could not be decided (the covariance failed or was not
  /// computed): then `identifiable` is false and identifiability_reason says why.
  bool identifiability_known = false;
  /// Empty when identifiable; else why not, or why it is unknown (one sentence).
  std::string identifiability_reason;
  /// Groups of parameters that cannot be separated (empty when identifiable).
  std::vector<std::string> unidentifiable;
  /// Non-empty when the solver did not move from its start (0 iterations, or the cost unchanged
  /// to function_tolerance): why, e.g. no adhesive signal for w, or the start is already a
  /// minimum.
  std::string no_move_reason;
  /// What the user must act on or weigh: a model outside its accuracy, data the fit cannot
  /// trust, a diagnosis that limits the answer.
  std::vector<std::string> warnings;
  /// What the user should know but need not act on (recorded in the report, the table and the
  /// map report, never a warning): a numerical error far below what matters, a documented
  /// approximation, a reader's choice between two copies of a header key.
  std::vector<std::string> notices;
  /// The data used and the fitted model at the same samples (for plots and residuals). Under
  /// FitOptions::errors_in_displacement a contact sample's P_fit is its force moved by its distance
  /// to the curve, so that P - P_fit is the residual the fit minimised.
  std::vector<double> delta, P, P_fit;
  /// A fit in time: each sample's time [s] (aligned with delta, P); empty otherwise.
  std::vector<double> t;
  /// Per sample (aligned with delta, P): excluded by the rule of FitOptions::exclusion_sigmas
  /// (the retract samples after the release, up to the first back at the baseline: a necking
  /// tail, peeling, a viscoelastic tail after the observed pull-off).
  std::vector<bool> excluded;
  std::size_t excluded_count = 0;
  /// Baseline::tilt: the baseline's slope [N/m] and its standard error (0 without).
  double baseline_slope = 0.0, baseline_slope_stderr = 0.0;
  /// The force offset [N] subtracted before the fit (FitOptions::remove_offset; 0 when none was).
  double baseline_offset = 0.0;
  /// The measured pull-off force [N]: the lowest retract force minus the retract's baseline
  /// measured from the data (pull_off_baseline), as instruments' software measures adhesion; no
  /// fitted parameter moves it, and every statement of the report about the force below the
  /// baseline is this number (NaN without retract samples).
  double pull_off_force = std::numeric_limits<double>::quiet_NaN();
  /// The baseline the pull-off is measured from [N]: the median of the last tenth of the retract
  /// where it is at rest, else of the first tenth of the approach, else the force's zero; and
  /// which of these, in words (empty without retract samples).
  double pull_off_baseline = std::numeric_limits<double>::quiet_NaN();
  std::string pull_off_baseline_source;
  /// The baseline came from samples at rest (false: the force's zero, where none is).
  bool pull_off_baseline_measured = false;
  /// How the retract let go of the contact, read from the data before the fit (docs/fitting.md,
  /// "Rules decided from the data"): empty without adhesion on the retract, else e.g. "a jump at
  /// the force minimum", "held past the force minimum, then a jump", "held to the end",
  /// "gradual: a tail, excluded".
  std::string retract_release;
  /// The data's noise [N]: 1.4826 MAD of the force's third differences in acquisition order,
  /// divided by sqrt(20) (a smooth curve cancels; white noise of sigma gives sigma), combined in
  /// quadrature with the displacement's noise (its own third differences) times the fitted
  /// curve's rms slope: noise in delta moves a sample along the curve.
  double noise = std::numeric_limits<double>::quiet_NaN();
  /// A runs test of the residuals' signs in acquisition order (Wald-Wolfowitz): the number of
  /// runs as a z-score against noise's expectation, NaN with fewer than 20 fitted samples.
  /// Below -4 with an rms residual above 1.5 x noise the residuals have structure: the model
  /// does not describe the data, which a warning says and `identifiable` then never claims.
  double runs_z = std::numeric_limits<double>::quiet_NaN();
  /// With measured contact radii or errors in the displacement: the noise each column's residuals
  /// were divided by - force [N], radius [m], displacement [m] - and whether each was given
  /// (FitOptions::force_noise, radius_noise, displacement_noise) or estimated; NaN where unused.
  double force_noise = std::numeric_limits<double>::quiet_NaN(), radius_noise = std::numeric_limits<double>::quiet_NaN();
  double displacement_noise = std::numeric_limits<double>::quiet_NaN();
  bool force_noise_given = false, radius_noise_given = false, displacement_noise_given = false;
  /// The residuals are not noise (runs_z, or an rms residual above 3 x noise): the model does not
  /// describe the data; `identifiable` is then false whatever the parameters' error bars say.
  bool residual_structure = false;
  double solve_seconds = 0.0;
  /// The contact point: method, value and error, and the samples the ranges kept.
  ContactPointReport contact_point;

  /// The estimate for p; throws Error if p was not free.
  const ParameterEstimate& operator[](FitParameter p) const;
  /// A few lines: status, estimates +- errors, rms, identifiability, warnings, notices.
  std::string brief_report() const;
  /// The contact point [m] the model's indentation delta_i - delta0 is measured from: the fitted
  /// delta0 when it was free, else the one held fixed (contact_point.value: a contact-point
  /// method's, or 0). Plots draw force against this indentation.
  double model_delta0() const;
  /// The verdict in one cell: "yes", or "no: " / "unknown: " followed by identifiability_reason
  /// (the fit-map table's and the map report's identifiability column).
  std::string identifiability() const;
};

/// Fits `curve` with the model of `scene`. Throws InputError for data that cannot be
/// fitted (fewer samples than free parameters, no contact region, a parameter the model
/// does not have) and DomainError for invalid options. Convergence failures are reported in
/// the summary, not thrown.
///
/// The contact region: the deepest 5 % of the branch's samples must lie 5 noise sigmas above
/// its lowest force (noise: the MAD of the shallowest quarter). Retract data without a
/// baseline - tension-only unloading, a necking tail - are judged on the unloading branch
/// itself: the retract samples up to the observed pull-off (the force minimum, in acquisition
/// order) are on the stable JKR branch (dP/d delta > 0 even in tension), and their deepest
/// 5 % must lie 5 sigmas above the minimum, sigma from the second differences of the retract
/// samples. Then P0 starts at 0, and samples after the pull-off the model cannot describe are
/// excluded by the rule of FitOptions::exclusion_sigmas (docs/fitting.md).
///
/// Ceres logs its internal diagnostics (a failed line-search polynomial, an evaluation failure
/// it recovers from) through glog on stderr; the summary reports what matters. The CLI and the
/// Python module silence glog below FATAL; a C++ program linking layerjkr decides for itself
/// (`FLAGS_minloglevel = google::GLOG_FATAL;`, as tools/fit_robustness.cpp does).
FitSummary fit(const CurveData& curve, const Scene& scene, const FitOptions& options);

/// The scene a fit describes: `scene` with each fitted value in place of the scene's own, so the
/// fit becomes a model again (curve, summary, simulate). E sets medium.E (a stack's moduli are
/// scaled together, as the fit scales them: E is the top layer's); K and G (or T) the
/// foundation's constants; w, R (sphere, paraboloid), sigma0 (replacing a z0), E_inf and tau (a
/// standard linear solid), beta (a power law), v_star and n (crack kinetics) their keys. delta0,
/// P0 and a joint fit's per-curve offsets belong to the data, not the scene, and are skipped.
/// The result is parsed from the edited JSON, so its origin holds that JSON (what a file would).
/// Throws InputError for a scene built in code (no JSON to edit) or a value the scene's JSON has
/// no place for (K fitted on a medium given by E, nu and h), naming the parameter.
Scene fitted_scene(const Scene& scene, const std::vector<ParameterEstimate>& parameters);

/// Several curves of one sample fitted together - a relaxing medium or crack kinetics measured at
/// several speeds: every parameter but delta0 and P0 is shared, each curve keeps its own contact
/// point and baseline where they are free.
struct JointFitSummary {
  /// The joint fit: its parameters are the shared ones (ParameterEstimate::curve = -1), then
  /// delta0 and P0 of each curve in turn (curve = its position in the input), with one covariance
  /// over them all; its samples are every curve's, one curve after another; its warnings name the
  /// curve whose residuals are not noise.
  FitSummary fit;
  /// Curve k's samples in fit.delta, fit.P, ...: [curve_begin[k], curve_begin[k + 1]).
  std::vector<std::size_t> curve_begin;
  std::vector<std::string> sources;  ///< each curve's CurveData::source
  /// Each curve fitted alone (the joint fit's start): what one speed says by itself.
  std::vector<FitSummary> alone;
};

/// Fits `curves` (at least 2) jointly with the scene's law in time (the scene must relax or have
/// crack kinetics: with an elastic scene each curve has its own answer - fit them one by one).
/// Starts from each curve fitted alone; throws InputError naming the curve that cannot be fitted
/// alone, and as fit() does otherwise.
JointFitSummary fit_joint(const std::vector<CurveData>& curves, const Scene& scene, const FitOptions& options);

}  // namespace layerjkr

namespace layerjkr {

/// One curve of a batch: its summary, or why it could not be fitted.
struct BatchItem {
  std::string source;  ///< file name or CurveData::source
  bool ok = false;
  std::string error;   ///< the Error's message when !ok
  /// Without the per-sample vectors (delta, P, P_fit, excluded), to bound memory; with
  /// BatchOptions::display_points, a thinned copy of them - for a curve that was read but could
  /// not be fitted, its samples as read (delta, P; P_fit and excluded empty).
  FitSummary summary;
  /// Instrument files: the curve's number in the file, map position [m] and grid pixel
  /// (-1 / NaN where the file has none, and for CSV files).
  int curve = -1;
  double x = std::numeric_limits<double>::quiet_NaN(), y = std::numeric_limits<double>::quiet_NaN();
  int grid_x = -1, grid_y = -1;
  /// BatchOptions::skip returned true: neither read nor fitted (ok = false, error empty).
  bool skipped = false;
  /// BatchOptions::cancelled stopped the batch before this item started (ok = false).
  bool cancelled = false;
};

/// The item's quality in one word, as fit-map's table (`quality`) and the map report's status
/// layer name it: "failed" (not fitted), "not converged", "not identifiable", "warning" (fitted
/// with warnings; notices do not count), or "ok".
std::string batch_quality(const BatchItem& item);

/// How a batch runs, and the hooks that let a caller keep what it finished. Every hook may be
/// empty. The hooks are called from the worker threads: `cancelled` and `skip` concurrently
/// (they must be thread-safe, e.g. read an atomic or immutable data); `progress` and `on_item`
/// one call at a time, under the batch's lock (they need no lock of their own, and should be
/// quick: workers wait for them).
struct BatchOptions {
  int jobs = 1;  ///< worker threads, >= 1
  /// Called after each curve (done, total).
  std::function<void(std::size_t, std::size_t)> progress;
  /// Polled before each curve starts; once true, no further curve starts. Running fits finish
  /// (a fit cannot be interrupted), so the items that ran are always a prefix of the input,
  /// every one of them passed to on_item; the rest are returned with `cancelled` set.
  std::function<bool()> cancelled;
  /// Called with each item's identity (source and curve number; nothing read yet, so no map
  /// position) before it is read: true skips it (`skipped` set), e.g. because an earlier run
  /// already fitted it.
  std::function<bool(const BatchItem&)> skip;
  /// Called with each finished item (fitted, failed or skipped) and its index, in input order:
  /// as soon as it and every earlier item are finished, so a caller can write results as they
  /// come and keep a deterministic order. If on_item or progress throws, no further curve starts
  /// and the batch rethrows the first such exception once the running fits finish.
  std::function<void(std::size_t, const BatchItem&)> on_item;
  /// fit_files only: the curves of each instrument file to fit, by position in the file (a
  /// range of a map is read without the rest). A file the range selects no curve of is one
  /// failed item saying so. CSV files hold one curve each and ignore it.
  CurveRange curves;
  /// 0: each item's summary drops its per-sample vectors. > 0 (>= 8): it keeps them thinned
  /// for display to about this many samples (thin_for_display, map_report.hpp), in the
  /// worker, before the full ones are released: 3 doubles and a bit per kept sample, about
  /// 5 kB per curve for kDefaultDisplayPoints (80 MB for a 128 x 128 map).
  std::size_t display_points = 0;
};

/// Fits many curves in parallel with the same scene and options. A curve that cannot be
/// read or fitted is reported in its BatchItem and never stops the batch. Results keep
/// the input order, one per curve (cancelled and skipped ones included, marked).
std::vector<BatchItem> fit_batch(const std::vector<CurveData>& curves, const Scene& scene,
                                 const FitOptions& options, const BatchOptions& batch = {});

/// The same for files: CSV files, each read with `csv`, and instrument files
/// (instrument.hpp), of which every curve is its own item, with its number, map position and
/// pixel, its tip position from the file's spring constant (or csv.spring_constant when > 0).
/// Instrument files are streamed: each file's index is read first (to number the items), each
/// curve by the worker that fits it, so a map's samples are never held whole; memory grows
/// only with the items' summaries. A file that cannot be read is one failed item, a curve that
/// cannot be read its own failed item; neither stops the batch. Only regular files
/// (links followed) are opened: a FIFO, a directory, a dangling or looping link is a failed item
/// naming what it is, checked before anything opens it (a FIFO would block).
std::vector<BatchItem> fit_files(const std::vector<std::string>& paths, const Scene& scene,
                                 const FitOptions& options, const CsvOptions& csv,
                                 const BatchOptions& batch = {});

}  // namespace layerjkr
