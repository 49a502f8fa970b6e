// layerjkr._core: instrument files (instrument.hpp). Every read runs with the GIL released and
// returns the curves as the dicts layerjkr.read_instrument documents; the conversion to numpy
// happens after, under the GIL. Ranges arrive as (begin, end) positions already checked by the
// Python layer (python/layerjkr/__init__.py), which owns the slice semantics.
#include "instrument.hpp"

#include "convert.hpp"

#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <cstddef>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "layerjkr/instrument.hpp"
#include "layerjkr/text.hpp"

namespace py = pybind11;

namespace layerjkr::python {
namespace {

py::dict curve_dict(const InstrumentCurve& c, const std::string& path, double spring_constant = 0.0,
                    double sensitivity = 0.0) {
  const CurveData d = to_curve_data(c, path, spring_constant, sensitivity);
  py::dict item;
  item["index"] = c.index, item["x"] = c.x, item["y"] = c.y, item["grid_x"] = c.grid_x, item["grid_y"] = c.grid_y;
  item["spring_constant"] = c.spring_constant, item["sensitivity"] = c.sensitivity;
  item["delta"] = to_array(d.delta), item["P"] = to_array(d.P);
  item["segment"] = py::array_t<int>(static_cast<py::ssize_t>(d.segment.size()), d.segment.data());
  // The samples' times [s] where the file gives segment durations (fits in time need them); else None.
  item["t"] = d.t.empty() ? py::object(py::none()) : py::object(to_array(d.t));
  return item;
}

py::list curve_list(const std::vector<InstrumentCurve>& curves, const std::string& path, double spring_constant = 0.0,
                    double sensitivity = 0.0) {
  py::list out;
  for (const InstrumentCurve& c : curves) out.append(curve_dict(c, path, spring_constant, sensitivity));
  return out;
}

py::list read_instrument(const std::string& path, std::size_t begin, std::optional<std::size_t> end,
                         double spring_constant, double sensitivity) {
  CurveRange range;
  range.begin = begin;
  if (end) range.end = *end;
  InstrumentFile f;
  {
    py::gil_scoped_release release;
    f = read_instrument_file(path, ReadLimits::from_environment(), range);
  }
  return curve_list(f.curves, f.path, spring_constant, sensitivity);
}

// The library's InstrumentReader behind a shared_ptr: a read in flight (GIL released) holds its
// own reference, so close() from another Python thread never frees the reader under it.
class Reader {
 public:
  explicit Reader(const std::string& path) {
    py::gil_scoped_release release;
    reader_ = std::make_shared<InstrumentReader>(path);
  }

  std::shared_ptr<InstrumentReader> open() const {
    if (!reader_) throw py::value_error("the instrument file is closed");
    return reader_;
  }
  void close() { reader_.reset(); }
  bool closed() const { return !reader_; }

  // Positions begin .. end - 1 (checked by the caller against size()), read in one release of
  // the GIL; a failing curve raises, naming the file and the curve.
  py::list curves(const std::vector<std::size_t>& positions) const {
    const std::shared_ptr<InstrumentReader> r = open();
    std::vector<InstrumentCurve> read;
    {
      py::gil_scoped_release release;
      read.reserve(positions.size());
      for (std::size_t i : positions) read.push_back(r->curve(i));
    }
    return curve_list(read, r->header().path);
  }

 private:
  std::shared_ptr<InstrumentReader> reader_;
};

py::dict header_dict(const InstrumentFile& h) {
  py::dict d;
  d["path"] = file_name(h.path), d["format"] = std::string(to_string(h.format));
  d["instrument"] = text(h.instrument), d["software"] = text(h.software);
  d["grid_shape"] = py::make_tuple(h.grid_shape_x, h.grid_shape_y);
  d["grid_size"] = py::make_tuple(h.grid_size_x, h.grid_size_y);
  d["grid_center"] = py::make_tuple(h.grid_center_x, h.grid_center_y);
  return d;
}

}  // namespace

py::str file_name(const std::string& name) {
  PyObject* o = PyUnicode_DecodeFSDefaultAndSize(name.data(), static_cast<Py_ssize_t>(name.size()));
  if (o == nullptr) throw py::error_already_set();
  return py::reinterpret_steal<py::str>(o);
}

py::str text(const std::string& s) { return py::str(layerjkr::printable(s)); }

py::list texts(const std::vector<std::string>& v) {
  py::list out;
  for (const std::string& s : v) out.append(text(s));
  return out;
}

void bind_instrument(py::module_& m) {
  m.def("read_instrument", &read_instrument, py::arg("path"), py::arg("begin") = 0, py::arg("end") = py::none(),
        py::arg("spring_constant") = 0.0, py::arg("sensitivity") = 0.0);
  py::class_<Reader>(m, "InstrumentReader", "An instrument file opened for random access (the library's InstrumentReader).")
      .def(py::init<const std::string&>(), py::arg("path"))
      .def("__len__", [](const Reader& r) { return r.open()->size(); })
      .def_property_readonly("header", [](const Reader& r) { return header_dict(r.open()->header()); })
      .def("curves", &Reader::curves, py::arg("positions"))
      .def("curve_number", [](const Reader& r, std::size_t i) { return r.open()->curve_number(i); }, py::arg("i"))
      .def("close", &Reader::close)
      .def_property_readonly("closed", &Reader::closed);
}

}  // namespace layerjkr::python
