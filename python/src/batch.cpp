// layerjkr._core: batches of curves (fit_batch, fit_files, interruptible by Ctrl-C), a map's
// images and TIFFs, provenance records and the interactive map report (bindings.hpp).
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <exception>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <tuple>
#include <utility>
#include <vector>

#include "bindings.hpp"
#include "convert.hpp"
#include "instrument.hpp"
#include "layerjkr/layerjkr.hpp"

namespace py = pybind11;

namespace layerjkr::python {
namespace {

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

void bind_batch(py::module_& m) {
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
}

}  // namespace layerjkr::python
