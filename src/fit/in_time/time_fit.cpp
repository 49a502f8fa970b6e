// fit() in time: a relaxing medium (Lee-Radok and Ting) or crack kinetics, fitted to every sample
// of a curve with its time - the history the force depends on - from an elastic fit's start.
#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>

#include "fit/run/fit_run.hpp"
#include "fit/run/fit_steps.hpp"
#include "layerjkr/error.hpp"
#include "fit/data/retract_reading.hpp"
#include "fit/in_time/time_evaluators.hpp"
#include "fit/in_time/time_fit.hpp"

namespace layerjkr::detail {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

}  // namespace

bool time_parameter(FitParameter q) {
  return q == FitParameter::E_inf || q == FitParameter::tau || q == FitParameter::beta || q == FitParameter::v_star ||
         q == FitParameter::n || q == FitParameter::drag || q == FitParameter::E_2 || q == FitParameter::tau_2;
}

namespace {

std::vector<double> base_velocity(const CurveData& curve, std::size_t n) {
  // The base, where the lever is held: the tip's indentation plus the lever's deflection P/k (the
  // tip itself under grips, k unknown). Its speed is the slope of a straight line through each
  // segment's samples: the instrument's ramp, not the noise of neighbouring samples.
  const double k = curve.spring_constant;
  std::vector<double> v(n, 0.0);
  for (std::size_t begin = 0; begin < n;) {
    std::size_t end = begin + 1;
    const int label = curve.segment.empty() ? 0 : curve.segment[begin];
    while (end < n && (curve.segment.empty() || curve.segment[end] == label)) ++end;
    const std::size_t m = end - begin;
    if (m >= 2) {
      double st = 0.0, sz = 0.0;
      for (std::size_t i = begin; i < end; ++i) {
        st += curve.t[i];
        sz += curve.delta[i] + (k > 0.0 ? curve.P[i] / k : 0.0);
      }
      const double tm = st / static_cast<double>(m), zm = sz / static_cast<double>(m);
      double stt = 0.0, stz = 0.0;
      for (std::size_t i = begin; i < end; ++i) {
        const double dt = curve.t[i] - tm;
        stt += dt * dt;
        stz += dt * (curve.delta[i] + (k > 0.0 ? curve.P[i] / k : 0.0) - zm);
      }
      const double slope = stt > 0.0 ? stz / stt : 0.0;
      std::fill(v.begin() + static_cast<std::ptrdiff_t>(begin), v.begin() + static_cast<std::ptrdiff_t>(end), slope);
    }
    begin = end;
  }
  return v;
}

}  // namespace

bool relaxing_adhesion(const Scene& scene) {
  return scene.medium.relaxation.kind != RelaxationLaw::Kind::elastic && scene.w > 0.0 &&
         scene.medium.type == MediumType::half_space && scene.adhesion.model == AdhesionModel::maugis_dugdale;
}

void check_request(const CurveData& curve, const Scene& scene, const FitOptions& o) {
  const bool relaxes = scene.medium.relaxation.kind != RelaxationLaw::Kind::elastic;
  const RelaxationLaw& law = scene.medium.relaxation;
  const std::string what = relaxes ? "a relaxing medium (" + law.describe() + ")"
                                   : "crack kinetics (" + scene.adhesion.kinetics->describe() + ")";
  const auto refuse = [&](const std::string& why) { throw InputError(curve.source + ": " + what + " is fitted in time; " + why); };
  if (curve.t.empty())
    refuse("the curve has no time: give each sample's time [s] (a CSV's t column; Python's fit(..., t=)), or read an "
           "instrument file whose segments have durations");
  if (curve.radius_only()) refuse("(P, a) data have no indentation history to follow");
  if (o.contact_point != ContactPointMethod::fit || o.indentation_range || o.force_range)
    refuse("the contact point is delta0 (free it, or leave it 0), and the history needs every sample: no contact-point "
           "method and no indentation or force range");
  if (o.retract_window != RetractWindow::all) refuse("the retract window would cut the history: use retract_window all");
  if (o.baseline == Baseline::tilt) refuse("a tilted baseline is not fitted in time: use baseline constant");
  if (relaxing_adhesion(scene) && law.kind == RelaxationLaw::Kind::power_law)
    refuse("with adhesion the contact snaps in at the instantaneous modulus, which a power law does not have: use a "
           "law with one (sls, prony, maxwell2, fractional_sls, fractional_maxwell)");
  if ((o.branch == Branch::dwell || o.branch == Branch::approach_dwell) && !relaxes)
    refuse("the " + std::string(to_string(o.branch)) + " branch is a relaxing medium's: crack kinetics fit approach, "
           "retract or all");
  for (FitParameter q : o.free) {
    const bool sls = law.kind == RelaxationLaw::Kind::prony && law.g.size() == 1;
    const bool fractional = law.kind == RelaxationLaw::Kind::fractional, two_term = law.two_term_form;
    std::string no;
    if (q == FitParameter::E_inf && !(relaxes && (sls || two_term || law.plateau_form)))
      no = "is a one-term Prony law's (\"sls\", or \"prony\" with one g), a two-term Maxwell law's (\"maxwell2\") or a "
           "law's with a plateau (\"power_law_plateau\", \"fractional_sls\")";
    else if (q == FitParameter::tau && !(relaxes && (sls || two_term || fractional)))
      no = "is a one-term Prony law's (\"sls\", or \"prony\" with one g), a two-term Maxwell law's or a fractional law's";
    else if ((q == FitParameter::E_2 || q == FitParameter::tau_2) && !(relaxes && two_term))
      no = "is a two-term Maxwell law's second arm (\"maxwell2\")";
    else if (q == FitParameter::beta && !(relaxes && (law.kind == RelaxationLaw::Kind::power_law || fractional)))
      no = "is a power law's (\"power_law\") or a fractional law's (\"fractional_sls\", \"fractional_maxwell\")";
    else if (q == FitParameter::drag && !relaxes)
      no = "is fitted with a relaxing medium (medium.viscoelastic): the crack-kinetics fit does not model it yet";
    else if ((q == FitParameter::v_star || q == FitParameter::n) && relaxes)
      no = "belongs to crack kinetics (adhesion.kinetics)";
    else if (q == FitParameter::R && relaxes)
      no = "is not fitted on a relaxing medium (the indenter is fixed in time fits)";
    else if ((q == FitParameter::w || q == FitParameter::sigma0) && relaxes && !relaxing_adhesion(scene))
      no = "is fitted on a relaxing medium where the scene models its adhesion: a half-space (medium.type "
           "half_space) with w > 0 and adhesion.model maugis_dugdale";
    else if (q == FitParameter::sigma0 || q == FitParameter::R)
      no = "is not fitted with crack kinetics";
    if (!no.empty())
      throw InputError("fit: free parameter " + std::string(to_string(q)) + " " + no + "; this scene has " + what);
  }
}

FitData select_time_data(const CurveData& curve, const FitOptions& options, double* span, double* force_span) {
  FitOptions approach = options;
  approach.branch = Branch::approach;
  approach.free.erase(std::remove_if(approach.free.begin(), approach.free.end(), time_parameter), approach.free.end());
  double s0 = 0.0, f0 = 0.0;
  const FitData base = select_fit_data(curve.without_dwell(), approach, &s0, &f0);
  FitData data;
  data.baseline = base.baseline;
  data.noise = base.noise;
  data.offset = base.offset;
  data.spring_constant = base.spring_constant;
  data.contact_slope = base.contact_slope;
  const std::vector<bool> retract = curve.retract_mask();
  double largest = 0.0;
  for (std::size_t i = 0; i < curve.size(); ++i) largest = std::max(largest, curve.weight.empty() ? 1.0 : curve.weight[i]);
  const auto segment = [&](std::size_t i) { return curve.segment.empty() ? (retract[i] ? 1 : 0) : curve.segment[i]; };
  const bool dwell_branch = options.branch == Branch::dwell || options.branch == Branch::approach_dwell;
  bool approached = false;
  std::size_t dwell_samples = 0;
  for (std::size_t i = 0; i < curve.size(); ++i) {
    const int s = segment(i);
    if (options.branch == Branch::approach && s != 0 && i > 0 && segment(i - 1) == 0) break;  // the approach's end
    if (dwell_branch && s == 1) break;  // nothing after the dwell changes it
    approached = approached || s == 0;
    const bool in_dwell = s == 2 && approached;  // a pause before the approach is off the surface
    dwell_samples += in_dwell ? 1 : 0;
    bool weighted = options.branch == Branch::all || (options.branch == Branch::approach ? s == 0 : s == 1);
    if (dwell_branch) weighted = in_dwell || (options.branch == Branch::approach_dwell && s == 0);
    data.delta.push_back(curve.delta[i]);
    data.P.push_back(curve.P[i] - base.offset);
    data.t.push_back(curve.t[i]);
    data.segment.push_back(s);
    data.retract.push_back(s == 1);
    data.sqrt_weight.push_back(weighted ? std::sqrt((curve.weight.empty() ? 1.0 : curve.weight[i]) / largest) : 0.0);
  }
  if (dwell_branch && dwell_samples == 0)
    throw InputError(curve.source + ": the " + to_string(options.branch) + " branch needs a dwell (samples of segment 2 "
                                    "between the approach and the retract); this curve has none");
  double lo = data.delta[0], hi = lo, plo = kNaN, phi = kNaN;
  for (std::size_t i = 0; i < data.P.size(); ++i) {
    lo = std::min(lo, data.delta[i]);
    hi = std::max(hi, data.delta[i]);
    if (data.sqrt_weight[i] > 0.0) {
      plo = std::isnan(plo) ? data.P[i] : std::min(plo, data.P[i]);
      phi = std::isnan(phi) ? data.P[i] : std::max(phi, data.P[i]);
    }
  }
  *span = hi - lo;
  *force_span = phi - plo;
  if (!(*force_span > 0.0)) throw InputError(curve.source + ": P is constant on the chosen branch; nothing to fit");
  if (std::find(options.free.begin(), options.free.end(), FitParameter::drag) != options.free.end())
    data.velocity = base_velocity(curve, data.P.size());
  if (data.residuals() <= options.free.size())
    throw InputError(curve.source + ": the " + to_string(options.branch) + " branch has " +
                     std::to_string(data.residuals()) + " samples; fitting " + std::to_string(options.free.size()) +
                     " parameters needs more samples than parameters");
  return data;
}

Scene elastic_scene(const Scene& scene) {
  Scene s = scene;
  s.medium.relaxation = RelaxationLaw{};
  s.adhesion.kinetics.reset();
  return s;
}

void law_values(const Scene& scene, SceneParameters* fixed) {
  const RelaxationLaw& law = scene.medium.relaxation;
  CurveParameters<double>& v = fixed->values;
  if (law.kind == RelaxationLaw::Kind::prony && law.g.size() == 1) {
    v.E_inf = v.E * (1.0 - law.g[0]);
    v.tau = law.tau[0];
  }
  v.beta = law.beta;
  if (law.kind == RelaxationLaw::Kind::fractional) v.tau = law.tau_f;
  if (law.two_term_form) {  // psi = E_inf/E + g[0] exp(-t/tau[0]) + g[1] exp(-t/tau[1])
    v.E_inf = v.E * (1.0 - law.g[0] - law.g[1]);
    v.tau = law.tau[0];
    v.E_2 = v.E * law.g[1];
    v.tau_2 = law.tau[1];
  }
  if (law.plateau_form) v.E_inf = v.E * law.plateau;
  if (scene.adhesion.kinetics) {
    v.v_star = scene.adhesion.kinetics->v_star;
    v.n = scene.adhesion.kinetics->n;
  }
}

FitSummary fit_in_time(const CurveData& curve, const Scene& scene, const FitOptions& options) {
  check_request(curve, scene, options);
  const bool relaxes = scene.medium.relaxation.kind != RelaxationLaw::Kind::elastic;
  double span = 0.0, force_span = 0.0;
  FitData data = select_time_data(curve, options, &span, &force_span);
  require_usable_loss_scale(options, force_span, curve.source);
  FitSummary out;
  const Scene elastic = elastic_scene(scene);
  const ResolvedModel resolved = resolve_model(elastic);
  SceneParameters fixed;
  FitOptions model_options = options;
  model_options.free.erase(std::remove_if(model_options.free.begin(), model_options.free.end(), time_parameter),
                           model_options.free.end());
  // A relaxing medium's elastic force is the JKR curve at w = 0; its table must reach the data's span.
  const std::unique_ptr<CurveModel> model = make_curve_model(elastic, resolved, model_options, span, &fixed);
  law_values(scene, &fixed);
  out.model = model->model_name();
  out.family = relaxes ? FitFamily::hereditary : FitFamily::kinetic;
  ParameterMap map = make_parameter_map(options, resolved, fixed, span, force_span);
  if (!data.velocity.empty()) {
    double fastest = 0.0;
    for (double v : data.velocity) fastest = std::max(fastest, std::abs(v));
    if (!(fastest > 0.0)) throw InputError(curve.source + ": free parameter drag needs the base to move; it rests throughout");
    map.drag_scale = force_span / fastest;  // x = 1: a drag force the size of the force span
  }
  out.warnings.insert(out.warnings.end(), fixed.warnings.begin(), fixed.warnings.end());
  const bool adhesive = relaxing_adhesion(scene);
  if (relaxes && scene.w > 0.0 && !adhesive)
    out.warnings.push_back("the scene's w = " + format_double(scene.w) + " J/m^2 is not in this fit: a fit on a relaxing "
                           "medium models adhesion on the half-space with adhesion.model maugis_dugdale only; a retract "
                           "below the baseline is then misfitted, as the residual diagnosis reports");
  out.notices.insert(out.notices.end(), curve.notes.begin(), curve.notes.end());
  out.notices.insert(out.notices.end(), resolved.notices.begin(), resolved.notices.end());
  std::vector<double> x(options.free.size(), 0.0);
  std::unique_ptr<ResidualModel> ev;
  RelaxingAdhesionEvaluator* adhesion_ev = nullptr;
  if (adhesive) {
    auto a = std::make_unique<RelaxingAdhesionEvaluator>(*scene.profile, scene.medium.nu, map, data, scene.medium.relaxation);
    adhesion_ev = a.get();
    ev = std::move(a);
  } else if (relaxes)
    ev = std::make_unique<HereditaryEvaluator>(*model, map, data, scene.medium.relaxation);
  else
    ev = std::make_unique<KineticEvaluator>(*model, map, data);
  start_in_time(curve, elastic, scene, options, data, *ev, map, x, &out);
  for (FitParameter q : options.free) {
    ParameterEstimate e;
    e.parameter = q;
    e.initial = map.value(q, x.data());
    out.parameters.push_back(e);
  }
  if (!ev->evaluate(x.data(), false))
    throw InputError(curve.source + ": the model in time cannot be evaluated at the start (does the curve begin "
                                    "before the contact, and does the model reach its deepest indentation?)");
  FitRun run(*ev, map, options, data, x);
  run.solve();
  run.try_extra_starts();
  const std::vector<bool> excluded = run.exclude_non_jkr();
  run.record(&out);
  out.t = data.t;
  out.excluded = excluded;
  for (std::size_t i = 0; i < data.P.size(); ++i)
    if (!(data.sqrt_weight[i] > 0.0) && !excluded[i]) out.excluded[i] = true;  // history only
  out.excluded_count = static_cast<std::size_t>(std::count(excluded.begin(), excluded.end(), true));
  assess_uncertainty(run, *ev, map, x, options, data, &out);
  explain_no_move(run, data, map, &out);
  out.baseline_offset = data.offset;
  diagnose_residuals(data, force_span, &out);
  name_misfit_in_time(data, map.drag(x.data()), &out);
  diagnose_indentation(data, &out);
  record_model_notes(*model, data, force_span, &out);
  const std::size_t history = static_cast<std::size_t>(std::count_if(
      data.sqrt_weight.begin(), data.sqrt_weight.end(), [](double w) { return !(w > 0.0); })) - out.excluded_count;
  if (history > 0)
    out.notices.push_back(std::to_string(history) + " samples off the " + std::string(to_string(options.branch)) +
                          " branch enter as the history the force depends on, not as residuals");
  judge_law(map, x, scene, data, &out);
  if (adhesion_ev)
    if (const std::string note = adhesion_ev->stepping_note(x.data()); !note.empty()) out.notices.push_back(note);
  record_pull_off(measure_pull_off(data, force_span), &out);  // the data's, whatever the fit did
  return out;
}

}  // namespace layerjkr::detail
