// libFuzzer target: fit-map's results table as --resume reads it back. Any input must give rows
// or throw layerjkr::Error; the rows are whole lines of the input, in order, after the header.
#include <cstdint>
#include <string>

#include "cli/results_table.hpp"
#include "layerjkr/error.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::string header =
      "file,curve,x,y,grid_x,grid_y,status,error,model,converged,iterations,rms_residual,identifiable,E,E_stderr\n";
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    const auto rows = layerjkr::cli::parse_results_table(text, header, "fuzz");
    std::string joined = rows.empty() ? std::string() : header;
    for (const auto& r : rows) {
      if (r.line.empty() || r.line.back() != '\n') __builtin_trap();
      joined += r.line;
    }
    if (text.compare(0, joined.size(), joined) != 0) __builtin_trap();
    if (text.find('\n', joined.size()) != std::string::npos && !joined.empty()) __builtin_trap();
    for (const auto& r : rows)
      if (layerjkr::cli::csv_cell(r.file).find('\n') != std::string::npos) __builtin_trap();
  } catch (const layerjkr::Error&) {
  }
  return 0;
}
