// Where tests write files: a fresh directory under the system temporary directory,
// removed with everything in it when the owner goes out of scope. ctest runs each test
// case as its own process, so a per-process directory (scratch()) never collides.
#pragma once

#include <stdlib.h>  // mkdtemp

#include <cstdio>
#include <filesystem>
#include <iostream>
#include <stdexcept>
#include <string>
#include <system_error>

namespace test {

class TempDir {
 public:
  TempDir() {
    std::string pattern = (std::filesystem::temp_directory_path() / "layerjkr_test_XXXXXX").string();
    if (mkdtemp(pattern.data()) == nullptr) throw std::runtime_error("cannot create " + pattern);
    path_ = pattern;
  }
  ~TempDir() {
    std::error_code ignored;  // a destructor must not throw; a leftover is harmless in /tmp
    std::filesystem::remove_all(path_, ignored);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;

  const std::filesystem::path& path() const { return path_; }
  std::string file(const std::string& name) const { return (path_ / name).string(); }

 private:
  std::filesystem::path path_;
};

/// The test process's own scratch directory, removed when the process exits.
inline const TempDir& scratch() {
  static const TempDir dir;
  return dir;
}

/// Reports a test as skipped: ctest matches this line (SKIP_REGULAR_EXPRESSION in
/// tests/CMakeLists.txt) and counts the test as skipped, with the reason in its output.
inline void report_skip(const std::string& reason) {
  std::cout << "LAYERJKR_SKIPPED: " << reason << std::endl;
}

}  // namespace test
