// fit_joint (fit.hpp): curves of one sample at several speeds, one law in time, each curve its own
// contact point and baseline - started from each curve fitted alone.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>

#include "fit/run/fit_run.hpp"
#include "fit/run/fit_steps.hpp"
#include "fit/evaluators/joint_evaluator.hpp"
#include "layerjkr/error.hpp"
#include "fit/in_time/time_evaluators.hpp"
#include "fit/in_time/time_fit.hpp"

namespace layerjkr {
namespace {

using detail::CurveModel;
using detail::FitData;
using detail::ParameterMap;
using detail::ResidualModel;

bool per_curve(FitParameter q) { return q == FitParameter::delta0 || q == FitParameter::P0; }

// Shared parameters that vary in log (all but beta, w, G and drag) start at the alone fits' geometric mean.
bool logarithmic(FitParameter q) {
  return q != FitParameter::beta && q != FitParameter::w && q != FitParameter::G && q != FitParameter::drag;
}

// One curve of the joint fit: its data, model, local map and evaluator (addresses stable).
struct Part {
  FitData data;
  std::unique_ptr<CurveModel> model;
  ParameterMap map;
  std::unique_ptr<ResidualModel> ev;
  std::vector<std::size_t> slot;  // local parameter j -> global slot
};

double estimate(const FitSummary& s, FitParameter q) { return s[q].value; }

// A curve of a joint fit in messages: its source (a file's path, Python's "curves[1]"), or its
// place counted from 1 where it has none.
std::string curve_name(std::size_t k, const std::string& source) {
  return source.empty() ? "curve " + std::to_string(k + 1) : source;
}

// The residual diagnosis of curve k's samples, said as the curve's.
void diagnose_part(const Part& part, const FitSummary& joint, std::size_t begin, std::size_t k, const std::string& source,
                   FitSummary* out) {
  FitSummary slice;
  const std::size_t n = part.data.P.size();
  slice.P.assign(joint.P.begin() + static_cast<long>(begin), joint.P.begin() + static_cast<long>(begin + n));
  slice.P_fit.assign(joint.P_fit.begin() + static_cast<long>(begin), joint.P_fit.begin() + static_cast<long>(begin + n));
  double ss = 0.0;
  std::size_t kept = 0;
  for (std::size_t i = 0; i < n; ++i)
    if (part.data.sqrt_weight[i] > 0.0) {
      ss += (slice.P[i] - slice.P_fit[i]) * (slice.P[i] - slice.P_fit[i]);
      ++kept;
    }
  slice.rms_residual = std::sqrt(ss / static_cast<double>(std::max<std::size_t>(kept, 1)));
  slice.identifiable = true;
  double lo = slice.P[0], hi = lo;
  for (double p : slice.P) lo = std::min(lo, p), hi = std::max(hi, p);
  detail::diagnose_residuals(part.data, hi - lo, &slice);
  if (!slice.residual_structure) return;
  out->residual_structure = true;
  out->warnings.push_back(curve_name(k, source) + ": " + slice.warnings.back());
  if (out->identifiable || out->identifiability_reason.empty()) {
    out->identifiable = false;
    out->identifiability_known = true;
    out->identifiability_reason = "the model does not describe " + curve_name(k, source);
  }
}

}  // namespace

JointFitSummary fit_joint(const std::vector<CurveData>& curves, const Scene& scene, const FitOptions& options) {
  const auto t_begin = std::chrono::steady_clock::now();
  options.validate();
  if (!options.bounds.empty())
    throw InputError("fit_joint: bounds are not supported in joint fits (fit each curve alone with them)");
  if (options.errors_in_displacement)
    throw InputError("fit_joint: errors_in_displacement (--displacement-noise) is supported in elastic fits of one "
                     "curve, not in joint fits in time");
  if (curves.size() < 2)
    throw InputError("fit_joint: give at least 2 curves (given " + std::to_string(curves.size()) + ")");
  if (!scene.profile) throw InputError("fit_joint: the scene has no indenter profile");
  if (scene.medium.relaxation.kind == RelaxationLaw::Kind::elastic && !scene.adhesion.kinetics)
    throw InputError("fit_joint: a joint fit shares a law in time across speeds; this scene's medium does not relax "
                     "and its adhesion has no kinetics (an elastic model's curves each have their own answer: fit them "
                     "one by one)");
  // The same measurement given twice would count its noise twice and shrink every error bar by
  // sqrt(2) with nothing learnt: refused, naming both.
  for (std::size_t k = 1; k < curves.size(); ++k)
    for (std::size_t i = 0; i < k; ++i)
      if (curves[i].delta == curves[k].delta && curves[i].P == curves[k].P && curves[i].t == curves[k].t &&
          curves[i].a == curves[k].a && curves[i].segment == curves[k].segment)
        throw InputError("fit_joint: " + curve_name(i, curves[i].source) + " and " + curve_name(k, curves[k].source) +
                         " hold the same samples: a joint fit of "
                         "one measurement given twice would count its noise twice and shrink every error bar; give "
                         "each measurement once");
  JointFitSummary j;
  for (std::size_t k = 0; k < curves.size(); ++k) {
    j.sources.push_back(curves[k].source);
    try {
      j.alone.push_back(fit(curves[k], scene, options));
    } catch (const Error& e) {
      throw InputError("fit_joint: " + curve_name(k, curves[k].source) + " cannot be fitted alone, "
                       "which starts the joint fit: " + e.what());
    }
  }
  // The data and models, with one length and force scale for every curve: a residual weighs the
  // same wherever it comes from.
  const bool relaxes = scene.medium.relaxation.kind != RelaxationLaw::Kind::elastic;
  const Scene elastic = detail::elastic_scene(scene);
  const ResolvedModel resolved = resolve_model(elastic);
  FitOptions model_options = options;
  model_options.free.erase(std::remove_if(model_options.free.begin(), model_options.free.end(), detail::time_parameter),
                           model_options.free.end());
  std::vector<std::unique_ptr<Part>> parts;
  double L = 0.0, F = 0.0;
  for (std::size_t k = 0; k < curves.size(); ++k) {
    auto part = std::make_unique<Part>();
    double span = 0.0, force_span = 0.0;
    part->data = detail::select_time_data(curves[k], options, &span, &force_span);
    for (std::size_t i = 0; i < part->data.P.size() && i < j.alone[k].excluded.size(); ++i)
      if (j.alone[k].excluded[i]) part->data.sqrt_weight[i] = 0.0;  // the tail its own fit excluded
    L = std::max(L, span);
    F = std::max(F, force_span);
    parts.push_back(std::move(part));
  }
  // One drag for one lever in one liquid: x = 1 is a drag force the size of the force span at the
  // fastest base speed of any curve.
  double fastest = 0.0;
  for (const auto& part : parts)
    for (double v : part->data.velocity) fastest = std::max(fastest, std::abs(v));
  // The layout: shared parameters first, then each curve's delta0 and P0.
  std::vector<FitParameter> shared, own;
  for (FitParameter q : options.free) (per_curve(q) ? own : shared).push_back(q);
  ParameterMap global;
  std::vector<double> x;
  for (FitParameter q : shared) global.free.push_back(q), global.slot_curve.push_back(-1), global.slot_ref.push_back(0.0);
  for (std::size_t k = 0; k < curves.size(); ++k) global.curve_names.push_back(curve_name(k, curves[k].source));
  for (std::size_t k = 0; k < curves.size(); ++k)
    for (FitParameter q : own) {
      global.free.push_back(q);
      global.slot_curve.push_back(static_cast<int>(k));
      global.slot_ref.push_back(estimate(j.alone[k], q));
    }
  x.assign(global.free.size(), 0.0);
  // Shared starts: the alone fits' geometric (log parameters) or arithmetic means.
  std::vector<double> start(shared.size());
  for (std::size_t s = 0; s < shared.size(); ++s) {
    double sum = 0.0;
    for (const FitSummary& a : j.alone)
      sum += logarithmic(shared[s]) ? std::log(std::max(estimate(a, shared[s]), 1e-300)) : estimate(a, shared[s]);
    sum /= static_cast<double>(j.alone.size());
    start[s] = logarithmic(shared[s]) ? std::exp(sum) : sum;
  }
  std::vector<detail::JointEvaluator::Part> joint_parts;
  for (std::size_t k = 0; k < parts.size(); ++k) {
    Part& p = *parts[k];
    detail::SceneParameters fixed;
    p.model = detail::make_curve_model(elastic, resolved, model_options, L, &fixed);
    detail::law_values(scene, &fixed);
    p.map = detail::make_parameter_map(options, resolved, fixed, L, F);
    for (std::size_t s = 0; s < shared.size(); ++s) {
      const int q = static_cast<int>(shared[s]);
      if (shared[s] == FitParameter::w) continue;  // s = s_scale x: one s_scale for all (below)
      if (shared[s] == FitParameter::G && !p.map.G_log) continue;
      p.map.ref[q] = start[s];
    }
    for (FitParameter q : own) p.map.ref[static_cast<int>(q)] = estimate(j.alone[k], q);
    if (k == 0) {
      global.slot = p.map.slot;
      global.ref = p.map.ref;
      global.fixed = p.map.fixed;
      global.L = L;
      global.F = F;
      global.G_scale = p.map.G_scale;
      global.G_log = p.map.G_log;
      global.s_scale = p.map.s_scale;
      global.beta_scale = p.map.beta_scale;
      global.drag_scale = fastest > 0.0 ? F / fastest : 1.0;
      for (FitParameter q : own) global.slot[static_cast<int>(q)] = -1;  // per curve: slot_curve says whose
      for (std::size_t s = 0; s < shared.size(); ++s) global.slot[static_cast<int>(shared[s])] = static_cast<int>(s);
    }
    p.map.s_scale = global.s_scale;
    p.map.drag_scale = global.drag_scale;
    for (FitParameter q : options.free) {
      const auto pos = static_cast<std::size_t>(std::find(global.free.begin(), global.free.end(), q) - global.free.begin());
      p.slot.push_back(per_curve(q) ? shared.size() + k * own.size() +
                                          static_cast<std::size_t>(std::find(own.begin(), own.end(), q) - own.begin())
                                    : pos);
    }
    if (detail::relaxing_adhesion(scene))
      p.ev = std::make_unique<detail::RelaxingAdhesionEvaluator>(*scene.profile, scene.medium.nu, p.map, p.data,
                                                                  scene.medium.relaxation);
    else if (relaxes)
      p.ev = std::make_unique<detail::HereditaryEvaluator>(*p.model, p.map, p.data, scene.medium.relaxation);
    else
      p.ev = std::make_unique<detail::KineticEvaluator>(*p.model, p.map, p.data);
    joint_parts.push_back({p.ev.get(), p.slot});
  }
  for (std::size_t s = 0; s < shared.size(); ++s) {
    if (shared[s] == FitParameter::w) x[s] = std::sqrt(std::max(start[s], 0.0)) / global.s_scale;
    if (shared[s] == FitParameter::G && !global.G_log) x[s] = start[s] / global.G_scale;
    if (shared[s] == FitParameter::drag) x[s] = start[s] / global.drag_scale;
  }
  detail::JointEvaluator ev(joint_parts, global.free.size());
  // One FitData over every curve, for the cost's scale, the record and the degrees of freedom.
  FitData data;
  for (const auto& p : parts) {
    for (auto [to, from] : {std::pair{&data.delta, &p->data.delta}, {&data.P, &p->data.P}, {&data.sqrt_weight, &p->data.sqrt_weight},
                            {&data.t, &p->data.t}})
      to->insert(to->end(), from->begin(), from->end());
    data.retract.insert(data.retract.end(), p->data.retract.begin(), p->data.retract.end());
    data.noise += p->data.noise / static_cast<double>(parts.size());
  }
  FitOptions jo = options;
  jo.free = global.free;
  jo.exclusion_sigmas = 0.0;  // each curve's own fit decided its exclusions
  jo.extra_starts = 0;
  FitSummary& out = j.fit;
  out.model = j.alone[0].model;
  out.family = j.alone[0].family;
  for (std::size_t g = 0; g < global.free.size(); ++g) {
    ParameterEstimate e;
    e.parameter = global.free[g];
    e.curve = global.slot_curve[g];
    e.initial = global.value_at(g, x.data());
    out.parameters.push_back(e);
  }
  if (!ev.evaluate(x.data(), false)) throw InputError("fit_joint: the joint model cannot be evaluated at its start");
  detail::FitRun run(ev, global, jo, data, x);
  run.solve();
  run.record(&out);
  out.t = data.t;
  out.excluded.assign(data.P.size(), false);
  for (std::size_t i = 0; i < data.P.size(); ++i) out.excluded[i] = !(data.sqrt_weight[i] > 0.0);
  detail::assess_uncertainty(run, ev, global, x, jo, data, &out);
  j.curve_begin = ev.first_point();
  for (std::size_t k = 0; k < parts.size(); ++k) diagnose_part(*parts[k], out, j.curve_begin[k], k, j.sources[k], &out);
  out.notices.push_back("start: each of the " + std::to_string(curves.size()) + " curves fitted alone; the shared "
                        "parameters at their " + std::string(shared.empty() ? "" : "geometric ") + "mean");
  detail::judge_plausibility(&out);
  out.solve_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t_begin).count();
  return j;
}

}  // namespace layerjkr
