// layerjkr CLI: outputs checked against the inputs, and input lists expanded.
#pragma once

#include <string>
#include <vector>

#include "output_file.hpp"

namespace layerjkr::cli {

/// Throws InputError (exit 2) if `output` (flag `flag`) is the same file, by device and inode,
/// as one of `inputs`: writing it would destroy the input. A missing output is never one.
void check_not_input(const std::string& output, const std::string& flag, const std::vector<std::string>& inputs);

/// Directories, glob patterns and files, in the order given. A directory gives every entry
/// whose name ends in .csv, .tab or an instrument extension, whatever it is (file, link - dangling or
/// looping -, FIFO, directory), sorted by name: the batch reports the ones it cannot read as
/// failed rows. A directory or a pattern that holds an Asylum map exported per channel
/// (is_asylum_map_export) is one input, the map. What a directory holds besides (sub-folders,
/// other files) is not read, and `skipped` gets one line a directory saying what and why. Throws
/// InputError for an input that names nothing or a directory that cannot be listed or holds no
/// such entry.
std::vector<std::string> expand_inputs(const std::vector<std::string>& inputs, std::vector<std::string>* skipped = nullptr);

}  // namespace layerjkr::cli
