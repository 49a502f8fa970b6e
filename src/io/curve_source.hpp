// Internal: one format's random access to the curves of a file, behind InstrumentReader
// (instrument.hpp). Opening reads the header and the index of the curves; each curve is then
// read on its own, so a range of a map is read without the rest and a map never sits whole
// in memory.
#pragma once

#include <cstddef>
#include <memory>
#include <string>
#include <vector>

#include "layerjkr/instrument.hpp"

namespace layerjkr::detail {

class CurveSource {
 public:
  virtual ~CurveSource() = default;
  /// The file's metadata (path, format, instrument, software, grid); `curves` is empty.
  virtual const InstrumentFile& header() const = 0;
  /// How many curves the file holds.
  virtual std::size_t size() const = 0;
  /// The curve at position i in [0, size()), in file order, read on its own. Safe to call
  /// from several threads at once. Throws InputError naming the file, the curve and the field.
  /// `channels` may leave optional channels out (a source that has them at no cost may fill them).
  virtual InstrumentCurve curve(std::size_t i, const CurveChannels& channels) const = 0;
  /// Every channel.
  InstrumentCurve curve(std::size_t i) const { return curve(i, CurveChannels{}); }
  /// The number curve i will carry (InstrumentCurve::index), known without reading it.
  virtual int number(std::size_t i) const { return static_cast<int>(i); }
};

std::unique_ptr<CurveSource> open_jpk(const std::string& path, InstrumentFormat format, const ReadLimits& limits);
/// The same from the archive's bytes (the fuzzer's way in); `path` names it in errors.
std::unique_ptr<CurveSource> open_jpk_bytes(std::string bytes, const std::string& path, InstrumentFormat format,
                                            const ReadLimits& limits);
std::unique_ptr<CurveSource> open_ibw(const std::string& path);
std::unique_ptr<CurveSource> open_ibw_bytes(std::string bytes, const std::string& path);
std::unique_ptr<CurveSource> open_nanoscope(const std::string& path, const ReadLimits& limits);
/// The per-channel files of an Asylum map export `path` names (asylum_map.cpp): a directory
/// holding LineLLLLPointPPPP<Channel>.ibw files, directly or in LineLLLL folders, or a glob
/// pattern every match of which is such a file; empty otherwise.
std::vector<std::string> asylum_channel_files(const std::string& path);
/// The map those files make, one curve per point, named `path`.
std::unique_ptr<CurveSource> open_asylum_map(const std::string& path, const std::vector<std::string>& files);
/// An AFM Workshop force map: a zip archive of the software's CSV exports, one per point
/// (afm_workshop_map.cpp).
std::unique_ptr<CurveSource> open_afm_workshop_map(const std::string& path, const ReadLimits& limits);
std::unique_ptr<CurveSource> open_nanoscope_bytes(std::string bytes, const std::string& path, const ReadLimits& limits);

}  // namespace layerjkr::detail

namespace layerjkr::detail {

/// The reader of afmformats' .h5 exports, installed by enable_hdf5_reading() (afmformats_hdf5.hpp)
/// in programs that link libhdf5; null elsewhere, and an .h5 file is then refused.
using Hdf5Opener = std::unique_ptr<CurveSource> (*)(const std::string& path, const ReadLimits& limits);
void set_hdf5_opener(Hdf5Opener opener);

}  // namespace layerjkr::detail
