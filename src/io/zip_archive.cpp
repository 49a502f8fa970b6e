// The zip index (zip_archive.hpp): the end records and the central directory, read in chunks;
// entries found by an open-addressing hash of their names; each read one positioned read of
// the local header and data, inflated by libdeflate (raw deflate, whole buffer: the central
// directory gives each entry's size) and checked against size and CRC-32.
#include "io/zip_archive.hpp"

#include <libdeflate.h>

#include <algorithm>
#include <cstdio>
#include <cstring>

#include "layerjkr/error.hpp"

namespace layerjkr::detail {
namespace {

constexpr std::uint32_t kLocalSignature = 0x04034b50, kCentralSignature = 0x02014b50,
                        kEndSignature = 0x06054b50, kEnd64Signature = 0x06064b50, kLocator64Signature = 0x07064b50;
constexpr std::uint16_t kDeflated = 8;  // the zip method number of deflate
constexpr std::size_t kEndSize = 22, kLocator64Size = 20, kEnd64Size = 56, kCentralSize = 46, kLocalSize = 30;

std::string mib(std::uint64_t bytes) {
  char text[32];
  std::snprintf(text, sizeof text, "%.1f", static_cast<double>(bytes) / (1024.0 * 1024.0));
  return std::to_string(bytes) + " bytes (" + text + " MiB)";
}

std::uint64_t le(const char* p, int n) {
  std::uint64_t v = 0;
  for (int i = n - 1; i >= 0; --i) v = (v << 8) | static_cast<unsigned char>(p[i]);
  return v;
}
std::uint16_t u16(const char* p) { return static_cast<std::uint16_t>(le(p, 2)); }
std::uint32_t u32(const char* p) { return static_cast<std::uint32_t>(le(p, 4)); }
std::uint64_t u64(const char* p) { return le(p, 8); }

// A word at a time: FNV-1a's byte loop over the ~50-byte names of a map was 4 % of reading.
std::uint64_t hash_name(std::string_view s) {
  std::uint64_t h = 0x9E3779B97F4A7C15ULL ^ s.size();
  std::size_t i = 0;
  std::uint64_t w = 0;
  for (; i + 8 <= s.size(); i += 8) {
    std::memcpy(&w, s.data() + i, 8);
    h = (h ^ w) * 0xFF51AFD7ED558CCDULL;
    h ^= h >> 32;
  }
  w = 0;
  if (i < s.size()) std::memcpy(&w, s.data() + i, s.size() - i);
  h = (h ^ w) * 0xC4CEB9FE1A85EC53ULL;
  return h ^ (h >> 29);  // the table takes the low bits: fold the well-mixed high ones in
}

// A decompressor per thread: allocating one (its tables, ~32 KB) costs more than a small entry.
// libdeflate inflates a whole buffer of known size, 2-3x zlib's speed on JPK channels
// (bench/map_reading), and its CRC-32 folds several bytes a step.
struct Decompressor {
  libdeflate_decompressor* d = libdeflate_alloc_decompressor();
  Decompressor() = default;
  ~Decompressor() { libdeflate_free_decompressor(d); }
  Decompressor(const Decompressor&) = delete;
  Decompressor& operator=(const Decompressor&) = delete;
};

}  // namespace

ZipArchive::ZipArchive(const std::string& path, const ReadLimits& limits)
    : path_(path), limits_(limits), bytes_(PositionedFile::open(path)) {
  read_directory();
  index_names();
}

ZipArchive::ZipArchive(std::string bytes, const std::string& path, const ReadLimits& limits)
    : path_(path), limits_(limits), bytes_(PositionedFile::of_bytes(std::move(bytes))) {
  read_directory();
  index_names();
}

ZipArchive::~ZipArchive() = default;

void ZipArchive::read_directory() {
  const std::uint64_t file_size = bytes_->size();
  auto not_zip = [&](const std::string& why) {
    throw InputError(path_ + ": cannot read it as a zip archive (" + why + ")");
  };
  if (file_size < kEndSize) not_zip("shorter than a zip's end record");
  // The end record sits in the last 22 bytes plus a comment of at most 65535.
  const std::size_t tail_size = static_cast<std::size_t>(std::min<std::uint64_t>(file_size, kEndSize + 65535));
  std::string tail(tail_size, '\0');
  if (!bytes_->read(file_size - tail_size, tail_size, tail.data())) not_zip("cannot read its end");
  std::size_t end = std::string::npos;
  for (std::size_t i = tail_size - kEndSize + 1; i-- > 0;)
    if (u32(&tail[i]) == kEndSignature && i + kEndSize + u16(&tail[i + 20]) == tail_size) {
      end = i;
      break;
    }
  if (end == std::string::npos) not_zip("no end of central directory record");
  const char* e = &tail[end];
  std::uint64_t entries = u16(e + 10), cd_size = u32(e + 12), cd_offset = u32(e + 16);
  if (u16(e + 4) != 0 || u16(e + 6) != 0) not_zip("it spans several disks");
  const std::uint64_t end_at = file_size - tail_size + end;
  if (end_at >= kLocator64Size && end >= kLocator64Size && u32(e - kLocator64Size) == kLocator64Signature) {
    const std::uint64_t at = u64(e - kLocator64Size + 8);
    char r[kEnd64Size];
    if (at > end_at - kLocator64Size || end_at - kLocator64Size - at < kEnd64Size || !bytes_->read(at, kEnd64Size, r) ||
        u32(r) != kEnd64Signature)
      not_zip("its zip64 end record is missing or corrupt");
    entries = u64(r + 32);
    cd_size = u64(r + 40);
    cd_offset = u64(r + 48);
  }
  if (cd_offset > end_at || cd_size > end_at - cd_offset) not_zip("its central directory lies outside the file");
  if (entries > cd_size / kCentralSize) not_zip("it declares more entries than its central directory can hold");
  entries_.reserve(static_cast<std::size_t>(entries));
  // The directory in chunks: a map's directory is 100 MB, held only as the compact index.
  std::string chunk;
  std::uint64_t chunk_at = cd_offset;  // file offset of chunk[0]
  std::size_t pos = 0;
  auto need = [&](std::size_t n) -> const char* {
    if (pos + n > chunk.size()) {
      chunk.erase(0, pos);
      chunk_at += pos;
      pos = 0;
      const std::uint64_t left = cd_offset + cd_size - (chunk_at + chunk.size());
      const std::size_t more = static_cast<std::size_t>(std::min<std::uint64_t>(left, std::max<std::size_t>(n, 1 << 20)));
      if (chunk.size() + more < n) not_zip("its central directory is truncated");
      const std::size_t old = chunk.size();
      chunk.resize(old + more);
      if (!bytes_->read(chunk_at + old, more, &chunk[old])) not_zip("cannot read its central directory");
    }
    const char* p = &chunk[pos];
    pos += n;
    return p;
  };
  for (std::uint64_t k = 0; k < entries; ++k) {
    const char* c = need(kCentralSize);
    if (u32(c) != kCentralSignature) not_zip("central directory entry " + std::to_string(k) + " is corrupt");
    Entry en;
    en.encrypted = (u16(c + 8) & 1) != 0;
    en.method = u16(c + 10);
    en.crc = u32(c + 16);
    en.compressed = u32(c + 20);
    en.size = u32(c + 24);
    const std::size_t name_length = u16(c + 28), extra_length = u16(c + 30), comment_length = u16(c + 32);
    const bool far_disk = u16(c + 34) != 0;
    en.local_offset = u32(c + 42);
    if (names_.size() + name_length > UINT32_MAX) not_zip("its entry names pass 4 GiB");
    en.name_offset = static_cast<std::uint32_t>(names_.size());
    en.name_length = static_cast<std::uint16_t>(name_length);
    names_.append(need(name_length), name_length);
    const auto entry_name = [&] { return "entry '" + names_.substr(en.name_offset, en.name_length) + "'"; };
    // The zip64 extra field holds, in order, the sizes and offset whose 32-bit fields are full.
    const char* extra = need(extra_length);
    for (std::size_t at = 0; at + 4 <= extra_length;) {
      const std::size_t id = u16(extra + at), length = u16(extra + at + 2);
      if (at + 4 + length > extra_length) break;
      if (id == 1) {
        std::size_t f = at + 4;
        for (std::uint64_t* field : {&en.size, &en.compressed, &en.local_offset})
          if (*field == UINT32_MAX) {
            if (f + 8 > at + 4 + length) not_zip(entry_name() + " has a short zip64 field");
            *field = u64(extra + f);
            f += 8;
          }
      }
      at += 4 + length;
    }
    need(comment_length);
    if (far_disk) not_zip(entry_name() + " is on another disk");
    if (en.local_offset > cd_offset || en.compressed > cd_offset - en.local_offset)
      not_zip(entry_name() + " declares data outside the file");
    entries_.push_back(en);
  }
}

std::string_view ZipArchive::name(std::size_t i) const {
  const Entry& en = entries_.at(i);
  return std::string_view(names_).substr(en.name_offset, en.name_length);
}

void ZipArchive::index_names() {
  std::size_t capacity = 16;
  while (capacity < 2 * entries_.size()) capacity *= 2;
  table_.assign(capacity, 0);
  for (std::size_t i = 0; i < entries_.size(); ++i) {
    const std::string_view n = name(i);
    for (std::size_t slot = hash_name(n) & (capacity - 1);; slot = (slot + 1) & (capacity - 1)) {
      if (table_[slot] == 0) {
        table_[slot] = static_cast<std::uint32_t>(i + 1);
        break;
      }
      // A second entry of one name would be read in place of the first or never: ambiguous.
      if (name(table_[slot] - 1) == n)
        throw InputError(path_ + ": the archive holds the entry '" + std::string(n) + "' twice");
    }
  }
}

std::optional<std::size_t> ZipArchive::find(std::string_view n) const {
  const std::size_t mask = table_.size() - 1;
  for (std::size_t slot = hash_name(n) & mask; table_[slot] != 0; slot = (slot + 1) & mask)
    if (name(table_[slot] - 1) == n) return table_[slot] - 1;
  return std::nullopt;
}

std::optional<std::uint64_t> ZipArchive::declared_size(std::string_view n) const {
  const std::optional<std::size_t> i = find(n);
  if (!i) return std::nullopt;
  return entries_[*i].size;
}

std::string ZipArchive::read(std::string_view n) const {
  // Built only for an error: a string per read showed in the profile of a map.
  const auto where = [&] { return path_ + ": entry '" + std::string(n) + "'"; };
  const std::optional<std::size_t> i = find(n);
  if (!i) throw InputError(path_ + ": the archive has no entry '" + std::string(n) + "'");
  const Entry& en = entries_[*i];
  if (en.encrypted) throw InputError(where() + " is encrypted; encrypted archives are not read");
  if (en.method != 0 && en.method != kDeflated)
    throw InputError(where() + " is compressed with method " + std::to_string(en.method) +
                     "; only stored (0) and deflate (8) entries are read");
  // The declared size bounds the allocation: check it before allocating anything.
  if (en.size > limits_.max_member_bytes)
    throw InputError(where() + " declares " + mib(en.size) + " uncompressed, over the limit of " +
                     mib(limits_.max_member_bytes) + " per entry; raise it with " + kMaxMemberEnv +
                     "=<MiB> (ReadLimits::max_member_bytes in the library) if the file is genuine");
  const std::uint64_t before = bytes_read_.fetch_add(en.size);
  if (en.size > limits_.max_archive_bytes - std::min(before, limits_.max_archive_bytes))
    throw InputError(where() + " declares " + mib(en.size) + " uncompressed, which with the " + mib(before) +
                     " read before passes the limit of " + mib(limits_.max_archive_bytes) + " per archive; raise it with " +
                     kMaxArchiveEnv + "=<MiB> (ReadLimits::max_archive_bytes in the library) if the file is genuine");
  if (en.compressed > limits_.max_member_bytes + (limits_.max_member_bytes >> 6) + 4096)
    throw InputError(where() + " declares " + mib(en.compressed) + " compressed, more than any entry within the limit needs");
  // One read for the local header and the data, guessing that the local extra field is as
  // long as a zip64 one; a longer one costs a second read.
  thread_local std::string raw;
  const std::size_t head = kLocalSize + en.name_length;
  auto fetch = [&](std::size_t extra) {
    const std::uint64_t want = head + extra + en.compressed;
    const std::uint64_t have = std::min<std::uint64_t>(want, bytes_->size() - en.local_offset);
    raw.resize(static_cast<std::size_t>(have));
    if (!bytes_->read(en.local_offset, raw.size(), raw.data())) throw InputError(where() + ": cannot read it");
    if (raw.size() < head) throw InputError(where() + " is truncated: its local header ends past the file");
  };
  fetch(32);
  if (u32(raw.data()) != kLocalSignature || u16(&raw[26]) != en.name_length ||
      std::memcmp(&raw[kLocalSize], names_.data() + en.name_offset, en.name_length) != 0)
    throw InputError(where() + " is corrupt: its local header does not match the central directory");
  const std::size_t extra = u16(&raw[28]);
  if (head + extra + en.compressed > raw.size()) fetch(extra);
  if (head + extra + en.compressed > raw.size())
    throw InputError(where() + " is truncated: its data end past the file");
  const char* data = raw.data() + head + extra;
  std::string out(static_cast<std::size_t>(en.size), '\0');
  if (en.method == 0) {
    if (en.compressed != en.size)
      throw InputError(where() + " is corrupt: stored with " + std::to_string(en.compressed) + " bytes but declares " +
                       std::to_string(en.size));
    std::memcpy(out.data(), data, out.size());
  } else {
    thread_local Decompressor inflater;
    if (!inflater.d) throw InputError(where() + ": libdeflate could not start (out of memory)");
    std::size_t produced = 0;
    const libdeflate_result rc =
        libdeflate_deflate_decompress(inflater.d, data, static_cast<std::size_t>(en.compressed), out.data(), out.size(), &produced);
    // A stream cut short reads as bad data to libdeflate (it cannot tell an end from damage).
    if (rc == LIBDEFLATE_BAD_DATA) throw InputError(where() + " is corrupt or truncated (invalid deflate data)");
    if (rc == LIBDEFLATE_INSUFFICIENT_SPACE)
      throw InputError(where() + " is corrupt: it holds more than its declared " + std::to_string(out.size()) + " bytes");
    if (rc != LIBDEFLATE_SUCCESS || produced != out.size())
      throw InputError(where() + " is truncated: " + std::to_string(produced) + " of its declared " +
                       std::to_string(out.size()) + " bytes");
  }
  if (raw.capacity() > (std::size_t{16} << 20)) std::string().swap(raw);  // keep no huge buffer per thread
  if (libdeflate_crc32(0, out.data(), out.size()) != en.crc)
    throw InputError(where() + " is corrupt (CRC error): its data do not match the checksum stored in the archive");
  return out;
}

}  // namespace layerjkr::detail
