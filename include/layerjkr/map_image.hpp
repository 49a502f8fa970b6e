// layerjkr: a map field as an image, and that image as a 32-bit float TIFF for ImageJ, Fiji
// and Gwyddion (fit-map --tiff DIR; Python BatchResults.image and to_tiff).
//
//   MapImage e = map_image(grid_x, grid_y, E_values);   // NaN where no curve was fitted
//   write_tiff(e, "E.tiff", "layerjkr fit-map: E [Pa]");
//
// Pixels are row-major, y (the map's slow axis, grid_y) by x (grid_x), as the instruments
// number them: row 0 is grid_y = 0. The TIFF is baseline, uncompressed, one strip,
// little-endian, SampleFormat 3 (IEEE float), with the description as its ImageDescription;
// NaN pixels stay NaN (ImageJ shows them as empty, Gwyddion masks them).
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace layerjkr {

/// A map field on its grid: `values[y * width + x]`, NaN where no value.
struct MapImage {
  std::size_t width = 0;   ///< pixels along x (grid_x), >= 1
  std::size_t height = 0;  ///< pixels along y (grid_y), >= 1
  std::vector<double> values;
};

/// Largest image map_image builds: 8192 x 8192 pixels (a 512 MB float64 grid), 30x the largest
/// AFM map in the project's data; beyond it a header's grid, not its curves, would set the size.
constexpr std::size_t kMaxMapImagePixels = std::size_t{8192} * 8192;

/// Places value k at pixel (grid_x[k], grid_y[k]); the grid is as wide and high as the largest
/// indices + 1. Entries with a negative index (a curve without a pixel) are skipped; a second
/// value on one pixel is an InputError naming the pixel (two maps mixed: pass one file's
/// curves). Throws InputError for lists of different lengths, no pixel at all, or a grid above
/// kMaxMapImagePixels.
MapImage map_image(const std::vector<int>& grid_x, const std::vector<int>& grid_y, const std::vector<double>& values);

/// Writes `image` to `path` as a 32-bit float TIFF (see above), replacing the file; the
/// description (printable ASCII, e.g. "layerjkr fit-map: E [Pa]") is its ImageDescription.
/// Values beyond float's range become +-inf. Throws InputError if the file cannot be written.
void write_tiff(const MapImage& image, const std::string& path, const std::string& description);

}  // namespace layerjkr
