// Internal: the text header of a Bruker NanoScope file (docs/instrument-files.md, NanoScope).
// Latin-1 lines `\Key: value` ending in CR LF, grouped in sections that start with `\*Name`;
// the header ends at `\*File list end` (then Ctrl-Z and padding up to the binary data).
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace layerjkr::detail {

/// The end of a NanoScope header; the text before it is the header.
constexpr std::string_view kNanoscopeHeaderEnd = "\\*File list end";
/// The most header text read before giving up on finding kNanoscopeHeaderEnd: 8 MiB. Headers
/// seen are 20-80 KiB (the first section's `Data length`: 20480, 40960, 80960), so this is
/// 100 times the largest, yet bounds what a file without the marker (an image of zeros, a
/// wrong file) costs: it is refused after 8 MiB instead of being read whole.
constexpr std::size_t kMaxNanoscopeHeader = std::size_t{8} << 20;

/// One `\@[group:]Name: T [soft scale] (hard scale unit/LSB) hard value unit` parameter
/// (T: V value, C scale, S select). A part that is absent or not a number is empty rather
/// than an error: real files carry broken ones (`(\Data length V/LSB)`), and only the
/// parameters a reader needs must be whole.
struct NanoscopeParameter {
  char type = 0;                      ///< 'V', 'C' or 'S'
  std::string soft_scale;             ///< e.g. "Sens. DeflSens" (brackets removed), or ""
  std::optional<double> hard_scale;   ///< the number in parentheses, e.g. 0.000375 (V/LSB)
  std::optional<double> hard_value;   ///< the number after the parentheses, e.g. 2.5 (V)
  std::string quoted;                 ///< for S: the quoted text, e.g. "Deflection Error"
};

/// A section `\*Name` and its lines in file order. Keys are kept as written after the
/// backslash and trimmed (`@4:Z scale`, `Scan Rate`): case matters, since a section may hold
/// both `Scan Rate` and `Scan rate` meaning different things.
struct NanoscopeSection {
  std::string name;
  std::vector<std::pair<std::string, std::string>> entries;  ///< (key, trimmed value)
  /// The first value of `key`, or nullptr.
  const std::string* find(std::string_view key) const;
  /// The first value of a key equal to `key` but for the case of its letters, or nullptr: for
  /// the keys NanoScope versions spell two ways (8.15 `Ramp size`, 9.20 `Ramp Size`).
  const std::string* find_any_case(std::string_view key) const;
};

/// A parsed header with the accessors the force reader needs; every failure is an InputError
/// naming the file, the section, the key, its value and what was expected.
class NanoscopeHeader {
 public:
  /// Parses `text`, which must end with kNanoscopeHeaderEnd (the caller found it).
  NanoscopeHeader(std::string_view text, std::string path);

  const std::vector<NanoscopeSection>& sections() const { return sections_; }
  /// The first section called `name`, or nullptr.
  const NanoscopeSection* section(std::string_view name) const;
  /// The first section called `name`; an error if there is none.
  const NanoscopeSection& need_section(std::string_view name) const;
  const std::string& path() const { return path_; }

  [[noreturn]] void fail(const NanoscopeSection& section, const std::string& what) const;
  /// The value of `key`; an error naming the section if it is missing.
  const std::string& text(const NanoscopeSection& section, std::string_view key) const;
  /// The whole value one finite number, optionally followed by a unit ("2000 nm"); the unit
  /// goes to `unit` when given.
  double number(const NanoscopeSection& section, std::string_view key, std::string* unit = nullptr) const;
  /// The whole value one whole number in [lo, hi].
  std::int64_t whole(const NanoscopeSection& section, std::string_view key, std::int64_t lo, std::int64_t hi) const;
  /// The value's whole numbers, each in [lo, hi] ("1024 1024").
  std::vector<std::int64_t> wholes(const NanoscopeSection& section, std::string_view key, std::int64_t lo,
                                   std::int64_t hi) const;
  /// The `\@` parameter `key` (e.g. "@4:Z scale"), parsed leniently; an error if missing.
  NanoscopeParameter parameter(const NanoscopeSection& section, std::string_view key) const;
  /// The hard value of `\@<soft_scale>` (e.g. "Sens. DeflSens" -> 27.39), searched in every
  /// section; an error naming `user` (the parameter that refers to it) unless finite and > 0.
  double sensitivity(const std::string& soft_scale, const std::string& user) const;

 private:
  std::string path_;
  std::vector<NanoscopeSection> sections_;
};

/// Parses one parameter value ("V [Sens. Zsens] (0.0067 V/LSB) 227.2 V"); never throws.
NanoscopeParameter parse_nanoscope_parameter(std::string_view value);

}  // namespace layerjkr::detail
