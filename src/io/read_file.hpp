// Internal: a whole file as bytes, for the readers that parse from memory.
#pragma once

#include <fstream>
#include <sstream>
#include <string>

#include "layerjkr/error.hpp"

namespace layerjkr::detail {

/// The file's bytes; throws InputError "<path>: cannot open <what>" / "cannot read <what>".
inline std::string read_file(const std::string& path, const std::string& what) {
  std::ifstream file(path, std::ios::binary);
  if (!file) throw InputError(path + ": cannot open " + what);
  std::ostringstream text;
  text << file.rdbuf();
  if (file.bad()) throw InputError(path + ": cannot read " + what);
  return text.str();
}

}  // namespace layerjkr::detail
