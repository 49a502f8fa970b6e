// layerjkr CLI: drawing with gnuplot (pngcairo) - the one place that starts it, and the mark
// every picture it draws carries.
#pragma once

#include <string>

namespace layerjkr::cli {

/// Runs `script` through gnuplot (its messages discarded: they must not reach a standard output
/// that carries a result) and checks that it wrote `png`, then marks `png` as layerjkr's
/// (mark_png). Throws Error naming `what` (the flag that asked for the plot) if gnuplot is
/// missing or fails.
void run_gnuplot(const std::string& script, const std::string& png, const std::string& what);

/// `path` as a gnuplot single-quoted string (quotes doubled), so no file name can end the
/// string and add commands; throws InputError for a name with a line break.
std::string gnuplot_quoted(const std::string& path);

/// Adds a PNG text chunk `Software` = `layerjkr` right after the image header of the PNG file at
/// `path` (rewritten in place; the picture is unchanged). Throws Error if it is not a PNG.
void mark_png(const std::string& path);

/// True if `path` is a PNG that mark_png marked: a picture layerjkr drew, which a later run may
/// replace. Reads its first 62 bytes.
bool is_marked_png(const std::string& path);

}  // namespace layerjkr::cli
