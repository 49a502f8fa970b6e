// Outputs of the CLI (output_file.hpp).
#include "output_file.hpp"

#include <fcntl.h>
#include <limits.h>
#include <stdlib.h>  // mkstemp
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <optional>

#include "layerjkr/error.hpp"

namespace layerjkr::cli {

namespace fs = std::filesystem;

namespace {

// The mode a new file would get (mkstemp creates 0600); read once, before any worker runs.
mode_t new_file_mode() {
  static const mode_t mode = [] {
    const mode_t mask = ::umask(022);
    ::umask(mask);
    return static_cast<mode_t>(0666 & ~mask);
  }();
  return mode;
}

// The descriptor a name stands for when it names one of this process's own: `-`, /dev/stdout,
// /dev/stderr, /dev/fd/N, /proc/self/fd/N. Writing through it is what the user's shell set up
// (a pipe, a terminal, a redirection whose file the shell already opened at its own offset).
std::optional<int> own_descriptor(const std::string& name) {
  if (name == "-" || name == "/dev/stdout") return 1;
  if (name == "/dev/stderr") return 2;
  for (const std::string prefix : {"/dev/fd/", "/proc/self/fd/"}) {
    if (name.compare(0, prefix.size(), prefix) != 0) continue;
    const std::string digits = name.substr(prefix.size());
    if (digits.empty() || digits.size() > 9 || digits.find_first_not_of("0123456789") != std::string::npos)
      return std::nullopt;
    return std::stoi(digits);
  }
  return std::nullopt;
}

// The name a chain of symbolic links starting at `name` ends at (the kernel's limit of 40
// links), or the first name on the way that is one of this process's descriptors (a link to
// /dev/stdout); the name itself if it is not a link.
std::string follow_links(const std::string& target) {
  std::string name = target;
  for (int hops = 0;; ++hops) {
    struct stat st {};
    if (own_descriptor(name) || ::lstat(name.c_str(), &st) != 0 || !S_ISLNK(st.st_mode)) return name;
    if (hops == 40) throw InputError(target + ": too many levels of symbolic links");
    std::string link(PATH_MAX, '\0');
    const ssize_t n = ::readlink(name.c_str(), link.data(), link.size());
    if (n < 0) throw InputError(target + ": cannot read the symbolic link " + name + " (" + std::strerror(errno) + ")");
    link.resize(static_cast<std::size_t>(n));
    fs::path next(link);
    if (next.is_relative()) next = fs::path(name).parent_path() / next;
    name = next.string();
  }
}

// Writes all of `text` to `fd`; the errno of a failure, or 0.
int write_all(int fd, const char* p, std::size_t left) {
  while (left > 0) {
    const ssize_t n = ::write(fd, p, left);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return n < 0 ? errno : ENOSPC;
    p += n;
    left -= static_cast<std::size_t>(n);
  }
  return 0;
}

// A file created exclusively from `pattern` (ending in XXXXXX, replaced in place); -1 and errno.
int make_temporary(std::string& pattern) {
  new_file_mode();
  return ::mkstemp(pattern.data());
}

std::string system_temporary_directory() {
  std::error_code ec;
  const fs::path dir = fs::temp_directory_path(ec);
  return ec ? std::string("/tmp") : dir.string();
}

}  // namespace

OutputFile::OutputFile(std::string target) : target_(std::move(target)) {
  if (target_.empty()) throw InputError("an output file name is empty");
  final_ = follow_links(target_);
  if (const std::optional<int> fd = own_descriptor(final_)) {
    const int flags = ::fcntl(*fd, F_GETFL);
    if (flags < 0 || (flags & O_ACCMODE) == O_RDONLY)
      throw InputError(target_ + ": descriptor " + std::to_string(*fd) + " is not open for writing");
    stdout_ = *fd == STDOUT_FILENO;
    open_stream(::fcntl(*fd, F_DUPFD_CLOEXEC, 3));
    return;
  }
  struct stat st {};
  if (::lstat(final_.c_str(), &st) != 0) {
    open_file(final_, false, 0, 0, 0);  // a new file (or a directory that takes none: said there)
    return;
  }
  const std::string via = final_ == target_ ? std::string() : " (the link " + target_ + " points to " + final_ + ")";
  if (S_ISDIR(st.st_mode))
    throw InputError(target_ + " is a directory" + via + "; name a file in it, for example " +
                     (fs::path(target_) / "results.csv").string());
  if (S_ISSOCK(st.st_mode)) throw InputError(target_ + " is a socket" + via + "; name a file, a FIFO or a device");
  if (S_ISFIFO(st.st_mode) || S_ISCHR(st.st_mode) || S_ISBLK(st.st_mode)) {
    // Blocks until a FIFO has a reader, as a shell's redirection does.
    const int fd = ::open(final_.c_str(), O_WRONLY | O_NOCTTY | O_CLOEXEC);
    if (fd < 0) throw InputError(target_ + ": cannot open it for writing (" + std::strerror(errno) + ")" + via);
    open_stream(fd);
    return;
  }
  open_file(final_, true, st.st_mode & 07777, st.st_uid, st.st_gid);
}

void OutputFile::open_stream(int fd) {
  if (fd < 0) throw InputError(target_ + ": cannot open it for writing (" + std::strerror(errno) + ")");
  fd_ = fd;
  stream_ = true;
  // A program that writes by name (gnuplot) writes a scratch file; commit() copies it.
  tmp_ = system_temporary_directory() + "/layerjkr-output.XXXXXX";
  const int scratch = make_temporary(tmp_);
  if (scratch < 0) {
    const int err = errno;
    tmp_.clear();
    fail("create a scratch file in " + system_temporary_directory(), err);
  }
  ::close(scratch);
}

void OutputFile::open_file(const std::string& name, bool exists, mode_t mode, uid_t uid, gid_t gid) {
  const fs::path p(name);
  const fs::path dir = p.parent_path().empty() ? fs::path(".") : p.parent_path();
  // The target's own name keeps a leftover recognisable; the random suffix makes it unguessable.
  tmp_ = (dir / ("." + p.filename().string().substr(0, 200) + ".XXXXXX")).string();
  fd_ = make_temporary(tmp_);
  if (fd_ < 0) {
    const int err = errno;
    tmp_.clear();
    throw InputError(target_ + ": cannot create a file in " + dir.string() + " (" + std::strerror(err) + ")");
  }
  mode_ = exists ? mode : new_file_mode();
  if (!exists) return;
  struct stat mine {};
  if (::fstat(fd_, &mine) != 0) fail("read the new file's owner", errno);
  if ((mine.st_uid != uid || mine.st_gid != gid) && ::fchown(fd_, uid, gid) != 0)
    fail("keep its owner (uid " + std::to_string(uid) + ", gid " + std::to_string(gid) +
             ") on the file that replaces it; write it as that user, or remove it first",
         errno);
}

OutputFile::~OutputFile() {
  if (fd_ >= 0) ::close(fd_);
  if (!tmp_.empty() && (stream_ || !committed_)) ::unlink(tmp_.c_str());
}

void OutputFile::fail(const std::string& what, int err) {
  if (fd_ >= 0) ::close(fd_);
  fd_ = -1;
  if (!tmp_.empty()) ::unlink(tmp_.c_str());
  tmp_.clear();
  throw InputError(target_ + ": cannot " + what + " (" + std::strerror(err) + ")");
}

void OutputFile::write(const std::string& text) {
  if (fd_ < 0) throw InputError(target_ + ": written after it was closed");
  if (stdout_) std::cout.flush();  // what the command printed before comes first
  if (const int err = write_all(fd_, text.data(), text.size())) fail("write the file", err);
}

void OutputFile::commit() {
  if (fd_ < 0) throw InputError(target_ + ": committed twice");
  if (stream_) {
    // What a program wrote by name (gnuplot's picture) goes through now.
    const int in = ::open(tmp_.c_str(), O_RDONLY | O_CLOEXEC);
    if (in < 0) fail("read the scratch file " + tmp_, errno);
    char buffer[1 << 16];
    for (;;) {
      const ssize_t n = ::read(in, buffer, sizeof buffer);
      if (n < 0 && errno == EINTR) continue;
      if (n <= 0) break;
      if (const int err = write_all(fd_, buffer, static_cast<std::size_t>(n))) {
        ::close(in);
        fail("write the file", err);
      }
    }
    ::close(in);
    const int fd = fd_;
    fd_ = -1;
    committed_ = true;
    if (::close(fd) != 0 && errno != EINTR) fail("write the file", errno);
    return;
  }
  // gnuplot may have rewritten the file by name (same inode): sync what the name holds now.
  if (::fchmod(fd_, mode_) != 0) fail("set the file's mode", errno);
  if (::fsync(fd_) != 0) fail("write the file", errno);
  const int fd = fd_;
  fd_ = -1;
  if (::close(fd) != 0) fail("write the file", errno);
  if (::rename(tmp_.c_str(), final_.c_str()) != 0) fail("replace the file", errno);
  committed_ = true;
  // The rename itself is durable once the directory is synced; a failure here loses nothing.
  const fs::path dir = fs::path(final_).parent_path();
  const int dfd = ::open(dir.empty() ? "." : dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (dfd >= 0) {
    ::fsync(dfd);
    ::close(dfd);
  }
}

ScratchFile::ScratchFile(const std::string& what) {
  path_ = system_temporary_directory() + "/layerjkr-" + what + ".XXXXXX";
  fd_ = make_temporary(path_);
  if (fd_ < 0) {
    const int err = errno;
    throw InputError("cannot create a scratch file in " + system_temporary_directory() + " (" + std::strerror(err) + ")");
  }
}

ScratchFile::~ScratchFile() {
  if (fd_ >= 0) ::close(fd_);
  ::unlink(path_.c_str());
}

void ScratchFile::write(const std::string& text) {
  if (const int err = write_all(fd_, text.data(), text.size()))
    throw InputError("cannot write the scratch file " + path_ + " (" + std::strerror(err) + ")");
}

void write_atomically(const std::string& path, const std::string& text) {
  OutputFile f(path);
  f.write(text);
  f.commit();
}

void prepare_derived_dir(const std::string& dir, const std::string& flag, const std::vector<std::string>& names,
                         bool force, bool (*ours)(const std::string& path), const std::string& what) {
  namespace fs = std::filesystem;
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) throw InputError(flag + " " + dir + ": cannot create the directory (" + ec.message() + ")");
  for (const std::string& name : names) {
    const std::string path = (fs::path(dir) / name).string();
    const fs::file_status st = fs::symlink_status(path, ec);
    if (force || !fs::exists(st)) continue;
    if (!fs::is_regular_file(st) || !ours(path))
      throw InputError(flag + " " + dir + ": " + name + " exists and is not " + what +
                       "; it is not replaced (move it, choose another directory, or give --force to replace it)");
  }
  if (!names.empty()) {
    const OutputFile probe((fs::path(dir) / names.back()).string());
  }
}

}  // namespace layerjkr::cli
