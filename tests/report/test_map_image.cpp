// Map images and their TIFF (layerjkr/map_image.hpp). Oracles: the pixels placed by hand; the
// TIFF read back by a reader written here from the TIFF 6.0 baseline (tags, offsets, IEEE
// floats) - and, in python/tests/test_package.py, by Pillow, a reader nobody here wrote.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <iterator>
#include <map>
#include <string>
#include <vector>

#include "layerjkr/error.hpp"
#include "layerjkr/map_image.hpp"
#include "support/temp_dir.hpp"

using namespace layerjkr;

namespace {

struct Tiff {
  std::map<int, std::uint32_t> tags;  // tag -> value or offset
  std::map<int, std::uint32_t> counts;
  std::vector<unsigned char> bytes;
  std::uint32_t u32(std::size_t at) const {
    return bytes[at] | bytes[at + 1] << 8 | bytes[at + 2] << 16 | static_cast<std::uint32_t>(bytes[at + 3]) << 24;
  }
  std::uint16_t u16(std::size_t at) const { return static_cast<std::uint16_t>(bytes[at] | bytes[at + 1] << 8); }
  float pixel(std::size_t k) const {
    const std::uint32_t bits = u32(tags.at(273) + 4 * k);
    float f = 0.0f;
    std::memcpy(&f, &bits, sizeof f);
    return f;
  }
};

Tiff read_tiff(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  Tiff t;
  t.bytes.assign(std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>());
  REQUIRE(t.bytes.size() > 8);
  REQUIRE(t.bytes[0] == 'I');
  REQUIRE(t.u16(2) == 42);
  const std::uint32_t ifd = t.u32(4);
  REQUIRE(ifd % 2 == 0);
  const int n = t.u16(ifd);
  int last = 0;
  for (int i = 0; i < n; ++i) {
    const std::size_t e = ifd + 2 + 12 * static_cast<std::size_t>(i);
    const int tag = t.u16(e), type = t.u16(e + 2);
    CHECK(tag > last);  // ascending, as the baseline requires
    last = tag;
    t.counts[tag] = t.u32(e + 4);
    t.tags[tag] = type == 3 && t.counts[tag] == 1 ? t.u16(e + 8) : t.u32(e + 8);
  }
  CHECK(t.u32(ifd + 2 + 12 * static_cast<std::size_t>(n)) == 0);  // one image
  return t;
}

}  // namespace

TEST_CASE("map_image places each value at its pixel, NaN elsewhere", "[report][tiff]") {
  const MapImage m = map_image({0, 2, 1, -1}, {0, 1, 1, 0}, {1.0, 2.0, 3.0, 99.0});
  CHECK(m.width == 3);
  CHECK(m.height == 2);
  REQUIRE(m.values.size() == 6);
  CHECK(m.values[0] == 1.0);
  CHECK(m.values[1 * 3 + 2] == 2.0);
  CHECK(m.values[1 * 3 + 1] == 3.0);
  for (std::size_t k : {1u, 2u, 3u}) CHECK(std::isnan(m.values[k]));
}

TEST_CASE("map_image refuses what is not one map, naming why", "[report][tiff]") {
  CHECK_THROWS_WITH(map_image({0, 0}, {1, 1}, {1.0, 2.0}), Catch::Contains("two curves on pixel (0, 1)"));
  CHECK_THROWS_WITH(map_image({0}, {1, 2}, {1.0}), Catch::Contains("1, 2 and 1 entries"));
  CHECK_THROWS_WITH(map_image({-1}, {-1}, {1.0}), Catch::Contains("no curve has a map pixel"));
  CHECK_THROWS_WITH(map_image({9000, 0}, {9000, 0}, {1.0, 2.0}), Catch::Contains("8192 x 8192"));
}

TEST_CASE("write_tiff: a baseline float TIFF whose pixels, size and description read back", "[report][tiff]") {
  const test::TempDir dir;
  const MapImage m = map_image({0, 1, 2, 0, 1}, {0, 0, 0, 1, 1}, {1.5, -2.25e-9, 3e6, 4.0, 1e300});
  const std::string path = dir.file("E.tiff");
  write_tiff(m, path, "layerjkr fit-map: E [Pa]\n\xce\xbc");
  const Tiff t = read_tiff(path);
  CHECK(t.tags.at(256) == 3);   // width
  CHECK(t.tags.at(257) == 2);   // height
  CHECK(t.tags.at(258) == 32);  // bits
  CHECK(t.tags.at(259) == 1);   // uncompressed
  CHECK(t.tags.at(277) == 1);
  CHECK(t.tags.at(278) == 2);   // one strip
  CHECK(t.tags.at(279) == 24);
  CHECK(t.tags.at(339) == 3);   // IEEE float
  const std::string text(t.bytes.begin() + t.tags.at(270), t.bytes.begin() + t.tags.at(270) + t.counts.at(270) - 1);
  CHECK(text == "layerjkr fit-map: E [Pa]???");  // printable ASCII only
  CHECK(t.pixel(0) == 1.5f);
  CHECK(t.pixel(1) == static_cast<float>(-2.25e-9));
  CHECK(t.pixel(2) == 3e6f);
  CHECK(t.pixel(3) == 4.0f);
  CHECK(std::isinf(t.pixel(4)));  // beyond float's range
  CHECK(std::isnan(t.pixel(5)));  // no curve there
  CHECK_THROWS_WITH(write_tiff(m, dir.file("no/such/dir/x.tiff"), "x"), Catch::Contains("cannot write"));
  CHECK_THROWS_AS(write_tiff(MapImage{}, dir.file("empty.tiff"), "x"), InputError);
}
