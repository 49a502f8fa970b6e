// Internal: the pieces of the JPK reader (jpk_reader.cpp) shared with the segment reader
// (jpk_segment.cpp): errors that name the archive and the entry, checked numbers, one segment.
#pragma once

#include <optional>
#include <string>
#include <string_view>

#include "io/java_properties.hpp"
#include "io/zip_archive.hpp"
#include "layerjkr/instrument.hpp"

namespace layerjkr::detail {

inline bool starts_with(std::string_view s, std::string_view prefix) { return s.substr(0, prefix.size()) == prefix; }
inline bool ends_with(std::string_view s, std::string_view suffix) {
  return s.size() >= suffix.size() && s.substr(s.size() - suffix.size()) == suffix;
}

class Reader {
 public:
  Reader(std::string path, const ZipArchive& zip) : path_(std::move(path)), zip_(zip) {}

  [[noreturn]] void fail(const std::string& where, const std::string& what) const;

  Properties properties(const std::string& name) const;

  /// The value of `key` in `header` (Properties or a segment's SegmentHeader); fails if absent.
  template <class Header>
  std::string_view value(const Header& header, std::string_view key, const std::string& where) const {
    const std::optional<std::string_view> v = header.find(key);
    if (!v) fail(where, "no '" + std::string(key) + "'");
    return *v;
  }

  // The whole value must be one finite number: "1,5", "1e-3e5", "NaN" and "Infinity" are
  // errors, not 1, 0.001 or a NaN passed on.
  template <class Header>
  double number(const Header& header, std::string_view key, const std::string& where) const {
    return to_number(key, value(header, key, where), where);
  }
  double to_number(std::string_view key, std::string_view text, const std::string& where) const;
  /// A whole number in [lo, hi], so that the cast to an integer type is defined.
  long long whole(std::string_view key, std::string_view text, double lo, double hi, const std::string& where) const;

  std::string read(std::string_view name) const { return zip_.read(name); }
  std::optional<std::uint64_t> declared_size(std::string_view name) const { return zip_.declared_size(name); }

 private:
  std::string path_;
  const ZipArchive& zip_;
};

/// Segment `dir` ("…/segments/N/"): its header, with the calibration it shares through
/// `shared` (shared-data/header.properties), and its channels. Sets the curve's spring
/// constant and sensitivity. The piezo height only if `channels` asks for it.
InstrumentSegment read_segment(const Reader& in, const Properties& shared, const std::string& dir,
                               InstrumentCurve& curve, const CurveChannels& channels);

}  // namespace layerjkr::detail
