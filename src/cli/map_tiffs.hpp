// fit-map --tiff DIR: each fitted field of each map as a 32-bit float TIFF (layerjkr/map_image.hpp).
#pragma once

#include <string>
#include <vector>

#include "layerjkr/fit.hpp"

namespace layerjkr::cli {

/// The TIFFs a run writes into DIR: for one input, FIELD.tiff; for several, STEM.FIELD.tiff
/// (STEM the file's name without its extension, STEM_2, STEM_3, ... for later inputs of a stem
/// already taken, so that no image overwrites another). FIELD is each free parameter, its
/// _stderr, pull_off and rms_residual.
std::vector<std::string> map_tiff_names(const std::vector<std::string>& inputs, const std::vector<FitParameter>& free);

/// Whether any of `inputs` can carry map positions (an instrument file or an Asylum map export; a
/// curve CSV cannot): --plot-dir and --tiff refuse, before anything is written, inputs none of
/// which can.
bool may_carry_map_positions(const std::vector<std::string>& inputs);

/// Creates DIR and refuses, before any fit, inputs none of which can carry map positions (curve
/// CSV files), and to replace a file there that is not a TIFF layerjkr wrote (its description
/// starts "layerjkr fit-map") unless `force`.
void prepare_tiff_dir(const std::string& dir, const std::vector<std::string>& inputs, const std::vector<std::string>& names,
                      bool force);

/// Writes the TIFFs of every input with map pixels (failed curves NaN). Returns how many were
/// written: 0 when no fitted curve had a map position (the caller says so; the table stands).
std::size_t write_map_tiffs(const std::vector<BatchItem>& items, const std::vector<std::string>& inputs,
                            const std::vector<FitParameter>& free, const std::string& dir);

}  // namespace layerjkr::cli
