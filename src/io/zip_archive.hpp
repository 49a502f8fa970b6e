// Internal: a read-only zip archive (libzip), entries by name, every read verified and bounded.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "layerjkr/instrument.hpp"

namespace layerjkr::detail {

/// The environment variables of ReadLimits::from_environment (named in limit errors).
inline constexpr const char* kMaxMemberEnv = "LAYERJKR_MAX_MEMBER_MB";
inline constexpr const char* kMaxArchiveEnv = "LAYERJKR_MAX_ARCHIVE_MB";

class ZipArchive {
 public:
  /// Opens `path`; throws InputError naming it if it is missing, not a zip archive, or
  /// names one entry twice. `limits` bound what read() may unpack.
  explicit ZipArchive(const std::string& path, const ReadLimits& limits = ReadLimits{});
  /// The same from the archive's bytes in memory (the fuzzer's way in); `path` names it in errors.
  ZipArchive(std::string bytes, const std::string& path, const ReadLimits& limits);
  ~ZipArchive();
  ZipArchive(const ZipArchive&) = delete;
  ZipArchive& operator=(const ZipArchive&) = delete;

  /// Every entry name, in archive order (directories end in '/').
  const std::vector<std::string>& names() const { return names_; }
  bool contains(const std::string& name) const;
  /// The uncompressed size the central directory declares for `name` (none if it is absent).
  std::optional<std::uint64_t> declared_size(const std::string& name) const;
  /// The whole uncompressed entry, checked against the central directory: exactly its
  /// declared size and CRC-32. Throws InputError naming the file and the entry if it is
  /// missing, truncated, longer than declared or corrupt, or if its declared size passes
  /// the member limit or, with what was read before, the archive limit (checked before
  /// anything is allocated).
  std::string read(const std::string& name) const;

 private:
  struct Handle;
  void list_names();
  std::string path_;
  ReadLimits limits_;
  std::unique_ptr<Handle> handle_;
  std::vector<std::string> names_;
  mutable std::uint64_t bytes_read_ = 0;
};

}  // namespace layerjkr::detail
