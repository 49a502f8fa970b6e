// afmformats' HDF5 export (io/afmformats_hdf5.hpp). The layout, from afmformats' fmt_hdf5.py and
// its test file fmt-hdf5-fd_version_0.13.3.h5 (h5dump): root attributes `software` ("afmformats")
// and `software version`; a group per curve named by its number, its metadata as scalar
// attributes (`spring constant` [N/m], `sensitivity` [m/V], `position x`, ... [m]) and its columns
// as 1-D datasets (`force` [N], `height (measured)`, `height (piezo)`, `tip position` [m],
// `segment` 0/1, `time` [s]). Read whole when opened (the files hold one curve or a few) under
// one lock: Debian's libhdf5 is built without thread safety.
#include "io/afmformats_hdf5.hpp"

#include <hdf5.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <mutex>
#include <optional>
#include <vector>

#include "io/instrument_readers.hpp"
#include "io/zip_archive.hpp"
#include "layerjkr/error.hpp"
#include "layerjkr/instrument.hpp"
#include "layerjkr/text.hpp"

namespace layerjkr::detail {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// H5T_NATIVE_DOUBLE is a macro of a comma expression (H5open(), the global id).
hid_t native_double() { return H5T_NATIVE_DOUBLE; }

std::mutex& hdf5_lock() {
  static std::mutex m;
  return m;
}

// An HDF5 identifier closed with its own close function.
class Id {
 public:
  Id(hid_t id, herr_t (*close)(hid_t)) : id_(id), close_(close) {}
  ~Id() {
    if (id_ >= 0) close_(id_);
  }
  Id(const Id&) = delete;
  Id& operator=(const Id&) = delete;
  bool ok() const { return id_ >= 0; }
  operator hid_t() const { return id_; }  // NOLINT(google-explicit-constructor): used as the C API's handle

 private:
  hid_t id_;
  herr_t (*close_)(hid_t);
};

struct Reader {
  std::string path;
  std::uint64_t max_samples;

  [[noreturn]] void fail(const std::string& what) const { throw InputError(path + ": afmformats HDF5 export: " + what); }

  // A scalar attribute's type and whether it holds one value; nullopt if absent.
  static std::optional<H5T_class_t> scalar_class(hid_t attr) {
    const Id space(H5Aget_space(attr), H5Sclose);
    const Id type(H5Aget_type(attr), H5Tclose);
    if (!space.ok() || !type.ok() || H5Sget_simple_extent_npoints(space) != 1) return std::nullopt;
    return H5Tget_class(type);
  }

  static std::optional<std::string> text(hid_t object, const char* name) {
    if (H5Aexists(object, name) <= 0) return std::nullopt;
    const Id attr(H5Aopen(object, name, H5P_DEFAULT), H5Aclose);
    if (!attr.ok() || scalar_class(attr) != H5T_STRING) return std::nullopt;
    const Id type(H5Aget_type(attr), H5Tclose);
    if (H5Tis_variable_str(type) > 0) {
      const Id memory(H5Tcopy(H5T_C_S1), H5Tclose);
      H5Tset_size(memory, H5T_VARIABLE);
      H5Tset_cset(memory, H5Tget_cset(type));
      char* value = nullptr;
      if (H5Aread(attr, memory, static_cast<void*>(&value)) < 0) return std::nullopt;
      std::string out = value ? value : "";
      H5free_memory(value);
      return out;
    }
    std::string buffer(H5Tget_size(type), '\0');
    const Id memory(H5Tcopy(type), H5Tclose);
    if (H5Aread(attr, memory, buffer.data()) < 0) return std::nullopt;
    return buffer.substr(0, buffer.find('\0'));
  }

  static std::optional<double> number(hid_t object, const char* name) {
    if (H5Aexists(object, name) <= 0) return std::nullopt;
    const Id attr(H5Aopen(object, name, H5P_DEFAULT), H5Aclose);
    const std::optional<H5T_class_t> c = attr.ok() ? scalar_class(attr) : std::nullopt;
    if (!c || (*c != H5T_FLOAT && *c != H5T_INTEGER)) return std::nullopt;
    double v = kNaN;
    if (H5Aread(attr, native_double(), &v) < 0) return std::nullopt;
    return v;
  }

  std::optional<std::vector<double>> column(hid_t group, const std::string& where, const char* name) const {
    if (H5Lexists(group, name, H5P_DEFAULT) <= 0) return std::nullopt;
    const Id data(H5Dopen2(group, name, H5P_DEFAULT), H5Dclose);
    if (!data.ok()) fail(where + "/" + name + " is not a dataset");
    const Id space(H5Dget_space(data), H5Sclose);
    const Id type(H5Dget_type(data), H5Tclose);
    const H5T_class_t c = H5Tget_class(type);
    if (H5Sget_simple_extent_ndims(space) != 1 || (c != H5T_FLOAT && c != H5T_INTEGER))
      fail(where + "/" + name + " is not a 1-D column of numbers");
    const hssize_t n = H5Sget_simple_extent_npoints(space);
    if (n < 0 || static_cast<std::uint64_t>(n) > max_samples)
      fail(where + "/" + name + " holds " + std::to_string(n) + " samples; at most " + std::to_string(max_samples) +
           " are read (" + kMaxArchiveEnv + ")");
    std::vector<double> v(static_cast<std::size_t>(n));
    if (n > 0 && H5Dread(data, native_double(), H5S_ALL, H5S_ALL, H5P_DEFAULT, v.data()) < 0)
      fail(where + "/" + name + " cannot be read");
    return v;
  }

  std::vector<std::string> curve_groups(hid_t file) const {
    H5G_info_t info{};
    if (H5Gget_info(file, &info) < 0) fail("its root group cannot be listed");
    std::vector<std::string> names;
    for (hsize_t i = 0; i < info.nlinks; ++i) {
      const ssize_t size = H5Lget_name_by_idx(file, ".", H5_INDEX_NAME, H5_ITER_INC, i, nullptr, 0, H5P_DEFAULT);
      if (size <= 0) continue;
      std::string name(static_cast<std::size_t>(size) + 1, '\0');
      H5Lget_name_by_idx(file, ".", H5_INDEX_NAME, H5_ITER_INC, i, name.data(), name.size(), H5P_DEFAULT);
      name.resize(static_cast<std::size_t>(size));
      if (!name.empty() && name.size() < 10 && std::all_of(name.begin(), name.end(), [](char ch) { return ch >= '0' && ch <= '9'; }))
        names.push_back(name);
    }
    std::sort(names.begin(), names.end(), [](const std::string& a, const std::string& b) { return std::stol(a) < std::stol(b); });
    if (names.empty()) fail("holds no curve group (\"0\", \"1\", ...)");
    return names;
  }

  InstrumentCurve curve(hid_t file, const std::string& name, std::uint64_t& samples) const {
    const Id group(H5Gopen2(file, name.c_str(), H5P_DEFAULT), H5Gclose);
    if (!group.ok()) fail("\"" + name + "\" is not a group");
    const std::string where = "curve " + name;
    InstrumentCurve c;
    c.index = static_cast<int>(std::stol(name));
    c.spring_constant = number(group, "spring constant").value_or(kNaN);
    if (!(c.spring_constant > 0.0) || !std::isfinite(c.spring_constant))
      fail(where + " has no spring constant attribute (finite and > 0 N/m): export it with its metadata");
    c.sensitivity = number(group, "sensitivity").value_or(0.0);
    c.x = number(group, "position x").value_or(kNaN);
    c.y = number(group, "position y").value_or(kNaN);
    c.grid_x = static_cast<int>(number(group, "grid index x").value_or(-1.0));
    c.grid_y = static_cast<int>(number(group, "grid index y").value_or(-1.0));
    const std::optional<std::vector<double>> force = column(group, where, "force");
    const std::optional<std::vector<double>> segment = column(group, where, "segment");
    if (!force || !segment) fail(where + " has no force or no segment column");
    std::optional<std::vector<double>> height = column(group, where, "height (measured)");
    if (!height)
      if (const auto tip = column(group, where, "tip position")) {
        height = *tip;
        for (std::size_t i = 0; i < height->size() && i < force->size(); ++i) (*height)[i] -= (*force)[i] / c.spring_constant;
      }
    if (!height) fail(where + " has neither height (measured) nor tip position");
    const std::optional<std::vector<double>> time = column(group, where, "time");
    const std::size_t n = force->size();
    if (segment->size() != n || height->size() != n || (time && time->size() != n))
      fail(where + ": its columns differ in length");
    samples += n;
    if (samples > max_samples) fail("holds more than " + std::to_string(max_samples) + " samples in all");
    // Runs of equal labels are the segments: 0 the approach (extend), 1 the retract.
    for (std::size_t begin = 0; begin < n;) {
      const double label = (*segment)[begin];
      if (label != 0.0 && label != 1.0)
        fail(where + ": segment[" + std::to_string(begin) + "] = " + format_double(label) + "; valid: 0, 1");
      std::size_t end = begin;
      while (end < n && (*segment)[end] == label) ++end;
      InstrumentSegment s;
      s.style = label == 0.0 ? SegmentStyle::extend : SegmentStyle::retract;
      s.force.assign(force->begin() + static_cast<std::ptrdiff_t>(begin), force->begin() + static_cast<std::ptrdiff_t>(end));
      s.height.assign(height->begin() + static_cast<std::ptrdiff_t>(begin), height->begin() + static_cast<std::ptrdiff_t>(end));
      const std::size_t m = end - begin;
      if (time && m > 1)  // to_curve_data places sample i at start + i duration / m
        s.duration = ((*time)[end - 1] - (*time)[begin]) * static_cast<double>(m) / static_cast<double>(m - 1);
      c.segments.push_back(std::move(s));
      begin = end;
    }
    return c;
  }
};

std::unique_ptr<CurveSource> read_locked(const std::string& path, const ReadLimits& limits) {
  const Reader r{path, limits.max_archive_bytes / sizeof(double)};
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);  // errors become InputErrors, not text on stderr
  if (H5Fis_hdf5(path.c_str()) <= 0) r.fail("is not an HDF5 file");
  const Id file(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose);
  if (!file.ok()) r.fail("cannot be opened");
  const std::optional<std::string> software = Reader::text(file, "software");
  if (software != "afmformats")
    throw InputError(path + ": an HDF5 file that afmformats did not write (root attribute software = '" +
                     printable(software.value_or("none")) + "'): of HDF5 files only afmformats' exports are read; " +
                     kAsylumPerPoint);
  InstrumentFile f;
  f.path = path;
  f.format = InstrumentFormat::afmformats_hdf5;
  f.software = "afmformats " + Reader::text(file, "software version").value_or("");
  std::uint64_t samples = 0;
  for (const std::string& name : r.curve_groups(file)) {
    f.curves.push_back(r.curve(file, name, samples));
    if (f.instrument.empty()) {
      const Id group(H5Gopen2(file, name.c_str(), H5P_DEFAULT), H5Gclose);
      f.instrument = Reader::text(group, "instrument").value_or("");
    }
  }
  return source_of(std::move(f));
}

}  // namespace

std::unique_ptr<CurveSource> open_afmformats_hdf5(const std::string& path, const ReadLimits& limits) {
  const std::lock_guard<std::mutex> hold(hdf5_lock());
  return read_locked(path, limits);
}

}  // namespace layerjkr::detail

namespace layerjkr {

void enable_hdf5_reading() { detail::set_hdf5_opener(&detail::open_afmformats_hdf5); }

}  // namespace layerjkr
