// Whether a fit's residuals look like noise (fit_steps.hpp, diagnose_residuals).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numeric>

#include "fit/run/fit_steps.hpp"

namespace layerjkr::detail {
namespace {

// Far fewer runs than noise gives: z below this (a one-sided p of 3e-5).
constexpr double kStructuredRunsZ = -4.0;
// ...and residuals larger than the noise by this factor: a misfit that matters.
constexpr double kStructuredRmsOverNoise = 1.5;
// Residuals this many times the noise are a misfit whatever their signs (a few samples far off,
// as a retract's tail fitted under the wrong control): chi^2 / N = 9.
constexpr double kMisfitRmsOverNoise = 3.0;
// Residuals below this fraction of the force span are rounding: no structure to speak of.
constexpr double kNumericalFloor = 1e-9;
constexpr std::size_t kMinRunsSamples = 20;
// The least noise a column's weight assumes, as a fraction of its span.
constexpr double kNoiseFloor = 1e-6;

// The rms of P about its mean over the samples not excluded: the residual of the best constant.
double spread_about_mean(const std::vector<double>& P, const std::vector<bool>& excluded) {
  double sum = 0.0, ss = 0.0;
  std::size_t n = 0;
  for (std::size_t i = 0; i < P.size(); ++i)
    if (i >= excluded.size() || !excluded[i]) {
      sum += P[i];
      ++n;
    }
  if (n == 0) return 0.0;
  const double mean = sum / static_cast<double>(n);
  for (std::size_t i = 0; i < P.size(); ++i)
    if (i >= excluded.size() || !excluded[i]) ss += (P[i] - mean) * (P[i] - mean);
  return std::sqrt(ss / static_cast<double>(n));
}

}  // namespace

double third_difference_noise(const std::vector<double>& v, const std::vector<std::size_t>& idx) {
  if (idx.size() < 4) return 0.0;
  std::vector<double> d3;
  d3.reserve(idx.size() - 3);
  for (std::size_t k = 3; k < idx.size(); ++k)
    d3.push_back(v[idx[k]] - 3.0 * v[idx[k - 1]] + 3.0 * v[idx[k - 2]] - v[idx[k - 3]]);
  const double m = median(d3);
  for (double& x : d3) x = std::abs(x - m);
  return kMadToSigma * median(d3) / std::sqrt(20.0);
}

void diagnose_residuals(const FitData& data, double force_span, FitSummary* out) {
  std::vector<std::size_t> kept;
  for (std::size_t i = 0; i < data.P.size(); ++i)
    if (data.sqrt_weight[i] > 0.0) kept.push_back(i);
  // Errors in the displacement: each residual is already a distance in units of the force noise.
  const bool distances = data.displacement_weight > 0.0;
  out->noise = distances ? out->force_noise : third_difference_noise(data.P, kept);
  const double delta_noise = distances ? 0.0 : third_difference_noise(data.delta, kept);
  // Noise in the displacement moves each sample along the curve: its force residual is the
  // curve's slope times it (a rig's 50 nm against a film's contact stiffness of 2e4 N/m is 1 mN
  // beside 2 uN of force noise). The displacement's own third differences measure it.
  if (delta_noise > 0.0 && kept.size() >= 3) {
    double slope2 = 0.0;
    std::size_t count = 0;
    // Not across a dwell (segment 2, fits in time): there the model's force moves with time at a
    // near-constant indentation, so the force change over a step of noise is no slope (it inflated
    // a stress-relaxation dwell's noise 43x, hiding its misfit).
    const auto resting = [&](std::size_t i) { return i < data.segment.size() && data.segment[i] == 2; };
    // Each sample's slope from fitted points a few samples apart, as far as the step needs to
    // exceed the noise (a rig's displacement noise can be larger than its step).
    constexpr std::size_t kWidest = 8;
    for (std::size_t k = 1; k + 1 < kept.size(); ++k) {
      for (std::size_t m = 1; m <= kWidest && m <= k && k + m < kept.size(); ++m) {
        const std::size_t a = kept[k - m], b = kept[k + m];
        if (resting(a) || resting(b)) break;
        const double dd = data.delta[b] - data.delta[a];
        if (std::abs(dd) > 4.0 * delta_noise) {  // a step the noise does not dominate
          const double slope = (out->P_fit[b] - out->P_fit[a]) / dd;
          slope2 += slope * slope;
          ++count;
          break;
        }
      }
    }
    if (count > 0) out->noise = std::hypot(out->noise, std::sqrt(slope2 / static_cast<double>(count)) * delta_noise);
  }
  std::size_t runs = 0, above = 0, below = 0;
  int last = 0;
  for (std::size_t i : kept) {
    const double r = out->P[i] - out->P_fit[i];
    const int s = r > 0.0 ? 1 : r < 0.0 ? -1 : 0;
    if (s == 0) continue;
    (s > 0 ? above : below) += 1;
    if (s != last) ++runs;
    last = s;
  }
  const double n = static_cast<double>(above + below);
  if (above + below < kMinRunsSamples || above == 0 || below == 0) return;
  const double mean = 2.0 * static_cast<double>(above) * static_cast<double>(below) / n + 1.0;
  const double var = (mean - 1.0) * (mean - 2.0) / (n - 1.0);
  if (!(var > 0.0)) return;
  out->runs_z = (static_cast<double>(runs) - mean) / std::sqrt(var);
  const double ratio = out->rms_residual / out->noise;
  const bool above_floor = out->rms_residual > kNumericalFloor * force_span;
  const bool runs_few = out->runs_z < kStructuredRunsZ && ratio > kStructuredRmsOverNoise;
  if (!above_floor || !(runs_few || ratio > kMisfitRmsOverNoise)) return;
  char what[320];
  std::snprintf(what, sizeof what,
                "the residuals are not noise: their rms %.3g N is %.3g times the data's noise %.3g N, with %zu runs of "
                "signs where noise would give %.0f +- %.0f (z = %.3g)",
                out->rms_residual, ratio, out->noise, runs, mean, std::sqrt(var), out->runs_z);
  out->residual_structure = true;
  out->warnings.push_back(std::string(what) + ": the model does not describe these data (check the model, the "
                                              "retract's control, the branch, the baseline); no error bar is a "
                                              "statement about the sample");
  if (out->identifiable || out->identifiability_reason.empty()) {
    out->identifiable = false;
    out->identifiability_known = true;
    out->identifiability_reason = std::string("the model does not describe the data (") + what + ")";
  }
}

void record_model_notes(const CurveModel& model, const FitData& data, double force_span, FitSummary* out) {
  // 1e-4: 500 times below the answers' default warning threshold (5 %), and below what any
  // measured force curve resolves.
  constexpr double kNegligibleModelError = 1e-4;
  const double error = model.measured_error();
  const double force_error = error * force_span;
  const bool negligible = error <= kNegligibleModelError || force_error < 0.1 * data.noise;
  for (const std::string& note : model.notes()) {
    if (negligible) {
      out->notices.push_back(note);
    } else {
      out->warnings.push_back(note + ": a force error of about " + short_number(force_error) + " N against the data's noise " +
                              short_number(data.noise) + " N limits the fit's precision");
    }
  }
}

void diagnose_indentation(const FitData& data, FitSummary* out) {
  if (!(data.contact_slope >= kRigidContactSlope)) return;
  const double share = std::min(1.0, data.contact_slope);
  const std::string what =
      "the tip barely indents: the contact slope d(deflection)/dz is " + short_number(data.contact_slope) +
      " (1 where the sample does not deform), so the lever (k = " + short_number(data.spring_constant) +
      " N/m) takes " + short_number(100.0 * share) + " % of the piezo's motion and the indentation is within the "
      "deflection's calibration error" +
      (data.contact_slope > 1.0 ? " (above 1: the deflection sensitivity itself is off by " +
                                      short_number(100.0 * (data.contact_slope - 1.0)) + " % or more)"
                                : std::string()) +
      ": the sample is far stiffer than the lever, and E cannot be told from a rigid sample - use a stiffer lever";
  out->warnings.push_back(what);
  out->identifiable = false;
  out->identifiability_known = true;
  out->identifiability_reason = what;
}

void weigh_columns(const FitOptions& options, double force_span, FitData& data, FitSummary* out) {
  // Radii and errors in the displacement exclude each other (fit.cpp refuses both together).
  if (!options.errors_in_displacement && (data.radius_driven || data.a.empty())) return;
  std::vector<std::size_t> all(data.P.size());
  std::iota(all.begin(), all.end(), std::size_t{0});
  // Floors: a noiseless (synthetic) column is taken as resolved to a millionth of its span, so
  // that neither swamps the other (rounding-level noise would make the solve ill-conditioned).
  out->force_noise = options.force_noise.value_or(std::max(third_difference_noise(data.P, all), kNoiseFloor * force_span));
  out->force_noise_given = options.force_noise.has_value();
  if (options.errors_in_displacement) {
    const auto [lo, hi] = std::minmax_element(data.delta.begin(), data.delta.end());
    out->displacement_noise =
        options.displacement_noise.value_or(std::max(third_difference_noise(data.delta, all), kNoiseFloor * (*hi - *lo)));
    out->displacement_noise_given = options.displacement_noise.has_value();
    data.displacement_weight = out->force_noise / out->displacement_noise;
    return;
  }
  std::vector<std::size_t> with_a;
  std::vector<double> a;
  for (std::size_t i = 0; i < data.a.size(); ++i)
    if (!std::isnan(data.a[i])) a.push_back(data.a[i]);
  with_a.resize(a.size());
  std::iota(with_a.begin(), with_a.end(), std::size_t{0});
  double a_max = 0.0;
  for (double v : a) a_max = std::max(a_max, v);
  out->radius_noise = options.radius_noise.value_or(std::max(third_difference_noise(a, with_a), kNoiseFloor * a_max));
  out->radius_noise_given = options.radius_noise.has_value();
  // Force residuals are divided by the force span: radius ones by sigma_a x span / sigma_P.
  data.a_scale = out->radius_noise * force_span / out->force_noise;
}

void judge_plausibility(FitSummary* out) {
  std::string why;
  for (const ParameterEstimate& e : out->parameters) {
    const std::string name = to_string(e.parameter), value = short_number(e.value);
    const bool modulus = e.parameter == FitParameter::E || e.parameter == FitParameter::K ||
                         e.parameter == FitParameter::E_inf || e.parameter == FitParameter::E_2;
    if (!std::isfinite(e.value))
      why = name + " is not finite";
    else if (modulus && !(e.value >= kPlausibleModulus[0] && e.value <= kPlausibleModulus[1]))
      why = name + " = " + value + " Pa lies outside every physical modulus [" + short_number(kPlausibleModulus[0]) +
            ", " + short_number(kPlausibleModulus[1]) + "] Pa";
    else if (e.parameter == FitParameter::w && e.value > kPlausibleWork)
      why = "w = " + value + " J/m^2 exceeds every physical work of adhesion (" + short_number(kPlausibleWork) + " J/m^2)";
    if (!why.empty()) break;
  }
  if (why.empty() && !out->P.empty()) {
    const auto [lo, hi] = std::minmax_element(out->P.begin(), out->P.end());
    const bool above_floor = out->rms_residual > kNumericalFloor * (*hi - *lo);
    // ...and with structure: residuals whose signs alternate as noise's do are noise the estimate
    // missed, not a model that fails.
    const bool structured = !(out->runs_z >= kStructuredRunsZ);
    const double spread = spread_about_mean(out->P, out->excluded);
    if (above_floor && structured && out->noise > 0.0 && out->rms_residual > kFailedRmsOverNoise * out->noise &&
        out->rms_residual > kFailedShareOfSpread * spread)
      why = "the rms residual " + short_number(out->rms_residual) + " N is " + short_number(out->rms_residual / out->noise) +
            " times the data's noise " + short_number(out->noise) + " N (more than " + short_number(kFailedRmsOverNoise) +
            ") and " + short_number(100.0 * out->rms_residual / spread) + " % of the forces' own spread about their mean " +
            short_number(spread) + " N (more than " + short_number(100.0 * kFailedShareOfSpread) +
            " %): the model does not describe these data at all";
    if (why.empty() && !std::isfinite(out->rms_residual)) why = "the rms residual is not finite";
  }
  if (why.empty()) return;
  out->failure = why;
  out->converged = false;
  out->termination = "failed: " + why + " (Ceres: " + out->termination + ")";
  out->identifiable = false;
  out->identifiability_reason = "the fit failed: " + why;
  out->warnings.push_back("the fit failed: " + why + "; no value it returned is a statement about the sample");
}

}  // namespace layerjkr::detail
