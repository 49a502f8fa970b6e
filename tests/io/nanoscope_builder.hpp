// Test helper: small Bruker NanoScope force files made in the test (text header, Ctrl-Z,
// padding, little-endian samples), laid out like the two PyFMReader files in
// ../shared/data/instrument/bruker, so that orders, sizes and damaged headers can be pinned
// without them. Header-only.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace test {

struct NanoscopeSpec {
  std::string version = "0x0920B046";
  std::string mode = "Force";  ///< or "Force Volume"
  int points = 1, lines = 1;   ///< force volume grid (Samps/line, Lines of the scan list)
  int n1 = 5, n2 = 3;          ///< extend, retract samples per curve
  int bytes = 2;               ///< bytes per sample
  std::string spring = "0.25";
  std::string defl_scale = "V [Sens. DeflSens] (0.0005000000 V/LSB) 2.500000 V";
  std::string defl_sens = "V 20.00000 ";
  std::string zsens = "V 10.00000 nm/V";
  std::string ramp = "V [Sens. Zsens] (0.006713765 V/LSB) 40.00000 V";  ///< 400 nm
  std::string scan_size = "3 ~m", x_offset = "100 nm", y_offset = "-50 nm";
  std::string samps;                ///< `Samps/line` of the channel if not "n1 n2"
  bool zsensor = false;             ///< also store a "Height Sensor" channel
  std::vector<std::int64_t> defl;   ///< every curve's samples in file order
  std::vector<std::int64_t> z;      ///< the same for the Z sensor
  long long data_length = -1;       ///< the deflection's `Data length` if >= 0
  long long data_offset = -1;       ///< its `Data offset` if >= 0
  std::string extra_scan_lines;     ///< lines added to the scan list
  std::string extra_force_lines;    ///< lines added to the force list
};

/// Little-endian two's complement samples of `bytes` bytes each.
inline std::string nanoscope_samples(const std::vector<std::int64_t>& v, int bytes) {
  std::string out;
  for (std::int64_t x : v) {
    const auto u = static_cast<std::uint64_t>(x);
    for (int b = 0; b < bytes; ++b) out.push_back(static_cast<char>((u >> (8 * b)) & 0xFF));
  }
  return out;
}

/// The file's bytes: header (padded to a multiple of 64 bytes), deflection, Z sensor.
inline std::string nanoscope_file(const NanoscopeSpec& s) {
  const std::string defl = nanoscope_samples(s.defl, s.bytes), z = nanoscope_samples(s.z, s.bytes);
  const std::string samps = s.samps.empty() ? std::to_string(s.n1) + " " + std::to_string(s.n2) : s.samps;
  auto header = [&](std::size_t size) {
    const std::size_t defl_at = s.data_offset >= 0 ? static_cast<std::size_t>(s.data_offset) : size;
    const std::string defl_len = std::to_string(s.data_length >= 0 ? static_cast<std::size_t>(s.data_length) : defl.size());
    std::string h = "\\*Force file list\r\n\\Version: " + s.version + "\r\n\\Data length: " + std::to_string(size) +
                    "\r\n\\*Equipment list\r\n\\Description: Test scope\r\n\\Microscope: Test AFM 8\r\n"
                    "\\*Scanner list\r\n\\@Sens. Zsens: " + s.zsens + "\r\n"
                    "\\*Ciao scan list\r\n\\Operating mode: " + s.mode + "\r\n\\Scan Size: " + s.scan_size +
                    "\r\n\\X Offset: " + s.x_offset + "\r\n\\Y Offset: " + s.y_offset +
                    "\r\n\\Samps/line: " + std::to_string(s.points) + "\r\n\\Lines: " + std::to_string(s.lines) +
                    "\r\n\\Capture mode : Single\r\n\\PF PGain\t: 99.8\r\n" + s.extra_scan_lines +
                    "\\@Sens. DeflSens: " + s.defl_sens + "\r\n\\@Sens. ZsensSens: V 500.0000 nm/V\r\n"
                    "\\*Ciao force list\r\n\\Scan rate: 1.0\r\n\\Forward vel.: 80\r\n\\Reverse vel.: 160\r\n" + s.extra_force_lines +
                    "\\Samps/line: " + samps + "\r\n\\@4:Ramp Size Zsweep: V [Sens. Zsens] (\\Data length V/LSB) 1 V\r\n"
                    "\\*Ciao force image list\r\n\\Data offset: " + std::to_string(defl_at) +
                    "\r\n\\Data length: " + defl_len + "\r\n\\Bytes/pixel: 2\r\n\\Samps/line: " + samps +
                    "\r\n\\Spring Constant: " + s.spring +
                    "\r\n\\@4:Image Data: S [DeflectionError] \"Deflection Error\"\r\n\\@4:Z scale: " + s.defl_scale +
                    "\r\n\\@4:Ramp Size: " + s.ramp + "\r\n";
    if (s.zsensor)
      h += "\\*Ciao force image list\r\n\\Data offset: " + std::to_string(defl_at + defl.size()) +
           "\r\n\\Data length: " + std::to_string(z.size()) + "\r\n\\Samps/line: " + samps +
           "\r\n\\@4:Image Data: S [ZSensor] \"Height Sensor\"\r\n"
           "\\@4:Z scale: V [Sens. ZsensSens] (0.0001000000 V/LSB) 1.000000 V\r\n";
    return h + "\\*File list end\r\n\x1a";
  };
  std::size_t size = 64;
  while (header(size).size() > size) size += 64;  // the size is written in the header itself
  std::string out = header(size);
  out.resize(size, '\0');
  return out + defl + z;
}

}  // namespace test
