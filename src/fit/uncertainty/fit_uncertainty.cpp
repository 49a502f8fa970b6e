// fit() step 4: error bars from ceres::Covariance, which parameters the data cannot separate
// (a null direction of J^T J, or a correlation above the limit), and w at its bound.
//
// The verdict never outruns the evidence: a parameter is identifiable only when its error bar
// (or, for w at its bound, its upper bound) was computed; when the covariance fails, every
// parameter without one says that its identifiability is unknown and why.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <utility>

#include <ceres/ceres.h>
#include <Eigen/Dense>

#include "fit/run/fit_run.hpp"
#include "fit/run/fit_steps.hpp"
#include "layerjkr/error.hpp"

namespace layerjkr::detail {
namespace {

using RowMajorMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// w ends "at its bound" when its dimensionless sqrt(w) coordinate is below this.
constexpr double kAtBound = 1e-9;
// ...or when holding it at 0 raises the deviance 2 delta cost / s^2 by less than this: the fitted
// w is then indistinguishable from 0 (a w of z standard errors raises it by about z^2).
constexpr double kNoSignalDeviance = 1e-6;
constexpr double kUpperBoundTolerance = 0.02;  // relative, on the deviance
constexpr int kUpperBoundSolves = 16;
constexpr double kUpperBoundBracket = 1e-3;  // in ln w
// Eigenvalues of the column-normalised J^T J below this fraction of the largest (singular
// values 1e-6 apart) are null directions; a parameter whose component in one exceeds
// kNullComponent belongs to the group the data cannot separate.
constexpr double kNullEigenvalueRatio = 1e-12;
constexpr double kNullComponent = 0.1;
// ceres::Covariance (DENSE_SVD) treats smaller reciprocal condition numbers as singular.
constexpr double kCovarianceMinReciprocalCondition = 1e-14;

const char* kUnknown = "identifiability unknown: ";


// What the Jacobian says at the solution: which free parameters it can separate (false: in a
// null direction, or a zero column), and J^T J to say, for a covariance that fails, the
// direction it is weakest in. w held at its bound is left out (its row and column are the identity).
struct Conditioning {
  std::vector<bool> separable;
  Eigen::MatrixXd JtJ;  ///< unscaled, as ceres::Covariance sees it (held w: a unit direction)
};

std::string direction(const Eigen::VectorXd& v, const ParameterMap& map, std::size_t held_slot) {
  std::vector<std::pair<double, std::size_t>> parts;
  for (Eigen::Index j = 0; j < v.size(); ++j)
    if (static_cast<std::size_t>(j) != held_slot && std::abs(v[j]) > kNullComponent)
      parts.emplace_back(std::abs(v[j]), static_cast<std::size_t>(j));
  std::sort(parts.rbegin(), parts.rend());
  std::string out;
  for (const auto& [c, j] : parts) {
    char buf[16];
    std::snprintf(buf, sizeof buf, "%.2f", c);
    out += (out.empty() ? "" : ", ") + map.name_at(j) + " (" + buf + ")";
  }
  return out;
}

Conditioning condition(const ResidualModel& ev, const FitOptions& options, std::size_t held_slot) {
  const std::size_t p_free = options.free.size();
  const Eigen::Map<const RowMajorMatrix> J(ev.jacobian().data(), static_cast<Eigen::Index>(ev.residuals().size()),
                                           static_cast<Eigen::Index>(p_free));
  Conditioning c;
  c.separable.assign(p_free, true);
  Eigen::MatrixXd JtJ = J.transpose() * J;
  if (held_slot < p_free) {
    const auto h = static_cast<Eigen::Index>(held_slot);
    JtJ.row(h).setZero();
    JtJ.col(h).setZero();
    JtJ(h, h) = JtJ.diagonal().maxCoeff() > 0.0 ? JtJ.diagonal().maxCoeff() : 1.0;
  }
  c.JtJ = JtJ;
  Eigen::VectorXd norms = JtJ.diagonal().cwiseSqrt();
  for (Eigen::Index j = 0; j < norms.size(); ++j) {
    if (norms[j] == 0.0) {
      c.separable[static_cast<std::size_t>(j)] = false;
      norms[j] = 1.0;
    }
  }
  const Eigen::VectorXd inv = norms.cwiseInverse();
  JtJ = inv.asDiagonal() * JtJ * inv.asDiagonal();
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(JtJ);
  const Eigen::VectorXd& ev2 = eig.eigenvalues();  // ascending
  for (Eigen::Index k = 0; k < ev2.size(); ++k) {
    if (ev2[k] > kNullEigenvalueRatio * ev2[ev2.size() - 1]) continue;
    const Eigen::VectorXd v = eig.eigenvectors().col(k);
    for (Eigen::Index j = 0; j < v.size(); ++j)
      if (std::abs(v[j]) > kNullComponent) c.separable[static_cast<std::size_t>(j)] = false;
  }
  if (held_slot < p_free) c.separable[held_slot] = true;  // judged by its upper bound instead
  return c;
}

// Names the rank-deficient group in the summary.
void report_rank_deficiency(const std::vector<bool>& separable, const ParameterMap& map, FitSummary* out) {
  std::string group;
  for (std::size_t j = 0; j < separable.size(); ++j)
    if (!separable[j]) group += (group.empty() ? "" : ", ") + map.name_at(j);
  if (group.empty()) return;
  out->unidentifiable.push_back(group + " (the Jacobian is rank-deficient: the data constrain only a combination)");
  for (std::size_t j = 0; j < separable.size(); ++j)
    if (!separable[j]) {
      out->parameters[j].identifiable = false;
      out->parameters[j].reason = "not separable: " + out->unidentifiable.back();
    }
}

// Pairs whose correlation exceeds the limit cannot be separated either: no error bars.
void report_correlated_pairs(const std::vector<bool>& separable, const ParameterMap& map, const FitOptions& options,
                             FitSummary* out) {
  const std::size_t p_free = separable.size();
  for (std::size_t i = 0; i < p_free; ++i)
    for (std::size_t j = i + 1; j < p_free; ++j)
      if (separable[i] && separable[j] && std::abs(out->correlation[i][j]) > options.correlation_limit) {
        out->unidentifiable.push_back(map.name_at(i) + " and " + map.name_at(j) +
                                      " (correlation " + short_number(out->correlation[i][j]) + ")");
        for (std::size_t k : {i, j}) {
          out->parameters[k].standard_error = kNaN;
          out->parameters[k].identifiable = false;
          out->parameters[k].reason = "not separable: " + out->unidentifiable.back();
        }
      }
}

// Standard errors (scaled by the residual variance) and correlations from the covariance:
// svd_covariance, or ceres::Covariance where a robust loss corrects the Jacobian.
// Returns why the covariance could not be computed, or "" when it was.
std::string compute_error_bars(ceres::Problem* problem, const ResidualModel& ev, double final_cost,
                               const ParameterMap& map, std::vector<double>& x, const FitOptions& options,
                               std::size_t residuals, const Conditioning& cond, std::size_t held_slot,
                               FitSummary* out) {
  const std::size_t p_free = x.size();
  const bool w_held = held_slot < p_free;
  const bool deficient = std::find(cond.separable.begin(), cond.separable.end(), false) != cond.separable.end();
  std::vector<double> C(p_free * p_free);
  bool computed;
  if (options.loss == LossType::none) {
    computed = svd_covariance(ev, held_slot, deficient, kCovarianceMinReciprocalCondition, &C);
  } else {
    if (w_held && !problem->HasManifold(x.data()))
      problem->SetManifold(x.data(), new ceres::SubsetManifold(static_cast<int>(p_free), {static_cast<int>(held_slot)}));
    ceres::Covariance::Options co;
    co.algorithm_type = ceres::DENSE_SVD;
    co.null_space_rank = deficient ? -1 : 0;
    co.min_reciprocal_condition_number = kCovarianceMinReciprocalCondition;
    ceres::Covariance cov(co);
    std::vector<const double*> blocks{x.data()};
    computed = cov.Compute(blocks, problem);
    if (computed) cov.GetCovarianceBlock(x.data(), x.data(), C.data());
  }
  if (!computed) {
    // Why, as ceres::Covariance judged it: the unscaled J^T J's reciprocal condition number and
    // its smallest eigenvector (computed only here: a fit whose covariance succeeds pays nothing).
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> raw(cond.JtJ);
    const Eigen::VectorXd& l = raw.eigenvalues();  // ascending
    const double rc = l[l.size() - 1] > 0.0 ? std::max(l[0], 0.0) / l[l.size() - 1] : 0.0;
    const std::string weakest = direction(raw.eigenvectors().col(0), map, held_slot);
    std::string why = "the covariance could not be computed: J^T J is singular to working precision (reciprocal "
                      "condition number " + short_number(rc) + ", below " +
                      short_number(kCovarianceMinReciprocalCondition) + ")";
    if (!weakest.empty()) why += " in the direction of " + weakest;
    return why;
  }
  const double dof = static_cast<double>(residuals - p_free + (w_held ? 1 : 0));
  const double s2 = 2.0 * final_cost / dof;  // scaled by the residual variance
  // Symmetric by construction: C from ceres may differ from its transpose in the last bit. Each
  // square root apart (their product can overflow), clamped to [-1, 1] where rounding leaves it
  // a bit beyond, NaN - unknown - where the variances are not finite and positive.
  for (std::size_t i = 0; i < p_free; ++i)
    for (std::size_t j = 0; j <= i; ++j)
      if (!(w_held && (i == held_slot || j == held_slot))) {
        // A variance over its own two square roots is 1 but for the last bit: exactly 1 here.
        const double r = i == j && C[i * p_free + i] > 0.0 && std::isfinite(C[i * p_free + i])
                             ? 1.0
                             : C[i * p_free + j] / std::sqrt(C[i * p_free + i]) / std::sqrt(C[j * p_free + j]);
        out->correlation[i][j] = out->correlation[j][i] = std::isfinite(r) ? std::clamp(r, -1.0, 1.0) : kNaN;
      }
  for (std::size_t j = 0; j < p_free; ++j) {
    if (!cond.separable[j] || j == held_slot) continue;
    out->parameters[j].standard_error = std::abs(map.derivative_at(j, x.data())) * std::sqrt(C[j * p_free + j] * s2);
    out->parameters[j].identifiable = std::isfinite(out->parameters[j].standard_error);
    if (!out->parameters[j].identifiable)
      out->parameters[j].reason = std::string(kUnknown) + "its variance is not finite";
  }
  report_correlated_pairs(cond.separable, map, options, out);
  return "";
}

// Error bars and verdicts at the run's current solution (w held at its bound or not). Returns
// why the covariance failed ("" if it did not, or was not computed).
std::string assess_once(FitRun& run, ResidualModel& ev, const ParameterMap& map, std::vector<double>& x,
                        const FitOptions& options, std::size_t residuals, FitSummary* out) {
  const std::size_t p_free = options.free.size();
  const int held = run.held_slot();
  const std::size_t held_slot = held >= 0 ? static_cast<std::size_t>(held) : p_free;
  out->unidentifiable.clear();
  for (auto& e : out->parameters) {
    e.identifiable = false;
    e.reason.clear();
  }
  if (!ev.evaluate(x.data(), true)) throw NumericalError("fit: the model cannot be evaluated at the solution");
  const Conditioning cond = condition(ev, options, held_slot);
  report_rank_deficiency(cond.separable, map, out);
  std::string failed, not_computed;
  const bool only_w_held = held_slot < p_free && p_free == 1;
  if (!options.compute_covariance)
    not_computed = "error bars were not asked for (FitOptions::compute_covariance = false)";
  else if (residuals <= p_free)
    not_computed = "no degrees of freedom are left for the error bars";
  else if (!only_w_held)
    failed = compute_error_bars(run.problem(), ev, run.final_cost(), map, x, options, residuals, cond, held_slot, out);
  const std::string& why = failed.empty() ? not_computed : failed;
  for (std::size_t j = 0; j < p_free; ++j) {
    ParameterEstimate& e = out->parameters[j];
    if (j == held_slot || !e.reason.empty() || e.identifiable) continue;
    e.reason = std::string(kUnknown) + why;
  }
  return failed;
}

// The one-sided 95 % upper bound on w held at 0 (see ParameterEstimate::upper_bound): the w at
// which refitting the others raises the deviance by kUpperBoundDeviance, by a secant on
// ln(deviance) against ln(w), safeguarded by bisection in ln(w). NaN if none is found.
double w_upper_bound(FitRun& run, const ParameterMap& map, double C0, double dof, std::string* why) {
  // Residuals at rounding level (noiseless data) give the deviance no scale.
  if (!(C0 > kNoiselessCost * dof) || !(dof > 0.0)) {
    *why = "the residuals are at rounding level, so there is no noise to scale a bound";
    return kNaN;
  }
  const double s2 = 2.0 * C0 / dof;
  auto deviance = [&](double w) {
    const double c = run.cost_with_w_held(std::sqrt(w) / map.s_scale);
    return std::isfinite(c) ? 2.0 * (c - C0) / s2 : std::numeric_limits<double>::infinity();
  };
  const double target = kUpperBoundDeviance;
  double lo = 0.0, hi = std::numeric_limits<double>::infinity();  // ln w bracket (lo: D below target)
  bool have_lo = false, have_hi = false;
  double w = map.s_scale * map.s_scale;  // the start's w scale
  double prev_w = kNaN, prev_D = kNaN;
  for (int k = 0; k < kUpperBoundSolves; ++k) {
    const double D = deviance(w);
    if (std::abs(D - target) < kUpperBoundTolerance * target) return w;
    const double u = std::log(w);
    if (D < target) {
      lo = have_lo ? std::max(lo, u) : u;
      have_lo = true;
    } else {
      hi = have_hi ? std::min(hi, u) : u;
      have_hi = true;
    }
    // A power law through the last two finite points; near w = 0 the deviance grows like w^2.
    double n = 2.0;
    if (std::isfinite(prev_D) && std::isfinite(D) && D > 0.0 && prev_D > 0.0 && prev_w != w)
      n = std::clamp(std::log(D / prev_D) / std::log(w / prev_w), 0.25, 4.0);
    // D <= 0 (holding w here is no worse than at 0): go up; a solve that failed: come down.
    double next = std::isfinite(D) && D > 0.0 ? u + std::log(target / D) / n : D < target ? u + 2.0 : u - 2.0;
    // The profile jumps where the model's pull-off crosses a sample: a tight bracket ends the
    // search at its upper end, the smallest w known to exceed the bound's deviance.
    if (have_lo && have_hi && hi - lo < kUpperBoundBracket) return std::exp(hi);
    if (have_lo && have_hi && !(next > lo && next < hi)) next = 0.5 * (lo + hi);
    if (have_lo && !have_hi) next = std::max(next, lo + 0.1);
    if (have_hi && !have_lo) next = std::min(next, hi - 0.1);
    prev_w = w;
    prev_D = D;
    w = std::exp(next);
  }
  *why = "the profile did not reach the bound's deviance in " + std::to_string(kUpperBoundSolves) + " refits";
  return kNaN;
}

// Summary-level verdict from the parameters'.
void conclude(FitSummary* out) {
  out->identifiable = std::all_of(out->parameters.begin(), out->parameters.end(),
                                  [](const ParameterEstimate& e) { return e.identifiable; });
  out->identifiability_known = out->identifiable || !out->unidentifiable.empty();
  out->identifiability_reason.clear();
  if (out->identifiable) return;
  if (!out->unidentifiable.empty()) {
    out->identifiability_reason = "the data cannot separate ";
    for (std::size_t k = 0; k < out->unidentifiable.size(); ++k)
      out->identifiability_reason += (k ? "; " : "") + out->unidentifiable[k];
    return;
  }
  for (const auto& e : out->parameters)
    if (!e.identifiable) {
      out->identifiability_reason = std::string(to_string(e.parameter)) + ": " + e.reason;
      return;
    }
}

}  // namespace

void assess_uncertainty(FitRun& run, ResidualModel& ev, const ParameterMap& map, std::vector<double>& x,
                        const FitOptions& options, const FitData& data, FitSummary* out) {
  const std::size_t p_free = options.free.size();
  const std::size_t residuals = data.residuals();
  const std::size_t w_slot = map.is_free(FitParameter::w) ? static_cast<std::size_t>(map.index(FitParameter::w)) : p_free;
  // No adhesive signal: w sits at 0 where the cost does not depend on sqrt(w) to first order,
  // or so near it that the covariance cannot be scaled. Refit with w held at 0 and keep that
  // fit when the deviance says w = 0 is as good.
  const bool at_zero = w_slot < p_free && x[w_slot] <= kAtBound;
  const char* sigma0_limit = at_zero ? nullptr : hold_sigma0_at_limit(run, map, x);
  if (sigma0_limit) {
    run.record(out);
    assess_once(run, ev, map, x, options, residuals, out);
    report_sigma0_at_limit(sigma0_limit, maugis_lambda_at(map, x), out);
    conclude(out);
    return;
  }
  const std::string failed = at_zero ? std::string() : assess_once(run, ev, map, x, options, residuals, out);
  bool held = false;
  if (w_slot < p_free && (at_zero || !failed.empty())) {
    double deviance = 0.0;
    bool no_signal = at_zero;
    if (!at_zero && !failed.empty()) {
      const double C = run.final_cost(), C0 = run.cost_with_w_held(0.0);
      const double dof = static_cast<double>(residuals - p_free);
      deviance = C0 <= C ? 0.0 : C > 0.0 ? (C0 - C) * dof / C : std::numeric_limits<double>::infinity();
      no_signal = std::isfinite(C0) && deviance < kNoSignalDeviance;
    }
    if (no_signal && run.hold_w(0.0)) {
      held = true;
      run.record(out);
      ParameterEstimate& w = out->parameters[w_slot];
      w.at_bound = true;
      assess_once(run, ev, map, x, options, residuals, out);
      const double dof = static_cast<double>(residuals - p_free + 1);
      const double C0 = p_free == 1 ? run.cost_with_w_held(0.0) : run.final_cost();
      std::string no_bound = "error bars were not asked for (compute_covariance = false)";
      w.upper_bound = options.compute_covariance ? w_upper_bound(run, map, C0, dof, &no_bound) : kNaN;
      std::string why = at_zero ? "the solver ended at w = 0" : "holding w at 0 raises the deviance by " +
                                                                    short_number(deviance) + ", below 1e-6";
      const bool any_retract = std::find(data.retract.begin(), data.retract.end(), true) != data.retract.end();
      std::string adhesive = !any_retract   ? "no retract samples, and the loading curve's shape does not call for w; "
                             : data.adhesive ? ""
                                             : "the retract shows no force below the baseline beyond noise; ";
      if (data.adhesive) {
        // The data show adhesion the model does not reproduce: never "no adhesive signal".
        const std::string shown = "the retract goes " + short_number(-data.dip) + " N below the baseline, " +
                                  short_number(-data.dip / std::max(data.noise, 1e-300)) + " noise sigmas";
        w.identifiable = false;
        w.upper_bound = kNaN;
        w.reason = "at its lower bound 0 although " + shown + ": the model does not reproduce the adhesion the "
                   "data show (check the retract's control, the model, the contact point)";
        out->warnings.push_back("w = 0 at its lower bound although " + shown +
                                ": the fit does not describe the adhesion the data show; no statement about w");
      } else {
        w.identifiable = std::isfinite(w.upper_bound);
        w.reason = "at its lower bound 0: no adhesive signal (" + adhesive + why + "); the error bar is one-sided: " +
                   (w.identifiable ? "w < " + short_number(w.upper_bound) + " J/m^2 (95 %, profile likelihood)"
                                   : std::string(kUnknown) + "no upper bound: " + no_bound);
        out->warnings.push_back("w = 0 at its lower bound: the data show no adhesion on this branch; the other "
                                "parameters and their error bars are from the fit with w held at 0" +
                                std::string(w.identifiable ? "; w < " + short_number(w.upper_bound) + " J/m^2 (95 %)" : ""));
      }
      // Re-evaluate where the others were assessed (the profile moved the evaluator).
      if (!ev.evaluate(x.data(), true)) throw NumericalError("fit: the model cannot be evaluated at the solution");
    }
  }
  if (at_zero && !held) assess_once(run, ev, map, x, options, residuals, out);
  check_sigma0_limits(run, ev, map, x, residuals, out);
  conclude(out);
}

void explain_no_move(const FitRun& run, const FitData& data, const ParameterMap& map, FitSummary* out) {
  if (run.moved_from_start()) return;
  std::string why;
  const bool any_retract = std::find(data.retract.begin(), data.retract.end(), true) != data.retract.end();
  if (map.is_free(FitParameter::w) && !data.adhesive && any_retract)
    why = "no adhesive signal for w: the retract shows no force below the baseline beyond noise (deepest " +
          short_number(-data.dip) + " N below it, noise " + short_number(data.noise) +
          " N), so w starts at its bound 0, where the cost does not depend on sqrt(w) to first order; ";
  switch (run.first_termination()) {
    case ceres::CONVERGENCE:
      why += "the start is already a minimum to the solver's tolerances (" + run.first_message() + ")";
      break;
    case ceres::NO_CONVERGENCE:
      why += "the solver reached its iteration limit without lowering the cost (" + run.first_message() + ")";
      break;
    default:
      why += "the solver stopped at the start: " + run.first_message();
  }
  out->no_move_reason = why;
}

}  // namespace layerjkr::detail
