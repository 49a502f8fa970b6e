// Internal: the on-disk store behind a Context (DiskCacheOptions in include/layerjkr/context.hpp).
//
// An entry is a vector of doubles stored under a key: a kind (what it is: "layer-kernel",
// "power-law-piece", ...) and a vector of doubles (what its numbers depend on). One file an
// entry, named <kind>-<16 hex digits>.bin by a 64-bit FNV-1a hash of the format, the library's
// version, the kind and the key; it holds all of these in full, so a hash collision, another
// version or a damaged file reads as a miss:
//
//   "layerjkr-cache\n\0" (16 bytes) | u32 format | u32 len, version | u32 len, kind |
//   u64 n, key doubles | u64 m, payload doubles | HMAC-SHA-256 of everything before it
//
// little-endian as this machine writes (the format field's byte order tells another machine's
// file apart). The HMAC's key is 32 random bytes in the folder's layerjkr-cache.key, a 0600 file
// of this user's made on first use: an entry someone else edited or wrote - even with a
// checksum recomputed - fails it and is rebuilt. The folder is made 0700; one owned by another
// user or writable by others is not used unless DiskCacheOptions::shared says so. Entries are
// opened without following links or blocking, and read only when regular, this user's and of an
// entry's size. Writes: mkstemp in the directory, write, rename over the name (atomic on POSIX
// filesystems), then trim the directory to its bound by removing the entries least recently
// used (a load touches the file's mtime) - only files of an entry's name that carry the cache's
// magic. Nothing here throws on I/O: a failure is counted, a refusal noted, and the caller
// builds the entry.
#pragma once

#include <atomic>
#include <memory>
#include <mutex>
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "layerjkr/context.hpp"
#include "layerjkr/error.hpp"

namespace layerjkr::detail {

class DiskCache {
 public:
  /// A disabled store when !options.enabled or no directory resolves.
  explicit DiskCache(const DiskCacheOptions& options);

  bool enabled() const { return !directory_.empty(); }
  const std::string& directory() const { return directory_; }

  /// The payload stored under (kind, key), if a whole and matching entry exists.
  std::optional<std::vector<double>> load(std::string_view kind, const std::vector<double>& key) const;
  /// Stores the payload under (kind, key), replacing any entry there.
  void store(std::string_view kind, const std::vector<double>& key, const std::vector<double>& payload) const;

  /// The entry's file name (tests damage it).
  std::string path_of(std::string_view kind, const std::vector<double>& key) const;

  std::size_t hits() const { return hits_; }
  std::size_t misses() const { return misses_; }
  std::size_t writes() const { return writes_; }
  std::size_t errors() const { return errors_; }
  /// Count a failure that happened before the store existed (a bad environment).
  void count_error() const { ++errors_; }
  /// Why the store is off, or which entries it refused (distinct, the first few).
  std::vector<std::string> notices() const;
  /// Adds a notice.
  void note(const std::string& message) const;

 private:
  void trim() const;
  bool prepare_directory(bool shared);
  bool load_key();
  /// The entry's HMAC-SHA-256 under key_ (32 bytes), empty on failure.
  std::string mac(const std::string& bytes) const;

  std::string directory_;
  std::string key_;
  std::uint64_t max_bytes_ = 0;
  mutable std::atomic<std::size_t> hits_{0}, misses_{0}, writes_{0}, errors_{0};
  mutable std::mutex notes_mutex_;
  mutable std::vector<std::string> notes_;
};

/// The object stored under (kind, key) in `disk`, or the one `build` makes (then stored). T is
/// read back by a constructor T(const std::vector<double>&) from what T::serialized() wrote; a
/// stored entry T refuses (it throws layerjkr::Error) counts as an error and is built again.
template <class T, class Build>
std::shared_ptr<const T> load_or_build(const DiskCache& disk, std::string_view kind, const std::vector<double>& key,
                                       Build build) {
  if (disk.enabled())
    if (std::optional<std::vector<double>> v = disk.load(kind, key)) {
      try {
        return std::make_shared<const T>(*v);
      } catch (const Error&) {
        disk.count_error();
      }
    }
  std::shared_ptr<const T> built = build();
  if (disk.enabled()) disk.store(kind, key, built->serialized());
  return built;
}

}  // namespace layerjkr::detail
