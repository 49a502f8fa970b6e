// layerjkr CLI: writing results safely and expanding input lists.
#pragma once

#include <string>
#include <vector>

namespace layerjkr::cli {

/// Every file the CLI writes goes through this: a private temporary file, created
/// exclusively (O_CREAT | O_EXCL, mode 0600 until committed, so a planted symlink is never
/// followed) under an unpredictable name `.NAME.XXXXXX` in the target's directory, written with
/// every error checked, fsync'd and renamed over the target by commit(). Without commit() -
/// any failure, an exception - the temporary file is removed. Constructing one checks up front
/// that the target's directory takes files, before any work. Errors throw InputError naming the
/// target. Not thread-safe: one writer at a time.
class OutputFile {
 public:
  explicit OutputFile(std::string target);
  ~OutputFile();
  OutputFile(const OutputFile&) = delete;
  OutputFile& operator=(const OutputFile&) = delete;

  /// Appends `text` (one write(2) call per chunk, retried on short writes and EINTR).
  void write(const std::string& text);
  /// fsync, close and rename onto the target (the target itself is replaced, never followed).
  void commit();
  /// The temporary file's path, for a program that writes it by name (gnuplot); the file
  /// exists and is empty.
  const std::string& temporary() const { return tmp_; }
  const std::string& target() const { return target_; }

 private:
  [[noreturn]] void fail(const std::string& what, int err);
  std::string target_, tmp_;
  int fd_ = -1;
};

/// Writes `text` to `path` through an OutputFile.
void write_atomically(const std::string& path, const std::string& text);

/// Throws InputError (exit 2) if `output` (flag `flag`) is the same file, by device and inode,
/// as one of `inputs`: writing it would destroy the input. A missing output is never one.
void check_not_input(const std::string& output, const std::string& flag, const std::vector<std::string>& inputs);

/// Directories, glob patterns and files, in the order given. A directory gives every entry
/// whose name ends in .csv or an instrument extension, whatever it is (file, link - dangling or
/// looping -, FIFO, directory), sorted by name: the batch reports the ones it cannot read as
/// failed rows. Throws InputError for an input that names nothing or a directory that cannot
/// be listed or holds no such entry.
std::vector<std::string> expand_inputs(const std::vector<std::string>& inputs);

}  // namespace layerjkr::cli
