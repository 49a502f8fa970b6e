// Output files and input lists of the CLI (files.hpp).
#include "files.hpp"

#include <fcntl.h>
#include <glob.h>
#include <stdlib.h>  // mkstemp
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>

#include "layerjkr/error.hpp"
#include "layerjkr/instrument.hpp"

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

}  // namespace

OutputFile::OutputFile(std::string target) : target_(std::move(target)) {
  if (target_.empty()) throw InputError("an output file name is empty");
  const fs::path p(target_);
  const fs::path dir = p.parent_path().empty() ? fs::path(".") : p.parent_path();
  // The target's own name keeps a leftover recognisable; the random suffix makes it unguessable.
  tmp_ = (dir / ("." + p.filename().string().substr(0, 200) + ".XXXXXX")).string();
  new_file_mode();
  fd_ = ::mkstemp(tmp_.data());
  if (fd_ < 0) {
    const int err = errno;
    tmp_.clear();
    throw InputError(target_ + ": cannot create a file in " + dir.string() + " (" + std::strerror(err) + ")");
  }
}

OutputFile::~OutputFile() {
  if (fd_ >= 0) ::close(fd_);
  if (!tmp_.empty()) ::unlink(tmp_.c_str());
}

void OutputFile::fail(const std::string& what, int err) {
  if (fd_ >= 0) ::close(fd_);
  fd_ = -1;
  ::unlink(tmp_.c_str());
  tmp_.clear();
  throw InputError(target_ + ": cannot " + what + " (" + std::strerror(err) + ")");
}

void OutputFile::write(const std::string& text) {
  if (fd_ < 0) throw InputError(target_ + ": written after it was closed");
  const char* p = text.data();
  std::size_t left = text.size();
  while (left > 0) {
    const ssize_t n = ::write(fd_, p, left);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) fail("write the file", n < 0 ? errno : ENOSPC);
    p += n;
    left -= static_cast<std::size_t>(n);
  }
}

void OutputFile::commit() {
  if (fd_ < 0) throw InputError(target_ + ": committed twice");
  // gnuplot may have rewritten the file by name: sync what the name holds now.
  if (::fchmod(fd_, new_file_mode()) != 0) fail("set the file's mode", errno);
  if (::fsync(fd_) != 0) fail("write the file", errno);
  const int fd = fd_;
  fd_ = -1;
  if (::close(fd) != 0) fail("write the file", errno);
  if (::rename(tmp_.c_str(), target_.c_str()) != 0) fail("replace the file", errno);
  tmp_.clear();
  // The rename itself is durable once the directory is synced; a failure here loses nothing.
  const fs::path dir = fs::path(target_).parent_path();
  const int dfd = ::open(dir.empty() ? "." : dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (dfd >= 0) {
    ::fsync(dfd);
    ::close(dfd);
  }
}

void write_atomically(const std::string& path, const std::string& text) {
  OutputFile f(path);
  f.write(text);
  f.commit();
}

void check_not_input(const std::string& output, const std::string& flag, const std::vector<std::string>& inputs) {
  struct stat out {};
  if (output.empty() || ::stat(output.c_str(), &out) != 0) return;
  for (const std::string& in : inputs) {
    struct stat s {};
    if (::stat(in.c_str(), &s) == 0 && s.st_dev == out.st_dev && s.st_ino == out.st_ino)
      throw InputError(flag + " " + output + " is the input " + in + "; writing it would destroy the input");
  }
}

std::vector<std::string> expand_inputs(const std::vector<std::string>& inputs) {
  std::vector<std::string> files;
  for (const auto& in : inputs) {
    std::error_code ec;
    if (fs::is_directory(in, ec)) {
      // By name only: the entry's type is the batch's to check and report (a loop, a FIFO).
      std::vector<std::string> found;
      fs::directory_iterator it(in, ec), end;
      for (; !ec && it != end; it.increment(ec)) {
        const fs::path& e = it->path();
        if (e.extension() == ".csv" || is_instrument_file(e.string())) found.push_back(e.string());
      }
      if (ec) throw InputError(in + ": cannot list the directory (" + ec.message() + ")");
      std::sort(found.begin(), found.end());
      if (found.empty()) throw InputError(in + ": the directory holds no .csv or instrument files");
      files.insert(files.end(), found.begin(), found.end());
    } else if (in.find_first_of("*?[") != std::string::npos) {
      glob_t g{};
      const int rc = glob(in.c_str(), 0, nullptr, &g);
      std::vector<std::string> found(g.gl_pathv, g.gl_pathv + (rc == 0 ? g.gl_pathc : 0));
      globfree(&g);
      if (found.empty()) throw InputError(in + ": the pattern matches no files");
      files.insert(files.end(), found.begin(), found.end());
    } else if (fs::exists(fs::symlink_status(in, ec))) {
      files.push_back(in);  // a FIFO or a broken link named on purpose still gets its row
    } else {
      throw InputError(in + ": no such file or directory");
    }
  }
  return files;
}

}  // namespace layerjkr::cli
