// The gnuplot pipe (gnuplot.hpp).
#include "gnuplot.hpp"

#include <cstdio>
#include <filesystem>

#include "layerjkr/error.hpp"

namespace layerjkr::cli {

void run_gnuplot(const std::string& script, const std::string& png, const std::string& what) {
  FILE* pipe = popen("gnuplot 2>&1", "w");
  if (!pipe) throw Error(what + ": cannot start gnuplot");
  std::fputs(script.c_str(), pipe);
  const int status = pclose(pipe);
  if (status != 0 || !std::filesystem::exists(png)) {
    std::remove(png.c_str());
    throw Error(what + ": gnuplot failed (is it installed? apt-get install gnuplot-nox)");
  }
}

}  // namespace layerjkr::cli
