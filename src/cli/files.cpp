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

void check_not_input(const std::string& output, const std::string& flag, const std::vector<std::string>& inputs) {
  struct stat out {};
  if (output.empty() || ::stat(output.c_str(), &out) != 0) return;
  for (const std::string& in : inputs) {
    struct stat s {};
    if (::stat(in.c_str(), &s) == 0 && s.st_dev == out.st_dev && s.st_ino == out.st_ino)
      throw InputError(flag + " " + output + " is the input " + in + "; writing it would destroy the input");
  }
}

namespace {

// "3 entries: the folder bruker/ (...), notes.txt, ..." - at most 4 named.
std::string skipped_line(const std::string& dir, const std::vector<std::string>& folders, const std::vector<std::string>& others) {
  std::string line = dir + ": not read: ";
  std::size_t named = 0;
  const auto list = [&](const std::vector<std::string>& v, const char* suffix) {
    std::string s;
    for (const std::string& e : v)
      if (named++ < 4) s += (s.empty() ? "" : ", ") + e + suffix;
    return s;
  };
  if (!folders.empty())
    line += std::to_string(folders.size()) + " folder(s) (" + list(folders, "/") +
            (folders.size() > 4 ? ", ..." : "") + "; a folder's own files are read: name a sub-folder to fit its curves)";
  if (!others.empty())
    line += std::string(folders.empty() ? "" : "; ") + std::to_string(others.size()) + " other file(s) (" +
            list(others, "") + (others.size() > 4 ? ", ..." : "") + "; not .csv or an instrument file)";
  return line;
}

}  // namespace

std::vector<std::string> expand_inputs(const std::vector<std::string>& inputs, std::vector<std::string>* skipped) {
  std::vector<std::string> files;
  for (const auto& in : inputs) {
    std::error_code ec;
    // A directory or a pattern of Asylum per-channel waves is one map: one input, not expanded.
    const bool one_map = is_asylum_map_export(in);
    if (!one_map && fs::is_directory(in, ec)) {
      // By name only: the entry's type is the batch's to check and report (a loop, a FIFO).
      std::vector<std::string> found, folders, others;
      fs::directory_iterator it(in, ec), end;
      for (; !ec && it != end; it.increment(ec)) {
        const fs::path& e = it->path();
        std::error_code type_ec;
        if (e.extension() == ".csv" || e.extension() == ".tab" || is_instrument_file(e.string()))
          found.push_back(e.string());
        else if (it->is_directory(type_ec))
          folders.push_back(e.filename().string());
        else
          others.push_back(e.filename().string());
      }
      if (ec) throw InputError(in + ": cannot list the directory (" + ec.message() + ")");
      std::sort(found.begin(), found.end());
      std::sort(folders.begin(), folders.end());
      std::sort(others.begin(), others.end());
      if (found.empty())
        throw InputError(in + ": the directory holds no .csv or instrument files" +
                         (folders.empty() ? std::string() : " (" + skipped_line(in, folders, {}).substr(in.size() + 2) + ")"));
      if (skipped && (!folders.empty() || !others.empty())) skipped->push_back(skipped_line(in, folders, others));
      files.insert(files.end(), found.begin(), found.end());
    } else if (!one_map && in.find_first_of("*?[") != std::string::npos) {
      glob_t g{};
      const int rc = glob(in.c_str(), 0, nullptr, &g);
      std::vector<std::string> found(g.gl_pathv, g.gl_pathv + (rc == 0 ? g.gl_pathc : 0));
      globfree(&g);
      if (found.empty()) throw InputError(in + ": the pattern matches no files");
      files.insert(files.end(), found.begin(), found.end());
    } else if (one_map || fs::exists(fs::symlink_status(in, ec))) {
      files.push_back(in);  // also a FIFO or a broken link named on purpose: it still gets its row
    } else {
      throw InputError(in + ": no such file or directory");
    }
  }
  return files;
}

}  // namespace layerjkr::cli
