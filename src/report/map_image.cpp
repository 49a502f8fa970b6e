// map_image and write_tiff (layerjkr/map_image.hpp). The TIFF layout follows the TIFF 6.0
// baseline (Adobe, 1992): header, the strip, the description, then one IFD with its entries in
// ascending tag order; SampleFormat (tag 339) = 3 marks IEEE floats, as ImageJ and Gwyddion read.
#include "layerjkr/map_image.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

#include "layerjkr/error.hpp"

namespace layerjkr {

MapImage map_image(const std::vector<int>& grid_x, const std::vector<int>& grid_y, const std::vector<double>& values) {
  if (grid_x.size() != grid_y.size() || grid_x.size() != values.size())
    throw InputError("map image: grid_x, grid_y and values have " + std::to_string(grid_x.size()) + ", " +
                     std::to_string(grid_y.size()) + " and " + std::to_string(values.size()) + " entries; give one each per curve");
  MapImage image;
  for (std::size_t k = 0; k < values.size(); ++k) {
    if (grid_x[k] < 0 || grid_y[k] < 0) continue;
    image.width = std::max(image.width, static_cast<std::size_t>(grid_x[k]) + 1);
    image.height = std::max(image.height, static_cast<std::size_t>(grid_y[k]) + 1);
  }
  if (image.width == 0)
    throw InputError("map image: no curve has a map pixel (instrument force maps and QI files have them)");
  if (static_cast<double>(image.width) * static_cast<double>(image.height) > static_cast<double>(kMaxMapImagePixels))
    throw InputError("map image: the grid is " + std::to_string(image.width) + " x " + std::to_string(image.height) +
                     " pixels; at most " + std::to_string(kMaxMapImagePixels) + " (8192 x 8192)");
  image.values.assign(image.width * image.height, std::numeric_limits<double>::quiet_NaN());
  std::vector<char> filled(image.values.size(), 0);
  for (std::size_t k = 0; k < values.size(); ++k) {
    if (grid_x[k] < 0 || grid_y[k] < 0) continue;
    const std::size_t at = static_cast<std::size_t>(grid_y[k]) * image.width + static_cast<std::size_t>(grid_x[k]);
    if (filled[at])
      throw InputError("map image: two curves on pixel (" + std::to_string(grid_x[k]) + ", " + std::to_string(grid_y[k]) +
                       "); an image is of one map: pass one file's curves");
    filled[at] = 1;
    image.values[at] = values[k];
  }
  return image;
}

namespace {

void put16(std::vector<unsigned char>& out, std::uint16_t v) {
  out.push_back(static_cast<unsigned char>(v & 0xffu));
  out.push_back(static_cast<unsigned char>(v >> 8));
}

void put32(std::vector<unsigned char>& out, std::uint32_t v) {
  for (int shift = 0; shift < 32; shift += 8) out.push_back(static_cast<unsigned char>((v >> shift) & 0xffu));
}

// One IFD entry: tag, type (3 SHORT, 4 LONG, 2 ASCII), count, value or offset.
void entry(std::vector<unsigned char>& out, std::uint16_t tag, std::uint16_t type, std::uint32_t count, std::uint32_t value) {
  put16(out, tag);
  put16(out, type);
  put32(out, count);
  if (type == 3 && count == 1) {  // a SHORT sits in the first two bytes of the field
    put16(out, static_cast<std::uint16_t>(value));
    put16(out, 0);
  } else {
    put32(out, value);
  }
}

}  // namespace

void write_tiff(const MapImage& image, const std::string& path, const std::string& description) {
  if (image.width == 0 || image.height == 0 || image.values.size() != image.width * image.height)
    throw InputError("write_tiff " + path + ": the image is empty or its values do not fill " +
                     std::to_string(image.width) + " x " + std::to_string(image.height) + " pixels");
  std::string text;
  for (char c : description) text += (c >= 32 && c < 127) ? c : '?';
  text += '\0';
  const std::uint64_t strip = 4ull * image.values.size();
  if (strip + text.size() + 1024 > std::numeric_limits<std::uint32_t>::max())
    throw InputError("write_tiff " + path + ": the image is too large for a TIFF (4 GB)");
  std::vector<unsigned char> out;
  out.reserve(static_cast<std::size_t>(strip) + text.size() + 256);
  out.push_back('I');
  out.push_back('I');
  put16(out, 42);
  const std::uint32_t strip_at = 8, text_at = strip_at + static_cast<std::uint32_t>(strip);
  std::uint32_t ifd_at = text_at + static_cast<std::uint32_t>(text.size());
  ifd_at += ifd_at % 2;  // word-aligned
  put32(out, ifd_at);
  for (double v : image.values) {
    const float f = static_cast<float>(v);  // beyond float's range: +-inf, NaN stays NaN
    std::uint32_t bits = 0;
    std::memcpy(&bits, &f, sizeof bits);
    put32(out, bits);
  }
  out.insert(out.end(), text.begin(), text.end());
  if (out.size() % 2) out.push_back(0);
  const auto w = static_cast<std::uint32_t>(image.width), h = static_cast<std::uint32_t>(image.height);
  put16(out, 12);
  entry(out, 256, 4, 1, w);                                // ImageWidth
  entry(out, 257, 4, 1, h);                                // ImageLength
  entry(out, 258, 3, 1, 32);                               // BitsPerSample
  entry(out, 259, 3, 1, 1);                                // Compression: none
  entry(out, 262, 3, 1, 1);                                // PhotometricInterpretation: BlackIsZero
  entry(out, 270, 2, static_cast<std::uint32_t>(text.size()), text_at);  // ImageDescription
  entry(out, 273, 4, 1, strip_at);                         // StripOffsets
  entry(out, 277, 3, 1, 1);                                // SamplesPerPixel
  entry(out, 278, 4, 1, h);                                // RowsPerStrip
  entry(out, 279, 4, 1, static_cast<std::uint32_t>(strip));  // StripByteCounts
  entry(out, 284, 3, 1, 1);                                // PlanarConfiguration: chunky
  entry(out, 339, 3, 1, 3);                                // SampleFormat: IEEE float
  put32(out, 0);                                           // no next IFD
  std::ofstream f(path, std::ios::binary | std::ios::trunc);
  if (f) f.write(reinterpret_cast<const char*>(out.data()), static_cast<std::streamsize>(out.size()));
  if (!f) throw InputError("write_tiff: cannot write " + path);
}

}  // namespace layerjkr
