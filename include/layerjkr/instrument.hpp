// layerjkr: force curves as they come off the instrument - JPK archives (.jpk-force,
// .jpk-force-map, .jpk-qi-data, .jpk-qi-series), Asylum Research / Igor binary waves (.ibw, version 5),
// Bruker NanoScope files (.spm, .000) and AFM Workshop maps (.zip of its CSV exports) - read in C++ with their calibration, without any
// Python stack; whole (read_instrument_file) or one curve at a time (InstrumentReader).
//
// JPK (zip archives of Java .properties headers and big-endian channel data): force is the
// vDeflection channel in its `force` slot, the measured height is strainGaugeHeight,
// capacitiveSensorHeight or measuredHeight (whichever the segment has) in its `nominal`
// slot, the piezo height the `height` channel in its `calibrated` slot. Raw values are
// scaled by their encoder, then by each conversion of the chain from the channel's base
// slot to the target slot (v = multiplier * v + offset); the `distance` multiplier is the
// sensitivity and the `force` multiplier the spring constant. Calibration stored once in
// `shared-data/header.properties` (lcd-info and segment-info indirection) is resolved.
// Igor: one 2-D float wave with columns Raw, Defl, ZSnsr (metres); force = Defl * k with k
// = SpringConstant from the note, measured height = -ZSnsr, piezo height = -Raw, segments
// split at the note's Indexes (Direction 1: extend, -1: retract).
// Bruker NanoScope force files (single ramps and force volumes, docs/instrument-files.md):
// force = raw x V/LSB of the deflection channel's `@4:Z scale` x `Sens. DeflSens` x
// `Spring Constant` (v9.2+ force volume 4-byte samples are counts x 256: divided by 256);
// extend = the first block, stored newest first and reversed to time order, retract = the
// second; `Samps/line: N1 N2` = (extend, retract); height from the ramp (`@4:Ramp Size` x
// `Sens. Zsens`, step ramp/N, 0 at the turnaround) or from a stored Z sensor channel;
// force volume curve c at grid_x = c % points per line, grid_y = c / points per line.
// Every value of ../shared/data/instrument/reference.json is reproduced by the tests
// (tests/io/test_instrument.cpp): JPK bit for bit, Igor to 1e-7 (float32 data); every value
// of bruker/reference.json by tests/io/test_nanoscope.cpp.
#pragma once

#include <cstddef>
#include <cstdint>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "layerjkr/curve_data.hpp"
#include "layerjkr/types.hpp"

namespace layerjkr {

/// One segment of a curve (approach, retract, pause), samples in acquisition order.
struct InstrumentSegment {
  SegmentStyle style = SegmentStyle::extend;  ///< as the file says (an unknown style is an error)
  std::vector<double> force;         ///< [N], positive = repulsive (cantilever deflected up)
  std::vector<double> height;        ///< measured height [m] (the sensor; larger = farther away)
  std::vector<double> piezo_height;  ///< commanded piezo height [m] (empty if absent)
  double duration = 0.0;             ///< [s]
};

/// One force curve with its calibration and map position.
struct InstrumentCurve {
  int index = 0;            ///< the curve's number in the file (JPK: index/N directory)
  int position_index = -1;  ///< grid position index written by the instrument (-1: none)
  double x = std::numeric_limits<double>::quiet_NaN();  ///< map position [m]
  double y = std::numeric_limits<double>::quiet_NaN();  ///< map position [m]
  int grid_x = -1, grid_y = -1;  ///< pixel of the map grid (-1: not a map)
  /// [N/m]; NaN where the file gives none (an Asylum map export without its image): then
  /// `force` holds the deflection [m], and to_curve_data needs a spring constant given.
  double spring_constant = 0.0;
  double sensitivity = 0.0;      ///< [m/V] (InvOLS)
  std::vector<InstrumentSegment> segments;
  /// What the reader decided that the user should know, e.g. which of two different copies of a
  /// header key it used; a fit reports them as notices (FitSummary::notices).
  std::vector<std::string> notes;

  /// Tip position of segment s [m]: measured height + force / k (on approach it falls).
  std::vector<double> tip_position(std::size_t s) const;
};

/// A file's curves and what it says about itself.
struct InstrumentFile {
  std::string path;
  InstrumentFormat format = InstrumentFormat::jpk_force;
  std::string instrument;  ///< e.g. "JPK00758-CellHesion-200", "MFP3D"
  std::string software;    ///< e.g. "4.3.11"
  int grid_shape_x = 0, grid_shape_y = 0;  ///< map grid (0: not a map)
  double grid_size_x = 0.0, grid_size_y = 0.0, grid_center_x = 0.0, grid_center_y = 0.0;  ///< [m]
  std::vector<InstrumentCurve> curves;
};

/// Bounds on what reading an archive may unpack, checked against the sizes the archive
/// declares before anything is allocated: a zip bomb or a lying header fails with a message
/// naming the entry, its size and the limit instead of exhausting memory. In the shared JPK
/// files the entries read are at most 127 KB and unpack to 1.3-2.3x the archive's size
/// (channel data barely compress, headers do 7-8x); the defaults leave room for large maps.
struct ReadLimits {
  /// Largest uncompressed entry [bytes]. Default 256 MiB: 64 M samples of a 4-byte channel,
  /// over 10 minutes of one segment at 100 kHz.
  std::uint64_t max_member_bytes = std::uint64_t{256} << 20;
  /// Largest total of the entries read from one archive [bytes]. Default 4 GiB: a 500 MB QI
  /// map unpacks to about 0.7 GB (ratio of the shared QI file), with 5x to spare.
  std::uint64_t max_archive_bytes = std::uint64_t{4} << 30;

  /// The defaults, replaced by the environment variables LAYERJKR_MAX_MEMBER_MB and
  /// LAYERJKR_MAX_ARCHIVE_MB where set (whole MiB, 1 to 1048576); any other value is an
  /// InputError naming the variable.
  static ReadLimits from_environment();
};

/// The format a file name says: .jpk-force, .jpk-force-map, .jpk-qi-data, .jpk-qi-series, .ibw, and for
/// Bruker NanoScope .spm or a numbered extension .000 - .999, for an AFM Workshop map .zip (an
/// archive of its CSV exports, one per point; a .zip of anything else is refused when read), for
/// afmformats' HDF5 export .h5 or .hdf5 (read only in programs that link libhdf5 - the CLI; others
/// refuse it saying so: src/io/afmformats_hdf5.hpp says why); none for any other name.
std::optional<InstrumentFormat> instrument_format(const std::string& path);
/// True if the file name ends in an extension read_instrument_file knows.
bool is_instrument_file(const std::string& path);
/// From now on, read afmformats' HDF5 exports (.h5, .hdf5) too (idempotent, thread-safe). Defined
/// in the build tree's target layerjkr_hdf5 (not installed with the package), which links libhdf5
/// (Debian's brings 34 shared libraries, which the library and the Python wheel do not carry); the
/// CLI links it and calls this at start. Without it an .h5 file is refused with an InputError
/// saying where it is read.
void enable_hdf5_reading();
/// True if `path` names an Asylum force map exported one Igor wave per channel per point
/// (format ibw-map): a directory holding LineLLLLPointPPPP<Channel>.ibw files (Defl, ZSnsr,
/// optionally Raw), directly or in LineLLLL folders, or a glob pattern every match of which is
/// such a file. InstrumentReader reads it as one map: a curve per point, its pixel from the name,
/// calibration and scan from the map image beside the files (a wave whose note says
/// ForceMapImage:1), else each point's note and no spring constant (then one must be given).
bool is_asylum_map_export(const std::string& path);
/// The known formats in words, for messages ("known: " + this).
std::string known_instrument_formats();

/// A half-open range [begin, end) of curve positions in file order (0-based; for JPK maps the
/// order of the index/N numbers, for NanoScope force volumes the order of the data block).
/// The default is every curve; `end` past the last curve stops at the last one.
struct CurveRange {
  std::size_t begin = 0;
  std::size_t end = std::numeric_limits<std::size_t>::max();
  /// Parses "A:B", "A:" or ":B" (whole numbers, A <= B); anything else is an InputError
  /// naming `what` (e.g. "--curves") and the text.
  static CurveRange parse(const std::string& text, const std::string& what);
  /// Where the range ends in a file of `count` curves (an end past the last stops there).
  std::size_t end_in(std::size_t count) const { return end < count ? end : count; }
  /// Throws InputError naming `path` if the range selects none of its `count` curves.
  void require_any(std::size_t count, const std::string& path) const;
};

/// An instrument file opened for reading its curves one at a time. Opening reads the header
/// and the index of the curves (for a JPK archive its central directory; for NanoScope the
/// text header), never the samples; curve(i) then reads curve i alone - random access, so
/// any range of a map is read without the rest, and a whole map's samples are never held.
/// Thread safety: curve() may be called from several threads at once (the archive's entries
/// are fetched under a lock and inflated and decoded outside it). Move-only; owns the file
/// handle, which stays open until destruction.
/// What a read unpacks beyond a curve's force and measured height.
struct CurveChannels {
  /// The commanded piezo height (InstrumentCurve::piezo_height). A fit does not use it: its
  /// batches leave it out (a third of a JPK map's channel data), and it is then empty.
  bool piezo_height = true;
};

class InstrumentReader {
 public:
  /// Opens `path` (its format from instrument_format). Throws InputError naming the file:
  /// missing, of no known format, or with a header that cannot be read (see read_instrument_file).
  explicit InstrumentReader(const std::string& path, const ReadLimits& limits = ReadLimits::from_environment());
  ~InstrumentReader();
  InstrumentReader(InstrumentReader&&) noexcept;
  InstrumentReader& operator=(InstrumentReader&&) noexcept;

  /// The file's metadata (path, format, instrument, software, map grid); `curves` is empty.
  const InstrumentFile& header() const;
  /// How many curves the file holds.
  std::size_t size() const;
  /// The curve at position i (< size()); throws InputError naming the file and the curve if it
  /// cannot be read or its spring constant is not finite and > 0, std::out_of_range past the end.
  InstrumentCurve curve(std::size_t i, const CurveChannels& channels = {}) const;
  /// The number curve i carries (InstrumentCurve::index: JPK's index/N, else the position),
  /// known without reading the curve; std::out_of_range past the end.
  int curve_number(std::size_t i) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// Reads every curve (or those of `range`) of a JPK archive, an Igor wave or a NanoScope file.
/// Throws InputError naming the file and
/// what is wrong (not a zip; an entry truncated, corrupt (CRC-32) or over `limits`; a missing
/// or duplicated header key, channel or calibration; a header number that is not a finite
/// number or out of range; data of another size than the header announces; unknown encoder).
InstrumentFile read_instrument_file(const std::string& path, const ReadLimits& limits, const CurveRange& range = {});
/// The same with ReadLimits::from_environment().
InstrumentFile read_instrument_file(const std::string& path);

/// One curve as the fit consumes it: delta = -tip_position, P = force, segment 0 for the
/// extend segments, 2 for pauses before the first retract (dwells), 1 for the rest, the reader's
/// notes, and each sample's time t = (the earlier segments' durations) + i duration / n (none
/// where a segment has no duration).
/// `source` names it in error messages. spring_constant > 0 [N/m] replaces the file's: the deflection is kept,
/// so force scales by k / k_file and the tip position is height + deflection. A curve whose
/// file gives no spring constant (NaN) needs one here (InputError naming `source` otherwise).
/// sensitivity > 0 [m/V] replaces the file's deflection sensitivity (curve.sensitivity, which it
/// needs): the deflection scales by sensitivity / the file's, and the force with it.
CurveData to_curve_data(const InstrumentCurve& curve, const std::string& source, double spring_constant = 0.0,
                        double sensitivity = 0.0);

}  // namespace layerjkr
