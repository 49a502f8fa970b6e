// Output files and input lists of the CLI (files.hpp).
#include "files.hpp"

#include <glob.h>

#include <algorithm>
#include <filesystem>
#include <fstream>

#include "layerjkr/error.hpp"
#include "layerjkr/instrument.hpp"

namespace layerjkr::cli {

namespace fs = std::filesystem;

void write_atomically(const std::string& path, const std::string& text) {
  const std::string tmp = path + ".tmp";
  {
    std::ofstream f(tmp, std::ios::binary);
    f << text;
    if (!f) throw InputError(path + ": cannot write the file");
  }
  fs::rename(tmp, path);
}

std::vector<std::string> expand_inputs(const std::vector<std::string>& inputs) {
  std::vector<std::string> files;
  for (const auto& in : inputs) {
    std::error_code ec;
    if (fs::is_directory(in, ec)) {
      std::vector<std::string> found;
      for (const auto& e : fs::directory_iterator(in))
        if (e.is_regular_file() && (e.path().extension() == ".csv" || is_instrument_file(e.path().string())))
          found.push_back(e.path().string());
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
    } else if (fs::is_regular_file(in, ec)) {
      files.push_back(in);
    } else {
      throw InputError(in + ": no such file or directory");
    }
  }
  return files;
}

}  // namespace layerjkr::cli
