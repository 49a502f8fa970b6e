// One fit's Ceres solves, restarts, exclusion and detilt (fit_run.hpp).
#include "fit/run/fit_run.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "core/line_fit.hpp"
#include "layerjkr/error.hpp"

namespace layerjkr::detail {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// The trust region starts this wide (in the dimensionless parameters): the data-driven
// start is close, so the first steps are near Gauss-Newton. Ceres' default (1e4) cost
// 2-3 extra iterations on the bundled sample and the real AFM curves.
constexpr double kInitialTrustRegionRadius = 1e8;
// Extra starts move the contact point by this fraction of the indentation span and the
// stiffness by this factor, alternately up and down, one ring further every two starts.
constexpr double kExtraStartContactStep = 0.05;
constexpr double kExtraStartStiffnessFactor = 3.0;

// Residual rows [row0, row1) of the shared evaluation, as one Ceres residual block.
class BlockCost final : public ceres::CostFunction {
 public:
  BlockCost(ResidualModel* eval, std::size_t row0, std::size_t row1, int n_free)
      : eval_(eval), row0_(row0), row1_(row1) {
    set_num_residuals(static_cast<int>(row1 - row0));
    mutable_parameter_block_sizes()->push_back(n_free);
  }
  bool Evaluate(double const* const* x, double* residuals, double** jacobians) const override {
    const bool jac = jacobians && jacobians[0];
    if (!eval_->evaluate(x[0], jac)) return false;
    const std::size_t n = static_cast<std::size_t>(parameter_block_sizes()[0]);
    std::copy(eval_->residuals().begin() + row0_, eval_->residuals().begin() + row1_, residuals);
    if (jac)
      std::copy(eval_->jacobian().begin() + row0_ * n, eval_->jacobian().begin() + row1_ * n,
                jacobians[0]);
    return true;
  }

 private:
  ResidualModel* eval_;
  std::size_t row0_, row1_;
};

}  // namespace

namespace {

int evaluations_of(const ceres::Solver::Summary& s) {
  return std::max(0, s.num_residual_evaluations) + std::max(0, s.num_jacobian_evaluations);
}

}  // namespace

bool finite_solve(const ceres::Solver::Summary& s) {
  if (!std::isfinite(s.initial_cost) || !std::isfinite(s.final_cost)) return false;
  for (const ceres::IterationSummary& it : s.iterations)
    if (!std::isfinite(it.cost) || !std::isfinite(it.gradient_max_norm)) return false;
  return true;
}

namespace {

double constant_force_cost(const FitData& data, double F) {
  double sw2 = 0.0, mean = 0.0;
  for (std::size_t i = 0; i < data.P.size(); ++i) {
    sw2 += data.sqrt_weight[i] * data.sqrt_weight[i];
    mean += data.sqrt_weight[i] * data.sqrt_weight[i] * data.P[i];
  }
  mean = sw2 > 0.0 ? mean / sw2 : 0.0;
  double cost = 0.0;
  for (std::size_t i = 0; i < data.P.size(); ++i) {
    const double r = data.sqrt_weight[i] * (data.P[i] - mean) / F;
    cost += 0.5 * r * r;
  }
  return cost;
}

}  // namespace

FitRun::FitRun(ResidualModel& ev, const ParameterMap& map, const FitOptions& options, FitData& data,
               std::vector<double>& x)
    : ev_(ev), cost_scale_(constant_force_cost(data, map.F)), map_(map), options_(options), data_(data), x_(x) {}

// One Ceres trust-region solve from xs; one residual block, or one per sample when a
// robust loss needs it.
std::unique_ptr<ceres::Problem> FitRun::solve_from(std::vector<double>& xs, ceres::Solver::Summary* summary,
                                                   int held) const {
  // One Ceres context per thread: creating it per fit costs more than a small fit. It must come
  // from Context::Create(): a default-constructed ceres::Context is only the opaque base, and
  // Ceres casts it to its implementation (whose thread pool mutex then lay in zeroed TLS in the
  // CLI by luck, and in garbage inside a Python module, where every fit failed with EINVAL).
  thread_local const std::unique_ptr<ceres::Context> context(ceres::Context::Create());
  ceres::Problem::Options po;
  po.context = context.get();
  po.disable_all_safety_checks = true;  // the blocks are built here, sized consistently
  po.cost_function_ownership = ceres::TAKE_OWNERSHIP;
  po.loss_function_ownership = ceres::TAKE_OWNERSHIP;
  auto problem = std::make_unique<ceres::Problem>(po);
  const int n = static_cast<int>(xs.size());
  const std::size_t last = ev_.points() - 1;
  if (options_.loss == LossType::none) {
    problem->AddResidualBlock(new BlockCost(&ev_, 0, ev_.row(last) + ev_.rows(last), n), nullptr, xs.data());
  } else {
    const double s = options_.loss_scale / map_.F;
    for (std::size_t i = 0; i <= last; ++i) {
      ceres::LossFunction* loss = options_.loss == LossType::huber
                                      ? static_cast<ceres::LossFunction*>(new ceres::HuberLoss(s))
                                      : new ceres::CauchyLoss(s);
      problem->AddResidualBlock(new BlockCost(&ev_, ev_.row(i), ev_.row(i) + ev_.rows(i), n), loss, xs.data());
    }
  }
  if (held >= 0)
    problem->SetManifold(xs.data(), new ceres::SubsetManifold(n, {held}));
  else if (map_.is_free(FitParameter::w))
    problem->SetParameterLowerBound(xs.data(), map_.index(FitParameter::w), 0.0);
  // The user's ranges (FitOptions::bounds) in the internal coordinates; a start outside one
  // begins at its edge.
  for (const ParameterBound& b : options_.bounds) {
    if (!map_.is_free(b.parameter) || map_.index(b.parameter) == held) continue;
    const int j = map_.index(b.parameter);
    const double lo = map_.coordinate(b.parameter, b.lower, xs.data()), hi = map_.coordinate(b.parameter, b.upper, xs.data());
    const auto k = static_cast<std::size_t>(j);
    xs[k] = std::min(std::max(xs[k], lo), hi);
    if (std::isfinite(lo)) problem->SetParameterLowerBound(xs.data(), j, lo);
    if (std::isfinite(hi)) problem->SetParameterUpperBound(xs.data(), j, hi);
  }
  ceres::Solver::Options so;
  so.linear_solver_type = ceres::DENSE_NORMAL_CHOLESKY;
  so.logging_type = options_.trace ? ceres::PER_MINIMIZER_ITERATION : ceres::SILENT;
  so.minimizer_progress_to_stdout = options_.trace;
  so.max_num_iterations = options_.max_iterations;
  so.function_tolerance = options_.function_tolerance;
  so.parameter_tolerance = options_.parameter_tolerance;
  // Relative to the problem's own scale: no rescaling of the data can meet it by itself.
  so.gradient_tolerance = options_.gradient_tolerance * std::max(cost_scale_, std::numeric_limits<double>::min());
  so.num_threads = 1;
  so.initial_trust_region_radius = kInitialTrustRegionRadius;
  ceres::Solve(so, problem.get(), summary);
  if (options_.trace) std::fprintf(stderr, "%s\n", summary->FullReport().c_str());
  return problem;
}

void FitRun::solve() {
  const bool first = !solved_;
  solved_ = true;
  if (!(linear_candidate() && solve_linear())) problem_ = solve_from(x_, &summary_, held_);
  if (!finite_solve(summary_)) {
    const std::string loss = options_.loss == LossType::none
                                 ? std::string()
                                 : " with the " + std::string(to_string(options_.loss)) + " loss of scale " +
                                       format_double(options_.loss_scale) + " N";
    throw NumericalError("fit: the cost or its gradient is not finite " +
                         std::string(std::isfinite(summary_.initial_cost) ? "during the solve" : "at the start") + loss +
                         " (Ceres: " + summary_.message + "); no result is reported");
  }
  iterations_ += static_cast<int>(summary_.iterations.size()) - 1;
  evaluations_ += evaluations_of(summary_);
  if (first) {
    moved_ = summary_.iterations.size() > 1 &&
             summary_.initial_cost - summary_.final_cost > options_.function_tolerance * summary_.initial_cost;
    first_termination_ = summary_.termination_type;
    first_message_ = summary_.message;
  }
}

bool FitRun::hold_w(double xw) { return hold(FitParameter::w, xw); }

bool FitRun::hold(FitParameter q, double xq) {
  const int slot = map_.index(q);
  const std::vector<double> before = x_;
  const int held_before = held_;
  x_[static_cast<std::size_t>(slot)] = xq;
  held_ = slot;
  if (!ev_.evaluate(x_.data(), false) || (x_.size() > 1 && !resolve_in_place())) {
    x_ = before;
    held_ = held_before;
    return false;
  }
  return true;
}

double FitRun::cost_with_w_held(double xw) { return cost_with_held(FitParameter::w, xw); }

double FitRun::cost_with_held(FitParameter q, double xq) {
  std::vector<double> xs = x_;
  xs[static_cast<std::size_t>(map_.index(q))] = xq;
  if (!ev_.evaluate(xs.data(), false)) return kNaN;
  if (xs.size() == 1) {  // nothing else to refit: the cost at xw (least squares; robust losses refit below)
    if (options_.loss == LossType::none) return least_squares_cost(ev_.residuals());
    return kNaN;
  }
  ceres::Solver::Summary s2;
  solve_from(xs, &s2, map_.index(q));
  return s2.IsSolutionUsable() && finite_solve(s2) ? s2.final_cost : kNaN;
}

void FitRun::try_extra_starts(int count, bool w_from_start) {
  if (count < 0) count = options_.extra_starts;
  const auto at = [&](std::vector<double>& v, FitParameter q) -> double& {
    return v[static_cast<std::size_t>(map_.index(q))];
  };
  bool moved = false;
  for (int k = 1; k <= count; ++k) {
    std::vector<double> xs(x_.size(), 0.0);
    if (map_.is_free(FitParameter::w)) at(xs, FitParameter::w) = at(x_, FitParameter::w) > 0 || w_from_start ? 1.0 : 0.0;
    const double sign = (k % 2) ? 1.0 : -1.0;
    const int ring = (k + 1) / 2;  // starts 1, 2 alternate sides; 3, 4 go twice as far
    if (map_.is_free(FitParameter::delta0)) at(xs, FitParameter::delta0) = sign * kExtraStartContactStep * ring;
    for (FitParameter q : {FitParameter::K, FitParameter::E})
      if (map_.is_free(q)) at(xs, q) = sign * std::log(kExtraStartStiffnessFactor) * ring;
    if (!ev_.evaluate(xs.data(), false)) continue;
    ceres::Solver::Summary s2;
    solve_from(xs, &s2, held_);
    if (s2.IsSolutionUsable() && finite_solve(s2) && s2.final_cost < summary_.final_cost) {
      summary_ = s2;
      x_ = xs;
      moved = true;
      iterations_ = static_cast<int>(s2.iterations.size()) - 1;
      evaluations_ = evaluations_of(s2);
    }
  }
  // The covariance needs a problem built on x itself, not on a start's copy: solve once
  // more from the winner (it stops at once).
  if (moved) solve();
}

// Solves again from x after the data (weights, detilted forces) changed. In place: the new
// problem points at x, which the covariance needs. Keeps x and the old solve if the new one
// is not usable (false).
bool FitRun::resolve_in_place() {
  ev_.invalidate();
  ceres::Solver::Summary s2;
  const std::vector<double> before = x_;
  auto p2 = solve_from(x_, &s2, held_);
  if (!s2.IsSolutionUsable() || !finite_solve(s2)) {
    x_ = before;
    return false;
  }
  iterations_ += static_cast<int>(s2.iterations.size()) - 1;
  evaluations_ += evaluations_of(s2);
  summary_ = s2;
  problem_ = std::move(p2);
  return true;
}

// In acquisition order, the retract samples from the first one the model has let go of up to
// the first that is back within exclusion_sigmas x noise of the baseline are not JKR. The baseline
// is what the model predicts there: P0, plus the lever's drag b v where a fit in time frees it.
// Refits without them until the set is stable (at most 4 passes); the baseline then comes from
// the detached samples beyond.
std::vector<bool> FitRun::exclude_non_jkr() {
  const std::size_t n = data_.P.size();
  std::vector<bool> excluded(n, false);
  if (options_.exclusion_sigmas == 0.0 || std::find(data_.retract.begin(), data_.retract.end(), true) == data_.retract.end())
    return excluded;
  const std::vector<double> weights = data_.sqrt_weight;
  // Noiseless (synthetic) data have no noise to scale by: a floor of 1e-6 of the force scale.
  const double band = std::max(options_.exclusion_sigmas * data_.noise, 1e-6 * map_.F);
  for (int pass = 0; pass < 4; ++pass) {
    if (!ev_.evaluate(x_.data(), false)) break;
    const double P0 = map_.is_free(FitParameter::P0) ? map_.value(FitParameter::P0, x_.data()) : 0.0;
    const double drag = map_.drag(x_.data());
    std::vector<bool> next(n, false);
    std::size_t first = n;
    for (std::size_t i = 0; i < n; ++i) {
      if (!data_.retract[i] || !ev_.detached()[i]) continue;
      const double baseline = P0 + (data_.velocity.empty() ? 0.0 : drag * data_.velocity[i]);
      if (std::abs(data_.P[i] - baseline) <= band) break;  // back at the baseline: the rest is baseline
      next[i] = true;
      first = std::min(first, i);
    }
    hold_tail_start(first, band, &next);
    if (next == excluded) break;
    excluded = next;
    for (std::size_t i = 0; i < n; ++i) data_.sqrt_weight[i] = excluded[i] ? 0.0 : weights[i];
    if (!resolve_in_place()) break;
  }
  return excluded;
}

// A tail that begins before the model lets go: under fixed grips the model holds the contact to
// its limit, past the data's pull-off, and a necking tail's first samples - already climbing back
// towards the baseline - sit above the model there by more than the band. Walking back from the
// first detached sample, in acquisition order, the retract samples after the observed pull-off
// (the force minimum) that lie above the model by more than the band belong to the tail: left
// in, they pull the model's limit out to them (E 3 % low and residuals 6.8 x the noise on a
// synthetic grips unloading with a 15-sample tail).
void FitRun::hold_tail_start(std::size_t first, double band, std::vector<bool>* tail) const {
  if (first == 0 || first >= data_.P.size() || !data_.retract[first - 1]) return;
  std::size_t bottom = first;  // the observed pull-off: the retract's force minimum before the tail
  for (std::size_t i = 0; i < first; ++i)
    if (data_.retract[i] && (bottom == first || data_.P[i] < data_.P[bottom])) bottom = i;
  const std::vector<double>& fit = ev_.predicted();
  for (std::size_t j = first; j-- > bottom + 1;) {
    if (!data_.retract[j] || !(data_.P[j] - fit[j] > band)) break;
    (*tail)[j] = true;
  }
}

// The slope of P against delta over the samples the model puts off contact (excluded ones
// have weight 0 and do not count); its error is that of the straight-line fit.
void FitRun::detilt_baseline(FitSummary* out) {
  if (!ev_.evaluate(x_.data(), false)) return;
  const std::vector<double>& fit = ev_.predicted();
  const double P0 = map_.is_free(FitParameter::P0) ? map_.value(FitParameter::P0, x_.data()) : 0.0;
  std::vector<std::size_t> off;
  for (std::size_t i = 0; i < data_.P.size(); ++i)
    if (data_.sqrt_weight[i] > 0.0 && fit[i] == P0) off.push_back(i);
  if (off.size() < 3) {
    out->warnings.push_back("baseline tilt: fewer than 3 samples off contact; no tilt fitted");
    return;
  }
  const LineFit line = fit_line(data_.delta, data_.P, off);
  if (!(line.sxx > 0.0)) return;
  out->baseline_slope = line.slope;
  out->baseline_slope_stderr = line.slope_stderr;
  for (std::size_t i = 0; i < data_.P.size(); ++i) data_.P[i] -= line.slope * (data_.delta[i] - line.mean_x);
  resolve_in_place();
}

void FitRun::record(FitSummary* out) {
  out->converged = summary_.termination_type == ceres::CONVERGENCE;
  out->termination = summary_.message;
  out->iterations = iterations_;
  out->function_evaluations = evaluations_;
  out->initial_cost = summary_.initial_cost;
  out->final_cost = summary_.final_cost;
  if (!ev_.evaluate(x_.data(), true)) throw NumericalError("fit: the model cannot be evaluated at the solution");
  out->points = data_.delta.size();
  out->points_in_contact = ev_.in_contact();
  out->delta = data_.delta;
  out->P = data_.P;
  out->P_fit = ev_.predicted();
  double ss = 0.0;
  std::size_t kept = 0;  // excluded samples (weight 0) are not part of the fit
  for (std::size_t i = 0; i < data_.P.size(); ++i)
    if (data_.sqrt_weight[i] > 0.0) {
      ss += (out->P_fit[i] - data_.P[i]) * (out->P_fit[i] - data_.P[i]);
      ++kept;
    }
  out->rms_residual = std::sqrt(ss / static_cast<double>(std::max<std::size_t>(kept, 1)));
  out->samples_fitted = kept;
  for (std::size_t j = 0; j < x_.size(); ++j) {
    out->parameters[j].value = map_.value_at(j, x_.data());
    out->parameters[j].standard_error = kNaN;
  }
  out->correlation.assign(x_.size(), std::vector<double>(x_.size(), kNaN));
}

}  // namespace layerjkr::detail
