// Internal: a read-only zip archive, entries by name, every read verified and bounded, safe to
// read from several threads at once.
//
// Why not libzip here: libzip 1.7 (Debian 12) builds a full directory entry, a name string and
// a hash node for every entry when it opens an archive. A 256 x 256 JPK QI map has 1.1 million
// entries, and zip_open alone took 1.9 s and 350 MB on it (measured, docs/benchmarks.md), more
// than the whole read may cost; its handles are not thread-safe either. This index keeps 32
// bytes per entry plus the names, reads each entry with one positioned read and inflates it
// with libdeflate outside any lock. libzip still writes archives (tests, tools).
#pragma once

#include <atomic>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "io/positioned_file.hpp"
#include "layerjkr/instrument.hpp"

namespace layerjkr::detail {

/// The environment variables of ReadLimits::from_environment (named in limit errors).
inline constexpr const char* kMaxMemberEnv = "LAYERJKR_MAX_MEMBER_MB";
inline constexpr const char* kMaxArchiveEnv = "LAYERJKR_MAX_ARCHIVE_MB";

class ZipArchive {
 public:
  /// Opens `path` and reads its central directory (zip or zip64, one disk). Throws InputError
  /// naming it if it is missing, not a zip archive, spans disks, names one entry twice or
  /// declares an entry outside the file. `limits` bound what read() may unpack.
  explicit ZipArchive(const std::string& path, const ReadLimits& limits = ReadLimits{});
  /// The same from the archive's bytes in memory (the fuzzer's way in); `path` names it in errors.
  ZipArchive(std::string bytes, const std::string& path, const ReadLimits& limits);
  ~ZipArchive();
  ZipArchive(const ZipArchive&) = delete;
  ZipArchive& operator=(const ZipArchive&) = delete;

  /// How many entries the archive holds (directories, whose names end in '/', included).
  std::size_t size() const { return entries_.size(); }
  /// Entry i's name, in archive order.
  std::string_view name(std::size_t i) const;
  bool contains(std::string_view name) const { return find(name).has_value(); }
  /// The uncompressed size the central directory declares for `name` (none if it is absent).
  std::optional<std::uint64_t> declared_size(std::string_view name) const;
  /// The whole uncompressed entry, checked against the central directory: exactly its declared
  /// size and CRC-32. Throws InputError naming the file and the entry if it is missing,
  /// encrypted, compressed other than stored or deflated, truncated, longer than declared or
  /// corrupt, or if its declared size passes the member limit or, with what was read before,
  /// the archive limit (checked before anything is allocated). Thread-safe.
  std::string read(std::string_view name) const;

 private:
  struct Entry {
    std::uint64_t local_offset = 0, compressed = 0, size = 0;
    std::uint32_t name_offset = 0, crc = 0;
    std::uint16_t name_length = 0, method = 0;
    bool encrypted = false;
  };
  void read_directory();
  void index_names();
  std::optional<std::size_t> find(std::string_view name) const;

  std::string path_;
  ReadLimits limits_;
  std::unique_ptr<PositionedFile> bytes_;
  std::vector<Entry> entries_;
  std::string names_;                // every name, back to back
  std::vector<std::uint32_t> table_;  // open addressing: entry index + 1, 0 = free
  mutable std::atomic<std::uint64_t> bytes_read_{0};  // the archive limit's tally
};

}  // namespace layerjkr::detail
