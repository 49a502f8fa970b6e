// fit(): the model, the parameter map, the Ceres trust-region solve and the summary;
// the steps are in fit_data.cpp, fit_start.cpp and fit_uncertainty.cpp.
#include "layerjkr/fit.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cmath>
#include <memory>
#include <limits>

#include <ceres/ceres.h>

#include "core/line_fit.hpp"
#include "fit_steps.hpp"
#include "layerjkr/error.hpp"

namespace layerjkr {
namespace {

using detail::CurveEvaluator;
using detail::CurveModel;
using detail::CurveParameters;
using detail::FitData;
using detail::ParameterMap;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// Residual rows [row0, row1) of the shared evaluation, as one Ceres residual block.
class BlockCost final : public ceres::CostFunction {
 public:
  BlockCost(CurveEvaluator* eval, std::size_t row0, std::size_t row1, int n_free)
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
  CurveEvaluator* eval_;
  std::size_t row0_, row1_;
};



// The trust region starts this wide (in the dimensionless parameters): the data-driven
// start is close, so the first steps are near Gauss-Newton. Ceres' default (1e4) cost
// 2-3 extra iterations on the bundled sample and the real AFM curves.
constexpr double kInitialTrustRegionRadius = 1e8;
// Extra starts move the contact point by this fraction of the indentation span and the
// stiffness by this factor, alternately up and down, one ring further every two starts.
constexpr double kExtraStartContactStep = 0.05;
constexpr double kExtraStartStiffnessFactor = 3.0;

bool has(const FitOptions& options, FitParameter q) {
  return std::find(options.free.begin(), options.free.end(), q) != options.free.end();
}

// Every free parameter must be one the model family can vary.
void require_supported(const CurveModel& model, const FitOptions& options) {
  for (FitParameter q : options.free)
    if (!model.supports(q)) {
      std::string why = q == FitParameter::R ? "R can vary only for a paraboloid indenter with a closed-form model"
                        : q == FitParameter::E ? "E can vary only for a layer or half-space medium"
                                               : std::string(to_string(q)) + " is not a parameter of this medium; use E";
      throw InputError(std::string("fit: free parameter ") + to_string(q) + " is not available for model '" +
                       model.model_name() + "' (" + why + ")");
    }
  if (has(options, FitParameter::E) && (has(options, FitParameter::K) || has(options, FitParameter::G)))
    throw InputError("fit: E and K/G cannot both be free (K and G follow from E, nu and h)");
}

// Where each free parameter sits in x, and the scales that make x dimensionless.
ParameterMap make_parameter_map(const FitOptions& options, const ResolvedModel& resolved,
                                detail::SceneParameters fixed, double span, double force_span) {
  if (has(options, FitParameter::K) || has(options, FitParameter::G))
    fixed.layer_foundation = false;  // K, G vary independently of E
  ParameterMap map;
  map.free = options.free;
  map.fixed = fixed;
  map.slot.fill(-1);
  for (std::size_t j = 0; j < options.free.size(); ++j)
    map.slot[static_cast<int>(options.free[j])] = static_cast<int>(j);
  map.L = span;
  map.F = force_span;
  const CurveParameters<double>& f = fixed.values;
  map.ref[static_cast<int>(FitParameter::K)] = f.K;
  map.ref[static_cast<int>(FitParameter::E)] = f.E;
  map.ref[static_cast<int>(FitParameter::R)] = f.R;
  map.ref[static_cast<int>(FitParameter::G)] = f.G;
  map.G_log = resolved.spec.kind == ModelKind::full_foundation && !resolved.automatic;
  map.G_scale = f.G != 0.0 ? std::abs(f.G) : f.K * span * span;
  map.s_scale = std::sqrt(force_span / span) * 0.1;
  return map;
}

// One Ceres trust-region solve from xs; one residual block, or one per sample when a
// robust loss needs it.
std::unique_ptr<ceres::Problem> solve(CurveEvaluator& ev, const ParameterMap& map,
                                      const FitOptions& options, std::vector<double>& xs,
                                      ceres::Solver::Summary* summary) {
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
  const std::size_t last = ev.points() - 1;
  if (options.loss == LossType::none) {
    problem->AddResidualBlock(new BlockCost(&ev, 0, ev.row(last) + ev.rows(last), n), nullptr, xs.data());
  } else {
    const double s = options.loss_scale / map.F;
    for (std::size_t i = 0; i <= last; ++i) {
      ceres::LossFunction* loss = options.loss == LossType::huber
                                      ? static_cast<ceres::LossFunction*>(new ceres::HuberLoss(s))
                                      : new ceres::CauchyLoss(s);
      problem->AddResidualBlock(new BlockCost(&ev, ev.row(i), ev.row(i) + ev.rows(i), n), loss, xs.data());
    }
  }
  if (has(options, FitParameter::w))
    problem->SetParameterLowerBound(xs.data(), map.index(FitParameter::w), 0.0);
  ceres::Solver::Options so;
  so.linear_solver_type = ceres::DENSE_NORMAL_CHOLESKY;
  so.logging_type = options.trace ? ceres::PER_MINIMIZER_ITERATION : ceres::SILENT;
  so.minimizer_progress_to_stdout = options.trace;
  so.max_num_iterations = options.max_iterations;
  so.function_tolerance = options.function_tolerance;
  so.parameter_tolerance = options.parameter_tolerance;
  so.gradient_tolerance = options.gradient_tolerance;
  so.num_threads = 1;
  so.initial_trust_region_radius = kInitialTrustRegionRadius;
  ceres::Solve(so, problem.get(), summary);
  if (options.trace) std::fprintf(stderr, "%s\n", summary->FullReport().c_str());
  return problem;
}

// Solves again from options.extra_starts perturbed starts; keeps the lowest cost.
void try_extra_starts(CurveEvaluator& ev, const ParameterMap& map, const FitOptions& options,
                      std::vector<double>& x, ceres::Solver::Summary& summary,
                      std::unique_ptr<ceres::Problem>& problem) {
  const auto at = [&](std::vector<double>& v, FitParameter q) -> double& {
    return v[static_cast<std::size_t>(map.index(q))];
  };
  bool moved = false;
  for (int k = 1; k <= options.extra_starts; ++k) {
    std::vector<double> xs(x.size(), 0.0);
    if (map.is_free(FitParameter::w)) at(xs, FitParameter::w) = at(x, FitParameter::w) > 0 ? 1.0 : 0.0;
    const double sign = (k % 2) ? 1.0 : -1.0;
    const int ring = (k + 1) / 2;  // starts 1, 2 alternate sides; 3, 4 go twice as far
    if (map.is_free(FitParameter::delta0)) at(xs, FitParameter::delta0) = sign * kExtraStartContactStep * ring;
    for (FitParameter q : {FitParameter::K, FitParameter::E})
      if (map.is_free(q)) at(xs, q) = sign * std::log(kExtraStartStiffnessFactor) * ring;
    if (!ev.evaluate(xs.data(), false)) continue;
    ceres::Solver::Summary s2;
    solve(ev, map, options, xs, &s2);
    if (s2.IsSolutionUsable() && s2.final_cost < summary.final_cost) {
      summary = s2;
      x = xs;
      moved = true;
    }
  }
  // The covariance needs a problem built on x itself, not on a start's copy: solve once
  // more from the winner (it stops at once).
  if (moved) problem = solve(ev, map, options, x, &summary);
}

// Solves again from x after the data (weights, detilted forces) changed. In place: the new
// problem points at x, which the covariance needs. Keeps x and the old solve if the new one
// is not usable (false).
bool resolve_in_place(CurveEvaluator& ev, const ParameterMap& map, const FitOptions& options, std::vector<double>& x,
                      ceres::Solver::Summary& summary, std::unique_ptr<ceres::Problem>& problem) {
  ev.invalidate();
  ceres::Solver::Summary s2;
  const std::vector<double> before = x;
  auto p2 = solve(ev, map, options, x, &s2);
  if (!s2.IsSolutionUsable()) {
    x = before;
    return false;
  }
  summary = s2;
  problem = std::move(p2);
  return true;
}

// The stated rule (FitOptions::exclusion_sigmas): in acquisition order, the retract samples
// from the first one the model has let go of up to the first that is back within
// exclusion_sigmas x noise of the baseline P0 are not JKR. Refits without them until the set
// is stable (at most 4 passes); the baseline then comes from the detached samples beyond.
std::vector<bool> exclude_non_jkr(CurveEvaluator& ev, const ParameterMap& map, const FitOptions& options,
                                  FitData& data, std::vector<double>& x, ceres::Solver::Summary& summary,
                                  std::unique_ptr<ceres::Problem>& problem) {
  const std::size_t n = data.P.size();
  std::vector<bool> excluded(n, false);
  if (options.exclusion_sigmas == 0.0 || std::find(data.retract.begin(), data.retract.end(), true) == data.retract.end())
    return excluded;
  const std::vector<double> weights = data.sqrt_weight;
  // Noiseless (synthetic) data have no noise to scale by: a floor of 1e-6 of the force scale.
  const double band = std::max(options.exclusion_sigmas * data.noise, 1e-6 * map.F);
  for (int pass = 0; pass < 4; ++pass) {
    if (!ev.evaluate(x.data(), false)) break;
    const double P0 = map.is_free(FitParameter::P0) ? map.value(FitParameter::P0, x.data()) : 0.0;
    std::vector<bool> next(n, false);
    for (std::size_t i = 0; i < n; ++i) {
      if (!data.retract[i] || !ev.detached()[i]) continue;
      if (std::abs(data.P[i] - P0) <= band) break;  // back at the baseline: the rest is baseline
      next[i] = true;
    }
    if (next == excluded) break;
    excluded = next;
    for (std::size_t i = 0; i < n; ++i) data.sqrt_weight[i] = excluded[i] ? 0.0 : weights[i];
    if (!resolve_in_place(ev, map, options, x, summary, problem)) break;
  }
  return excluded;
}

// Baseline::tilt: the slope of P against delta over the samples the model puts
// off contact (excluded ones have weight 0 and do not count), removed from the data, then one
// more solve. The slope's error is that of the straight-line fit.
void detilt_baseline(CurveEvaluator& ev, const ParameterMap& map, const FitOptions& options, FitData& data,
                     std::vector<double>& x, ceres::Solver::Summary& summary,
                     std::unique_ptr<ceres::Problem>& problem, FitSummary* out) {
  if (!ev.evaluate(x.data(), false)) return;
  const std::vector<double>& fit = ev.predicted();
  const double P0 = map.is_free(FitParameter::P0) ? map.value(FitParameter::P0, x.data()) : 0.0;
  std::vector<std::size_t> off;
  for (std::size_t i = 0; i < data.P.size(); ++i)
    if (data.sqrt_weight[i] > 0.0 && fit[i] == P0) off.push_back(i);
  if (off.size() < 3) {
    out->warnings.push_back("baseline tilt: fewer than 3 samples off contact; no tilt fitted");
    return;
  }
  const detail::LineFit line = detail::fit_line(data.delta, data.P, off);
  if (!(line.sxx > 0.0)) return;
  out->baseline_slope = line.slope;
  out->baseline_slope_stderr = line.slope_stderr;
  for (std::size_t i = 0; i < data.P.size(); ++i) data.P[i] -= line.slope * (data.delta[i] - line.mean_x);
  resolve_in_place(ev, map, options, x, summary, problem);
}

// The solution, the fitted curve and its rms into the summary.
void record_solution(CurveEvaluator& ev, const ParameterMap& map, const FitData& data,
                     const std::vector<double>& x, const ceres::Solver::Summary& summary,
                     FitSummary* out) {
  out->converged = summary.termination_type == ceres::CONVERGENCE;
  out->termination = summary.message;
  out->iterations = static_cast<int>(summary.iterations.size()) - 1;
  out->initial_cost = summary.initial_cost;
  out->final_cost = summary.final_cost;
  if (!ev.evaluate(x.data(), true)) throw NumericalError("fit: the model cannot be evaluated at the solution");
  out->points = data.delta.size();
  out->points_in_contact = ev.in_contact();
  out->delta = data.delta;
  out->P = data.P;
  out->P_fit = ev.predicted();
  double ss = 0.0;
  std::size_t kept = 0;  // excluded samples (weight 0) are not part of the fit
  for (std::size_t i = 0; i < data.P.size(); ++i)
    if (data.sqrt_weight[i] > 0.0) {
      ss += (out->P_fit[i] - data.P[i]) * (out->P_fit[i] - data.P[i]);
      ++kept;
    }
  out->rms_residual = std::sqrt(ss / static_cast<double>(std::max<std::size_t>(kept, 1)));
  for (std::size_t j = 0; j < x.size(); ++j) {
    out->parameters[j].value = map.value(map.free[j], x.data());
    out->parameters[j].standard_error = kNaN;
  }
  out->correlation.assign(x.size(), std::vector<double>(x.size(), kNaN));
}

// The stiffness that lets the retract go, as the evaluator takes it: 0 for load control,
// infinity for fixed grips.
double control_stiffness(const FitOptions& options, const CurveData& curve) {
  const double k = options.cantilever_stiffness.value_or(curve.spring_constant);
  switch (options.retract_control) {
    case RetractControl::load: return 0.0;
    case RetractControl::fixed_grips: return std::numeric_limits<double>::infinity();
    case RetractControl::automatic: return k > 0.0 ? k : 0.0;
    case RetractControl::cantilever: break;
  }
  if (!(k > 0.0))
    throw InputError(curve.source + ": retract control 'cantilever' needs the cantilever's spring constant, which "
                                    "the curve does not carry; give it (FitOptions::cantilever_stiffness [N/m])");
  return k;
}

}  // namespace

const ParameterEstimate& FitSummary::operator[](FitParameter p) const {
  for (const auto& e : parameters)
    if (e.parameter == p) return e;
  throw Error(std::string("FitSummary: parameter ") + to_string(p) + " was not free in this fit");
}

FitSummary fit(const CurveData& curve, const Scene& scene, const FitOptions& options) {
  const auto t_begin = std::chrono::steady_clock::now();
  options.validate();
  curve.validate();
  if (!scene.profile) throw InputError("fit: the scene has no indenter profile");

  double span = 0.0, force_span = 0.0;
  FitData data = detail::select_fit_data(curve, options, &span, &force_span);
  FitSummary out;
  detail::SceneParameters fixed;
  const ResolvedModel resolved = resolve_model(scene);
  const std::unique_ptr<CurveModel> model = detail::make_curve_model(scene, resolved, options, span, &fixed);
  out.model = model->model_name();
  out.family = model->family();
  require_supported(*model, options);
  ParameterMap map = make_parameter_map(options, resolved, fixed, span, force_span);  // the start refines it
  if (resolved.spec.ode)
    out.warnings.push_back("solver 'ode' verifies the closed forms; the fit evaluates the same "
                           "foundation in closed form");
  out.warnings.insert(out.warnings.end(), fixed.warnings.begin(), fixed.warnings.end());
  for (const auto& note : model->notes()) out.warnings.push_back(note);

  std::vector<double> x(options.free.size(), 0.0);
  const double k = control_stiffness(options, curve);
  data.cantilever = k > 0.0;
  CurveEvaluator ev(*model, map, data, k);
  detail::find_start(data, map, ev, x, curve.source);
  for (FitParameter q : options.free) {
    ParameterEstimate e;
    e.parameter = q;
    e.initial = map.value(q, x.data());
    out.parameters.push_back(e);
  }
  // A start outside the model's domain is a data problem.
  if (!ev.evaluate(x.data(), false))
    throw InputError(curve.source + ": the model cannot be evaluated at the data-driven start "
                                    "(the indentation exceeds the model's range of radii)");

  ceres::Solver::Summary summary;
  std::unique_ptr<ceres::Problem> problem = solve(ev, map, options, x, &summary);
  try_extra_starts(ev, map, options, x, summary, problem);
  const std::vector<double> weights = data.sqrt_weight;
  std::vector<bool> excluded = exclude_non_jkr(ev, map, options, data, x, summary, problem);
  if (options.baseline == Baseline::tilt) {
    detilt_baseline(ev, map, options, data, x, summary, problem, &out);
    data.sqrt_weight = weights;  // the exclusion is decided again on the detilted data
    ev.invalidate();
    excluded = exclude_non_jkr(ev, map, options, data, x, summary, problem);
  }
  record_solution(ev, map, data, x, summary, &out);
  out.excluded = excluded;
  const double P0 = map.is_free(FitParameter::P0) ? map.value(FitParameter::P0, x.data()) : 0.0;
  for (std::size_t i = 0; i < data.P.size(); ++i)
    if (data.retract[i] && !(data.P[i] - P0 >= out.pull_off_force)) out.pull_off_force = data.P[i] - P0;  // NaN at first
  out.excluded_count = static_cast<std::size_t>(std::count(excluded.begin(), excluded.end(), true));
  detail::assess_uncertainty(ev, problem.get(), summary.final_cost, map, x, options, data.residuals(), &out);
  if (options.branch == Branch::approach && has(options, FitParameter::w))
    out.warnings.push_back("on approach the model snaps in at zero load, so w is identified only "
                           "through the shape of the loading curve; fit the retract branch for w");
  out.solve_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t_begin).count();
  return out;
}

}  // namespace layerjkr
