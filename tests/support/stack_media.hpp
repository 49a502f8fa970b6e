// Test helpers: stacks of layers written as brace lists (layered_medium.hpp).
#pragma once

#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "layerjkr/layered_medium.hpp"

namespace test {

/// The layers (top first) on a rigid base.
inline layerjkr::LayeredMedium stack(std::vector<layerjkr::StackLayer> layers,
                                      layerjkr::Base base = layerjkr::Base::bonded) {
  layerjkr::LayeredMedium m;
  m.layers = std::move(layers);
  m.base = base;
  return m;
}

/// The layers (top first) bonded to an elastic half-space of modulus Es [Pa] and ratio nus.
inline layerjkr::LayeredMedium on_half_space(std::vector<layerjkr::StackLayer> layers, double Es, double nus) {
  layerjkr::LayeredMedium m = stack(std::move(layers));
  m.substrate = layerjkr::Substrate{Es, nus};
  return m;
}

/// One row of a reference table of tools/stack_*reference.py: the case's name and its numbers.
struct ReferenceRow {
  std::string name;
  std::vector<double> values;
};

/// The rows of `path` (data/stack/*.csv; '#' comments and the "case," header skipped). Throws
/// std::runtime_error naming the file if it cannot be opened.
inline std::vector<ReferenceRow> read_reference_rows(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot open " + path);
  std::vector<ReferenceRow> rows;
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#' || line.rfind("case,", 0) == 0) continue;
    std::stringstream cells(line);
    ReferenceRow row;
    std::getline(cells, row.name, ',');
    std::string cell;
    while (std::getline(cells, cell, ',')) row.values.push_back(std::stod(cell));
    rows.push_back(std::move(row));
  }
  return rows;
}

}  // namespace test
