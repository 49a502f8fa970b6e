// layerjkr._core: the pybind11 layer under the Python package (python/layerjkr/__init__.py).
// It binds the library's public API and its answers (answer.hpp, fit.hpp) as they are: no
// front-end code, no JSON. Options arrive typed; their strings go through the library's one
// spelling registry (types.hpp, parse_enum) named as the Python parameter they came from.
// Every long call releases the GIL; arrays come in as float64 (converted if needed) and go
// out as new arrays. python/layerjkr/_core.pyi describes this module.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <exception>
#include <mutex>
#include <limits>
#include <optional>
#include <string>
#include <thread>
#include <tuple>
#include <utility>
#include <vector>

#include "instrument.hpp"
#include "layerjkr/layerjkr.hpp"

namespace py = pybind11;
using namespace layerjkr;

namespace {

using Array = py::array_t<double, py::array::c_style | py::array::forcecast>;
/// Segment labels: a numpy int64 array passes without a Python object per sample.
using Labels = py::array_t<std::int64_t, py::array::c_style | py::array::forcecast>;

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

std::vector<double> to_vector(const Array& a, const char* name) {
  if (a.ndim() != 1)
    throw InputError(std::string(name) + " must be a 1-D array; got " + std::to_string(a.ndim()) + " dimensions");
  return std::vector<double>(a.data(), a.data() + a.size());
}

py::array_t<double> to_array(const std::vector<double>& v) {
  py::array_t<double> out(static_cast<py::ssize_t>(v.size()));
  std::copy(v.begin(), v.end(), out.mutable_data());
  return out;
}

py::array_t<bool> to_bool_array(const std::vector<bool>& v) {
  py::array_t<bool> out(static_cast<py::ssize_t>(v.size()));
  for (std::size_t i = 0; i < v.size(); ++i) out.mutable_data()[i] = v[i];
  return out;
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
                       std::optional<Interval> force_range, std::optional<Interval> baseline_window) {
  FitOptions o;
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
    cs.push_back(curve_of(d, P, seg, t, "curve " + std::to_string(k + 1)));
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

BatchOptions batch_options(int jobs) {
  if (jobs < 1) throw InputError("jobs = " + std::to_string(jobs) + " must be >= 1");
  BatchOptions b;
  b.jobs = jobs;
  return b;
}

// Runs a batch on a helper thread while the calling thread, every 100 ms, takes the GIL for
// PyErr_CheckSignals: Ctrl-C cancels the batch (no new curve starts; running fits finish) and
// raises KeyboardInterrupt (or whatever the signal handler raised) within a fit's time, with the
// finished BatchItems attached as the exception's `batch_items`.
template <class Run>
std::vector<BatchItem> run_interruptible(BatchOptions b, Run run) {
  std::atomic<bool> cancel{false};
  b.cancelled = [&cancel] { return cancel.load(); };
  std::vector<BatchItem> items;
  std::exception_ptr error;
  bool interrupted = false;
  {
    py::gil_scoped_release release;
    std::mutex m;
    std::condition_variable cv;
    bool finished = false;
    std::thread batch([&] {
      try {
        items = run(b);
      } catch (...) {
        error = std::current_exception();
      }
      const std::lock_guard<std::mutex> guard(m);
      finished = true;
      cv.notify_all();
    });
    std::unique_lock<std::mutex> lock(m);
    while (!cv.wait_for(lock, std::chrono::milliseconds(100), [&] { return finished; })) {
      if (interrupted) continue;
      lock.unlock();
      {
        py::gil_scoped_acquire gil;
        interrupted = PyErr_CheckSignals() != 0;  // the error stays set for below
      }
      if (interrupted) cancel = true;
      lock.lock();
    }
    lock.unlock();
    batch.join();
  }
  if (interrupted) {
    py::error_already_set raised;
    py::list done;
    for (const BatchItem& it : items)
      if (!it.cancelled) done.append(py::cast(it));
    if (raised.value()) py::setattr(raised.value(), "batch_items", done);
    throw raised;
  }
  if (error) std::rethrow_exception(error);
  return items;
}

std::vector<BatchItem> fit_batch_py(const std::vector<std::pair<Array, Array>>& curves, const Scene& scene,
                                    const FitOptions& options, int jobs, std::size_t display_points) {
  BatchOptions b = batch_options(jobs);
  b.display_points = display_points;
  std::vector<CurveData> data;
  for (std::size_t i = 0; i < curves.size(); ++i) {
    CurveData c;
    c.delta = to_vector(curves[i].first, "delta");
    c.P = to_vector(curves[i].second, "P");
    c.source = "curve " + std::to_string(i);
    data.push_back(std::move(c));
  }
  return run_interruptible(b, [&](const BatchOptions& o) { return fit_batch(data, scene, options, o); });
}

// curves: (begin, end) positions of each instrument file, checked by the Python layer.
std::vector<BatchItem> fit_files_py(const std::vector<std::string>& paths, const Scene& scene, const FitOptions& options,
                                    const CsvOptions& csv, int jobs,
                                    const std::optional<std::pair<std::size_t, std::size_t>>& curves,
                                    std::size_t display_points) {
  BatchOptions b = batch_options(jobs);
  b.display_points = display_points;
  if (curves) b.curves = CurveRange{curves->first, curves->second};
  return run_interruptible(b, [&](const BatchOptions& o) { return fit_files(paths, scene, options, csv, o); });
}

}  // namespace

PYBIND11_MODULE(_core, m) {
  m.doc() = "layerjkr C++ core (use the layerjkr package, not this module)";
  m.attr("__version__") = layerjkr::version();  // the library's, by construction
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
      .def("__repr__", [](const Scene& s) {
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
        py::arg("indentation_range"), py::arg("force_range"), py::arg("baseline_window"));
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

  py::class_<ParameterEstimate>(m, "ParameterEstimate", "One fitted parameter (ParameterEstimate), SI units.")
      .def_property_readonly("name", [](const ParameterEstimate& p) {  // a joint fit's own: "delta0[2]"
        return std::string(to_string(p.parameter)) + (p.curve >= 0 ? "[" + std::to_string(p.curve + 1) + "]" : "");
      })
      .def_property_readonly("parameter", [](const ParameterEstimate& p) { return std::string(to_string(p.parameter)); })
      .def_property_readonly("curve", [](const ParameterEstimate& p) -> py::object {
        return p.curve >= 0 ? py::object(py::int_(p.curve)) : py::object(py::none());
      })
      .def_readonly("value", &ParameterEstimate::value)
      .def_readonly("standard_error", &ParameterEstimate::standard_error)
      .def_readonly("initial", &ParameterEstimate::initial)
      .def_readonly("at_bound", &ParameterEstimate::at_bound)
      .def_readonly("upper_bound", &ParameterEstimate::upper_bound)
      .def_readonly("identifiable", &ParameterEstimate::identifiable)
      .def_property_readonly("reason", [](const ParameterEstimate& p) { return python::text(p.reason); });

  py::class_<FitSummary>(m, "FitSummary", "A fit's summary (FitSummary).")
      .def_readonly("converged", &FitSummary::converged)
      .def_readonly("termination", &FitSummary::termination)
      .def_readonly("iterations", &FitSummary::iterations)
      .def_readonly("model", &FitSummary::model)
      .def_property_readonly("family", [](const FitSummary& s) { return std::string(to_string(s.family)); })
      .def_readonly("parameters", &FitSummary::parameters)
      .def_property_readonly("correlation", [](const FitSummary& s) {
        const auto n = static_cast<py::ssize_t>(s.parameters.size());
        py::array_t<double> c({n, n});
        for (py::ssize_t i = 0; i < n; ++i)
          for (py::ssize_t k = 0; k < n; ++k)
            *c.mutable_data(i, k) = s.correlation.empty() ? std::nan("")
                                                          : s.correlation[static_cast<std::size_t>(i)][static_cast<std::size_t>(k)];
        return c;
      })
      .def_readonly("rms_residual", &FitSummary::rms_residual)
      .def_readonly("samples_fitted", &FitSummary::samples_fitted)
      .def_property_readonly("chi_square", &FitSummary::chi_square)
      .def_property_readonly("reduced_chi_square", &FitSummary::reduced_chi_square)
      .def_property_readonly("aic", &FitSummary::aic)
      .def_property_readonly("bic", &FitSummary::bic)
      .def_readonly("initial_cost", &FitSummary::initial_cost)
      .def_readonly("final_cost", &FitSummary::final_cost)
      .def_readonly("points", &FitSummary::points)
      .def_readonly("points_in_contact", &FitSummary::points_in_contact)
      .def_readonly("identifiable", &FitSummary::identifiable)
      .def_readonly("identifiability_known", &FitSummary::identifiability_known)
      .def_property_readonly("identifiability_reason", [](const FitSummary& s) { return python::text(s.identifiability_reason); })
      .def_property_readonly("identifiability", [](const FitSummary& s) { return python::text(s.identifiability()); })
      .def_readonly("unidentifiable", &FitSummary::unidentifiable)
      .def_property_readonly("no_move_reason", [](const FitSummary& s) { return python::text(s.no_move_reason); })
      .def_property_readonly("warnings", [](const FitSummary& s) { return python::texts(s.warnings); })
      .def_property_readonly("notices", [](const FitSummary& s) { return python::texts(s.notices); })
      .def_readonly("noise", &FitSummary::noise)
      .def_readonly("runs_z", &FitSummary::runs_z)
      .def_readonly("residual_structure", &FitSummary::residual_structure)
      .def_readonly("force_noise", &FitSummary::force_noise)
      .def_readonly("radius_noise", &FitSummary::radius_noise)
      .def_readonly("force_noise_given", &FitSummary::force_noise_given)
      .def_readonly("radius_noise_given", &FitSummary::radius_noise_given)
      .def_property_readonly("delta", [](const FitSummary& s) { return to_array(s.delta); })
      .def_property_readonly("P", [](const FitSummary& s) { return to_array(s.P); })
      .def_property_readonly("P_fit", [](const FitSummary& s) { return to_array(s.P_fit); })
      .def_property_readonly("t", [](const FitSummary& s) { return to_array(s.t); })
      .def_property_readonly("excluded", [](const FitSummary& s) { return to_bool_array(s.excluded); })
      .def_readonly("excluded_count", &FitSummary::excluded_count)
      .def_readonly("baseline_slope", &FitSummary::baseline_slope)
      .def_readonly("baseline_slope_stderr", &FitSummary::baseline_slope_stderr)
      .def_readonly("baseline_offset", &FitSummary::baseline_offset)
      .def_readonly("pull_off_force", &FitSummary::pull_off_force)
      .def_readonly("solve_seconds", &FitSummary::solve_seconds)
      .def_property_readonly("contact_point", [](const FitSummary& s) {
        const ContactPointReport& c = s.contact_point;
        py::dict d;
        d["method"] = std::string(to_string(c.method));
        d["value"] = c.value;
        d["stderr"] = c.standard_error;
        d["baseline"] = c.baseline;
        d["range_reference"] = c.range_reference;
        d["approach_samples"] = c.approach_samples;
        d["samples_in_range"] = c.samples_in_range;
        return d;
      })
      .def("brief_report", [](const FitSummary& s) { return python::text(s.brief_report()); });

  py::class_<BatchItem>(m, "BatchItem", "One curve of a batch (BatchItem).")
      .def_property_readonly("source", [](const BatchItem& it) { return python::file_name(it.source); })
      .def_readonly("ok", &BatchItem::ok)
      .def_property_readonly("error", [](const BatchItem& it) { return python::text(it.error); })
      .def_readonly("summary", &BatchItem::summary)
      .def_readonly("curve", &BatchItem::curve)
      .def_readonly("x", &BatchItem::x)
      .def_readonly("y", &BatchItem::y)
      .def_readonly("grid_x", &BatchItem::grid_x)
      .def_readonly("grid_y", &BatchItem::grid_y)
      .def_property_readonly("quality", &batch_quality);

  // A map field's image and its TIFF (map_image.hpp): the same placement and writer as fit-map --tiff.
  m.def("map_image", [](const std::vector<int>& grid_x, const std::vector<int>& grid_y, const std::vector<double>& values) {
        const MapImage image = map_image(grid_x, grid_y, values);
        py::array_t<double> out({image.height, image.width});
        std::copy(image.values.begin(), image.values.end(), out.mutable_data());
        return out;
      }, py::arg("grid_x"), py::arg("grid_y"), py::arg("values"));
  m.def("write_tiff", [](const std::string& path, const py::array_t<double, py::array::c_style | py::array::forcecast>& a,
                         const std::string& description) {
        if (a.ndim() != 2 || a.shape(0) < 1 || a.shape(1) < 1)
          throw InputError("write_tiff " + path + ": the image must be a non-empty 2-D array");
        MapImage image;
        image.height = static_cast<std::size_t>(a.shape(0));
        image.width = static_cast<std::size_t>(a.shape(1));
        image.values.assign(a.data(), a.data() + a.size());
        py::gil_scoped_release release;
        write_tiff(image, path, description);
      }, py::arg("path"), py::arg("image"), py::arg("description"));

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
          if (bracket != std::string::npos) estimate.curve = std::stoi(name.substr(bracket + 1)) - 1;
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
  m.def("fit_batch", &fit_batch_py, py::arg("curves"), py::arg("scene"), py::arg("options"), py::arg("jobs"),
        py::arg("display_points") = 0);
  m.def("fit_files", &fit_files_py, py::arg("paths"), py::arg("scene"), py::arg("options"), py::arg("csv"),
        py::arg("jobs"), py::arg("curves") = py::none(), py::arg("display_points") = 0);

  // Provenance (provenance.hpp): inputs as (path, size, sha256, error) tuples, the record as JSON text.
  m.def("record_file", [](const std::string& path) {
        InputRecord r;
        {
          py::gil_scoped_release release;
          r = record_file(path);
        }
        // The path as records hold it (escape_bytes: valid UTF-8, reversible), the reason printable.
        return py::make_tuple(escape_bytes(r.path), r.size, r.sha256, printable(r.error));
      },
      py::arg("path"));
  m.def("record_bytes", [](const std::string& name, const py::buffer& data) {
        const py::buffer_info b = data.request();
        if (!PyBuffer_IsContiguous(b.view(), 'C')) throw InputError(name + ": the array must be C-contiguous to be hashed");
        const InputRecord r = record_bytes(name, b.ptr, static_cast<std::size_t>(b.size * b.itemsize));
        return py::make_tuple(r.path, r.size, r.sha256, r.error);
      },
      py::arg("name"), py::arg("data"));
  m.def("provenance", [](const Scene& scene, const FitOptions& options, std::optional<CsvOptions> csv,
                         const std::vector<std::tuple<std::string, std::uint64_t, std::string, std::string>>& inputs) {
        std::vector<InputRecord> records;
        for (const auto& [path, size, sha, error] : inputs) records.push_back({unescape_bytes(path), size, sha, error});
        return provenance_json(scene, options, csv ? &*csv : nullptr, records);
      },
      py::arg("scene"), py::arg("options"), py::arg("csv"), py::arg("inputs"));
  m.attr("DEFAULT_DISPLAY_POINTS") = kDefaultDisplayPoints;
  m.def(
      "prepare_report_dir", [](const std::string& dir, const std::string& flag) { prepare_report_dir(dir, flag); },
      py::arg("dir"), py::arg("flag"));
  m.def(
      "map_report_html",
      [](const std::vector<BatchItem>& items, const FitOptions& options, const std::string& title,
         const std::string& subtitle) {
        MapReportOptions r;
        r.free = options.free;
        r.title = title;
        r.subtitle = subtitle;
        std::string html;
        {
          py::gil_scoped_release release;
          html = map_report_html(items, r);
        }
        return py::bytes(html);
      },
      py::arg("items"), py::arg("options"), py::arg("title"), py::arg("subtitle"));
  layerjkr::python::bind_instrument(m);
}
