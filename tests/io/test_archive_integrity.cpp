// Every archive member is verified before its bytes are used (issue #21): the CRC-32 and
// size the central directory declares, the sample counts the segment header announces, and
// the declared size against ReadLimits before anything is allocated. Damaged copies are
// built in a temporary directory: from a synthetic archive (always) and from the shared
// spot3 force curve (skipped visibly when ../shared is absent).
#include <catch2/catch.hpp>

#include <cstdlib>
#include <random>

#include "jpk_builder.hpp"
#include "layerjkr/error.hpp"
#include "layerjkr/instrument.hpp"
#include "support/temp_dir.hpp"
#include "support/test_support.hpp"

using namespace layerjkr;

using test::input_error;

namespace {

const std::string kSpot3 = std::string(LAYERJKR_SOURCE_DIR) + "/../shared/data/instrument/fmt-jpk-fd_spot3-0192.jpk-force";
bool have_spot3() { return std::ifstream(kSpot3).good(); }

// Every sample of every channel, so that "the same data" means bit-identical.
std::vector<double> all_values(const InstrumentFile& f) {
  std::vector<double> out;
  for (const InstrumentCurve& c : f.curves) {
    out.insert(out.end(), {c.spring_constant, c.sensitivity, c.x, c.y, static_cast<double>(c.position_index)});
    for (const InstrumentSegment& s : c.segments) {
      out.push_back(s.duration);
      out.push_back(static_cast<double>(s.style));
      for (const auto* v : {&s.force, &s.height, &s.piezo_height}) out.insert(out.end(), v->begin(), v->end());
    }
  }
  return out;
}

bool same_bits(const std::vector<double>& a, const std::vector<double>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0;
}

std::string synthetic(const test::TempDir& dir, const std::string& name,
                      const std::vector<test::Member>& members = test::jpk_members()) {
  const std::string path = dir.file(name);
  test::write_zip(path, members);
  return path;
}

}  // namespace

TEST_CASE("a synthetic archive reads, and its members are the ones the tests damage", "[io][archive]") {
  test::TempDir dir;
  const InstrumentFile f = read_instrument_file(synthetic(dir, "good.jpk-force"));
  REQUIRE(f.curves.size() == 1);
  REQUIRE(f.curves[0].segments.size() == 1);
  CHECK(f.curves[0].segments[0].force.size() == 8);
  CHECK(f.curves[0].spring_constant == 0.05);
}

TEST_CASE("a member whose stored CRC-32 is wrong fails, naming the file and the member", "[io][archive]") {
  test::TempDir dir;
  for (const std::string member : {"header.properties", "segments/0/channels/vDeflection.dat"}) {
    INFO(member);
    for (bool deflate : {true, false}) {
      std::vector<test::Member> members = test::jpk_members();
      for (auto& m : members) m.deflate = deflate;
      std::string bytes = test::read_bytes(synthetic(dir, "base.jpk-force", members));
      test::patch_member(bytes, member, "crc", 0x12345678);
      const std::string path = dir.file("bad_crc.jpk-force");
      test::write_bytes(path, bytes);
      CHECK_THAT(input_error([&] { read_instrument_file(path); }),
                           Catch::Matchers::Contains("bad_crc.jpk-force") && Catch::Matchers::Contains(member) &&
                               Catch::Matchers::Contains("checksum"));
    }
  }
}

TEST_CASE("a member whose declared size lies fails: shorter or longer than its data", "[io][archive]") {
  test::TempDir dir;
  const std::string member = "segments/0/channels/strainGaugeHeight.dat";  // 16 bytes
  for (std::uint32_t declared : {8U, 15U, 17U, 64U}) {
    INFO("declared " << declared);
    std::string bytes = test::read_bytes(synthetic(dir, "base.jpk-force"));
    test::patch_member(bytes, member, "size", declared);
    const std::string path = dir.file("lying_size.jpk-force");
    test::write_bytes(path, bytes);
    CHECK_THAT(input_error([&] { read_instrument_file(path); }),
                         Catch::Matchers::Contains("lying_size.jpk-force") && Catch::Matchers::Contains(member));
  }
}

TEST_CASE("a member cut short or with a sample count other than the header's fails", "[io][archive]") {
  test::TempDir dir;
  std::vector<test::Member> odd = test::jpk_members();
  odd[2].bytes.pop_back();  // vDeflection: 15 bytes, half a sample, and no count to compare with
  odd[1].bytes.erase(0, odd[1].bytes.find('\n') + 1);
  REQUIRE(odd[1].bytes.find("num-points") == std::string::npos);
  CHECK_THAT(input_error([&] { read_instrument_file(synthetic(dir, "odd.jpk-force", odd)); }),
                       Catch::Matchers::Contains("vDeflection.dat") && Catch::Matchers::Contains("whole number"));
  std::vector<test::Member> short_both = test::jpk_members();
  short_both[2].bytes.resize(14);  // both channels 7 samples, the header says 8
  short_both[3].bytes.resize(14);
  CHECK_THAT(input_error([&] { read_instrument_file(synthetic(dir, "short.jpk-force", short_both)); }),
                       Catch::Matchers::Contains("vDeflection.dat") && Catch::Matchers::Contains("announces 8"));
  // Checked against the declared size before unpacking: a bomb in a channel's place fails
  // with the header's count under any limit.
  std::vector<test::Member> bomb = test::jpk_members();
  bomb[2].bytes.assign(std::size_t{4} << 20, '\0');
  CHECK_THAT(input_error([&] { read_instrument_file(synthetic(dir, "bomb.jpk-force", bomb)); }),
             Catch::Matchers::Contains("declares 4194304 bytes") && Catch::Matchers::Contains("announces 8 samples"));
}

TEST_CASE("a declared 4 GB member fails before anything is allocated, naming the limit", "[io][archive]") {
  test::TempDir dir;
  std::string bytes = test::read_bytes(synthetic(dir, "base.jpk-force"));
  test::patch_member(bytes, "header.properties", "size", 0xFFFFFFF0U);  // a header: no count to check it against
  const std::string path = dir.file("huge.jpk-force");
  test::write_bytes(path, bytes);
  CHECK_THAT(input_error([&] { read_instrument_file(path); }),
                       Catch::Matchers::Contains("huge.jpk-force") && Catch::Matchers::Contains("'header.properties'") &&
                           Catch::Matchers::Contains("4294967280 bytes (4096.0 MiB)") && Catch::Matchers::Contains("268435456 bytes (256.0 MiB)") &&
                           Catch::Matchers::Contains("LAYERJKR_MAX_MEMBER_MB"));
}

TEST_CASE("a highly compressible member over the member or archive limit fails - raised limits read it", "[io][archive]") {
  test::TempDir dir;
  // 2 MiB of samples that deflate to a few KB: a small bomb against limits set low here.
  const int n = 1 << 20;
  std::vector<test::Member> members = test::jpk_members(n);
  REQUIRE(members[2].bytes.size() == std::size_t{2} << 20);
  for (test::Member& m : members)  // constant channels: the ramps of jpk_members barely deflate
    if (m.bytes.size() == std::size_t{2} << 20) m.bytes.assign(m.bytes.size(), '\0');
  const std::string path = synthetic(dir, "bomb.jpk-force", members);
  CHECK(test::read_bytes(path).size() < 100000);
  ReadLimits low;
  low.max_member_bytes = std::uint64_t{1} << 20;
  CHECK_THAT(input_error([&] { read_instrument_file(path, low); }),
                       Catch::Matchers::Contains("bomb.jpk-force") && Catch::Matchers::Contains("channels/") &&
                           Catch::Matchers::Contains("2097152 bytes") && Catch::Matchers::Contains("1048576 bytes") &&
                           Catch::Matchers::Contains("LAYERJKR_MAX_MEMBER_MB"));
  ReadLimits total;
  total.max_archive_bytes = std::uint64_t{3} << 20;  // the first channel fits, the second does not
  CHECK_THAT(input_error([&] { read_instrument_file(path, total); }),
                       Catch::Matchers::Contains("per archive") && Catch::Matchers::Contains("LAYERJKR_MAX_ARCHIVE_MB"));
  CHECK(read_instrument_file(path).curves[0].segments[0].force.size() == static_cast<std::size_t>(n));
}

TEST_CASE("the limits come from LAYERJKR_MAX_MEMBER_MB / LAYERJKR_MAX_ARCHIVE_MB - bad values are errors", "[io][archive]") {
  ::unsetenv("LAYERJKR_MAX_MEMBER_MB");
  ::unsetenv("LAYERJKR_MAX_ARCHIVE_MB");
  CHECK(ReadLimits::from_environment().max_member_bytes == ReadLimits{}.max_member_bytes);
  ::setenv("LAYERJKR_MAX_MEMBER_MB", "1", 1);
  ::setenv("LAYERJKR_MAX_ARCHIVE_MB", "2048", 1);
  CHECK(ReadLimits::from_environment().max_member_bytes == std::uint64_t{1} << 20);
  CHECK(ReadLimits::from_environment().max_archive_bytes == std::uint64_t{2048} << 20);
  test::TempDir dir;
  const std::string path = synthetic(dir, "bomb.jpk-force", test::jpk_members(1 << 20));
  CHECK_THROWS_WITH(read_instrument_file(path), Catch::Contains("over the limit of 1048576 bytes"));
  for (const char* bad : {"0", "-5", "1.5", "abc", "", "99999999999"}) {
    ::setenv("LAYERJKR_MAX_MEMBER_MB", bad, 1);
    CHECK_THROWS_WITH(ReadLimits::from_environment(), Catch::Contains("LAYERJKR_MAX_MEMBER_MB") &&
                                                          Catch::Contains("[1, 1048576]"));
  }
  ::unsetenv("LAYERJKR_MAX_MEMBER_MB");
  ::unsetenv("LAYERJKR_MAX_ARCHIVE_MB");
}

TEST_CASE("an entry name given twice in one archive fails", "[io][archive]") {
  test::TempDir dir;
  std::vector<test::Member> members = test::jpk_members();
  members.push_back(members[2]);
  // libzip refuses to write a duplicate name; rename a copy after writing instead.
  members.back().name = "segments/0/channels/vDeflectioN.dat";
  std::string bytes = test::read_bytes(synthetic(dir, "base.jpk-force", members));
  const std::size_t at = test::zip_records(bytes, "segments/0/channels/vDeflectioN.dat").first + 46;
  bytes[at + std::string("segments/0/channels/vDeflectio").size()] = 'n';
  const std::string path = dir.file("twice.jpk-force");
  test::write_bytes(path, bytes);
  CHECK_THROWS_WITH(read_instrument_file(path), Catch::Contains("twice.jpk-force") && Catch::Contains("twice"));
}

TEST_CASE("spot3 with the bit at byte 10611 flipped fails instead of fitting 8.4 kPa", "[io][archive]") {
  if (!have_spot3()) {
    test::report_skip(kSpot3 + " is absent (the shared data beside the repository)");
    return;
  }
  test::TempDir dir;
  std::string bytes = test::read_bytes(kSpot3);
  bytes[10611] = static_cast<char>(bytes[10611] ^ 1);
  const std::string path = dir.file("spot3_flip.jpk-force");
  test::write_bytes(path, bytes);
  CHECK_THAT(input_error([&] { read_instrument_file(path); }),
                       Catch::Matchers::Contains("spot3_flip.jpk-force") && Catch::Matchers::Contains("entry 'segments/"));
}

TEST_CASE("60 seeded single-bit flips of spot3: each fails or reads bit-identical data", "[io][archive]") {
  if (!have_spot3()) {
    test::report_skip(kSpot3 + " is absent (the shared data beside the repository)");
    return;
  }
  test::TempDir dir;
  const std::string original = test::read_bytes(kSpot3);
  const std::vector<double> expected = all_values(read_instrument_file(kSpot3));
  std::mt19937 rng(21);
  std::uniform_int_distribution<std::size_t> byte(0, original.size() - 1);
  std::uniform_int_distribution<int> bit(0, 7);
  int failed = 0, identical = 0;
  for (int k = 0; k < 60; ++k) {
    std::string bytes = original;
    const std::size_t at = byte(rng);
    const int b = bit(rng);
    bytes[at] = static_cast<char>(bytes[at] ^ (1 << b));
    const std::string path = dir.file("flip.jpk-force");
    test::write_bytes(path, bytes);
    INFO("byte " << at << " bit " << b);
    std::vector<double> got;
    std::string error;
    try {
      got = all_values(read_instrument_file(path));
    } catch (const InputError& e) {
      error = e.what();
    }
    if (error.empty()) {
      CHECK(same_bits(got, expected));
      ++identical;
    } else {
      CHECK_THAT(error, Catch::Contains("flip.jpk-force"));
      ++failed;
    }
  }
  std::cout << "60 flips: " << failed << " refused, " << identical << " read identical data\n";
}
