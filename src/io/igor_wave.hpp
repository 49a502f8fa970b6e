// Internal: an Igor binary wave, version 5 (either byte order) - the container of Asylum
// Research's force curves, their per-channel map exports and map images. Layout: BinHeader5
// (64 bytes), WaveHeader5 (320), the data (column-major), then formula, note, data units,
// dimension units and dimension labels (32 bytes each, a dimension's own label first); Asylum
// appends a preview trailer, which is ignored.
#pragma once

#include <array>
#include <cstddef>
#include <map>
#include <set>
#include <string>
#include <vector>

namespace layerjkr::detail {

/// The wave note, Latin-1 `Key:Value` lines separated by CR (the first ':' splits; values
/// trimmed). Asylum writes keys more than once: SaveForce and SaveImage in every force file,
/// and in the curves its ARDF export writes (AR 13.16) the map's header block first and each
/// curve's own block after its Indexes, with SpringConstant, MostPosZVoltage, ... repeated. A
/// repeat with the same value is one value. Where the copies differ (XLVDT, YLVDT,
/// DisplaySpringConstant there) the last - the curve's own block - is used, as afmformats,
/// SciFiReaders and magic-afm read it, and notes() says so.
class IgorNote {
 public:
  /// `fail` prefixes errors (the file's path).
  IgorNote(const std::string& text, std::string path);
  /// The value of `key` (the last copy), or nullptr.
  const std::string* find(const std::string& key) const;
  std::string text(const std::string& key) const;
  /// The whole value one finite number > 0 ("1,1841" and "1e-3e5" are errors, not 1 or 0.001).
  double positive(const std::string& key) const;
  /// A comma-separated list of finite numbers or NaN in any case (Direction's marker for a pause:
  /// AR writes NaN, its ARDF export Nan), an empty last item allowed ("NaN,1,-1,"); empty if
  /// the key is absent; anything else is an error naming the key.
  std::vector<double> list(const std::string& key) const;
  /// The notes find() made, in the order it made them.
  const std::vector<std::string>& notes() const { return notes_; }

 private:
  [[noreturn]] void fail(const std::string& what) const;
  std::string path_;
  std::map<std::string, std::vector<std::string>> values_;
  mutable std::set<std::string> noted_;
  mutable std::vector<std::string> notes_;
};

/// A wave's values and what Igor says about them.
struct IgorWave {
  std::array<std::size_t, 4> dims{};  ///< points along each dimension (0 where unused)
  double row_step = 0.0;              ///< the row dimension's scale (sfA[0]: seconds for a force curve)
  std::string name;                   ///< the wave's own name (e.g. "Line0000Point0000Defl", "ForceMap01")
  /// Labels of each dimension's indices (the dimension's own label dropped); empty if none.
  std::array<std::vector<std::string>, 4> labels;
  std::vector<double> data;  ///< float32 or float64 values widened to double, column-major
  IgorNote note;

  std::size_t rows() const { return dims[0]; }
  /// The number of columns: dims[1], at least 1.
  std::size_t columns() const { return dims[1] > 0 ? dims[1] : 1; }
  /// True for a wave of more than two dimensions, or two with no label of a force channel on
  /// its columns and a map image's note (ForceMapImage:1): a picture, not a force curve.
  bool is_image() const;
};

/// Parses a whole wave from its bytes; `path` names it in every InputError (not version 5,
/// truncated, sizes that do not fit the file, data other than float32 / float64).
IgorWave parse_igor_wave(const std::string& bytes, const std::string& path);

}  // namespace layerjkr::detail
