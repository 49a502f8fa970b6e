// layerjkr CLI: the options `fit` and `fit-map` share, as typed on the command line, and
// their mapping to the library's typed options (fit.hpp, curve_data.hpp).
#pragma once

#include <string>

#include "layerjkr/curve_data.hpp"
#include "layerjkr/fit.hpp"
#include "layerjkr/scene.hpp"

namespace CLI {
class App;
}

namespace layerjkr::cli {

/// The flags shared by `fit` and `fit-map`, as typed.
struct FitArguments {
  std::string scene, free, loss = "none", branch = "approach", units = "m,N";
  double spring_constant = 0.0, sensitivity = 0.0, z_sign = 1.0, deflection_sign = 1.0;
  double force_noise = 0.0, radius_noise = 0.0;  ///< --force-noise, --radius-noise (0: estimated)
  std::string displacement_noise;  ///< --displacement-noise SD | auto ("" unset: delta exact)
  bool keep_offset = false;                      ///< --keep-offset
  int extra_starts = 0, max_iterations = 200;
  int curve = -1;  ///< --curve: which curve of a file holding several (-1: it must hold one)
  std::string control = "auto";  ///< --control: auto | load | cantilever | grips
  std::string baseline = "constant";  ///< --baseline: constant | tilt
  std::string window = "all";    ///< --window: all | pull-off | fraction:F
  std::string contact_point = "fit";  ///< --contact-point: fit | threshold | rov | gof
  /// --indentation-range [m], --force-range (fractions), --baseline-window [m]: MIN:MAX ("" unset)
  std::string indentation_range, force_range, baseline_window;
  std::string bounds;  ///< --bounds NAME=MIN:MAX[,...] (SI units; an empty end is unbounded)
};

/// The arguments as library options.
struct Prepared {
  Scene scene;
  FitOptions options;
  CsvOptions csv;
};
/// Everything but the scene; throws InputError naming the flag.
Prepared prepare_options(const FitArguments& args);
/// prepare_options and the scene loaded from args.scene.
Prepared prepare(const FitArguments& args);

/// Registers the shared flags on a subcommand.
void add_fit_options(CLI::App& command, FitArguments& args);

}  // namespace layerjkr::cli
