// layerjkr._core: the pybind11 layer under the Python package (python/layerjkr/__init__.py).
// It exposes the C++ public API and the front-end reports the CLI prints (src/cli/reports.hpp,
// fit_commands.hpp), so Python gets the CLI's numbers from the same code. Every long call
// releases the GIL; arrays come in as float64 (converted if needed) and go out as new arrays.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <chrono>
#include <cmath>
#include <string>
#include <vector>

#include "fit_commands.hpp"
#include "layerjkr/layerjkr.hpp"
#include "reports.hpp"

namespace py = pybind11;
using namespace layerjkr;

namespace {

using Array = py::array_t<double, py::array::c_style | py::array::forcecast>;

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

// `inner_seconds` (the benchmark's hook): the time spent in the C++ curve itself.
// The output - one (8, n) block whose rows the dict views - is made and touched before the
// GIL is released, while the interpreter's caches are warm; the computation then fills it and
// frees its own data without the GIL, so little Python work is left for after it.
py::dict curve_impl(const Scene& scene, const Array& radii, double* inner_seconds) {
  const std::vector<double> a = to_vector(radii, "a");
  const auto n = static_cast<py::ssize_t>(a.size());
  py::array_t<double> block({py::ssize_t{8}, n});
  std::fill_n(block.mutable_data(), 8 * n, 0.0);
  static const char* const names[] = {"a", "P", "delta", "P_H", "delta_H", "S", "dS_da", "error_est"};
  py::dict d;
  for (py::ssize_t k = 0; k < 8; ++k)
    d[names[k]] = py::array_t<double>({n}, {static_cast<py::ssize_t>(sizeof(double))}, block.data(k, 0), block);
  double* out = block.mutable_data();
  std::vector<std::string> warnings;
  std::string note;
  {
    py::gil_scoped_release release;
    const auto start = std::chrono::steady_clock::now();
    cli::CurveTable t = cli::curve_table(scene, a);
    if (inner_seconds) *inner_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    for (py::ssize_t i = 0; i < n; ++i) {
      const auto k = static_cast<std::size_t>(i);
      const AdhesiveState& s = t.states[k];
      const double row[8] = {a[k], s.P, s.delta, s.hertz.P_H, s.hertz.delta_H, s.hertz.S, s.hertz.dS_da, t.error_est[k]};
      for (py::ssize_t r = 0; r < 8; ++r) out[r * n + i] = row[r];
    }
    warnings = std::move(t.warnings);
    note = std::move(t.choice_note);
  }
  d["warnings"] = warnings;
  d["note"] = note;
  return d;
}

py::dict curve(const Scene& scene, const Array& radii) { return curve_impl(scene, radii, nullptr); }

// The binding's overhead without the C++ curve's own time (python/bench/bench_python.py).
py::tuple curve_timed(const Scene& scene, const Array& radii) {
  double inner = 0.0;
  py::dict d = curve_impl(scene, radii, &inner);
  return py::make_tuple(d, inner);
}

std::string summary(const Scene& scene) {
  py::gil_scoped_release release;
  return cli::summary_report(scene).json.dump();
}

// The fit options from the CLI's flag names (fit_commands.hpp), as strings and numbers.
cli::Prepared prepared_options(const std::vector<std::string>& free, const py::dict& options) {
  cli::FitArguments a;
  std::string list;
  for (const std::string& f : free) list += (list.empty() ? "" : ",") + f;
  a.free = list;
  for (const auto& [key_handle, value] : options) {
    const std::string key = py::str(key_handle);
    if (key == "branch") a.branch = value.cast<std::string>();
    else if (key == "loss") a.loss = value.cast<std::string>();
    else if (key == "control") a.control = value.cast<std::string>();
    else if (key == "baseline") a.baseline = value.cast<std::string>();
    else if (key == "window") a.window = value.cast<std::string>();
    else if (key == "units") a.units = value.cast<std::string>();
    else if (key == "starts") a.extra_starts = value.cast<int>();
    else if (key == "max_iterations") a.max_iterations = value.cast<int>();
    else if (key == "spring_constant") a.spring_constant = value.cast<double>();
    else if (key == "curve") a.curve = value.cast<int>();
    else
      throw InputError("fit: unknown option '" + key +
                       "' (known: branch, loss, control, baseline, window, units, starts, max_iterations, spring_constant, curve)");
  }
  return cli::prepare_options(a);
}

struct FitOutput {
  std::string report;  // the JSON keys of `layerjkr fit --out`
  std::string brief;
  std::vector<double> delta, P, P_fit;
  std::vector<bool> excluded;
};

FitOutput fit_arrays(const Array& delta, const Array& P, const py::object& segment, const Scene& scene,
                     const std::vector<std::string>& free, const py::dict& options) {
  cli::Prepared p = prepared_options(free, options);
  CurveData c;
  c.delta = to_vector(delta, "delta");
  c.P = to_vector(P, "P");
  c.source = "array";
  c.spring_constant = p.csv.spring_constant;
  if (!segment.is_none()) c.segment = segment.cast<std::vector<int>>();
  FitOutput out;
  py::gil_scoped_release release;
  if (p.cantilever_required && !(c.spring_constant > 0.0))
    throw InputError("control 'cantilever' needs the spring constant: spring_constant=k [N/m]");
  const FitSummary s = fit(c, scene, p.options);
  out.report = cli::report_json(s, p.options.branch).dump();
  out.brief = s.brief_report();
  out.delta = s.delta, out.P = s.P, out.P_fit = s.P_fit, out.excluded = s.excluded;
  return out;
}

py::list batch_items(const std::vector<BatchItem>& items, Branch branch) {
  py::list out;
  for (const BatchItem& it : items) {
    py::dict d;
    d["source"] = it.source, d["ok"] = it.ok, d["error"] = it.error, d["curve"] = it.curve;
    d["x"] = it.x, d["y"] = it.y, d["grid_x"] = it.grid_x, d["grid_y"] = it.grid_y;
    d["report"] = it.ok ? cli::report_json(it.summary, branch).dump() : std::string();
    out.append(d);
  }
  return out;
}

py::list fit_files_py(const std::vector<std::string>& paths, const Scene& scene, const std::vector<std::string>& free,
                      const py::dict& options, int jobs) {
  if (jobs < 1) throw InputError("jobs = " + std::to_string(jobs) + " must be >= 1");
  const cli::Prepared p = prepared_options(free, options);
  std::vector<BatchItem> items;
  {
    py::gil_scoped_release release;
    BatchOptions b;
    b.jobs = jobs;
    items = fit_files(paths, scene, p.options, p.csv, b);
  }
  return batch_items(items, p.options.branch);
}

py::list fit_batch_py(const std::vector<std::pair<Array, Array>>& curves, const Scene& scene,
                      const std::vector<std::string>& free, const py::dict& options, int jobs) {
  if (jobs < 1) throw InputError("jobs = " + std::to_string(jobs) + " must be >= 1");
  const cli::Prepared p = prepared_options(free, options);
  std::vector<CurveData> data;
  for (std::size_t i = 0; i < curves.size(); ++i) {
    CurveData c;
    c.delta = to_vector(curves[i].first, "delta");
    c.P = to_vector(curves[i].second, "P");
    c.source = "curve " + std::to_string(i);
    c.spring_constant = p.csv.spring_constant;
    data.push_back(std::move(c));
  }
  std::vector<BatchItem> items;
  {
    py::gil_scoped_release release;
    BatchOptions b;
    b.jobs = jobs;
    items = fit_batch(data, scene, p.options, b);
  }
  return batch_items(items, p.options.branch);
}

py::list read_instrument(const std::string& path) {
  InstrumentFile f;
  {
    py::gil_scoped_release release;
    f = read_instrument_file(path);
  }
  py::list out;
  for (const InstrumentCurve& c : f.curves) {
    const CurveData d = to_curve_data(c, path);
    py::dict item;
    item["index"] = c.index, item["x"] = c.x, item["y"] = c.y, item["grid_x"] = c.grid_x, item["grid_y"] = c.grid_y;
    item["spring_constant"] = c.spring_constant, item["sensitivity"] = c.sensitivity;
    item["delta"] = to_array(d.delta), item["P"] = to_array(d.P);
    item["segment"] = py::array_t<int>(static_cast<py::ssize_t>(d.segment.size()), d.segment.data());
    out.append(item);
  }
  return out;
}

}  // namespace

PYBIND11_MODULE(_core, m) {
  m.doc() = "layerjkr C++ core (use the layerjkr package, not this module)";
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
    } catch (const DomainError& x) {
      PyErr_SetString(exceptions().domain.ptr(), x.what());
    } catch (const InputError& x) {
      PyErr_SetString(exceptions().input.ptr(), x.what());
    } catch (const NumericalError& x) {
      PyErr_SetString(exceptions().numerical.ptr(), x.what());
    } catch (const Error& x) {
      PyErr_SetString(exceptions().error.ptr(), x.what());
    }
  });

  py::class_<Scene>(m, "Scene", "A parsed scene (the CLI's JSON schema); make one with layerjkr.scene().")
      .def_property_readonly("w", [](const Scene& s) { return s.w; })
      .def_property_readonly("profile", [](const Scene& s) { return s.profile->describe(); })
      .def_property_readonly("model", [](const Scene& s) { return std::string(to_string(s.model)); });
  m.def("parse_scene", &parse_scene, py::arg("json_text"), py::arg("source") = "scene");
  m.def("with_table_profile", [](Scene s, std::vector<double> r, std::vector<double> z) {
        s.profile = make_table_profile(std::move(r), std::move(z));
        return s;
      },
      py::arg("scene"), py::arg("r"), py::arg("z"));
  m.def("load_scene", &load_scene, py::arg("path"));
  m.def("curve", &curve, py::arg("scene"), py::arg("a"));
  m.def("_curve_timed", &curve_timed, py::arg("scene"), py::arg("a"));
  m.def("summary", &summary, py::arg("scene"));
  py::class_<FitOutput>(m, "FitOutput")
      .def_readonly("report", &FitOutput::report)
      .def_readonly("brief", &FitOutput::brief)
      .def_property_readonly("delta", [](const FitOutput& o) { return to_array(o.delta); })
      .def_property_readonly("P", [](const FitOutput& o) { return to_array(o.P); })
      .def_property_readonly("P_fit", [](const FitOutput& o) { return to_array(o.P_fit); })
      .def_property_readonly("excluded", [](const FitOutput& o) {
        py::array_t<bool> a(static_cast<py::ssize_t>(o.excluded.size()));
        for (std::size_t i = 0; i < o.excluded.size(); ++i) a.mutable_data()[i] = o.excluded[i];
        return a;
      });
  m.def("fit", &fit_arrays, py::arg("delta"), py::arg("P"), py::arg("segment"), py::arg("scene"), py::arg("free"),
        py::arg("options"));
  m.def("fit_files", &fit_files_py, py::arg("paths"), py::arg("scene"), py::arg("free"), py::arg("options"), py::arg("jobs"));
  m.def("fit_batch", &fit_batch_py, py::arg("curves"), py::arg("scene"), py::arg("free"), py::arg("options"), py::arg("jobs"));
  m.def("read_instrument", &read_instrument, py::arg("path"));
}
