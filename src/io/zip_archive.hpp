// Internal: a read-only zip archive (libzip), entries by name.
#pragma once

#include <memory>
#include <string>
#include <vector>

namespace layerjkr::detail {

class ZipArchive {
 public:
  /// Opens `path`; throws InputError naming it if it is missing or not a zip archive.
  explicit ZipArchive(const std::string& path);
  ~ZipArchive();
  ZipArchive(const ZipArchive&) = delete;
  ZipArchive& operator=(const ZipArchive&) = delete;

  /// Every entry name, in archive order (directories end in '/').
  const std::vector<std::string>& names() const { return names_; }
  bool contains(const std::string& name) const;
  /// The whole uncompressed entry; throws InputError if it is missing, truncated or corrupt.
  std::string read(const std::string& name) const;

 private:
  struct Handle;
  std::string path_;
  std::unique_ptr<Handle> handle_;
  std::vector<std::string> names_;
};

}  // namespace layerjkr::detail
