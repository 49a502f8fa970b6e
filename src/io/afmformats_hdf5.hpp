// Internal: afmformats' HDF5 export (.h5), read through libhdf5 (afmformats_hdf5.cpp).
//
// Why a separate target (layerjkr_hdf5) that the library does not link: Debian's libhdf5 pulls
// in libcurl, libssl, Kerberos, LDAP and GnuTLS - 34 shared libraries - which the self-contained
// Python wheel would have to carry for one exchange format. The CLI links it and calls
// enable_hdf5_reading() (instrument.hpp) at start; any other program reads .h5 files once it does
// the same, and without it an .h5 file is refused with a message saying where it is read.
#pragma once

#include <memory>
#include <string>

#include "io/curve_source.hpp"

namespace layerjkr::detail {

/// An afmformats HDF5 export (root attribute software = "afmformats"; one group "0", "1", ... per
/// curve with its metadata as attributes and its columns as 1-D datasets), read whole; `path`
/// names it in errors. Throws InputError naming the file and what is missing or malformed.
std::unique_ptr<CurveSource> open_afmformats_hdf5(const std::string& path, const ReadLimits& limits);

}  // namespace layerjkr::detail
