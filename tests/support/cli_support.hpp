// Helpers for tests that run the layerjkr executable.
#pragma once

#include <sys/stat.h>
#include <sys/wait.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string>
#include <tuple>
#include <vector>

#include "support/temp_dir.hpp"

namespace test::cli {

struct Run {
  int code = -1;
  std::string out, err;
};

inline std::string slurp(const std::string& path) {
  std::ifstream f(path);
  std::stringstream s;
  s << f.rdbuf();
  return s.str();
}

// The CLI executable, and the bundled sample curve with its scene and the flags that fit it.
// LAYERJKR_TEST_CLI, if set, names another build of the CLI to test (e.g. an older commit's,
// to see a new test fail there).
inline std::string cli_path() {
  const char* other = std::getenv("LAYERJKR_TEST_CLI");
  return other && *other ? other : LAYERJKR_CLI_PATH;
}
inline std::string sample_curve() { return std::string(LAYERJKR_SOURCE_DIR) + "/data/curves/hydrogel_film_two_term.csv"; }
inline std::string sample_scene() { return std::string(LAYERJKR_SOURCE_DIR) + "/data/scenes/hydrogel_film_two_term.json"; }
inline std::string sample_fit_flags() { return " --scene " + sample_scene() + " --branch all --free E,w,delta0,P0"; }

// A path for `name` in this test process's scratch directory (removed at exit).
inline std::string unique(const std::string& name) { return test::scratch().file(name); }

// Every entry under `root` (links not followed) with what a write would change: type, inode,
// size, mode, owner and modification time (not for directories: creating and renaming a
// temporary file beside a named output changes its directory's time, and nothing else).
using Listing = std::map<std::string, std::tuple<unsigned, unsigned long, long long, unsigned, unsigned, long long>>;
inline Listing listing(const std::filesystem::path& root) {
  Listing l;
  std::error_code ec;
  for (std::filesystem::recursive_directory_iterator it(root, std::filesystem::directory_options::skip_permission_denied, ec), end;
       !ec && it != end; it.increment(ec)) {
    struct stat st {};
    if (::lstat(it->path().c_str(), &st) != 0) continue;
    l[it->path().string()] = {static_cast<unsigned>(st.st_mode & S_IFMT), static_cast<unsigned long>(st.st_ino),
                              static_cast<long long>(st.st_size), static_cast<unsigned>(st.st_mode & 07777),
                              static_cast<unsigned>(st.st_uid),
                              S_ISDIR(st.st_mode) ? 0LL : static_cast<long long>(st.st_mtim.tv_sec) * 1000000000LL + st.st_mtim.tv_nsec};
  }
  return l;
}

// True if the command line `cmd` names `path` as something it may write: a word of it (split at
// spaces and quotes), or the file a word that is a symbolic link names, is the path, a directory
// holding it, or a table whose record it is (X.csv or X gives X.json).
inline bool named_by(const std::string& cmd, const std::string& path) {
  std::vector<std::string> words(1);
  for (char c : cmd) {
    if (c == ' ' || c == '\'' || c == '"' || c == '\n') {
      if (!words.back().empty()) words.emplace_back();
    } else {
      words.back() += c;
    }
  }
  for (std::size_t k = 0, n = words.size(); k < n; ++k) {
    std::string& w = words[k];
    while (w.size() > 1 && w.back() == '/') w.pop_back();
    std::error_code ec;
    if (std::filesystem::is_symlink(w, ec))  // an output named through a link writes the file it names
      words.push_back(std::filesystem::weakly_canonical(w, ec).string());
  }
  const auto is_word = [&](const std::string& p) { return std::find(words.begin(), words.end(), p) != words.end(); };
  for (std::string p = path; !p.empty() && p != "/"; p = std::filesystem::path(p).parent_path().string())
    if (is_word(p)) return true;
  const std::string json = ".json";
  if (path.size() > json.size() && path.compare(path.size() - json.size(), json.size(), json) == 0) {
    const std::string stem = path.substr(0, path.size() - json.size());
    return is_word(stem + ".csv") || is_word(stem);
  }
  return false;
}

// Runs the CLI with `args`; with raw = true, `args` is the whole command line. Every run checks
// that nothing it did not name changed in the test's scratch directory (a before/after listing):
// an output never replaces or touches a file the user did not name. A violation throws, failing
// the test with the paths.
inline Run run(const std::string& args, bool raw = false) {
  const std::string out = unique("cli.out"), err = unique("cli.err");
  const std::string cmd = (raw ? args : cli_path() + " " + args) + " >" + out + " 2>" +
                          err + " </dev/null";
  const Listing before = listing(test::scratch().path());
  const int status = std::system(cmd.c_str());
  const Listing after = listing(test::scratch().path());
  Run r;
  r.code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  r.out = slurp(out);
  r.err = slurp(err);
  std::string unnamed;
  const auto check = [&](const Listing& a, const Listing& b) {
    for (const auto& [path, entry] : a) {
      if (path == out || path == err) continue;
      const auto found = b.find(path);
      if ((found == b.end() || found->second != entry) && !named_by(cmd, path)) unnamed += "\n  " + path;
    }
  };
  check(before, after);
  check(after, before);
  if (!unnamed.empty())
    throw std::runtime_error("the command changed what it did not name:" + unnamed + "\ncommand: " + cmd);
  return r;
}

// A new directory `name` in this test process's scratch directory.
inline std::filesystem::path fresh_dir(const std::string& name) {
  const std::filesystem::path dir = unique(name);
  std::filesystem::create_directories(dir);
  return dir;
}

inline std::size_t count_lines(const std::string& s) {
  return static_cast<std::size_t>(std::count(s.begin(), s.end(), '\n'));
}

inline std::string write_file(const std::string& name, const std::string& text) {
  const std::string path = unique(name);
  std::ofstream(path) << text;
  return path;
}

inline std::vector<std::string> lines(const std::string& text) {
  std::vector<std::string> out;
  std::stringstream s(text);
  for (std::string line; std::getline(s, line);) out.push_back(line);
  return out;
}

}  // namespace test::cli
