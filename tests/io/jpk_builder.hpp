// Test helper: small JPK force archives and Igor waves made in the test, so that damaged
// and hostile files can be built byte by byte without ../shared. Header-only; the tests
// that include it link libzip.
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <cstring>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <zip.h>

namespace test {

struct Member {
  std::string name, bytes;
  bool deflate = true;
};

/// Writes `members` as a zip archive at `path` (libzip, as JPK's own writer would).
inline void write_zip(const std::string& path, const std::vector<Member>& members) {
  int code = 0;
  zip_t* zip = zip_open(path.c_str(), ZIP_CREATE | ZIP_TRUNCATE, &code);
  if (!zip) throw std::runtime_error("cannot create " + path);
  for (const Member& m : members) {
    zip_source_t* src = zip_source_buffer(zip, m.bytes.data(), m.bytes.size(), 0);
    const zip_int64_t i = src ? zip_file_add(zip, m.name.c_str(), src, ZIP_FL_ENC_UTF_8) : -1;
    if (i < 0 || zip_set_file_compression(zip, static_cast<zip_uint64_t>(i), m.deflate ? ZIP_CM_DEFLATE : ZIP_CM_STORE, 0) != 0)
      throw std::runtime_error("cannot add " + m.name + " to " + path);
  }
  if (zip_close(zip) != 0) throw std::runtime_error("cannot write " + path);
}

/// Big-endian signed 16-bit samples, as JPK stores them.
inline std::string shorts(const std::vector<int>& v) {
  std::string out;
  for (int x : v) {
    const auto u = static_cast<std::uint16_t>(static_cast<std::int16_t>(x));
    out += static_cast<char>(u >> 8);
    out += static_cast<char>(u & 0xFF);
  }
  return out;
}

/// The members of a one-segment JPK force curve of `n` samples; `header` and `segment` are
/// appended to the two headers (a key given there overrides nothing: it is added, so tests
/// pass keys the minimal headers lack, or repeat one on purpose).
inline std::vector<Member> jpk_members(int n = 8, const std::string& header = "", const std::string& segment = "") {
  std::vector<int> force, height;
  for (int i = 0; i < n; ++i) {
    force.push_back(100 * i - 300);
    height.push_back(1000 - 50 * i);
  }
  std::string seg =
      "force-segment-header.num-points=" + std::to_string(n) + "\n"
      "force-segment-header.duration=1.0\n"
      "force-segment-header.settings.style=extend\n";
  for (const char* ch : {"vDeflection", "strainGaugeHeight"}) {
    const std::string c = std::string("channel.") + ch + ".";
    seg += c + "data.file.name=channels/" + ch + ".dat\n" + c + "data.type=short\n" + c + "data.encoder.type=signedshort\n" +
           c + "data.encoder.scaling.multiplier=1.0E-4\n" + c + "data.encoder.scaling.offset=0.0\n" + c +
           "conversion-set.conversions.base=volts\n";
  }
  seg += "channel.vDeflection.conversion-set.conversion.distance.base-calibration-slot=volts\n"
         "channel.vDeflection.conversion-set.conversion.distance.scaling.multiplier=5.0E-8\n"
         "channel.vDeflection.conversion-set.conversion.distance.scaling.offset=0.0\n"
         "channel.vDeflection.conversion-set.conversion.force.base-calibration-slot=distance\n"
         "channel.vDeflection.conversion-set.conversion.force.scaling.multiplier=0.05\n"
         "channel.vDeflection.conversion-set.conversion.force.scaling.offset=0.0\n"
         "channel.strainGaugeHeight.conversion-set.conversion.nominal.base-calibration-slot=volts\n"
         "channel.strainGaugeHeight.conversion-set.conversion.nominal.scaling.multiplier=1.0E-5\n"
         "channel.strainGaugeHeight.conversion-set.conversion.nominal.scaling.offset=0.0\n";
  const std::string top =
      "force-scan-series.header.position.x=1.0E-6\n"
      "force-scan-series.header.position.y=2.0E-6\n"
      "force-scan-series.header.position-index=0\n";
  return {{"header.properties", top + header},
          {"segments/0/segment-header.properties", seg + segment},
          {"segments/0/channels/vDeflection.dat", shorts(force)},
          {"segments/0/channels/strainGaugeHeight.dat", shorts(height)}};
}

/// A JPK force map (.jpk-force-map) at `path`: curve k (of `curves`) sits at (k % side, k / side)
/// um on a `side` x `side` um square centred at 0 (pitch 1 um), each one jpk_members' curve of
/// `n` samples under index/k/; the top header announces an `ilength` x `jlength` grid over that
/// square (`side` x `side` for the honest map; 1e6 x 1e6 puts 4 curves on a mostly empty grid).
inline void write_jpk_map(const std::string& path, int curves, int side, long long ilength, long long jlength,
                          int n = 8) {
  const auto grid = [&](const char* key, const std::string& v) {
    return std::string("force-scan-map.position-pattern.grid.") + key + "=" + v + "\n";
  };
  const double pixel = 1e-6;
  std::vector<Member> members{{"header.properties",
                               grid("ilength", std::to_string(ilength)) + grid("jlength", std::to_string(jlength)) +
                                   grid("ulength", std::to_string(pixel * side)) + grid("vlength", std::to_string(pixel * side)) +
                                   grid("xcenter", "0.0") + grid("ycenter", "0.0")}};
  for (int k = 0; k < curves; ++k) {
    const double x = (static_cast<double>(k % side) + 0.5 - 0.5 * side) * pixel;
    const double y = (static_cast<double>(k / side) + 0.5 - 0.5 * side) * pixel;
    const std::string prefix = "index/" + std::to_string(k) + "/";
    for (Member m : jpk_members(n)) {
      if (m.name == "header.properties") {
        std::ostringstream h;
        h.precision(17);
        h << "force-scan-series.header.position.x=" << x << "\nforce-scan-series.header.position.y=" << y
          << "\nforce-scan-series.header.position-index=" << k << "\n";
        m.bytes = h.str();
      }
      m.name = prefix + m.name;
      members.push_back(std::move(m));
    }
  }
  write_zip(path, members);
}

inline std::string read_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

inline void write_bytes(const std::string& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary) << bytes;
}

/// Offsets of the central-directory record and the local header of `name` in a zip's bytes.
inline std::pair<std::size_t, std::size_t> zip_records(const std::string& zip, const std::string& name) {
  auto u16 = [&](std::size_t at) { return static_cast<std::size_t>(static_cast<unsigned char>(zip[at]) |
                                                                   static_cast<unsigned char>(zip[at + 1]) << 8); };
  auto u32 = [&](std::size_t at) { return u16(at) | u16(at + 2) << 16; };
  for (std::size_t at = zip.find("PK\x01\x02"); at != std::string::npos; at = zip.find("PK\x01\x02", at + 4))
    if (zip.compare(at + 46, u16(at + 28), name) == 0 && u16(at + 28) == name.size()) return {at, u32(at + 42)};
  throw std::runtime_error("no central-directory record for " + name);
}

inline void put_u32(std::string& bytes, std::size_t at, std::uint32_t v) {
  for (int k = 0; k < 4; ++k) bytes[at + static_cast<std::size_t>(k)] = static_cast<char>((v >> (8 * k)) & 0xFF);
}

/// Sets the CRC-32 (field "crc") or the uncompressed size ("size") that both the central
/// directory and the local header of `name` declare.
inline void patch_member(std::string& zip, const std::string& name, const std::string& field, std::uint32_t v) {
  const auto [central, local] = zip_records(zip, name);
  const std::size_t c = field == "crc" ? 16 : 24, l = field == "crc" ? 14 : 22;
  put_u32(zip, central + c, v);
  put_u32(zip, local + l, v);
}

/// An Igor binary wave v5 (little-endian, float64) with columns Raw, Defl, ZSnsr of `rows`
/// rows and the note `note` ("Key:Value\r..."), the layout ibw_reader.cpp reads.
inline std::string igor_wave(const std::string& note, int rows = 6) {
  const std::size_t cols = 3, data_bytes = static_cast<std::size_t>(rows) * cols * 8, wfm = 320 + data_bytes;
  std::string labels(32 * (cols + 1), '\0');
  const char* names[] = {"Raw", "Defl", "ZSnsr"};
  for (std::size_t c = 0; c < cols; ++c) std::memcpy(&labels[32 * (c + 1)], names[c], std::strlen(names[c]));
  std::string b(64 + wfm, '\0');
  auto put = [&](std::size_t at, const void* v, std::size_t n) { std::memcpy(&b[at], v, n); };
  const std::int16_t version = 5, type = 4;
  const std::int32_t wfm_size = static_cast<std::int32_t>(wfm), note_size = static_cast<std::int32_t>(note.size()),
                     label_size = static_cast<std::int32_t>(labels.size()), n_rows = rows, n_cols = 3;
  const double step = 1e-3;
  put(0, &version, 2);
  put(4, &wfm_size, 4);
  put(12, &note_size, 4);
  put(40, &label_size, 4);
  put(64 + 16, &type, 2);
  put(64 + 68, &n_rows, 4);
  put(64 + 72, &n_cols, 4);
  put(64 + 84, &step, 8);
  for (int r = 0; r < rows; ++r)
    for (std::size_t c = 0; c < cols; ++c) {
      const double v = 1e-9 * (r + 1) * static_cast<double>(c + 1);
      put(64 + 320 + (c * static_cast<std::size_t>(rows) + static_cast<std::size_t>(r)) * 8, &v, 8);
    }
  return b + note + labels;
}

/// An Igor binary wave v5 (little-endian, float32) of any shape: `dims` (0 where unused), the
/// wave's name, per-dimension index labels (each dimension's own label left empty) and its
/// values column-major; the layout igor_wave.cpp reads and Asylum writes its map exports in.
inline std::string igor_wave_of(const std::string& name, std::array<int, 4> dims, const std::vector<std::vector<std::string>>& labels,
                                const std::vector<float>& values, const std::string& note, double row_step = 1e-3) {
  std::string label_bytes;
  std::int32_t label_sizes[4] = {0, 0, 0, 0};
  for (std::size_t d = 0; d < labels.size() && d < 4; ++d) {
    if (labels[d].empty()) continue;
    std::string block(32 * (labels[d].size() + 1), '\0');
    for (std::size_t i = 0; i < labels[d].size(); ++i)
      std::memcpy(&block[32 * (i + 1)], labels[d][i].data(), std::min<std::size_t>(31, labels[d][i].size()));
    label_sizes[d] = static_cast<std::int32_t>(block.size());
    label_bytes += block;
  }
  const std::size_t data_bytes = values.size() * 4, wfm = 320 + data_bytes;
  std::string b(64 + wfm, '\0');
  auto put = [&](std::size_t at, const void* v, std::size_t n) { std::memcpy(&b[at], v, n); };
  const std::int16_t version = 5, type = 2;
  const std::int32_t wfm_size = static_cast<std::int32_t>(wfm), note_size = static_cast<std::int32_t>(note.size());
  put(0, &version, 2);
  put(4, &wfm_size, 4);
  put(12, &note_size, 4);
  for (int d = 0; d < 4; ++d) put(36 + 4 * static_cast<std::size_t>(d), &label_sizes[d], 4);
  put(64 + 16, &type, 2);
  std::memcpy(&b[64 + 28], name.data(), std::min<std::size_t>(31, name.size()));
  for (int d = 0; d < 4; ++d) put(64 + 68 + 4 * static_cast<std::size_t>(d), &dims[static_cast<std::size_t>(d)], 4);
  put(64 + 84, &row_step, 8);
  put(64 + 320, values.data(), data_bytes);
  return b + note + label_bytes;
}

/// An Asylum force map of 3 points x 2 lines exported one wave per channel per point, laid out
/// as SOFA's public data are, under `root`: LineLLLL/LineLLLLPointPPPP{Defl,ZSnsr}.ibw (with
/// `folders`, else flat), 9 float32 rows each (Defl = (r + 1 + line) nm, ZSnsr = (100 - r +
/// point) nm; notes XLVDT = point um, YLVDT = 2 line um, Indexes 0,3,6,8), and with `with_image`
/// the map image ForceMap01.ibw beside the folders: SpringConstant 0.5, InvOLS 3.5e-8, a 4 x 2 um
/// scan offset by (1, -1) um, FMapScanPoints 3, FMapScanLines 2, ForceMapImage:1.
inline void write_asylum_map_export(const std::string& root, bool with_image, bool folders = true) {
  constexpr int points = 3, lines = 2, rows = 9;
  const auto put = [](const std::string& path, const std::string& bytes) {
    std::filesystem::create_directories(std::filesystem::path(path).parent_path());
    std::ofstream(path, std::ios::binary) << bytes;
  };
  for (int line = 0; line < lines; ++line)
    for (int point = 0; point < points; ++point)
      for (const std::string chan : {"Defl", "ZSnsr"}) {
        char base[64];
        std::snprintf(base, sizeof base, "Line%04dPoint%04d", line, point);
        std::vector<float> v;
        for (int r = 0; r < rows; ++r)
          v.push_back(chan == "Defl" ? static_cast<float>((r + 1 + line) * 1e-9) : static_cast<float>((100 - r + point) * 1e-9));
        const std::string note = "XLVDT:" + std::to_string(1e-6 * point) + "\rYLVDT:" + std::to_string(2e-6 * line) +
                                 "\rIndexes:0,3,6,8,\r";
        const std::string dir = folders ? root + "/Line" + std::string(base + 4, 4) : root;
        put(dir + "/" + base + chan + ".ibw", igor_wave_of(base + chan, {rows, 0, 0, 0}, {{}, {chan}}, v, note, 5e-4));
      }
  if (with_image) {
    const std::string note = "ScanSize: 4e-06\rFastScanSize: 4e-06\rSlowScanSize: 2e-06\rXOffset: 1e-06\rYOffset: -1e-06\r"
                             "ScanAngle: 0\rInvOLS: 3.5e-08\rSpringConstant: 0.5\rFMapScanPoints: 3\rFMapScanLines: 2\r"
                             "ForceMapImage:1\rVersion: 120804+2130\r";
    put(root + "/ForceMap01.ibw", igor_wave_of("ForceMap01", {points, lines, 2, 0}, {{}, {}, {"MapHeight", "MapAdhesion"}},
                                               std::vector<float>(points * lines * 2, 1e-7f), note));
  }
}

}  // namespace test
