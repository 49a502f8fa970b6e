// layerjkr._core: a fit's answer as Python sees it - ParameterEstimate and FitSummary, their
// arrays new numpy arrays, their texts printable (bindings.hpp).
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <string>
#include <vector>

#include "bindings.hpp"
#include "convert.hpp"
#include "instrument.hpp"
#include "layerjkr/layerjkr.hpp"

namespace py = pybind11;

namespace layerjkr::python {

void bind_fit_summary(py::module_& m) {
  py::class_<ParameterEstimate>(m, "ParameterEstimate", "One fitted parameter (ParameterEstimate), SI units.")
      .def_property_readonly("name", [](const ParameterEstimate& p) {  // a joint fit's own: "delta0[1]", from 0
        return std::string(to_string(p.parameter)) + (p.curve >= 0 ? "[" + std::to_string(p.curve) + "]" : "");
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
      .def_readonly("function_evaluations", &FitSummary::function_evaluations)
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
      .def_readonly("displacement_noise", &FitSummary::displacement_noise)
      .def_readonly("displacement_noise_given", &FitSummary::displacement_noise_given)
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
}

}  // namespace layerjkr::python
