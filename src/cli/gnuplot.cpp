// The gnuplot pipe (gnuplot.hpp).
#include "gnuplot.hpp"

#include <cstdio>
#include <filesystem>

#include "layerjkr/error.hpp"

namespace layerjkr::cli {

void run_gnuplot(const std::string& script, const std::string& png, const std::string& what) {
  std::error_code ec;
  FILE* pipe = popen("gnuplot 2>&1", "w");
  if (!pipe) throw Error(what + ": cannot start gnuplot");
  std::fputs(script.c_str(), pipe);
  const int status = pclose(pipe);
  if (status != 0 || std::filesystem::file_size(png, ec) == 0 || ec)
    throw Error(what + ": gnuplot failed (is it installed? apt-get install gnuplot-nox)");
}

std::string gnuplot_quoted(const std::string& path) {
  if (path.find_first_of("\n\r") != std::string::npos)
    throw InputError("a plot file name holds a line break, which gnuplot cannot take: " + path);
  std::string q = "'";
  for (char c : path) q += c == '\'' ? std::string("''") : std::string(1, c);
  return q + "'";
}

}  // namespace layerjkr::cli
