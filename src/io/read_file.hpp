// Internal: a whole file as bytes, for the readers that parse from memory.
#pragma once

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <system_error>

#include "layerjkr/error.hpp"

namespace layerjkr::detail {

/// What read_file reads unless its caller sets a limit: 512 MiB.
constexpr std::uint64_t kDefaultMaxFileBytes = std::uint64_t{512} << 20;

/// "512 MiB" for a whole number of MiB, else the byte count.
inline std::string describe_bytes(std::uint64_t n) {
  return n % (1u << 20) == 0 ? std::to_string(n >> 20) + " MiB" : std::to_string(n) + " bytes";
}

// Why `path` is not a regular file the readers may open, or "" when it is one. Checked before
// opening: opening a FIFO blocks until someone writes to it (fit_files, provenance's record_file).
inline std::string not_a_file(const std::string& path) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::file_status st = fs::status(path, ec);
  if (fs::is_regular_file(st)) return {};
  if (fs::is_directory(st)) return path + ": is a directory, not a curve file";
  if (fs::is_fifo(st)) return path + ": is a FIFO (named pipe), not a regular file; not opened, reading it could block";
  if (fs::is_socket(st)) return path + ": is a socket, not a regular file";
  if (fs::is_block_file(st) || fs::is_character_file(st)) return path + ": is a device, not a regular file";
  if (ec == std::errc::too_many_symbolic_link_levels) return path + ": is a symbolic link loop";
  std::error_code lec;
  if (fs::is_symlink(fs::symlink_status(path, lec))) return path + ": is a dangling symbolic link (its target does not exist)";
  if (ec) return path + ": cannot be read (" + ec.message() + ")";
  return path + ": is not a regular file";
}

/// The file's bytes, at most `max_bytes` of them. Throws InputError naming the path for a
/// file that cannot be opened or read, a directory or device (/dev/urandom would never
/// end), or a file larger than the limit (naming the limit and `raise_with`, how to raise
/// it). Pipes are read up to the limit. The text is read once into its final string.
inline std::string read_file(const std::string& path, const std::string& what,
                             std::uint64_t max_bytes = kDefaultMaxFileBytes,
                             const std::string& raise_with = "") {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::file_status st = fs::status(path, ec);
  const std::string limit = "the limit for " + what + " is " + describe_bytes(max_bytes) +
                            (raise_with.empty() ? "" : "; raise it with " + raise_with);
  if (!ec && (fs::is_directory(st) || fs::is_character_file(st) || fs::is_block_file(st) ||
              fs::is_socket(st)))
    throw InputError(path + ": cannot read " + what + ": not a regular file");
  std::ifstream file(path, std::ios::binary);
  if (!file) throw InputError(path + ": cannot open " + what);
  std::string text;
  if (fs::is_regular_file(st)) {
    const std::uintmax_t size = fs::file_size(path, ec);
    if (!ec && size > max_bytes)
      throw InputError(path + ": " + what + " has " + std::to_string(size) + " bytes; " + limit);
    if (!ec) text.reserve(static_cast<std::size_t>(size));
  }
  // Chunks up to the limit: a file that grows or a pipe cannot exceed it either.
  char chunk[1 << 16];
  while (file.read(chunk, sizeof chunk) || file.gcount() > 0) {
    text.append(chunk, static_cast<std::size_t>(file.gcount()));
    if (text.size() > max_bytes) throw InputError(path + ": " + what + " is larger than allowed; " + limit);
  }
  if (file.bad()) throw InputError(path + ": cannot read " + what);
  return text;
}

}  // namespace layerjkr::detail
