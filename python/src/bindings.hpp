// layerjkr._core's binding files beside module.cpp, one per concept: a fit's answer
// (fit_summary.cpp) and batches of curves with their maps, records and reports (batch.cpp).
#pragma once

#include <pybind11/pybind11.h>

namespace layerjkr::python {

/// Adds the classes ParameterEstimate and FitSummary to `m`.
void bind_fit_summary(pybind11::module_& m);
/// Adds BatchItem, fit_batch, fit_files, map_image, write_tiff, the provenance records and the map report to `m`.
void bind_batch(pybind11::module_& m);

}  // namespace layerjkr::python
