// Internal: a file's bytes read at any offset, from several threads at once - a file descriptor
// read with pread (no shared file offset), or bytes already in memory (the fuzzers' way in).
// The zip index and the NanoScope reader read through it.
#pragma once

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdint>
#include <cstring>
#include <memory>
#include <string>

#include "layerjkr/error.hpp"

namespace layerjkr::detail {

class PositionedFile {
 public:
  /// Opens `path`; throws InputError naming it if it cannot be opened or is not a regular file.
  static std::unique_ptr<PositionedFile> open(const std::string& path) {
    const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
    if (fd < 0) throw InputError(path + ": cannot open it (" + std::strerror(errno) + ")");
    std::unique_ptr<PositionedFile> file(new PositionedFile(fd));  // closes fd if fstat fails
    struct stat st {};
    if (::fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) throw InputError(path + ": cannot read it: not a regular file");
    file->size_ = static_cast<std::uint64_t>(st.st_size);
    return file;
  }
  /// The bytes themselves.
  static std::unique_ptr<PositionedFile> of_bytes(std::string bytes) {
    std::unique_ptr<PositionedFile> file(new PositionedFile(-1));
    file->size_ = bytes.size();
    file->bytes_ = std::move(bytes);
    return file;
  }
  ~PositionedFile() {
    if (fd_ >= 0) ::close(fd_);
  }
  PositionedFile(const PositionedFile&) = delete;
  PositionedFile& operator=(const PositionedFile&) = delete;

  std::uint64_t size() const { return size_; }
  /// Reads [offset, offset + n) into `out` (the caller keeps it within size()); false if the
  /// file cannot be read or ends sooner (it changed since it was opened).
  bool read(std::uint64_t offset, std::size_t n, char* out) const {
    if (fd_ < 0) {
      std::memcpy(out, bytes_.data() + offset, n);
      return true;
    }
    for (std::size_t got = 0; got < n;) {
      const ssize_t r = ::pread(fd_, out + got, n - got, static_cast<off_t>(offset + got));
      if (r < 0 && errno == EINTR) continue;
      if (r <= 0) return false;
      got += static_cast<std::size_t>(r);
    }
    return true;
  }

 private:
  explicit PositionedFile(int fd) : fd_(fd) {}
  int fd_ = -1;
  std::string bytes_;
  std::uint64_t size_ = 0;
};

}  // namespace layerjkr::detail
