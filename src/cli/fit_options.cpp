// The fit flags and their mapping to typed library options (fit_options.hpp). The CLI's
// mini-languages (E,w lists, huber:SCALE, fraction:F) end here.
#include "fit_options.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <optional>
#include <set>
#include <sstream>
#include <vector>

#include <CLI/CLI.hpp>

#include "layerjkr/error.hpp"
#include "layerjkr/types.hpp"

namespace layerjkr::cli {
namespace {

// "E,w,delta0": known names, no duplicates, at least one.
std::vector<FitParameter> parse_free(const std::string& list) {
  std::vector<FitParameter> out;
  std::set<FitParameter> seen;
  std::stringstream in(list);
  std::string item;
  while (std::getline(in, item, ',')) {
    const std::optional<FitParameter> p = from_string<FitParameter>(item);
    if (!p) throw InputError("--free: '" + item + "' is not a fit parameter (known: " + known_names<FitParameter>() + "; T reads as G, w0 as w, V as v_star, N as n)");
    if (!seen.insert(*p).second) throw InputError("--free: '" + item + "' is listed twice");
    out.push_back(*p);
  }
  if (out.empty()) throw InputError("--free: give at least one parameter (e.g. E,w,delta0)");
  return out;
}

void parse_loss(const std::string& text, FitOptions& o) {
  if (text == "none") return;
  const auto colon = text.find(':');
  const std::optional<LossType> kind = from_string<LossType>(text.substr(0, colon));
  if (!kind || *kind == LossType::none || colon == std::string::npos)
    throw InputError("--loss = \"" + text + "\" is invalid; use none, huber:SCALE or cauchy:SCALE (SCALE in N)");
  o.loss = *kind;
  const std::string scale = text.substr(colon + 1);
  char* end = nullptr;
  const double s = std::strtod(scale.c_str(), &end);
  if (scale.empty() || *end != '\0' || !(s > 0.0) || !std::isfinite(s))
    throw InputError("--loss: scale '" + scale + "' must be a finite number > 0 [N]");
  o.loss_scale = s;
}

void parse_window(const std::string& text, FitOptions& o) {
  if (text == "all") {
    o.retract_window = RetractWindow::all;
  } else if (text == "pull-off" || text == "pull_off") {
    o.retract_window = RetractWindow::to_pull_off;
  } else if (text.rfind("fraction:", 0) == 0) {
    const std::string f = text.substr(9);
    char* end = nullptr;
    const double v = std::strtod(f.c_str(), &end);
    if (f.empty() || *end != '\0' || !(v > 0.0 && v <= 1.0))
      throw InputError("--window fraction:" + f + " is invalid; the fraction must be in (0, 1]");
    o.retract_window = RetractWindow::force_fraction;
    o.window_fraction = v;
  } else {
    throw InputError("--window = \"" + text + "\" is invalid; use all, pull-off or fraction:F");
  }
}

// --displacement-noise SD | auto: errors in the displacement, its noise given [length unit] or estimated.
void parse_displacement_noise(const std::string& text, double length_unit, FitOptions& o) {
  if (text.empty()) return;
  o.errors_in_displacement = true;
  if (text == "auto") return;
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  if (*end != '\0' || !(v > 0.0) || !std::isfinite(v))
    throw InputError("--displacement-noise = \"" + text + "\" is invalid; give the noise, a finite number > 0 in the "
                     "length unit, or auto to estimate it from the data");
  o.displacement_noise = v * length_unit;
}

// "MIN:MAX" with MIN < MAX, both finite and within [lo, hi]; "" leaves the range unset.
std::optional<Interval> parse_range(const std::string& text, const char* flag, double lo, double hi,
                                    const char* valid) {
  if (text.empty()) return std::nullopt;
  const auto colon = text.find(':');
  auto number = [&](const std::string& t, double* v) {
    char* end = nullptr;
    *v = std::strtod(t.c_str(), &end);
    return !t.empty() && *end == '\0' && std::isfinite(*v) && *v >= lo && *v <= hi;
  };
  double a = 0.0, b = 0.0;
  if (colon == std::string::npos || !number(text.substr(0, colon), &a) || !number(text.substr(colon + 1), &b) ||
      !(a < b))
    throw InputError(std::string(flag) + " = \"" + text + "\" is invalid; use MIN:MAX with " + valid);
  return Interval{a, b};
}

// "E=1e3:1e5,w=0:" -> FitOptions::bounds (SI units; an empty end is no bound on that side).
std::vector<ParameterBound> parse_bounds(const std::string& text) {
  std::vector<ParameterBound> out;
  if (text.empty()) return out;
  std::size_t start = 0;
  while (start <= text.size()) {
    const std::size_t comma = std::min(text.find(',', start), text.size());
    const std::string item = text.substr(start, comma - start);
    const std::size_t eq = item.find('='), colon = item.find(':', eq == std::string::npos ? 0 : eq);
    const auto fail = [&]() {
      throw InputError("--bounds: \"" + item + "\" is invalid; use NAME=MIN:MAX (SI units, an empty end unbounded), "
                       "e.g. E=1e3:1e5,w=0:");
    };
    if (eq == std::string::npos || colon == std::string::npos) fail();
    ParameterBound b;
    b.parameter = parse_enum<FitParameter>(item.substr(0, eq), "--bounds");
    const auto end = [&](const std::string& t, double infinite) {
      if (t.empty()) return infinite;
      char* stop = nullptr;
      const double v = std::strtod(t.c_str(), &stop);
      if (*stop != '\0' || !std::isfinite(v)) fail();
      return v;
    };
    b.lower = end(item.substr(eq + 1, colon - eq - 1), -std::numeric_limits<double>::infinity());
    b.upper = end(item.substr(colon + 1), std::numeric_limits<double>::infinity());
    out.push_back(b);
    start = comma + 1;
  }
  return out;
}

}  // namespace

Prepared prepare_options(const FitArguments& a) {
  Prepared p;
  p.options.free = parse_free(a.free);
  p.options.branch = parse_enum<Branch>(a.branch, "--branch");
  parse_loss(a.loss, p.options);
  p.options.extra_starts = a.extra_starts;
  p.options.max_iterations = a.max_iterations;
  parse_units(a.units, p.csv);
  p.csv.spring_constant = a.spring_constant;
  p.csv.sensitivity = a.sensitivity;
  p.csv.z_sign = a.z_sign;
  p.csv.deflection_sign = a.deflection_sign;
  p.csv.curve = a.curve;
  // The spring constant comes with the curve (an instrument file, or --spring-constant, which
  // the readers put into CurveData::spring_constant).
  p.options.retract_control = parse_enum<RetractControl>(a.control, "--control");
  p.options.baseline = parse_enum<Baseline>(a.baseline, "--baseline");
  p.options.remove_offset = !a.keep_offset;
  parse_window(a.window, p.options);
  p.options.contact_point = parse_enum<ContactPointMethod>(a.contact_point, "--contact-point");
  const double inf = std::numeric_limits<double>::max();
  p.options.indentation_range =
      parse_range(a.indentation_range, "--indentation-range", -inf, inf, "MIN < MAX, finite, in m");
  p.options.force_range = parse_range(a.force_range, "--force-range", 0.0, 1.0, "0 <= MIN < MAX <= 1 (fractions)");
  p.options.baseline_window = parse_range(a.baseline_window, "--baseline-window", -inf, inf, "MIN < MAX, finite, in m");
  p.options.bounds = parse_bounds(a.bounds);
  // Given in the CSV's units, like the columns they describe.
  if (a.force_noise != 0.0) p.options.force_noise = a.force_noise * p.csv.force_unit;
  if (a.radius_noise != 0.0) p.options.radius_noise = a.radius_noise * p.csv.length_unit;
  parse_displacement_noise(a.displacement_noise, p.csv.length_unit, p.options);
  try {
    p.options.validate();
    p.csv.validate();
  } catch (const DomainError& e) {
    throw InputError(std::string("invalid option: ") + e.what());
  }
  return p;
}

Prepared prepare(const FitArguments& a) {
  Prepared p = prepare_options(a);
  p.scene = load_scene(a.scene);
  return p;
}

void add_fit_options(CLI::App& c, FitArguments& a) {
  c.add_option("--scene", a.scene, "Scene JSON: indenter, medium, model; starting values")->required();
  c.add_option("--free", a.free, "Parameters to fit, comma-separated: K,G (or T),w,delta0,P0,E,R,sigma0, and in time "
                                 "E_inf,tau (a standard linear solid), beta (a power law; with E_inf a power_law_plateau), beta,tau (a fractional law; with E_inf a fractional_sls), E_2,tau_2 (with E_inf,tau: a two-term Maxwell law, maxwell2), v_star,n (crack kinetics), drag (the lever's drag in liquid)")->required();
  c.add_option("--loss", a.loss, "Robust loss: none | huber:SCALE | cauchy:SCALE (SCALE in N)");
  c.add_option("--branch", a.branch, "approach | retract | all | dwell | approach_dwell (default approach; the dwell branches are fits in time of a curve with a dwell: its samples alone, or with the approach, the history before them entering as history)");
  c.add_option("--units", a.units, "Units of the CSV: LENGTH,FORCE, e.g. nm,nN (default m,N)");
  c.add_option("--spring-constant", a.spring_constant,
               "Cantilever stiffness [N/m] for z,deflection data; for instrument files it replaces the file's, or "
               "gives one it lacks");
  c.add_option("--sensitivity", a.sensitivity,
               "Instrument files: the deflection sensitivity [m/V] replacing the file's (the deflection rescales), or "
               "giving one it lacks (a JPK calibration force-save)");
  c.add_option("--z-sign", a.z_sign, "z,deflection data: +1 if z grows as the tip approaches the sample, -1 if it decreases");
  c.add_option("--deflection-sign", a.deflection_sign, "z,deflection data: +1 if deflection > 0 when the sample pushes the tip away, else -1");
  c.add_option("--starts", a.extra_starts, "Extra starts around the data-driven guess (default 0)");
  c.add_option("--max-iterations", a.max_iterations, "Ceres iteration limit (default 200)");
  c.add_option("--bounds", a.bounds,
               "Ranges of free parameters, NAME=MIN:MAX[,...] in SI units (an empty end is unbounded), e.g. "
               "E=1e3:1e5,w=0:; one that ends at a bound has no error bar and a warning says so");
  c.add_option("--curve", a.curve, "Which curve of a file holding several: fit, of an instrument map or export; fit-map, of a CSV export only (an instrument map takes --curves A:B)");
  c.add_option("--baseline", a.baseline, "constant | tilt (a linear baseline from the samples off contact)");
  c.add_flag("--keep-offset", a.keep_offset,
             "With P0 not free: keep the forces as they are (by default an offset of the samples at rest is subtracted, "
             "as JPK's software and nanite do)");
  c.add_option("--window", a.window,
               "Retract samples used: all | pull-off (largest force to the force minimum) | fraction:F (the top F "
               "of the unloading force range)");
  c.add_option("--control", a.control,
               "Retract control: auto (cantilever when the spring constant is known, else read from the data: grips where the contact holds past the force minimum, else load) | load | "
               "cantilever | grips");
  c.add_option("--contact-point", a.contact_point,
               "Contact point on approach: fit (delta0 fitted, default) | threshold (baseline + 5 sigma) | rov "
               "(ratio of variances) | gof (goodness-of-fit scan); docs/fitting.md");
  c.add_option("--indentation-range", a.indentation_range,
               "MIN:MAX [m]: fit the approach samples whose indentation from the contact point is in the range");
  c.add_option("--force-range", a.force_range,
               "MIN:MAX: approach samples by force, as fractions of the largest force above the baseline (0 <= MIN < MAX <= 1)");
  c.add_option("--force-noise", a.force_noise,
               "With measured contact radii (delta,P,a) or --displacement-noise: the force's noise [force unit]; "
               "default estimated from the data");
  c.add_option("--displacement-noise", a.displacement_noise,
               "SD | auto: (delta,P) data whose displacement has noise of its own (a JKR rig's sensor): each sample's "
               "residual is its distance to the curve, force and displacement in their own noises (orthogonal "
               "distance regression); SD [length unit], or auto to estimate it from the data");
  c.add_option("--radius-noise", a.radius_noise,
               "With measured contact radii: the radius's noise [length unit]; default estimated from the data");
  c.add_option("--baseline-window", a.baseline_window,
               "MIN:MAX [m]: the delta range of the baseline samples (default: the quarter with the smallest delta)");
}

}  // namespace layerjkr::cli
