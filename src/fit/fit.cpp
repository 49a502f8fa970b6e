// fit(): the model, the parameter map, the Ceres trust-region solve and the summary;
// the steps are in fit_data.cpp, fit_start.cpp and fit_uncertainty.cpp.
#include "layerjkr/fit.hpp"

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <cstdio>
#include <cmath>
#include <limits>

#include <ceres/ceres.h>

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


}  // namespace

const ParameterEstimate& FitSummary::operator[](FitParameter p) const {
  for (const auto& e : parameters)
    if (e.parameter == p) return e;
  throw Error(std::string("FitSummary: parameter ") + to_string(p) + " was not free in this fit");
}

FitSummary fit(const CurveData& curve, const Scene& scene, const FitOptions& options) {
  const auto t_begin = std::chrono::steady_clock::now();
  options.Validate();
  curve.Validate();
  if (!scene.profile) throw InputError("fit: the scene has no indenter profile");

  double span = 0.0, force_span = 0.0;
  FitData data = detail::select_fit_data(curve, options, &span, &force_span);
  const std::size_t p_free = options.free.size();
  FitSummary out;
  // The model and which parameters it can vary.
  detail::SceneParameters fixed;
  const std::unique_ptr<CurveModel> model = detail::make_curve_model(scene, options, span, &fixed);
  out.model = model->model_name();
  out.family = model->family();
  for (FitParameter q : options.free)
    if (!model->supports(q)) {
      std::string why = q == FitParameter::R ? "R can vary only for a paraboloid indenter with a closed-form model"
                        : q == FitParameter::E ? "E can vary only for a layer or half-space medium"
                                               : std::string(to_string(q)) + " is not a parameter of this medium; use E";
      throw InputError(std::string("fit: --free ") + to_string(q) + " is not available for model '" +
                       out.model + "' (" + why + ")");
    }
  const auto has = [&](FitParameter q) {
    return std::find(options.free.begin(), options.free.end(), q) != options.free.end();
  };
  if (has(FitParameter::E) && (has(FitParameter::K) || has(FitParameter::G)))
    throw InputError("fit: E and K/G cannot both be free (K and G follow from E, nu and h)");
  if (scene.medium.type == MediumType::layer && (has(FitParameter::K) || has(FitParameter::G)))
    fixed.layer_foundation = false;  // K, G vary independently of E

  ParameterMap map;
  map.free = options.free;
  map.fixed = fixed;
  map.slot.fill(-1);
  for (std::size_t j = 0; j < p_free; ++j) map.slot[static_cast<int>(options.free[j])] = static_cast<int>(j);
  map.L = span;
  map.F = force_span;
  const CurveParameters<double>& f = fixed.values;
  map.ref[static_cast<int>(FitParameter::K)] = f.K;
  map.ref[static_cast<int>(FitParameter::E)] = f.E;
  map.ref[static_cast<int>(FitParameter::R)] = f.R;
  map.ref[static_cast<int>(FitParameter::G)] = f.G;
  map.G_log = scene.model == SceneModel::full;
  map.G_scale = f.G != 0.0 ? std::abs(f.G) : f.K * span * span;
  map.s_scale = std::sqrt(force_span / span) * 0.1;
  if (scene.solver == Solver::ode)
    out.warnings.push_back("solver 'ode' verifies the closed forms; the fit evaluates the same "
                           "foundation in closed form");
  out.warnings.insert(out.warnings.end(), fixed.warnings.begin(), fixed.warnings.end());
  for (const auto& note : model->notes()) out.warnings.push_back(note);

  std::vector<double> x(p_free, 0.0);
  CurveEvaluator ev(*model, map, data);
  detail::find_start(data, map, ev, x, curve.source);
  for (FitParameter q : options.free) {
    ParameterEstimate e;
    e.parameter = q;
    e.initial = map.value(q, x.data());
    out.parameters.push_back(e);
  }

  // Ceres: one residual block, or one per sample when a robust loss needs it.
  auto solve = [&](std::vector<double>& xs, ceres::Solver::Summary* summary) {
    // One Ceres context per thread: creating it per fit costs more than a small fit.
    thread_local ceres::Context context;
    ceres::Problem::Options po;
    po.context = &context;
    po.disable_all_safety_checks = true;  // the blocks are built here, sized consistently
    po.cost_function_ownership = ceres::TAKE_OWNERSHIP;
    po.loss_function_ownership = ceres::TAKE_OWNERSHIP;
    auto problem = std::make_unique<ceres::Problem>(po);
    const int n = static_cast<int>(p_free);
    if (options.loss == LossType::none) {
      problem->AddResidualBlock(new BlockCost(&ev, 0, ev.row(data.delta.size() - 1) +
                                                          ev.rows(data.delta.size() - 1), n),
                                nullptr, xs.data());
    } else {
      const double s = options.loss_scale / map.F;
      for (std::size_t i = 0; i < data.delta.size(); ++i) {
        ceres::LossFunction* loss = options.loss == LossType::huber
                                        ? static_cast<ceres::LossFunction*>(new ceres::HuberLoss(s))
                                        : new ceres::CauchyLoss(s);
        problem->AddResidualBlock(new BlockCost(&ev, ev.row(i), ev.row(i) + ev.rows(i), n), loss,
                                  xs.data());
      }
    }
    if (has(FitParameter::w))
      problem->SetParameterLowerBound(xs.data(), map.index(FitParameter::w), 0.0);
    ceres::Solver::Options so;
    so.linear_solver_type = ceres::DENSE_NORMAL_CHOLESKY;
    so.logging_type = ceres::SILENT;
    so.minimizer_progress_to_stdout = std::getenv("LAYERJKR_FIT_TRACE") != nullptr;
    if (so.minimizer_progress_to_stdout) so.logging_type = ceres::PER_MINIMIZER_ITERATION;
    so.max_num_iterations = options.max_iterations;
    so.function_tolerance = options.function_tolerance;
    so.parameter_tolerance = options.parameter_tolerance;
    so.gradient_tolerance = options.gradient_tolerance;
    so.num_threads = 1;
    so.initial_trust_region_radius = 1e8;  // the data-driven start is close: begin near Gauss-Newton
    ceres::Solve(so, problem.get(), summary);
    if (so.minimizer_progress_to_stdout) fprintf(stderr, "%s\n", summary->FullReport().c_str());
    return problem;
  };

  // Evaluate the start; a start outside the model's domain is a data problem.
  if (!ev.evaluate(x.data(), false))
    throw InputError(curve.source + ": the model cannot be evaluated at the data-driven start "
                                    "(the indentation exceeds the model's range of radii)");

  ceres::Solver::Summary summary;
  std::unique_ptr<ceres::Problem> problem = solve(x, &summary);
  for (int k = 1; k <= options.extra_starts; ++k) {
    std::vector<double> xs(p_free, 0.0);
    if (map.is_free(FitParameter::w)) xs[static_cast<std::size_t>(map.index(FitParameter::w))] = x[static_cast<std::size_t>(map.index(FitParameter::w))] > 0 ? 1.0 : 0.0;
    const double sign = (k % 2) ? 1.0 : -1.0;
    const int ring = (k + 1) / 2;  // starts 1, 2 alternate sides; 3, 4 go twice as far
    if (map.is_free(FitParameter::delta0))
      xs[static_cast<std::size_t>(map.index(FitParameter::delta0))] = sign * 0.05 * ring;
    for (FitParameter q : {FitParameter::K, FitParameter::E})
      if (map.is_free(q)) xs[static_cast<std::size_t>(map.index(q))] = sign * std::log(3.0) * ring;
    if (!ev.evaluate(xs.data(), false)) continue;
    ceres::Solver::Summary s2;
    auto p2 = solve(xs, &s2);
    if (s2.IsSolutionUsable() && s2.final_cost < summary.final_cost) {
      summary = s2;
      x = xs;
      problem = std::move(p2);
    }
  }

  out.converged = summary.termination_type == ceres::CONVERGENCE;
  out.termination = summary.message;
  out.iterations = static_cast<int>(summary.iterations.size()) - 1;
  out.initial_cost = summary.initial_cost;
  out.final_cost = summary.final_cost;
  if (!ev.evaluate(x.data(), true))
    throw NumericalError("fit: the model cannot be evaluated at the solution");
  out.points = data.delta.size();
  out.points_in_contact = ev.in_contact();
  out.delta = data.delta;
  out.P = data.P;
  out.P_fit = ev.predicted();
  double ss = 0.0;
  for (std::size_t i = 0; i < data.P.size(); ++i) ss += (out.P_fit[i] - data.P[i]) * (out.P_fit[i] - data.P[i]);
  out.rms_residual = std::sqrt(ss / static_cast<double>(data.P.size()));
  for (std::size_t j = 0; j < p_free; ++j) {
    out.parameters[j].value = map.value(options.free[j], x.data());
    out.parameters[j].stderr_ = kNaN;
  }
  out.correlation.assign(p_free, std::vector<double>(p_free, kNaN));

  detail::assess_uncertainty(ev, problem.get(), summary.final_cost, map, x, options, data.residuals(), &out);
  if (options.branch == Branch::approach && has(FitParameter::w))
    out.warnings.push_back("on approach the model snaps in at zero load, so w is identified only "
                           "through the shape of the loading curve; fit the retract branch for w");
  out.solve_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t_begin).count();
  return out;
}

}  // namespace layerjkr
