// fit(): data-driven start, Ceres trust region, covariance and identifiability.
#include "layerjkr/fit.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <cstdlib>
#include <cstdio>
#include <cmath>
#include <limits>
#include <numeric>

#include <ceres/ceres.h>
#include <Eigen/Dense>

#include "curve_evaluator.hpp"
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

double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  const auto mid = v.begin() + v.size() / 2;
  std::nth_element(v.begin(), mid, v.end());
  return *mid;
}


struct Start {
  double delta0 = 0.0, P0 = 0.0, stiffness_factor = 1.0, w = 0.0;
  std::size_t contact = 0;
  bool found = true;  ///< false: no trial put >= 3 samples in contact with a positive stiffness
};

// The non-adhesive master curve P(t) at the reference stiffness, tabulated once so a scan
// over contact points costs one interpolation per sample.
struct MasterCurve {
  std::vector<double> t, P;
};

MasterCurve master_curve(const CurveEvaluator& ev, const CurveParameters<double>& p, double span,
                         bool retract) {
  MasterCurve m;
  detail::BranchStart bs;
  if (!ev.branch_start(p, retract ? detail::StartKind::pull_off : detail::StartKind::zero_load, &bs)) throw InputError("fit: the initial guess has no stable branch");
  // Uniform in t = delta - delta0 over every offset the scan tries.
  const double t_hi = 2.0 * span;
  m.t.push_back(bs.delta);
  double P_start, d_start;
  ev.curve(p, bs.a, &d_start, &P_start, nullptr, nullptr);
  m.P.push_back(P_start);
  double lo = bs.a;
  const int n = 160;
  for (int k = 1; k <= n && bs.delta < t_hi; ++k) {
    const double t = bs.delta + (t_hi - bs.delta) * k / n;
    double P;
    const double a = ev.solve_radius(p, t, lo, lo, &P);
    if (!std::isfinite(a)) break;
    lo = a;
    m.t.push_back(t);
    m.P.push_back(P);
  }
  return m;
}

// Contact point and stiffness by a scan: for each trial delta0 the stiffness factor is the
// linear least-squares solution, so a scene's stiffness may be off by any factor.
Start scan_start(const FitData& d, const MasterCurve& approach, const MasterCurve& retract,
                 const ParameterMap& map, double P0, double span) {
  const bool free_d0 = map.is_free(FitParameter::delta0);
  const bool free_k = map.is_free(FitParameter::K) || map.is_free(FitParameter::E);
  const std::size_t n = d.delta.size(), stride = std::max<std::size_t>(1, n / 48);
  const double dmin = *std::min_element(d.delta.begin(), d.delta.end());
  // A subsample per branch, sorted by delta, so each trial walks the master curve once.
  std::array<std::vector<std::pair<double, double>>, 2> pts;
  for (std::size_t i = 0; i < n; i += stride) pts[d.retract[i] ? 1 : 0].emplace_back(d.delta[i], d.P[i] - P0);
  for (auto& v : pts) std::sort(v.begin(), v.end());
  const std::array<const MasterCurve*, 2> masters{&approach, &retract};
  auto trial = [&](double d0, Start* s) {
    double spp = 0.0, spy = 0.0, syy = 0.0, base = 0.0;
    std::size_t contact = 0;
    for (int b = 0; b < 2; ++b) {
      const MasterCurve& mc = *masters[b];
      std::size_t k = 0;
      for (const auto& [delta, y] : pts[b]) {
        const double x = delta - d0;
        if (x < mc.t.front()) {
          base += y * y;
          continue;
        }
        while (k + 1 < mc.t.size() && mc.t[k + 1] <= x) ++k;
        const double m = k + 1 < mc.t.size()
                             ? mc.P[k] + (x - mc.t[k]) / (mc.t[k + 1] - mc.t[k]) * (mc.P[k + 1] - mc.P[k])
                             : mc.P.back();
        ++contact;
        spp += m * m;
        spy += m * y;
        syy += y * y;
      }
    }
    double k = free_k ? (spp > 0.0 ? std::max(spy / spp, 0.0) : 0.0) : 1.0;
    const double cost = base + syy - 2.0 * k * spy + k * k * spp;
    s->delta0 = d0;
    s->stiffness_factor = k > 0.0 ? k : 1.0;
    s->contact = contact;
    return contact >= 3 && k > 0.0 ? cost : std::numeric_limits<double>::infinity();
  };
  Start best;
  best.P0 = P0;
  if (!free_d0) {
    trial(0.0, &best);
    return best;
  }
  double best_cost = std::numeric_limits<double>::infinity();
  double step = span / 16.0;
  double centre = dmin + 0.5 * span;
  int count = 17;
  for (int pass = 0; pass < 3; ++pass) {
    const double c0 = centre;
    for (int k = 0; k < count; ++k) {
      Start s;
      s.P0 = P0;
      const int offset = k - count / 2;
      const double d0 = c0 + offset * step;
      const double c = trial(d0, &s);
      if (c < best_cost) {
        best_cost = c;
        best = s;
      }
    }
    centre = best.delta0;
    step /= 4.0;
    count = 9;
  }
  best.found = std::isfinite(best_cost);
  return best;
}

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

  // The samples of the chosen branch.
  const std::vector<std::size_t> idx = curve.select(options.branch);
  FitData data;
  const std::size_t approach_count =
      curve.segment.empty()
          ? static_cast<std::size_t>(std::max_element(curve.delta.begin(), curve.delta.end()) - curve.delta.begin()) + 1
          : 0;
  for (auto* v : {&data.delta, &data.P, &data.a, &data.sqrt_weight}) v->reserve(idx.size());
  data.retract.reserve(idx.size());
  for (std::size_t i : idx) {
    data.delta.push_back(curve.delta[i]);
    data.P.push_back(curve.P[i]);
    data.a.push_back(curve.a.empty() ? kNaN : curve.a[i]);
    data.sqrt_weight.push_back(curve.weight.empty() ? 1.0 : std::sqrt(curve.weight[i]));
    const bool retract = curve.segment.empty() ? i >= approach_count : curve.segment[i] == 1;
    data.retract.push_back(retract);
  }
  if (curve.a.empty()) data.a.clear();
  const std::size_t p_free = options.free.size();
  if (data.residuals() <= p_free)
    throw InputError(curve.source + ": the " + to_string(options.branch) + " branch has " +
                     std::to_string(data.delta.size()) + " samples; fitting " +
                     std::to_string(p_free) + " parameters needs more samples than parameters");
  const auto [dmin, dmax] = std::minmax_element(data.delta.begin(), data.delta.end());
  const auto [pmin, pmax] = std::minmax_element(data.P.begin(), data.P.end());
  const double span = *dmax - *dmin, force_span = *pmax - *pmin;
  if (!(span > 0.0)) throw InputError(curve.source + ": delta is constant on the chosen branch; nothing to fit");
  if (!(force_span > 0.0)) throw InputError(curve.source + ": P is constant on the chosen branch; nothing to fit");

  {
    // A contact region exists only if the force grows with delta somewhere: the deepest
    // tenth of the samples must lie clearly above the lowest force (on retract the whole
    // contact may be tensile, so the free samples are no reference).
    // The deepest samples must lie clearly above the lowest force: a loading curve rises
    // with delta, and on retract even an all-tensile contact rises from pull-off.
    std::vector<std::size_t> by_delta(data.delta.size());
    std::iota(by_delta.begin(), by_delta.end(), std::size_t{0});
    std::sort(by_delta.begin(), by_delta.end(), [&](auto i, auto j) { return data.delta[i] < data.delta[j]; });
    const std::size_t m20 = std::max<std::size_t>(1, by_delta.size() / 20);
    double deep = 0.0;
    std::vector<double> shallow;
    for (std::size_t k = 0; k < m20; ++k) deep += data.P[by_delta[by_delta.size() - 1 - k]];
    deep /= static_cast<double>(m20);
    for (std::size_t k = 0; k < std::max<std::size_t>(1, by_delta.size() / 4); ++k) shallow.push_back(data.P[by_delta[k]]);
    const double centre = median(shallow);
    for (auto& v : shallow) v = std::abs(v - centre);
    const double sigma = 1.4826 * median(shallow);
    if (!(deep - *std::min_element(data.P.begin(), data.P.end()) > 5.0 * sigma))
      throw InputError(curve.source + ": no contact region - the force does not grow with delta on the " +
                       to_string(options.branch) + " branch (check the sign conventions: delta grows "
                       "towards the sample, P is positive when repulsive)");
  }
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
  map.G_log = scene.model == "full";
  map.G_scale = f.G != 0.0 ? std::abs(f.G) : f.K * span * span;
  map.s_scale = std::sqrt(force_span / span) * 0.1;
  data.a_scale = 1.0;
  if (!data.a.empty()) {
    double amax = 0.0;
    for (double v : data.a)
      if (!std::isnan(v)) amax = std::max(amax, v);
    data.a_scale = amax > 0.0 ? amax : 1.0;
  }
  if (scene.solver == "ode")
    out.warnings.push_back("solver 'ode' verifies the closed forms; the fit evaluates the same "
                           "foundation in closed form");
  {
    const BuiltScene built = scene.model == "auto" || scene.model == "exact" ||
                                     scene.model == "edge_corrected"
                                 ? BuiltScene{}
                                 : build_scene(scene);
    for (const auto& w : built.warnings) out.warnings.push_back(w);
  }
  for (const auto& note : model->notes()) out.warnings.push_back(note);

  // Data-driven start: baseline from the lowest quarter in delta, then a contact-point
  // scan with the stiffness solved linearly at each trial.
  std::vector<double> low;
  {
    std::vector<std::size_t> order(data.delta.size());
    std::iota(order.begin(), order.end(), std::size_t{0});
    std::sort(order.begin(), order.end(), [&](auto i, auto j) { return data.delta[i] < data.delta[j]; });
    for (std::size_t k = 0; k < std::max<std::size_t>(order.size() / 4, 1); ++k) low.push_back(data.P[order[k]]);
  }
  const double P0_start = has(FitParameter::P0) ? median(low) : 0.0;
  std::vector<double> x(p_free, 0.0);
  CurveEvaluator ev(*model, map, data);
  // Alternate the contact-point scan (at the current w) and the adhesion estimate: w from
  // the deepest force dip on retract, where the model's pull-off must match it.
  double dip = 0.0;
  for (std::size_t i = 0; i < data.P.size(); ++i)
    if (data.retract[i]) dip = std::min(dip, data.P[i] - P0_start);
  double noise;
  {
    std::vector<double> dev;
    const double mid = median(low);
    dev.reserve(low.size());
    for (double v : low) dev.push_back(std::abs(v - mid));
    noise = 1.4826 * median(dev);
  }
  const bool adhesive_data = dip < -std::max(5.0 * noise, 1e-6 * force_span);
  const bool estimate_w = has(FitParameter::w) && adhesive_data;
  if (adhesive_data) {
    // Retract samples are in contact until the observed pull-off: the first sample after
    // the deepest force that is back above half the dip (P(delta) is flat at pull-off, so
    // the deepest sample itself may come a few samples early).
    std::size_t deepest = data.P.size();
    for (std::size_t i = 0; i < data.P.size(); ++i)
      if (data.retract[i] && (deepest == data.P.size() || data.P[i] < data.P[deepest])) deepest = i;
    std::size_t jump = deepest;
    while (jump < data.P.size() && (!data.retract[jump] || data.P[jump] < P0_start + 0.5 * dip)) ++jump;
    data.contact.assign(data.P.size(), -1);
    for (std::size_t i = 0; i < data.P.size(); ++i)
      if (data.retract[i]) data.contact[i] = i < jump ? 1 : 0;
  }
  const int stiffness_index = static_cast<int>(has(FitParameter::K) ? FitParameter::K : FitParameter::E);
  for (int pass = 0; pass < 8; ++pass) {
    CurveParameters<double> p;
    double d0, P0;
    map.physical(x.data(), &p, &d0, &P0);
    const bool any_retract = std::find(data.retract.begin(), data.retract.end(), true) != data.retract.end();
    const bool any_approach = std::find(data.retract.begin(), data.retract.end(), false) != data.retract.end();
    const MasterCurve none{{std::numeric_limits<double>::infinity()}, {0.0}};
    const Start start = scan_start(data, any_approach ? master_curve(ev, p, span, false) : none,
                                   any_retract ? master_curve(ev, p, span, true) : none, map,
                                   P0_start, span);
    if (!start.found) {
      // An all-tensile retract (w = 0 cannot produce it): put the contact point at the
      // observed pull-off, keep the scene's stiffness, estimate w and scan again.
      if (!(pass == 0 && estimate_w))
        throw InputError(curve.source + ": no contact region - no trial contact point puts three or more "
                         "samples in contact with a positive stiffness (check the sign conventions)");
      const auto deepest = std::min_element(data.P.begin(), data.P.end()) - data.P.begin();
      map.ref[static_cast<int>(FitParameter::delta0)] = data.delta[static_cast<std::size_t>(deepest)];
      map.ref[static_cast<int>(FitParameter::P0)] = P0_start;
    }
    if (start.found) {
      map.ref[static_cast<int>(FitParameter::delta0)] = start.delta0;
      map.ref[static_cast<int>(FitParameter::P0)] = start.P0;
    }
    if (has(FitParameter::K) || has(FitParameter::E)) {
      map.ref[stiffness_index] *= start.stiffness_factor;
      if (has(FitParameter::G) && !map.G_log) map.G_scale *= start.stiffness_factor;
      if (has(FitParameter::G) && map.G_log) map.ref[static_cast<int>(FitParameter::G)] *= start.stiffness_factor;
    }
    // Without adhesion and shear term the curve's shape does not depend on the stiffness.
    const bool settled = start.found && (std::abs(std::log(start.stiffness_factor)) < 0.01 || (p.s == 0.0 && p.G == 0.0));
    if (!estimate_w && settled) break;
    if (estimate_w && settled && pass >= 2) break;
    if (!estimate_w) continue;
    map.physical(x.data(), &p, &d0, &P0);
    double lo = std::log(1e-12 * force_span / span), hi = std::log(1e6 * force_span / span);
    for (int it = 0; it < 40; ++it) {
      const double mid = 0.5 * (lo + hi);
      p.s = std::sqrt(std::exp(mid));
      detail::BranchStart bs;
      double P = 0.0, d;
      const bool ok = ev.branch_start(p, detail::StartKind::pull_off, &bs);
      if (ok) ev.curve(p, bs.a, &d, &P, nullptr, nullptr);
      (ok && P > dip ? lo : hi) = mid;
    }
    map.s_scale = std::sqrt(std::exp(0.5 * (lo + hi)));
    x[static_cast<std::size_t>(map.index(FitParameter::w))] = 1.0;
  }
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

  // Identifiability: the column-scaled Jacobian's null space names the parameters the
  // data cannot separate.
  const std::size_t m = ev.residuals().size();
  const Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>> J(
      ev.jacobian().data(), static_cast<Eigen::Index>(m), static_cast<Eigen::Index>(p_free));
  std::vector<bool> separable(p_free, true);
  const std::size_t w_slot = map.is_free(FitParameter::w) ? static_cast<std::size_t>(map.index(FitParameter::w)) : p_free;
  if (w_slot < p_free && x[w_slot] <= 1e-9) {
    out.parameters[w_slot].at_bound = true;
    out.warnings.push_back("w = 0 at its lower bound: the data show no adhesion on this branch; "
                           "its error bar is one-sided and not reported");
  }
  {
    // Eigenvalues of the column-normalised J^T J are the squared singular values; a
    // ratio below 1e-12 (singular values 1e-6 apart) is a null direction.
    // w held at its bound 0 is left out: dP/d sqrt(w) at fixed delta vanishes at w = 0
    // (the shifts of P and delta cancel to first order), so its column is zero there.
    const bool held = w_slot < p_free && out.parameters[w_slot].at_bound;
    Eigen::MatrixXd JtJ = J.transpose() * J;
    if (held) {
      JtJ.row(static_cast<Eigen::Index>(w_slot)).setZero();
      JtJ.col(static_cast<Eigen::Index>(w_slot)).setZero();
      JtJ(static_cast<Eigen::Index>(w_slot), static_cast<Eigen::Index>(w_slot)) = 1.0;
    }
    Eigen::VectorXd norms = JtJ.diagonal().cwiseSqrt();
    for (Eigen::Index j = 0; j < norms.size(); ++j) {
      if (norms[j] == 0.0) {
        separable[static_cast<std::size_t>(j)] = false;
        norms[j] = 1.0;
      }
    }
    const Eigen::VectorXd inv = norms.cwiseInverse();
    JtJ = inv.asDiagonal() * JtJ * inv.asDiagonal();
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(JtJ);
    const Eigen::VectorXd& ev2 = eig.eigenvalues();  // ascending
    for (Eigen::Index k = 0; k < ev2.size(); ++k) {
      if (ev2[k] > 1e-12 * ev2[ev2.size() - 1]) continue;
      const Eigen::VectorXd v = eig.eigenvectors().col(k);
      for (Eigen::Index j = 0; j < v.size(); ++j)
        if (std::abs(v[j]) > 0.1) separable[static_cast<std::size_t>(j)] = false;
    }
    std::string group;
    for (std::size_t j = 0; j < p_free; ++j)
      if (!separable[j]) {
        group += (group.empty() ? "" : ", ") + std::string(to_string(options.free[j]));
        out.parameters[j].identifiable = false;
      }
    if (!group.empty()) {
      out.identifiable = false;
      out.unidentifiable.push_back(group + " (the Jacobian is rank-deficient: the data constrain only a combination)");
    }
  }

  const bool w_held = w_slot < p_free && out.parameters[w_slot].at_bound;
  if (options.compute_covariance && data.residuals() > p_free && !(w_held && p_free == 1)) {
    if (w_held) problem->SetManifold(x.data(), new ceres::SubsetManifold(static_cast<int>(p_free), {static_cast<int>(w_slot)}));
    ceres::Covariance::Options co;
    co.algorithm_type = ceres::DENSE_SVD;
    int deficient = 0;
    for (bool s : separable) deficient += s ? 0 : 1;
    co.null_space_rank = deficient > 0 ? -1 : 0;
    co.min_reciprocal_condition_number = 1e-14;
    ceres::Covariance cov(co);
    std::vector<const double*> blocks{x.data()};
    if (cov.Compute(blocks, problem.get())) {
      std::vector<double> C(p_free * p_free);
      cov.GetCovarianceBlock(x.data(), x.data(), C.data());
      const double dof = static_cast<double>(data.residuals() - p_free);
      const double s2 = 2.0 * summary.final_cost / dof;  // scaled by the residual variance
      for (std::size_t i = 0; i < p_free; ++i)
        for (std::size_t j = 0; j < p_free; ++j)
          if (!(w_held && (i == w_slot || j == w_slot)))
            out.correlation[i][j] = C[i * p_free + j] / std::sqrt(C[i * p_free + i] * C[j * p_free + j]);
      for (std::size_t j = 0; j < p_free; ++j) {
        if (!separable[j] || out.parameters[j].at_bound) continue;
        out.parameters[j].stderr_ =
            std::abs(map.derivative(options.free[j], x.data())) * std::sqrt(C[j * p_free + j] * s2);
      }
      for (std::size_t i = 0; i < p_free; ++i)
        for (std::size_t j = i + 1; j < p_free; ++j)
          if (separable[i] && separable[j] && std::abs(out.correlation[i][j]) > options.correlation_limit) {
            out.identifiable = false;
            out.unidentifiable.push_back(std::string(to_string(options.free[i])) + " and " +
                                         to_string(options.free[j]) + " (correlation " +
                                         format_double(out.correlation[i][j]) + ")");
            out.parameters[i].stderr_ = kNaN;
            out.parameters[j].stderr_ = kNaN;
            out.parameters[i].identifiable = false;
            out.parameters[j].identifiable = false;
          }
    } else {
      out.warnings.push_back("the covariance could not be computed (ceres::Covariance failed)");
    }
  }
  if (options.branch == Branch::approach && has(FitParameter::w))
    out.warnings.push_back("on approach the model snaps in at zero load, so w is identified only "
                           "through the shape of the loading curve; fit the retract branch for w");
  out.solve_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t_begin).count();
  return out;
}

}  // namespace layerjkr
