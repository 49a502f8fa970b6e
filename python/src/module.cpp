// layerjkr._core: the pybind11 layer under the Python package (python/layerjkr/__init__.py).
// It binds the library's public API and its answers (answer.hpp, fit.hpp) as they are: no
// front-end code, no JSON. Options arrive typed; their strings go through the library's one
// spelling registry (types.hpp, parse_enum) named as the Python parameter they came from.
// Every long call releases the GIL; arrays come in as float64 (converted if needed) and go
// out as new arrays. python/layerjkr/_core.pyi describes this module.
#include <glog/logging.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <cmath>
#include <exception>
#include <limits>
#include <optional>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "bindings.hpp"
#include "convert.hpp"
#include "instrument.hpp"
#include "layerjkr/layerjkr.hpp"

namespace py = pybind11;
using namespace layerjkr;

namespace {

using python::Array;
using python::Labels;
using python::to_array;
using python::to_vector;

// The layerjkr.Error hierarchy: DomainError and InputError are also ValueErrors,
// NumericalError an ArithmeticError, so generic handlers catch them too.
struct Exceptions {
  py::handle error, domain, input, numerical;
};
Exceptions& exceptions() {
  static Exceptions e;
  return e;
}

py::handle new_exception(py::module_& m, const char* name, py::handle bases, const char* doc) {
  const std::string qualified = std::string("layerjkr.") + name;
  PyObject* type = PyErr_NewExceptionWithDoc(qualified.c_str(), doc, bases.ptr(), nullptr);
  if (type == nullptr) throw py::error_already_set();
  m.add_object(name, py::handle(type));  // the module keeps the reference
  return py::handle(type);
}


py::object point_or_none(const std::optional<CriticalPoint>& p) {
  if (!p) return py::none();
  return py::make_tuple(p->a, p->P, p->delta);
}

AnswerOptions answer_options(double warning_threshold) {
  AnswerOptions o;
  o.warning_threshold = warning_threshold;
  o.validate();
  return o;
}

// The curve as (block, warnings, model, reference, choice, seconds): block is one (8, n) array
// with the rows a, P, delta, P_H, delta_H, S, dS_da, error_estimate. It is made and touched
// before the GIL is released, while the interpreter's caches are warm; the computation then
// fills it and frees its own data without the GIL, so little Python work is left after it.
py::tuple curve(const Scene& scene, const Array& radii, double warning_threshold) {
  const AnswerOptions options = answer_options(warning_threshold);
  std::vector<double> a = to_vector(radii, "a");
  const auto n = static_cast<py::ssize_t>(a.size());
  py::array_t<double> block({py::ssize_t{9}, n});
  std::fill_n(block.mutable_data(), 9 * n, 0.0);
  double* out = block.mutable_data();
  CurveAnswer c;
  {
    py::gil_scoped_release release;
    c = solve_curve(scene, a, options);
    for (py::ssize_t i = 0; i < n; ++i) {
      const auto k = static_cast<std::size_t>(i);
      const AdhesiveState& s = c.states[k];
      const double row[9] = {s.a, s.P, s.delta, s.hertz.P_H, s.hertz.delta_H, s.hertz.S, s.hertz.dS_da, c.error_estimate[k], s.c};
      for (py::ssize_t r = 0; r < 9; ++r) out[r * n + i] = row[r];
    }
    c.states = {};
    c.error_estimate = {};
    a = {};
  }
  py::object choice = c.choice ? py::cast(*c.choice) : py::none();
  return py::make_tuple(block, c.warnings, c.model, c.reference, choice, c.seconds, c.notices);
}

SummaryAnswer summary(const Scene& scene, double warning_threshold, const std::optional<std::string>& control,
                      double rate, double stiffness, double start_force) {
  AnswerOptions options = answer_options(warning_threshold);
  if (control) {
    options.retract = RetractDrive{parse_enum<RetractControl>(*control, "control"), rate, stiffness};
    options.retract_start_force = start_force;
    options.validate();
  }
  py::gil_scoped_release release;
  return solve_summary(scene, options);
}

// The typed keywords of layerjkr.fit as the library's FitOptions; every string through the
// registry under the Python parameter's name.
FitOptions fit_options(const std::vector<std::string>& free, const std::string& branch, const std::string& control,
                       std::optional<double> spring_constant, const std::string& baseline, const std::string& window,
                       double window_fraction, const std::string& loss, std::optional<double> loss_scale, int starts,
                       int max_iterations, const std::string& contact_point, std::optional<Interval> indentation_range,
                       std::optional<Interval> force_range, std::optional<Interval> baseline_window,
                       const std::vector<std::tuple<std::string, double, double>>& bounds,
                       bool errors_in_displacement, std::optional<double> displacement_noise,
                       std::optional<double> force_noise) {
  FitOptions o;
  o.errors_in_displacement = errors_in_displacement;
  o.displacement_noise = displacement_noise;
  o.force_noise = force_noise;
  for (const auto& [name, lower, upper] : bounds)
    o.bounds.push_back({parse_enum<FitParameter>(name, "bounds"), lower, upper});
  o.contact_point = parse_enum<ContactPointMethod>(contact_point, "contact_point");
  o.indentation_range = indentation_range;
  o.force_range = force_range;
  o.baseline_window = baseline_window;
  for (const std::string& f : free) o.free.push_back(parse_enum<FitParameter>(f, "free"));
  o.branch = parse_enum<Branch>(branch, "branch");
  o.retract_control = parse_enum<RetractControl>(control, "control");
  o.cantilever_stiffness = spring_constant;
  o.baseline = parse_enum<Baseline>(baseline, "baseline");
  o.retract_window = parse_enum<RetractWindow>(window, "window");
  o.window_fraction = window_fraction;
  o.loss = parse_enum<LossType>(loss, "loss");
  o.loss_scale = loss_scale.value_or(0.0);
  o.extra_starts = starts;
  o.max_iterations = max_iterations;
  o.validate();
  return o;
}

CsvOptions csv_options(const std::string& units, std::optional<double> spring_constant, std::optional<double> sensitivity,
                       double z_sign, double deflection_sign, std::optional<int> curve) {
  CsvOptions c;
  parse_units(units, c);
  c.spring_constant = spring_constant.value_or(0.0);
  c.sensitivity = sensitivity.value_or(0.0);
  c.z_sign = z_sign;
  c.deflection_sign = deflection_sign;
  c.curve = curve.value_or(-1);
  c.validate();
  return c;
}

// One curve from arrays: delta, P, optional segment labels and times.
CurveData curve_of(const Array& delta, const Array& P, const std::optional<Labels>& segment,
                   const std::optional<Array>& t, const std::string& source) {
  CurveData c;
  c.delta = to_vector(delta, "delta");
  c.P = to_vector(P, "P");
  c.source = source;
  if (segment) {
    if (segment->ndim() != 1)
      throw InputError("segment must be a 1-D array; got " + std::to_string(segment->ndim()) + " dimensions");
    const auto labels = segment->unchecked<1>();
    c.segment.resize(static_cast<std::size_t>(labels.shape(0)));
    for (py::ssize_t i = 0; i < labels.shape(0); ++i) {
      const std::int64_t v = labels(i);
      if (v < std::numeric_limits<int>::min() || v > std::numeric_limits<int>::max())
        throw InputError("segment[" + std::to_string(i) + "] = " + std::to_string(v) +
                         " is not a segment label; valid values: 0 (approach), 1 (retract), 2 (dwell)");
      c.segment[static_cast<std::size_t>(i)] = static_cast<int>(v);
    }
  }
  if (t) c.t = to_vector(*t, "t");
  return c;
}

FitSummary fit_arrays(const Array& delta, const Array& P, const std::optional<Labels>& segment,
                      const std::optional<Array>& t, const Scene& scene, const FitOptions& options) {
  const CurveData c = curve_of(delta, P, segment, t, "array");
  py::gil_scoped_release release;
  return fit(c, scene, options);
}

// Curves as (delta, P, segment, t) tuples, fitted jointly: (joint summary, curve_begin, sources, alone).
py::tuple fit_joint_arrays(const std::vector<std::tuple<Array, Array, std::optional<Labels>, std::optional<Array>>>& curves,
                           const Scene& scene, const FitOptions& options) {
  std::vector<CurveData> cs;
  for (std::size_t k = 0; k < curves.size(); ++k) {
    const auto& [d, P, seg, t] = curves[k];
    cs.push_back(curve_of(d, P, seg, t, "curves[" + std::to_string(k) + "]"));  // Python's index, from 0
  }
  JointFitSummary j;
  {
    py::gil_scoped_release release;
    j = fit_joint(cs, scene, options);
  }
  return py::make_tuple(j.fit, j.curve_begin, j.sources, j.alone);
}

// simulate_curve's arrays: (t, delta, P, a, segment, source); t and a empty where not made.
py::tuple simulate_py(const Scene& scene, const SimulationOptions& o) {
  CurveData c;
  {
    py::gil_scoped_release release;
    c = simulate_curve(scene, o);
  }
  py::array_t<int> segment(static_cast<py::ssize_t>(c.segment.size()));
  std::copy(c.segment.begin(), c.segment.end(), segment.mutable_data());
  return py::make_tuple(to_array(c.t), to_array(c.delta), to_array(c.P), to_array(c.a), segment, c.source, c.notes);
}

SimulationOptions simulation_options(double max_indentation, double speed, double retract_speed, double dwell,
                                     std::size_t points, double free_fraction, double noise, std::uint64_t seed,
                                     bool with_radius, const std::string& branch, double delta0, double P0,
                                     const std::string& control, double stiffness, double drag) {
  SimulationOptions o;
  o.max_indentation = max_indentation;
  o.speed = speed;
  o.retract_speed = retract_speed;
  o.dwell = dwell;
  o.points_per_branch = points;
  o.free_fraction = free_fraction;
  o.noise = noise;
  o.seed = seed;
  o.with_radius = with_radius;
  o.branch = parse_enum<Branch>(branch, "branch");
  o.delta0 = delta0;
  o.P0 = P0;
  o.control = parse_enum<RetractControl>(control, "control");
  o.cantilever_stiffness = stiffness;
  o.drag = drag;
  o.validate();
  return o;
}

}  // namespace

PYBIND11_MODULE(_core, m) {
  m.doc() = "layerjkr C++ core (use the layerjkr package, not this module)";
  m.attr("__version__") = layerjkr::version();  // the library's, by construction
  // Ceres logs its internal diagnostics through glog ("Logging before InitGoogleLogging", "Failed
  // to extract eigenvalues"), which read like a crash in a notebook; a fit reports through its
  // own warnings, as the CLI does.
  FLAGS_minloglevel = google::GLOG_FATAL;
  Exceptions& e = exceptions();
  e.error = new_exception(m, "Error", py::handle(PyExc_Exception), "Base class of everything layerjkr raises.");
  e.domain = new_exception(m, "DomainError", py::make_tuple(e.error, py::handle(PyExc_ValueError)).release(),
                           "A parameter outside its valid range (the message names it, its value and the range).");
  e.input = new_exception(m, "InputError", py::make_tuple(e.error, py::handle(PyExc_ValueError)).release(),
                          "Malformed or insufficient input data, files or options.");
  e.numerical = new_exception(m, "NumericalError", py::make_tuple(e.error, py::handle(PyExc_ArithmeticError)).release(),
                              "A computation that could not reach its accuracy.");
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const DomainError& x) {  // messages made printable: they may echo bytes from a file
      PyErr_SetString(exceptions().domain.ptr(), printable(x.what()).c_str());
    } catch (const InputError& x) {
      PyErr_SetString(exceptions().input.ptr(), printable(x.what()).c_str());
    } catch (const NumericalError& x) {
      PyErr_SetString(exceptions().numerical.ptr(), printable(x.what()).c_str());
    } catch (const Error& x) {
      PyErr_SetString(exceptions().error.ptr(), printable(x.what()).c_str());
    }
  });

  py::class_<Scene>(m, "Scene", "A parsed scene (the CLI's JSON schema); make one with layerjkr.scene().")
      .def_property_readonly("w", [](const Scene& s) { return s.w; }, "Work of adhesion [J/m^2].")
      .def_property_readonly("profile", [](const Scene& s) { return s.profile->describe(); }, "The indenter, described.")
      .def_property_readonly("model", [](const Scene& s) { return std::string(to_string(s.model)); },
                             "The scene's model key.")
      .def_property_readonly("json", [](const Scene& s) { return s.origin.json; },
                             "The JSON the scene was parsed from ('' for one built in code).")
      // Its values, as its JSON gives them (E, nu, h, the law's tau ...): a scene is read by what
      // it holds; one built in code shows its model and indenter.
      .def("__repr__", [](const Scene& s) {
        if (!s.origin.json.empty()) return "layerjkr.Scene(" + python::text(s.origin.json).cast<std::string>() + ")";
        return "layerjkr.Scene(model='" + std::string(to_string(s.model)) + "', profile='" + s.profile->describe() + "')";
      });
  m.def("parse_scene", &parse_scene, py::arg("json_text"), py::arg("source") = "scene");
  m.def("unit_of", [](const std::string& name) { return std::string(unit_of(parse_enum<FitParameter>(name, "parameter"))); },
        py::arg("name"), "The SI unit of a fitted parameter, as the reports write it.");
  m.def("with_table_profile", [](Scene s, std::vector<double> r, std::vector<double> z) {
        s.profile = make_table_profile(std::move(r), std::move(z));
        return s;
      },
      py::arg("scene"), py::arg("r"), py::arg("z"));
  m.def("load_scene", &load_scene, py::arg("path"));

  py::class_<AutoChoice>(m, "AutoChoice", "What model 'auto' chose (AutoChoice).")
      .def_property_readonly("model", [](const AutoChoice& c) { return std::string(to_string(c.model)); })
      .def_readonly("estimated_error", &AutoChoice::estimated_error)
      .def_readonly("tolerance", &AutoChoice::tolerance)
      .def_readonly("judged_at", &AutoChoice::judged_at)
      .def("brief_report", &AutoChoice::brief_report);

  py::class_<SummaryAnswer>(m, "SummaryAnswer", "A scene's summary (SummaryAnswer).")
      .def_property_readonly("model", [](const SummaryAnswer& s) { return s.contact.model; })
      .def_property_readonly("w", [](const SummaryAnswer& s) { return s.contact.w; })
      .def_property_readonly("zero_load_radius", [](const SummaryAnswer& s) { return s.contact.zero_load_radius; })
      .def_property_readonly("pull_off", [](const SummaryAnswer& s) { return point_or_none(s.contact.pull_off); })
      .def_property_readonly("fixed_grips", [](const SummaryAnswer& s) { return point_or_none(s.contact.fixed_grips); })
      .def_property_readonly("error", [](const SummaryAnswer& s) {
        return py::make_tuple(s.error.pull_off_force, s.error.zero_load_radius, s.error.reference);
      })
      .def_readonly("profile", &SummaryAnswer::profile)
      .def_readonly("K", &SummaryAnswer::K)
      .def_readonly("G", &SummaryAnswer::G)
      .def_readonly("g_is_tension", &SummaryAnswer::g_is_tension)
      .def_readonly("E_star", &SummaryAnswer::E_star)
      .def_property_readonly("adhesion_model", [](const SummaryAnswer& s) { return std::string(to_string(s.contact.adhesion)); })
      .def_property_readonly("adhesion", [](const SummaryAnswer& s) -> py::object {
        if (!s.adhesion) return py::none();
        const AdhesionCheck& c = *s.adhesion;
        return py::make_tuple(c.lambda, c.sigma0, c.sigma0_assumed, c.pull_off_error, c.basis);
      })
      .def_readonly("choice", &SummaryAnswer::choice)
      .def_property_readonly("warnings", [](const SummaryAnswer& s) { return python::texts(s.warnings); })
      .def_property_readonly("notices", [](const SummaryAnswer& s) { return python::texts(s.notices); })
      .def_readonly("seconds", &SummaryAnswer::seconds)
      .def_property_readonly("kinetic", [](const SummaryAnswer& s) -> py::object {
        if (!s.kinetic) return py::none();
        const KineticSummary& k = *s.kinetic;
        py::dict d;
        d["drive"] = k.drive.describe();
        d["control"] = std::string(to_string(k.drive.control));
        d["rate"] = k.drive.rate;
        d["rate_unit"] = std::string(k.drive.control == RetractControl::load ? "N/s" : "m/s");
        d["start_force"] = k.start_force;
        d["pull_off_force"] = k.pull_off.P;
        d["pull_off"] = py::make_tuple(k.pull_off.a, k.pull_off.P, k.pull_off.delta);
        d["pull_off_time"] = k.pull_off_time;
        d["separation_time"] = k.separation_time;
        d["equilibrium_pull_off_force"] = k.equilibrium_pull_off.P;
        d["equilibrium_separation"] =
            py::make_tuple(k.equilibrium_separation.a, k.equilibrium_separation.P, k.equilibrium_separation.delta);
        d["rates"] = to_array(k.rates);
        d["pull_off_forces"] = to_array(k.pull_off_forces);
        d["rate_ratio"] = k.rate_ratio;
        d["regime"] = k.regime();
        return d;
      });

  m.def("curve", &curve, py::arg("scene"), py::arg("a"), py::arg("warning_threshold"));
  m.def("summary", &summary, py::arg("scene"), py::arg("warning_threshold"), py::arg("control") = py::none(),
        py::arg("rate") = 0.0, py::arg("stiffness") = 0.0, py::arg("start_force") = 0.0);

  py::class_<FitOptions>(m, "FitOptions", "The library's FitOptions; make them with fit_options().")
      .def_property_readonly("branch", [](const FitOptions& o) { return std::string(to_string(o.branch)); })
      .def_property_readonly("free", [](const FitOptions& o) {
        std::vector<std::string> names;
        for (FitParameter p : o.free) names.emplace_back(to_string(p));
        return names;
      });
  m.def("fit_options", &fit_options, py::kw_only(), py::arg("free"), py::arg("branch"), py::arg("control"),
        py::arg("spring_constant"), py::arg("baseline"), py::arg("window"), py::arg("window_fraction"), py::arg("loss"),
        py::arg("loss_scale"), py::arg("starts"), py::arg("max_iterations"), py::arg("contact_point"),
        py::arg("indentation_range"), py::arg("force_range"), py::arg("baseline_window"),
        py::arg("bounds") = std::vector<std::tuple<std::string, double, double>>{},
        py::arg("errors_in_displacement") = false, py::arg("displacement_noise") = py::none(),
        py::arg("force_noise") = py::none());
  py::class_<CsvOptions>(m, "CsvOptions", "The library's CsvOptions; make them with csv_options().");
  m.def("csv_options", &csv_options, py::kw_only(), py::arg("units"), py::arg("spring_constant"),
        py::arg("sensitivity") = py::none(), py::arg("z_sign"),
        py::arg("deflection_sign"), py::arg("curve"));
  // "LENGTH,FORCE" -> (metres per length unit, newtons per force unit): fit()'s units=.
  m.def("unit_scales", [](const std::string& units) {
        CsvOptions c;
        parse_units(units, c);
        return std::pair<double, double>{c.length_unit, c.force_unit};
      }, py::arg("units"));

  m.def("fit", &fit_arrays, py::arg("delta"), py::arg("P"), py::arg("segment"), py::arg("t"), py::arg("scene"),
        py::arg("options"));
  // The scene a fit describes (fitted_scene): from the scene's JSON as the fit's provenance kept it
  // and the fitted (name, value) pairs; a joint fit's per-curve names ("delta0[2]", as ParameterEstimate's
  // name above spells them) carry their curve, which fitted_scene leaves with the data.
  m.def("fitted_scene", [](const std::string& scene_json, const std::vector<std::pair<std::string, double>>& values) {
        std::vector<ParameterEstimate> estimates;
        for (const auto& [name, value] : values) {
          const std::size_t bracket = name.find('[');
          ParameterEstimate estimate;
          estimate.parameter = parse_enum<FitParameter>(name.substr(0, bracket), "parameter");
          if (bracket != std::string::npos) estimate.curve = std::stoi(name.substr(bracket + 1));  // from 0
          estimate.value = value;
          estimates.push_back(estimate);
        }
        return fitted_scene(parse_scene(scene_json, "the fit's scene"), estimates);
      }, py::arg("scene_json"), py::arg("values"));
  m.def("fit_joint", &fit_joint_arrays, py::arg("curves"), py::arg("scene"), py::arg("options"));
  m.attr("MAX_POINTS_PER_BRANCH") = SimulationOptions::kMaxPointsPerBranch;
  py::class_<SimulationOptions>(m, "SimulationOptions", "The library's SimulationOptions; make them with simulation_options().");
  m.def("simulation_options", &simulation_options, py::kw_only(), py::arg("max_indentation"), py::arg("speed"),
        py::arg("retract_speed"), py::arg("dwell"), py::arg("points"), py::arg("free_fraction"), py::arg("noise"),
        py::arg("seed"), py::arg("with_radius"), py::arg("branch"), py::arg("delta0"), py::arg("P0"), py::arg("control"),
        py::arg("stiffness"), py::arg("drag") = 0.0);
  m.def("simulate", &simulate_py, py::arg("scene"), py::arg("options"));

  layerjkr::python::bind_fit_summary(m);
  layerjkr::python::bind_batch(m);
  layerjkr::python::bind_instrument(m);
}
