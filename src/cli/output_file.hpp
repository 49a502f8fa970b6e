// layerjkr CLI: every file the CLI writes, written like a Unix tool writes it.
#pragma once

#include <sys/types.h>

#include <string>
#include <vector>

namespace layerjkr::cli {

/// One output of a command. Where it goes is decided when it is opened, before any work, from
/// what the name is then:
///  - `-`, /dev/stdout, /dev/stderr, /dev/fd/N or /proc/self/fd/N: that descriptor of this
///    process, written through (a shell redirection, a pipe, a terminal);
///  - a FIFO, a character or a block device, named or reached through symbolic links: opened
///    and written through, never renamed over (`--out /dev/null` stays /dev/null);
///  - a regular file or a name that does not exist yet, symbolic links followed to the name
///    they end at (as a shell's `>` does): written to a private temporary file created
///    exclusively (O_CREAT | O_EXCL, mode 0600 until committed, so a link planted at a
///    predictable name is never followed) under an unpredictable name `.NAME.XXXXXX` in that
///    directory, fsync'd and renamed over it by commit(). A file replaced keeps its mode and
///    owner (refused before the work when the owner cannot be kept); a new file gets 0666 less
///    the umask. Without commit() - any failure, an exception - the temporary file is removed;
///  - a directory or a socket: refused (InputError naming it).
/// Errors throw InputError naming the target. Not thread-safe: one writer at a time.
class OutputFile {
 public:
  explicit OutputFile(std::string target);
  ~OutputFile();
  OutputFile(const OutputFile&) = delete;
  OutputFile& operator=(const OutputFile&) = delete;

  /// Appends `text` (write(2) calls retried on short writes and EINTR).
  void write(const std::string& text);
  /// A file: fsync, set its mode, rename onto the target. A stream: what a program wrote to
  /// temporary() is copied to it.
  void commit();
  /// A file a program writes by name (gnuplot): the temporary file itself, or for a stream a
  /// private scratch file in the system's temporary directory that commit() copies. It exists.
  const std::string& temporary() const { return tmp_; }
  /// The name as the user gave it.
  const std::string& target() const { return target_; }
  /// Written through to a stream (a descriptor, a FIFO or a device): nothing is replaced, and
  /// nothing belongs beside it (fit-map writes no record beside a table that is a stream).
  bool is_stream() const { return stream_; }
  /// Written to this process's standard output (`-`, /dev/stdout, /dev/fd/1).
  bool is_standard_output() const { return stdout_; }

 private:
  [[noreturn]] void fail(const std::string& what, int err);
  void open_stream(int fd);
  void open_file(const std::string& name, bool exists, mode_t mode, uid_t uid, gid_t gid);

  std::string target_, final_, tmp_;
  int fd_ = -1;
  bool stream_ = false, stdout_ = false, committed_ = false;
  mode_t mode_ = 0;
};

/// A private temporary file in the system's temporary directory ($TMPDIR, else /tmp) for a
/// program that reads a file by name (gnuplot's data), removed when it goes out of scope. Its
/// name says what it is for (`what`, e.g. "plot"). Errors throw InputError.
class ScratchFile {
 public:
  explicit ScratchFile(const std::string& what);
  ~ScratchFile();
  ScratchFile(const ScratchFile&) = delete;
  ScratchFile& operator=(const ScratchFile&) = delete;

  void write(const std::string& text);
  const std::string& path() const { return path_; }

 private:
  std::string path_;
  int fd_ = -1;
};

/// Writes `text` to `path` through an OutputFile.
void write_atomically(const std::string& path, const std::string& text);

/// A directory of derived files (`flag` DIR: --plot-dir's pictures, --tiff's images), checked
/// before any work: created if missing, and each of `names` in it either absent, one layerjkr
/// wrote (`ours(path)`), or replaced only with `force`; otherwise InputError naming the file
/// and `what` layerjkr writes there. The last name is opened as a probe of writability.
void prepare_derived_dir(const std::string& dir, const std::string& flag, const std::vector<std::string>& names,
                         bool force, bool (*ours)(const std::string& path), const std::string& what);

}  // namespace layerjkr::cli
