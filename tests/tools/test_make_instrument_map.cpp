// tools/make_instrument_map, the generator of bench/map_reading.cpp's big maps, run at
// SIDE = 8 in this test's own temporary directory: the QI archive has every entry where
// the source's layout says, each curve's header places it on the 8 x 8 grid, and its data
// are the source curve's bytes unchanged; the NanoScope force volume has its curve-count
// keys and data blocks set for 64 curves and curve c's bytes are source curve c % 256's.
// Both are then read through the library: positions on the grid, samples the source's.
// Skipped, not failed, when ../shared is absent (the generator's sources live there).
#include <zip.h>

#include <catch2/catch.hpp>

#include <algorithm>
#include <fstream>
#include <map>
#include <sstream>

#include "layerjkr/instrument.hpp"
#include "support/cli_support.hpp"
#include "support/temp_dir.hpp"

namespace {

const std::string kDir = std::string(LAYERJKR_SOURCE_DIR) + "/../shared/data/instrument/";
const std::string kQi = kDir + "fmt-jpk-fd_2020.02.07-16.29.05.036.jpk-qi-data";
const std::string kSpm = kDir + "bruker/20200903_Egel2.0_00023.spm";
constexpr int kSide = 8;
constexpr int kCurves = kSide * kSide;

bool have(const std::string& path) {
  if (std::ifstream(path).good()) return true;
  test::report_skip(path + " is absent (the shared data beside the repository)");
  return false;
}

test::cli::Run generate(const std::string& args) {
  return test::cli::run(std::string(LAYERJKR_MAKE_INSTRUMENT_MAP) + " " + args, true);
}

std::string bytes_of(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  std::stringstream s;
  s << f.rdbuf();
  return s.str();
}

struct Zip {
  explicit Zip(const std::string& path) {
    int err = 0;
    z = zip_open(path.c_str(), ZIP_RDONLY, &err);
    REQUIRE(z != nullptr);
  }
  ~Zip() { zip_discard(z); }
  Zip(const Zip&) = delete;
  Zip& operator=(const Zip&) = delete;

  std::vector<std::string> names() const {
    std::vector<std::string> out;
    for (zip_int64_t i = 0; i < zip_get_num_entries(z, 0); ++i)
      out.push_back(zip_get_name(z, static_cast<zip_uint64_t>(i), 0));
    return out;
  }
  zip_stat_t stat(const std::string& name) const {
    zip_stat_t st;
    REQUIRE(zip_stat(z, name.c_str(), 0, &st) == 0);
    return st;
  }
  std::string read(const std::string& name) const {
    const zip_stat_t st = stat(name);
    std::string out(static_cast<std::size_t>(st.size), '\0');
    zip_file_t* f = zip_fopen(z, name.c_str(), 0);
    REQUIRE(f != nullptr);
    const zip_int64_t n = zip_fread(f, out.data(), out.size());
    zip_fclose(f);
    REQUIRE(n == static_cast<zip_int64_t>(out.size()));
    return out;
  }
  zip_t* z = nullptr;
};

// The value of the first `key=value` line whose key ends in `suffix`.
std::string property(const std::string& text, const std::string& suffix) {
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) {
    const std::size_t eq = line.find('=');
    if (eq != std::string::npos && eq >= suffix.size() && line.compare(eq - suffix.size(), suffix.size(), suffix) == 0)
      return line.substr(eq + 1);
  }
  return "(no " + suffix + ")";
}

// NanoScope header values by section: values["\\*Ciao scan list"]["\\Lines"] (the first
// section of a name and the first key of a name in it).
std::map<std::string, std::map<std::string, std::string>> nanoscope_header(const std::string& file) {
  std::map<std::string, std::map<std::string, std::string>> out;
  const std::string header = file.substr(0, file.find("\\*File list end"));
  std::string section;
  bool seen = false;
  for (std::size_t b = 0; b < header.size();) {
    std::size_t e = header.find("\r\n", b);
    if (e == std::string::npos) e = header.size();
    const std::string line = header.substr(b, e - b);
    b = e + 2;
    if (line.rfind("\\*", 0) == 0) {
      seen = out.count(line) > 0;
      section = line;
      out[section];
      continue;
    }
    const std::size_t colon = line.find(": ");
    if (!seen && colon != std::string::npos) out[section].emplace(line.substr(0, colon), line.substr(colon + 2));
  }
  return out;
}

}  // namespace

TEST_CASE("make_instrument_map qi: 8 x 8 copies of the 4 source curves, each placed on the grid", "[tools]") {
  if (!have(kQi)) return;
  const test::TempDir dir;
  const std::string out = dir.file("map.jpk-qi-data");
  const test::cli::Run run = generate("qi 8 " + out);
  INFO(run.err);
  REQUIRE(run.code == 0);
  CHECK(run.out.find(std::to_string(kCurves) + " curves") != std::string::npos);

  // Entry names: index/K/<rest> of the source become index/n/<rest> for every n with
  // n % 4 = K, in the source's place; the other entries stay, in their order.
  const Zip src(kQi), map(out);
  std::vector<std::string> expected;
  std::map<int, std::vector<std::string>> rests;
  bool curves_done = false;
  for (const std::string& name : src.names()) {
    if (name.rfind("index/", 0) == 0 && name.size() > 6) {
      const std::size_t slash = name.find('/', 6);
      rests[std::stoi(name.substr(6, slash - 6))].push_back(name.substr(slash + 1));
      continue;
    }
    if (!rests.empty() && !curves_done) {
      for (int n = 0; n < kCurves; ++n)
        for (const std::string& rest : rests[n % 4]) expected.push_back("index/" + std::to_string(n) + "/" + rest);
      curves_done = true;
    }
    expected.push_back(name);
  }
  REQUIRE(rests.size() == 4);
  CHECK(expected.size() == 1094);  // 64 curves x 17 entries + 6 others ("index/" among them)
  CHECK(map.names() == expected);

  const std::string top = map.read("header.properties");
  CHECK(property(top, ".grid.ilength") == "8");
  CHECK(property(top, ".grid.jlength") == "8");
  CHECK(property(top, ".indexes.max") == "63");
  CHECK(property(top, ".grid.ulength") == property(src.read("header.properties"), ".grid.ulength"));
  for (int n = 0; n < kCurves; ++n) {
    const std::string p = "index/" + std::to_string(n) + "/";
    CHECK(property(map.read(p + "header.properties"), ".header.position-index") == std::to_string(n));
    // Channel data copied as stored: the same compressed size and CRC as the source's.
    const std::string q = "index/" + std::to_string(n % 4) + "/";
    for (const char* rest : {"segments/0/channels/vDeflection.dat", "segments/1/channels/measuredHeight.dat"}) {
      CHECK(map.stat(p + rest).comp_size == src.stat(q + rest).comp_size);
      CHECK(map.stat(p + rest).crc == src.stat(q + rest).crc);
    }
  }

  // Through the library: positions on the 8 x 8 grid, samples those of the source curve.
  const layerjkr::InstrumentFile source = layerjkr::read_instrument_file(kQi);
  const layerjkr::InstrumentFile made = layerjkr::read_instrument_file(out);
  CHECK(made.grid_shape_x == kSide);
  CHECK(made.grid_shape_y == kSide);
  CHECK(made.grid_size_x == source.grid_size_x);
  REQUIRE(made.curves.size() == static_cast<std::size_t>(kCurves));
  for (int n = 0; n < kCurves; ++n) {
    const layerjkr::InstrumentCurve& c = made.curves[static_cast<std::size_t>(n)];
    const layerjkr::InstrumentCurve& s = source.curves[static_cast<std::size_t>(n % 4)];
    INFO("curve " << n);
    CHECK(c.index == n);
    CHECK(c.position_index == n);
    CHECK(c.grid_x == n % kSide);
    CHECK(c.grid_y == n / kSide);
    CHECK(c.spring_constant == s.spring_constant);
    REQUIRE(c.segments.size() == s.segments.size());
    for (std::size_t k = 0; k < c.segments.size(); ++k) {
      CHECK(c.segments[k].force == s.segments[k].force);
      CHECK(c.segments[k].height == s.segments[k].height);
    }
  }
}

TEST_CASE("make_instrument_map nanoscope: an 8 x 8 force volume of the 16 x 16 source's curves", "[tools]") {
  if (!have(kSpm)) return;
  const test::TempDir dir;
  const std::string out = dir.file("map.spm");
  const test::cli::Run run = generate("nanoscope 8 " + out);
  INFO(run.err);
  REQUIRE(run.code == 0);
  const std::string src = bytes_of(kSpm), map = bytes_of(out);
  auto s = nanoscope_header(src), m = nanoscope_header(map);

  // The source: 16 x 16 curves of 1024 + 1024 int32 samples, then a 16 x 16 int32 image.
  const std::size_t offset = 80960, curve = 2048 * 4, pixel = 4;
  REQUIRE(s["\\*Ciao force image list"]["\\Data offset"] == std::to_string(offset));
  REQUIRE(s["\\*Ciao force image list"]["\\Data length"] == std::to_string(256 * curve));
  // The header keeps its size; each block shrinks from 256 to 64 curves (pixels).
  CHECK(map.size() == src.size() - (256 - kCurves) * (curve + pixel));
  CHECK(m["\\*Force file list"]["\\Data length"] == std::to_string(offset));
  CHECK(map.find("\\*File list end\r\n\x1a") < offset);
  CHECK(m["\\*Ciao scan list"]["\\Samps/line"] == "8");
  CHECK(m["\\*Ciao scan list"]["\\Lines"] == "8");
  CHECK(m["\\*Ciao force list"]["\\force/line"] == "8");
  CHECK(m["\\*Ciao force list"]["\\Samples / line"] == "8");
  CHECK(m["\\*Ciao force list"]["\\Samps/line"] == "1024 1024");  // samples per curve stay
  CHECK(m["\\*Ciao force image list"]["\\Data offset"] == std::to_string(offset));
  CHECK(m["\\*Ciao force image list"]["\\Data length"] == std::to_string(kCurves * curve));
  CHECK(m["\\*Ciao image list"]["\\Data offset"] == std::to_string(offset + kCurves * curve));
  CHECK(m["\\*Ciao image list"]["\\Data length"] == std::to_string(kCurves * pixel));
  CHECK(m["\\*Ciao image list"]["\\Number of lines"] == "8");
  for (std::size_t c = 0; c < kCurves; ++c)
    CHECK(map.compare(offset + c * curve, curve, src, offset + (c % 256) * curve, curve) == 0);
  CHECK(map.compare(offset + kCurves * curve, kCurves * pixel, src, offset + 256 * curve, kCurves * pixel) == 0);
  // Every other header line is the source's.
  std::size_t changed = 0;
  for (const auto& [section, keys] : s)
    for (const auto& [key, value] : keys) changed += m[section][key] != value ? 1 : 0;
  CHECK(changed == 11);  // 4 curve counts, 3 data lengths/offsets, 4 image sizes

  // Through the library: an 8 x 8 grid whose curve c is the source's curve c % 256.
  const layerjkr::InstrumentReader source(kSpm), made(out);
  REQUIRE(made.size() == static_cast<std::size_t>(kCurves));
  CHECK(made.header().grid_shape_x == kSide);
  CHECK(made.header().grid_shape_y == kSide);
  CHECK(made.header().grid_size_x == source.header().grid_size_x);  // the scan size is kept
  for (std::size_t c = 0; c < kCurves; ++c) {
    const layerjkr::InstrumentCurve a = made.curve(c), b = source.curve(c % 256);
    INFO("curve " << c);
    CHECK(a.grid_x == static_cast<int>(c % kSide));
    CHECK(a.grid_y == static_cast<int>(c / kSide));
    CHECK(a.spring_constant == b.spring_constant);
    REQUIRE(a.segments.size() == b.segments.size());
    for (std::size_t k = 0; k < a.segments.size(); ++k) {
      CHECK(a.segments[k].force == b.segments[k].force);
      CHECK(a.segments[k].height == b.segments[k].height);
    }
  }
}

TEST_CASE("make_instrument_map: bad arguments or an absent source exit 2 with one line", "[tools]") {
  const test::TempDir dir;
  const std::string out = dir.file("never.spm");
  const std::vector<std::string> bad = {"",
                                        "qi 8",
                                        "qi 0 " + out,
                                        "qi 8x " + out,
                                        "maps 8 " + out,
                                        "nanoscope 8 " + out + " --source",
                                        "qi 8 " + out + " --source " + dir.file("absent")};
  for (const std::string& args : bad) {
    INFO("make_instrument_map " << args);
    const test::cli::Run run = generate(args);
    CHECK(run.code == 2);
    CHECK(run.err.find("make_instrument_map: ") == 0);
    CHECK(std::count(run.err.begin(), run.err.end(), '\n') == 1);
    CHECK(run.out.empty());
  }
  CHECK_FALSE(std::ifstream(out).good());
}
