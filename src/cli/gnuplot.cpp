// The gnuplot pipe and the mark on its pictures (gnuplot.hpp).
#include "gnuplot.hpp"

#include <libdeflate.h>

#include <array>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>

#include "layerjkr/error.hpp"

namespace layerjkr::cli {
namespace {

constexpr std::array<unsigned char, 8> kPngSignature{0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
constexpr std::size_t kHeaderEnd = 8 + 4 + 4 + 13 + 4;  // the signature and the IHDR chunk
// tEXt: keyword "Software" (registered by the PNG specification), a NUL, the text.
const std::string kMarkData = std::string("Software") + '\0' + "layerjkr";

std::string big_endian(std::uint32_t v) {
  return {static_cast<char>(v >> 24), static_cast<char>(v >> 16), static_cast<char>(v >> 8), static_cast<char>(v)};
}

std::string mark_chunk() {
  const std::string body = "tEXt" + kMarkData;
  const std::uint32_t crc = libdeflate_crc32(0, body.data(), body.size());
  return big_endian(static_cast<std::uint32_t>(kMarkData.size())) + body + big_endian(crc);
}

bool starts_as_png(const std::string& bytes) {
  return bytes.size() >= kHeaderEnd && std::equal(kPngSignature.begin(), kPngSignature.end(), bytes.begin(),
                                                  [](unsigned char a, char b) { return a == static_cast<unsigned char>(b); }) &&
         bytes.compare(12, 4, "IHDR") == 0;
}

}  // namespace

void run_gnuplot(const std::string& script, const std::string& png, const std::string& what) {
  std::error_code ec;
  FILE* pipe = popen("gnuplot >/dev/null 2>&1", "w");
  if (!pipe) throw Error(what + ": cannot start gnuplot");
  std::fputs(script.c_str(), pipe);
  const int status = pclose(pipe);
  if (status != 0 || std::filesystem::file_size(png, ec) == 0 || ec)
    throw Error(what + ": gnuplot failed (is it installed? apt-get install gnuplot-nox)");
  mark_png(png);
}

std::string gnuplot_quoted(const std::string& path) {
  if (path.find_first_of("\n\r") != std::string::npos)
    throw InputError("a plot file name holds a line break, which gnuplot cannot take: " + path);
  std::string q = "'";
  for (char c : path) q += c == '\'' ? std::string("''") : std::string(1, c);
  return q + "'";
}

void mark_png(const std::string& path) {
  std::string bytes;
  {
    std::ifstream in(path, std::ios::binary);
    bytes.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  }
  if (!starts_as_png(bytes)) throw Error(path + ": gnuplot did not write a PNG");
  bytes.insert(kHeaderEnd, mark_chunk());
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  out.flush();
  if (!out) throw Error(path + ": cannot write the picture");
}

bool is_marked_png(const std::string& path) {
  const std::string chunk = mark_chunk();
  std::string bytes(kHeaderEnd + chunk.size(), '\0');
  std::ifstream in(path, std::ios::binary);
  in.read(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  return in && starts_as_png(bytes) && bytes.compare(kHeaderEnd, chunk.size(), chunk) == 0;
}

}  // namespace layerjkr::cli
