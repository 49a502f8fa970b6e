// InstrumentReader's random access against the whole-file read (the oracle: the same curves,
// bit for bit, in any order and from two threads at once), curve ranges, zip64 end records,
// and the messages for files of no known format. Needs ../shared (skipped visibly without).
#include <catch2/catch.hpp>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <functional>
#include <iterator>
#include <fstream>
#include <stdexcept>
#include <thread>
#include <utility>
#include <vector>

#include "layerjkr/error.hpp"
#include "layerjkr/instrument.hpp"
#include "support/temp_dir.hpp"
#include "support/test_support.hpp"

using namespace layerjkr;

namespace {

const std::string kDir = std::string(LAYERJKR_SOURCE_DIR) + "/../shared/data/instrument/";
const std::string kQi = kDir + "fmt-jpk-fd_2020.02.07-16.29.05.036.jpk-qi-data";
const std::string kForceVolume = kDir + "bruker/20200903_Egel2.0_00023.spm";
bool have_data() { return std::ifstream(kQi).good() && std::ifstream(kForceVolume).good(); }

const std::vector<std::string> kFiles = {
    kDir + "fmt-jpk-fd_spot3-0192.jpk-force", kDir + "fmt-jpk-fd_flipsign_2015.05.22-15.31.49.352.jpk-force",
    kDir + "fmt-jpk-fd_map2x2_extracted.jpk-force-map", kQi, kDir + "fmt-igor-fd_SiN_FD_plot.ibw",
    kDir + "bruker/20200904_Egel4-Z1.0_00025.spm", kForceVolume};

bool same(const std::vector<double>& a, const std::vector<double>& b) {
  return a.size() == b.size() && std::equal(a.begin(), a.end(), b.begin(), [](double x, double y) {
           return std::memcmp(&x, &y, sizeof x) == 0;
         });
}

bool same(const InstrumentCurve& a, const InstrumentCurve& b) {
  bool ok = a.index == b.index && a.position_index == b.position_index && a.grid_x == b.grid_x &&
            a.grid_y == b.grid_y && same(std::vector<double>{a.x, a.y}, std::vector<double>{b.x, b.y}) && a.spring_constant == b.spring_constant &&
            a.sensitivity == b.sensitivity && a.segments.size() == b.segments.size();
  for (std::size_t s = 0; ok && s < a.segments.size(); ++s)
    ok = same(a.segments[s].force, b.segments[s].force) && same(a.segments[s].height, b.segments[s].height) &&
         same(a.segments[s].piezo_height, b.segments[s].piezo_height) && a.segments[s].style == b.segments[s].style;
  return ok;
}

std::string bytes_of(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>()};
}

void put(std::string& s, std::uint64_t v, int n) {
  for (int i = 0; i < n; ++i) s += static_cast<char>((v >> (8 * i)) & 0xFF);
}
std::uint64_t get(const std::string& s, std::size_t at, int n) {
  std::uint64_t v = 0;
  for (int i = n - 1; i >= 0; --i) v = (v << 8) | static_cast<unsigned char>(s[at + static_cast<std::size_t>(i)]);
  return v;
}

// The same archive with its end record in the zip64 form: a zip64 end record and locator, and
// a classic end record whose counts and offsets are all saturated, as big maps are written.
std::string as_zip64(const std::string& zip) {
  const std::size_t end = zip.size() - 22;
  REQUIRE(get(zip, end, 4) == 0x06054b50);
  const std::uint64_t entries = get(zip, end + 10, 2), cd_size = get(zip, end + 12, 4), cd_offset = get(zip, end + 16, 4);
  std::string out = zip.substr(0, end);
  // (value, bytes): the zip64 end record, its locator, then the saturated classic end record.
  const std::vector<std::pair<std::uint64_t, int>> fields = {
      {0x06064b50, 4}, {44, 8},         {45, 2},           {45, 2},     {0, 4},          {0, 4},
      {entries, 8},    {entries, 8},    {cd_size, 8},      {cd_offset, 8},
      {0x07064b50, 4}, {0, 4},          {end, 8},          {1, 4},
      {0x06054b50, 4}, {0, 2},          {0, 2},            {0xFFFF, 2}, {0xFFFF, 2},     {0xFFFFFFFF, 4},
      {0xFFFFFFFF, 4}, {0, 2}};
  for (const auto& [value, bytes] : fields) put(out, value, bytes);
  return out;
}

std::string input_error(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "(no InputError)";
}

}  // namespace

TEST_CASE("random access reads every curve as the whole-file read does, in any order and from two threads",
          "[io][instrument][reader]") {
  if (!have_data()) {
    test::report_skip(kDir + " is absent (the shared data beside the repository)");
    return;
  }
  for (const std::string& path : kFiles) {
    INFO(path);
    const InstrumentFile whole = read_instrument_file(path);
    const InstrumentReader reader(path);
    REQUIRE(reader.size() == whole.curves.size());
    CHECK(reader.header().curves.empty());
    CHECK(reader.header().format == whole.format);
    CHECK(reader.header().instrument == whole.instrument);
    CHECK(reader.header().grid_shape_x == whole.grid_shape_x);
    for (std::size_t i = reader.size(); i-- > 0;) {  // backwards: nothing depends on reading in order
      CHECK(same(reader.curve(i), whole.curves[i]));
      CHECK(reader.curve_number(i) == whole.curves[i].index);
    }
    std::vector<char> ok(2, 1);
    std::vector<std::thread> threads;
    for (int t = 0; t < 2; ++t)
      threads.emplace_back([&, t] {
        for (int round = 0; round < 3; ++round)
          for (std::size_t i = 0; i < reader.size(); ++i) {
            const std::size_t k = t == 0 ? i : reader.size() - 1 - i;
            ok[static_cast<std::size_t>(t)] &= static_cast<char>(same(reader.curve(k), whole.curves[k]));
          }
      });
    for (auto& t : threads) t.join();
    CHECK(ok[0]);
    CHECK(ok[1]);
    CHECK_THROWS_AS(reader.curve(reader.size()), std::out_of_range);
    CHECK_THROWS_AS(reader.curve_number(reader.size()), std::out_of_range);
  }
}

TEST_CASE("a curve range reads those curves only - past the end it stops at the last", "[io][instrument][reader]") {
  if (!have_data()) {
    test::report_skip(kDir + " is absent (the shared data beside the repository)");
    return;
  }
  const InstrumentFile whole = read_instrument_file(kForceVolume);
  REQUIRE(whole.curves.size() == 256);
  const InstrumentFile part = read_instrument_file(kForceVolume, ReadLimits{}, CurveRange{100, 103});
  REQUIRE(part.curves.size() == 3);
  for (std::size_t i = 0; i < 3; ++i) CHECK(same(part.curves[i], whole.curves[100 + i]));
  CHECK(read_instrument_file(kForceVolume, ReadLimits{}, CurveRange{250, 999}).curves.size() == 6);
  CHECK(read_instrument_file(kForceVolume, ReadLimits{}, CurveRange{300, 999}).curves.empty());
}

TEST_CASE("CurveRange::parse takes A:B, A: and :B and names the option for anything else", "[io][instrument][reader]") {
  CHECK(CurveRange::parse("2:5", "--curves").begin == 2);
  CHECK(CurveRange::parse("2:5", "--curves").end == 5);
  CHECK(CurveRange::parse("3:", "--curves").end == CurveRange{}.end);
  CHECK(CurveRange::parse(":4", "--curves").begin == 0);
  CHECK(CurveRange::parse("4:4", "--curves").end == 4);
  for (const char* bad : {"", "5", "5:2", "a:b", "1:2:3", "-1:3", "1.5:3", " 1:3"}) {
    INFO(bad);
    CHECK_THAT(input_error([&] { CurveRange::parse(bad, "--curves"); }),
               Catch::Contains("--curves = '" + std::string(bad) + "'") && Catch::Contains("A:B"));
  }
}

TEST_CASE("an archive whose end record is in the zip64 form reads the same", "[io][instrument][reader]") {
  if (!have_data()) {
    test::report_skip(kDir + " is absent (the shared data beside the repository)");
    return;
  }
  test::TempDir dir;
  const std::string path = dir.file("zip64.jpk-qi-data");
  std::ofstream(path, std::ios::binary) << as_zip64(bytes_of(kQi));
  const InstrumentFile whole = read_instrument_file(kQi), again = read_instrument_file(path);
  REQUIRE(again.curves.size() == whole.curves.size());
  for (std::size_t i = 0; i < whole.curves.size(); ++i) CHECK(same(again.curves[i], whole.curves[i]));
  // A zip64 locator pointing nowhere is an error naming the file, not a crash.
  std::string broken = as_zip64(bytes_of(kQi));
  broken[broken.size() - 22 - 20 + 8] = 0x7F;
  const std::string bad = dir.file("bad64.jpk-qi-data");
  std::ofstream(bad, std::ios::binary) << broken;
  CHECK_THAT(input_error([&] { InstrumentReader r(bad); }), Catch::Contains("bad64.jpk-qi-data") && Catch::Contains("zip64"));
}

TEST_CASE("files of no known format say what they are and list the known formats", "[io][instrument][reader]") {
  test::TempDir dir;
  auto file = [&](const std::string& name, const std::string& bytes) {
    const std::string path = dir.file(name);
    std::ofstream(path, std::ios::binary) << bytes;
    return path;
  };
  const std::string pfc = file("capture.pfc", std::string("\\*Force file list\r\n") + std::string(64, '\0'));
  CHECK_THAT(input_error([&] { InstrumentReader r(pfc); }),
             Catch::Contains("capture.pfc") && Catch::Contains("PeakForce Capture") && Catch::Contains(".spm"));
  const std::string image = file("scan.dat", "\\*File list\r\n\\Version: 0x09200000\r\n");
  CHECK_THAT(input_error([&] { InstrumentReader r(image); }),
             Catch::Contains("scan.dat") && Catch::Contains("image file") && Catch::Contains(".jpk-qi-data"));
  const std::string other = file("other.bin", std::string("\x01\x02\0\0", 4));
  CHECK_THAT(input_error([&] { InstrumentReader r(other); }),
             Catch::Contains("other.bin") && Catch::Contains("not an instrument file") && Catch::Contains("NanoScope"));
  CHECK(instrument_format("a/b.spm") == InstrumentFormat::nanoscope);
  CHECK(instrument_format("a/b.007") == InstrumentFormat::nanoscope);
  CHECK(!instrument_format("a.0b/c").has_value());
  CHECK(!instrument_format("a/b.0007").has_value());
  CHECK(instrument_format("x.jpk-qi-data") == InstrumentFormat::jpk_qi_data);
  if (!have_data()) {
    test::report_skip(kDir + " is absent: the renamed NanoScope file is not tried");
    return;
  }
  // A NanoScope force file keeps its header when renamed: it is read by what it holds.
  const std::string renamed = file("renamed.bin", bytes_of(kForceVolume));
  CHECK(InstrumentReader(renamed).size() == 256);
}

TEST_CASE("a read without the piezo height gives every other channel bit for bit, in every format",
          "[io][instrument][reader]") {
  if (!have_data()) {
    test::report_skip(kDir + " is absent: the channel choice is checked on the public files");
    return;
  }
  for (const std::string& path : kFiles) {
    const InstrumentReader reader(path);
    bool any_piezo = false;
    for (std::size_t i = 0; i < std::min<std::size_t>(reader.size(), 5); ++i) {
      InstrumentCurve all = reader.curve(i);
      const InstrumentCurve fit = reader.curve(i, CurveChannels{false});
      for (InstrumentSegment& s : all.segments) {
        any_piezo = any_piezo || !s.piezo_height.empty();
        s.piezo_height.clear();
      }
      INFO(path << " curve " << i);
      CHECK(same(all, fit));
      for (const InstrumentSegment& s : fit.segments) CHECK(s.piezo_height.empty());
    }
    if (path.find("spot3") != std::string::npos) CHECK(any_piezo);  // the file has one to leave out
  }
}
