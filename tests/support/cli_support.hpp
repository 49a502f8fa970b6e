// Helpers for tests that run the layerjkr executable.
#pragma once

#include <sys/wait.h>

#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
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
inline std::string cli_path() { return LAYERJKR_CLI_PATH; }
inline std::string sample_curve() { return std::string(LAYERJKR_SOURCE_DIR) + "/data/curves/hydrogel_film_two_term.csv"; }
inline std::string sample_scene() { return std::string(LAYERJKR_SOURCE_DIR) + "/data/scenes/hydrogel_film_two_term.json"; }
inline std::string sample_fit_flags() { return " --scene " + sample_scene() + " --branch all --free E,w,delta0,P0"; }

// A path for `name` in this test process's scratch directory (removed at exit).
inline std::string unique(const std::string& name) { return test::scratch().file(name); }

// Runs the CLI with `args`; with raw = true, `args` is the whole command line.
inline Run run(const std::string& args, bool raw = false) {
  const std::string out = unique("cli.out"), err = unique("cli.err");
  const std::string cmd = (raw ? args : std::string(LAYERJKR_CLI_PATH) + " " + args) + " >" + out + " 2>" +
                          err + " </dev/null";
  const int status = std::system(cmd.c_str());
  Run r;
  r.code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  r.out = slurp(out);
  r.err = slurp(err);
  return r;
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
