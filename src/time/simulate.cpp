// Synthetic curves: the fit's forward model, evaluated with the contact module's lookups - at
// equilibrium, or in time for a relaxing medium (Lee-Radok, Ting) and for crack kinetics.
#include "layerjkr/simulate.hpp"

#include <cmath>
#include <cstdio>
#include <limits>
#include <random>

#include "time/crack_kinetics.hpp"
#include "layerjkr/adhesion.hpp"
#include "layerjkr/built_scene.hpp"
#include "layerjkr/contact.hpp"
#include "layerjkr/error.hpp"
#include "layerjkr/viscoelastic.hpp"
#include "layerjkr/viscoelastic_adhesion.hpp"

namespace layerjkr {

void SimulationOptions::validate() const {
  const char* fn = "SimulationOptions";
  if (points_per_branch < 2 || points_per_branch > kMaxPointsPerBranch)
    throw DomainError(fn, "points_per_branch", static_cast<double>(points_per_branch),
                      "[2, " + std::to_string(kMaxPointsPerBranch) + "]");
  detail::require_positive(fn, "max_indentation", max_indentation);
  detail::require_non_negative(fn, "free_fraction", free_fraction);
  detail::require_finite(fn, "delta0", delta0);
  detail::require_finite(fn, "P0", P0);
  if (!(noise >= 0.0 && noise <= kMaxNoise)) throw DomainError(fn, "noise", noise, "[0, " + format_double(kMaxNoise) + "] N");
  const std::string speeds = "0 or [" + format_double(kSpeedRange[0]) + ", " + format_double(kSpeedRange[1]) + "] m/s";
  for (const auto& [name, v] : {std::pair{"speed", speed}, {"retract_speed", retract_speed}})
    if (!(v == 0.0 || (v >= kSpeedRange[0] && v <= kSpeedRange[1]))) throw DomainError(fn, name, v, speeds);
  if (!(dwell >= 0.0 && std::isfinite(dwell))) throw DomainError(fn, "dwell", dwell, "finite and >= 0 [s]");
  if (!(drag >= 0.0 && std::isfinite(drag))) throw DomainError(fn, "drag", drag, "finite and >= 0 [N s/m]");
  if (drag > 0.0 && !(speed > 0.0))
    throw InputError(std::string(fn) + ": drag = " + format_double(drag) + " N s/m needs a speed (the force is b v)");
  if (speed > 0.0 && dwell > 0.0) {
    // The dwell's samples come at the approach's interval: bounded before any is made.
    const double dt = (1.0 + free_fraction) * max_indentation / (speed * static_cast<double>(points_per_branch - 1));
    const double most = static_cast<double>(kMaxDwellSamples) * dt;
    if (!(dwell / dt <= static_cast<double>(kMaxDwellSamples)))
      throw DomainError(fn, "dwell", dwell,
                        "[0, " + format_double(most) + "] s: at the approach's sampling interval " + format_double(dt) +
                            " s a longer dwell takes more than " + std::to_string(kMaxDwellSamples) +
                            " samples (fewer points or a faster approach sample it more coarsely)");
  }
  if ((retract_speed > 0.0 || dwell > 0.0) && !(speed > 0.0))
    throw DomainError(fn, retract_speed > 0.0 ? "retract_speed" : "dwell", retract_speed > 0.0 ? retract_speed : dwell,
                      "used only with a speed > 0 (the curve in time)");
  if (control != RetractControl::fixed_grips && control != RetractControl::cantilever)
    throw DomainError(fn, std::string("control (") + to_string(control) + ")", 0.0, "grips or cantilever");
  if (control == RetractControl::cantilever && !(cantilever_stiffness > 0.0 && std::isfinite(cantilever_stiffness)))
    throw DomainError(fn, "cantilever_stiffness", cantilever_stiffness, "finite and > 0 [N/m] with control cantilever");
}

namespace {

// One sample of the ramp before the physics answers it.
struct Sample {
  double t = 0.0, delta = 0.0;
  int segment = 0;
};

// The approach from `lo` to `d_max`, the dwell there and the retract to `lo_r`: evenly in delta,
// the retract starting at d_max again (without time, as before time existed); in time, at the
// speeds, the retract one step after the turn (or the dwell).
std::vector<Sample> ramp(double lo, double d_max, double lo_r, const SimulationOptions& o) {
  const std::size_t n = o.points_per_branch;
  std::vector<Sample> out;
  const bool timed = o.speed > 0.0;
  const double dt = timed ? (d_max - lo) / (o.speed * static_cast<double>(n - 1)) : 0.0;
  for (std::size_t i = 0; i < n; ++i)
    out.push_back({static_cast<double>(i) * dt,
                   i + 1 == n ? d_max : lo + (d_max - lo) * static_cast<double>(i) / static_cast<double>(n - 1), 0});
  const double t_turn = out.back().t;
  const auto dwells = timed ? static_cast<std::size_t>(std::llround(o.dwell / dt)) : 0;
  for (std::size_t k = 1; k <= dwells; ++k) out.push_back({t_turn + static_cast<double>(k) * dt, d_max, 2});
  const double v_r = o.retract_speed > 0.0 ? o.retract_speed : o.speed;
  const double t_back = out.back().t, span = d_max - lo_r;
  for (std::size_t k = 0; k < n; ++k) {
    if (timed) {
      const double f = static_cast<double>(k + 1) / static_cast<double>(n);
      out.push_back({t_back + f * span / v_r, d_max - f * span, 1});
    } else {
      out.push_back({0.0, d_max - span * static_cast<double>(k) / static_cast<double>(n - 1), 1});
    }
  }
  return out;
}

// What a sample answers: force and contact radius (the ramp's delta may change: a cantilever's tip).
struct Answer {
  double P = 0.0, a = 0.0, delta = 0.0;
};

// At equilibrium: the stable branch from zero load on approach and at rest, to the pull-off on
// retract.
std::vector<Answer> equilibrium(const std::vector<Sample>& ramp, const AdhesiveSolution& sol, double d_contact,
                                double d_release, bool with_radius) {
  std::vector<Answer> out;
  for (const Sample& s : ramp) {
    Answer a{0.0, 0.0, s.delta};
    if (s.delta >= (s.segment == 1 ? d_release : d_contact)) {
      a.P = sol.force_at_delta(s.delta);
      if (with_radius) a.a = sol.contact_radius_at_delta(s.delta);
    }
    out.push_back(a);
  }
  return out;
}

// A relaxing medium without adhesion: Lee-Radok and Ting over the ramp's indentation history.
// The hereditary response at the ramp's samples, integrated on the samples' grid subdivided m
// times (the history is piecewise linear in time between samples, so the finer grid is exact).
HereditaryResponse hereditary_on(const std::vector<Sample>& ramp, const AdhesiveSolution& sol, const RelaxationLaw& law,
                                 std::size_t m) {
  std::vector<double> t, d;
  t.reserve((ramp.size() - 1) * m + 1);
  d.reserve(t.capacity());
  for (std::size_t i = 0; i < ramp.size(); ++i) {
    if (i > 0)
      for (std::size_t k = 1; k < m; ++k) {
        const double f = static_cast<double>(k) / static_cast<double>(m);
        t.push_back(ramp[i - 1].t + f * (ramp[i].t - ramp[i - 1].t));
        d.push_back(ramp[i - 1].delta + f * (ramp[i].delta - ramp[i - 1].delta));
      }
    t.push_back(ramp[i].t);
    d.push_back(ramp[i].delta);
  }
  const HereditaryResponse fine = hereditary_response(t, d, [&](double x) { return sol.force_at_delta(x); }, law);
  HereditaryResponse out;
  for (std::size_t i = 0; i < ramp.size(); ++i) {
    out.P.push_back(fine.P[i * m]);
    out.delta1.push_back(fine.delta1[i * m]);
  }
  return out;
}

// The hereditary sum converges at order ~1.3 in the step for a power law (4.4e-5 of the peak force
// at 200 samples a branch, 2.4e-6 at 2 000): the grid is halved until two in a row agree to
// kHereditaryTolerance of the peak force at every sample (the change bounds the finer one's error:
// order >= 1), or the refined grid would pass kMaxHereditarySamples; the estimate goes in `note`.
constexpr double kHereditaryTolerance = 1e-6;
constexpr std::size_t kMaxHereditarySamples = 4'000'000;

std::vector<Answer> relaxing(const std::vector<Sample>& ramp, const AdhesiveSolution& sol, const RelaxationLaw& law,
                             bool with_radius, std::string* note) {
  std::size_t m = 1;
  HereditaryResponse r = hereditary_on(ramp, sol, law, m);
  double peak = 0.0, change = std::numeric_limits<double>::infinity();
  for (double P : r.P) peak = std::max(peak, std::abs(P));
  while ((ramp.size() - 1) * m * 2 + 1 <= kMaxHereditarySamples) {
    HereditaryResponse finer = hereditary_on(ramp, sol, law, 2 * m);
    change = 0.0;
    for (std::size_t i = 0; i < r.P.size(); ++i) change = std::max(change, std::abs(finer.P[i] - r.P[i]));
    r = std::move(finer);
    m *= 2;
    if (change <= kHereditaryTolerance * peak) break;
  }
  const double relative = peak > 0.0 ? change / peak : 0.0;
  *note = "the relaxing medium's force is integrated on a grid " + std::to_string(m) + "x finer than the samples: "
          "estimated error " + format_double(relative) + " of the peak force (the change from the last halving of "
          "the step)" + (relative > kHereditaryTolerance ? std::string(", above ") + format_double(kHereditaryTolerance) +
                                                              ": the grid reached its bound of " +
                                                              std::to_string(kMaxHereditarySamples) + " steps"
                                                        : std::string());
  std::vector<Answer> out;
  for (std::size_t i = 0; i < ramp.size(); ++i)
    out.push_back({r.P[i], with_radius && r.delta1[i] > 0.0 ? sol.contact_radius_at_delta(r.delta1[i]) : 0.0, ramp[i].delta});
  return out;
}

// Adhesion on a relaxing half-space: the Maugis-Dugdale contact stepped in time
// (viscoelastic_adhesion.hpp) from the snap-in at the first approach sample at or past Maugis'
// zero-load indentation;
// free before it and once the contact is lost (*lost then true).
std::vector<Answer> relaxing_adhesive(const std::vector<Sample>& ramp, const Scene& scene, const SimulationOptions& o,
                                      std::string* note, bool* lost) {
  const bool with_radius = o.with_radius;
  const double nu = scene.medium.nu, E_star = scene.medium.E / (1.0 - nu * nu);
  // Where the fit snaps the contact in too (time_relaxing_adhesion.cpp).
  const double d_snap = dugdale_zero_load_indentation(*scene.profile, E_star, scene.w, scene.adhesion.dugdale_stress(scene.w));
  std::size_t first = 0;
  while (first < ramp.size() && !(ramp[first].segment == 0 && ramp[first].delta >= d_snap)) ++first;
  std::vector<double> t, d;
  for (std::size_t i = first; i < ramp.size(); ++i) t.push_back(ramp[i].t), d.push_back(ramp[i].delta);
  // A simulated truth ten times tighter than the stepping's default: a fit's own model error stays
  // below the truth's.
  RelaxingDugdaleOptions stepping;
  stepping.tolerance = 1e-4;
  // A lever drives the whole curve from its base (the ramp's delta), approach and retract alike.
  if (o.control == RetractControl::cantilever) stepping.cantilever_stiffness = o.cantilever_stiffness;
  const RelaxingDugdaleResponse r = relaxing_dugdale_response(*scene.profile, E_star, scene.medium.relaxation, scene.w,
                                                              scene.adhesion.dugdale_stress(scene.w), t, d, stepping);
  std::vector<Answer> out;
  double peak = 0.0;
  for (std::size_t i = 0; i < ramp.size(); ++i) {
    const bool in = i >= first && i - first < r.separated_at;
    out.push_back({in ? r.P[i - first] : 0.0, in && with_radius ? r.a[i - first] : 0.0,
                   i >= first ? r.tip[i - first] : ramp[i].delta});
    peak = std::max(peak, std::abs(out.back().P));
  }
  *lost = r.separated_at < t.size();
  char figures[160];
  std::snprintf(figures, sizeof figures, "%d steps per sample, %d points over %.3g m): estimated force error %.2g N (%.2g of the peak)",
                r.substeps, r.grid_points, r.extent, r.force_error, peak > 0.0 ? r.force_error / peak : 0.0);
  *note = "adhesion on the relaxing half-space is the Maugis-Dugdale contact stepped in time (" + std::string(figures) +
          (r.converged ? std::string() : std::string(", above the 1e-4 target: the step reached its bound"));
  return out;
}

// The retract's control value at the deepest point: the indenter, or a cantilever's base.
double control_at_turn(const SimulationOptions& o, double d_max, double P_max) {
  return o.control == RetractControl::cantilever ? d_max + P_max / o.cantilever_stiffness : d_max;
}

// Crack kinetics: the retract from the equilibrium contact at d_max by the ODE, sample by sample;
// the rest at equilibrium. The ramp's retract samples are the control's (grips: the tip; a
// cantilever: its base), turned into the tip's position.
std::vector<Answer> kinetic(const std::vector<Sample>& ramp, const AdhesiveSolution& sol, const Scene& scene,
                            const SimulationOptions& o, double d_contact, double d_max, bool with_radius) {
  // The approach and the dwell at equilibrium; every retract sample is the ODE's (free until then).
  std::vector<Answer> out = equilibrium(ramp, sol, d_contact, std::numeric_limits<double>::infinity(), with_radius);
  const double a_max = sol.contact_radius_at_delta(d_max), P_max = sol.force_at_delta(d_max);
  const ContactModelPtr model = sol.law().contact();
  detail::KineticStepper stepper([&](double a) { return model->state(a); }, scene.w, *scene.adhesion.kinetics,
                                 o.control, o.cantilever_stiffness);
  const double c_turn = control_at_turn(o, d_max, P_max);
  bool started = false;
  for (std::size_t i = 0; i < ramp.size(); ++i) {
    if (ramp[i].segment != 1) continue;
    const double c = c_turn - (d_max - ramp[i].delta);  // the control withdraws as the ramp does
    if (!started) {
      stepper.start(ramp[i - 1].t, a_max, c_turn);
      started = true;
    }
    if (!stepper.advance(ramp[i].t, c))
      throw NumericalError("simulate: the crack's kinetics could not be integrated at t = " + format_double(ramp[i].t) + " s");
    const detail::CrackPoint p = stepper.point();
    out[i] = {p.P, with_radius ? stepper.a() : 0.0, o.control == RetractControl::cantilever ? p.delta : c};
  }
  return out;
}

// Where the kinetic retract lets go: the control's value at separation, from a run stepped finely.
double kinetic_release(const AdhesiveSolution& sol, const Scene& scene, const SimulationOptions& o, double d_max,
                       double d_release) {
  const double a_max = sol.contact_radius_at_delta(d_max), P_max = sol.force_at_delta(d_max);
  const ContactModelPtr model = sol.law().contact();
  detail::KineticStepper stepper([&](double a) { return model->state(a); }, scene.w, *scene.adhesion.kinetics,
                                 o.control, o.cantilever_stiffness);
  const double c0 = control_at_turn(o, d_max, P_max);
  const double v = o.retract_speed > 0.0 ? o.retract_speed : o.speed;
  const double T = (d_max - d_release) / v, h = 1e-3 * T;
  stepper.start(0.0, a_max, c0);
  for (int k = 0; k < 1000000 && !stepper.separated(); ++k)
    if (!stepper.step(stepper.t() + 1e3 * T, c0 - v * (stepper.t() + 1e3 * T), h))
      throw NumericalError("simulate: the crack's kinetics could not be integrated (" + scene.adhesion.kinetics->describe() + ")");
  if (!stepper.separated()) throw NumericalError("simulate: the kinetic retract did not let go");
  return stepper.control();  // free: the tip sits where the grips or the unbent lever hold it
}

}  // namespace

CurveData simulate_curve(const Scene& scene, const SimulationOptions& o) {
  o.validate();
  if (o.branch == Branch::dwell || o.branch == Branch::approach_dwell)
    throw InputError("simulate: branch = " + std::string(to_string(o.branch)) +
                     " is a fit's choice; simulate writes approach, retract or all (a dwell is in all)");
  const bool relaxes = scene.medium.relaxation.kind != RelaxationLaw::Kind::elastic;
  const bool kinetics = scene.adhesion.kinetics.has_value();
  if ((relaxes || kinetics) && !(o.speed > 0.0))
    throw InputError(std::string("simulate: ") + (relaxes ? "a relaxing medium (" + scene.medium.relaxation.describe() + ")"
                                                           : "crack kinetics (" + scene.adhesion.kinetics->describe() + ")") +
                     " answers in time: give the indenter's speed [m/s] (--speed)");
  const bool adhesive_relaxing = relaxes && scene.w > 0.0;
  if (adhesive_relaxing && scene.medium.type != MediumType::half_space)
    throw InputError("simulate: adhesion (w = " + format_double(scene.w) + " J/m^2) on a relaxing " +
                     std::string(to_string(scene.medium.type)) + " is not modelled; it is on the half-space "
                     "(medium.type half_space, with adhesion.model maugis_dugdale)");
  if (adhesive_relaxing && scene.adhesion.model != AdhesionModel::maugis_dugdale)
    throw InputError("simulate: adhesion (w = " + format_double(scene.w) + " J/m^2) on a relaxing medium needs its "
                     "adhesive zone: set adhesion.model = maugis_dugdale with sigma0 or z0 (a sharp JKR edge never "
                     "relaxes, so its toughening would not depend on the speed)");
  if (o.control == RetractControl::cantilever && !kinetics && !adhesive_relaxing)
    throw InputError("simulate: a cantilever-controlled retract is modelled with crack kinetics (adhesion.kinetics) or "
                     "with adhesion on a relaxing half-space only; the other scenes follow the fixed-grips branch to the "
                     "pull-off");
  // Where contact starts without adhesion sets the radius scale for "auto".
  const double a_scale = std::sqrt(o.max_indentation * scene.profile->length_scale());
  const BuiltScene built = build_scene(scene, 0.1 * a_scale);
  // The scene's adhesion model (JKR unless its "adhesion" key says otherwise), as the fit's; a
  // relaxing medium's elastic force at the instantaneous modulus.
  const AdhesiveSolution sol(make_adhesive_law(built.model, built.resolved.spec, scene.w, scene.adhesion));
  const double a_floor = 1e-9 * a_scale;
  const double a_zero = scene.w > 0.0 ? sol.zero_load_radius().value_or(a_floor) : a_floor;
  const double d_contact = sol.at(a_zero).delta;
  double d_release = d_contact;
  if (scene.w > 0.0)
    if (const auto po = sol.pull_off()) d_release = po->delta;
  const double d_max = d_contact + o.max_indentation;
  if (kinetics) d_release = kinetic_release(sol, scene, o, d_max, d_release);
  // A relaxing medium's history must start out of contact: its contact starts at delta = 0 (w
  // = 0), which the solution's smallest radius puts a rounding error above (1e-24 m).
  const double lo = relaxes ? std::min(d_contact - o.free_fraction * o.max_indentation, 0.0)
                            : d_contact - o.free_fraction * o.max_indentation;
  const double lo_r = d_release - o.free_fraction * (d_max - d_release);
  std::vector<Sample> samples = ramp(lo, d_max, lo_r, o);
  std::string accuracy;
  std::vector<Answer> adhesive;
  if (adhesive_relaxing) {
    // A relaxing contact may hold on past the elastic pull-off: the retract is extended (the span
    // below d_max doubled, up to 4 times) until the contact is lost within it.
    bool lost = false;
    for (int k = 0;; ++k) {
      adhesive = relaxing_adhesive(samples, scene, o, &accuracy, &lost);
      if (lost || k == 4) break;
      samples = ramp(lo, d_max, d_max - 2.0 * (d_max - samples.back().delta), o);
    }
    if (!lost) accuracy += "; the contact holds to the retract's end";
  }
  const std::vector<Answer> answers = adhesive_relaxing ? adhesive
                                      : relaxes    ? relaxing(samples, sol, scene.medium.relaxation, o.with_radius, &accuracy)
                                      : kinetics ? kinetic(samples, sol, scene, o, d_contact, d_max, o.with_radius)
                                                 : equilibrium(samples, sol, d_contact, d_release, o.with_radius);

  CurveData c;
  c.source = "simulated(" + built.model->name() + ")";
  if (!accuracy.empty()) c.notes.push_back(accuracy);
  std::mt19937_64 rng(o.seed);
  std::normal_distribution<double> gauss(0.0, 1.0);
  for (std::size_t i = 0; i < samples.size(); ++i) {
    const Sample& s = samples[i];
    if ((o.branch == Branch::approach && s.segment != 0) || (o.branch == Branch::retract && s.segment != 1)) continue;
    c.delta.push_back(answers[i].delta + o.delta0);
    // The lever's drag: b times the base's speed towards the sample (a dwell rests).
    const double v = s.segment == 0 ? o.speed : s.segment == 1 ? -(o.retract_speed > 0.0 ? o.retract_speed : o.speed) : 0.0;
    c.P.push_back(answers[i].P + o.P0 + o.drag * v + (o.noise > 0.0 ? o.noise * gauss(rng) : 0.0));
    c.segment.push_back(s.segment);
    if (o.speed > 0.0) c.t.push_back(s.t);
    if (o.with_radius) c.a.push_back(answers[i].a);
    const std::size_t k = c.P.size() - 1;
    if (!std::isfinite(c.delta[k]) || !std::isfinite(c.P[k]) || (!c.t.empty() && !std::isfinite(c.t[k])))
      throw InputError("simulate: sample " + std::to_string(k) + " is not finite (t = " +
                           (c.t.empty() ? std::string("-") : format_double(c.t[k])) + " s, delta = " +
                           format_double(c.delta[k]) + " m, P = " + format_double(c.P[k]) +
                           " N): the options' scales overflow (max_indentation, delta0, P0, noise, speeds)");
  }
  return c;
}

}  // namespace layerjkr
