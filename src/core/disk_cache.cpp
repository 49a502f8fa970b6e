// The on-disk store of a Context's kernels and tables (disk_cache.hpp).
#include "core/disk_cache.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <libdeflate.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <string>
#include <system_error>
#include <vector>

#include "layerjkr/error.hpp"
#include "layerjkr/provenance.hpp"

namespace layerjkr {
namespace {

constexpr char kMagic[16] = "layerjkr-cache\n";  // 15 characters and the NUL
constexpr std::uint32_t kFormat = 1;
constexpr std::uint64_t kMinBytes = std::uint64_t{1} << 20;
constexpr std::uint64_t kMaxMegabytes = std::uint64_t{1} << 30;  // 1 PiB: any disk

std::string env(const char* name) {
  const char* v = std::getenv(name);
  return v ? std::string(v) : std::string();
}

}  // namespace

DiskCacheOptions DiskCacheOptions::from_environment() {
  DiskCacheOptions o;
  o.enabled = true;
  std::string flag = env("LAYERJKR_CACHE");
  std::transform(flag.begin(), flag.end(), flag.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (flag == "off" || flag == "0" || flag == "false" || flag == "no") o.enabled = false;
  else if (!flag.empty() && flag != "on" && flag != "1" && flag != "true" && flag != "yes")
    throw InputError("LAYERJKR_CACHE = '" + env("LAYERJKR_CACHE") + "': expected on or off (1/0, true/false, yes/no)");
  o.directory = env("LAYERJKR_CACHE_DIR");
  const std::string mb = env("LAYERJKR_CACHE_MAX_MB");
  if (!mb.empty()) {
    char* end = nullptr;
    errno = 0;
    const unsigned long long v = std::strtoull(mb.c_str(), &end, 10);
    if (errno != 0 || end == mb.c_str() || *end != '\0' || mb[0] == '-' || v < 1 || v > kMaxMegabytes)
      throw InputError("LAYERJKR_CACHE_MAX_MB = '" + mb + "': expected a whole number of MiB in [1, " +
                       std::to_string(kMaxMegabytes) + "]");
    o.max_bytes = static_cast<std::uint64_t>(v) << 20;
  }
  return o;
}

std::string DiskCacheOptions::resolved_directory() const {
  if (!directory.empty()) return directory;
  if (const std::string xdg = env("XDG_CACHE_HOME"); !xdg.empty()) return xdg + "/layerjkr";
  if (const std::string home = env("HOME"); !home.empty()) return home + "/.cache/layerjkr";
  return {};
}

void DiskCacheOptions::validate() const {
  if (max_bytes < kMinBytes)
    throw DomainError("DiskCacheOptions", "max_bytes", static_cast<double>(max_bytes), ">= 1048576 (1 MiB)");
}

namespace detail {
namespace {

std::uint64_t fnv1a(const std::string& bytes) {
  std::uint64_t h = 0xcbf29ce484222325ULL;
  for (unsigned char c : bytes) h = (h ^ c) * 0x100000001b3ULL;
  return h;
}

void put(std::string& out, const void* p, std::size_t n) { out.append(static_cast<const char*>(p), n); }
void put_u32(std::string& out, std::uint32_t v) { put(out, &v, sizeof v); }
void put_u64(std::string& out, std::uint64_t v) { put(out, &v, sizeof v); }
void put_text(std::string& out, std::string_view s) {
  put_u32(out, static_cast<std::uint32_t>(s.size()));
  out.append(s);
}
void put_doubles(std::string& out, const std::vector<double>& v) {
  put_u64(out, v.size());
  put(out, v.data(), v.size() * sizeof(double));
}

// The file's bytes up to the payload: what identifies the entry.
std::string identity(std::string_view kind, const std::vector<double>& key) {
  std::string s(kMagic, sizeof kMagic);
  put_u32(s, kFormat);
  put_text(s, version());
  put_text(s, kind);
  put_doubles(s, key);
  return s;
}

bool read_whole(const std::string& path, std::string& out) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) return false;
  struct stat st {};
  bool ok = ::fstat(fd, &st) == 0 && S_ISREG(st.st_mode) && st.st_size < (std::int64_t{1} << 34);
  if (ok) {
    out.resize(static_cast<std::size_t>(st.st_size));
    std::size_t done = 0;
    while (ok && done < out.size()) {
      const ssize_t n = ::pread(fd, out.data() + done, out.size() - done, static_cast<off_t>(done));
      if (n < 0 && errno == EINTR) continue;
      ok = n > 0;
      if (ok) done += static_cast<std::size_t>(n);
    }
  }
  ::close(fd);
  return ok;
}

bool write_all(int fd, const std::string& bytes) {
  std::size_t done = 0;
  while (done < bytes.size()) {
    const ssize_t n = ::write(fd, bytes.data() + done, bytes.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    done += static_cast<std::size_t>(n);
  }
  return true;
}

}  // namespace

DiskCache::DiskCache(const DiskCacheOptions& options) : max_bytes_(options.max_bytes) {
  if (!options.enabled) return;
  options.validate();
  directory_ = options.resolved_directory();
}

std::string DiskCache::path_of(std::string_view kind, const std::vector<double>& key) const {
  char hex[17];
  std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(fnv1a(identity(kind, key))));
  return directory_ + "/" + std::string(kind) + "-" + hex + ".bin";
}

std::optional<std::vector<double>> DiskCache::load(std::string_view kind, const std::vector<double>& key) const {
  const std::string path = path_of(kind, key);
  std::string bytes;
  if (!read_whole(path, bytes)) {
    ++misses_;
    return std::nullopt;
  }
  const std::string id = identity(kind, key);
  std::uint64_t n = 0;
  const std::size_t head = id.size() + sizeof n;
  bool ok = bytes.size() >= head + sizeof(std::uint32_t) && bytes.compare(0, id.size(), id) == 0;
  if (ok) {
    std::memcpy(&n, bytes.data() + id.size(), sizeof n);
    ok = n <= (bytes.size() - head) / sizeof(double) && bytes.size() == head + n * sizeof(double) + sizeof(std::uint32_t);
  }
  if (ok) {
    std::uint32_t crc = 0;
    std::memcpy(&crc, bytes.data() + bytes.size() - sizeof crc, sizeof crc);
    ok = libdeflate_crc32(0, bytes.data(), bytes.size() - sizeof crc) == crc;
  }
  if (!ok) {  // another version's or key's file under this name, or a damaged one: rebuilt
    ++misses_;
    return std::nullopt;
  }
  std::vector<double> payload(static_cast<std::size_t>(n));
  std::memcpy(payload.data(), bytes.data() + head, payload.size() * sizeof(double));
  ::utimensat(AT_FDCWD, path.c_str(), nullptr, 0);  // recently used: trimmed last
  ++hits_;
  return payload;
}

void DiskCache::store(std::string_view kind, const std::vector<double>& key, const std::vector<double>& payload) const {
  std::error_code ec;
  std::filesystem::create_directories(directory_, ec);
  std::string bytes = identity(kind, key);
  put_doubles(bytes, payload);
  put_u32(bytes, libdeflate_crc32(0, bytes.data(), bytes.size()));
  const std::string path = path_of(kind, key);
  std::string temp = path + ".XXXXXX";
  const int fd = ::mkstemp(temp.data());
  if (fd < 0) {
    ++errors_;
    return;
  }
  ::fchmod(fd, 0644);  // mkstemp's 0600 would hide the entry from a cluster job's other users
  const bool written = write_all(fd, bytes);
  const bool closed = ::close(fd) == 0;
  if (!written || !closed || ::rename(temp.c_str(), path.c_str()) != 0) {
    ::unlink(temp.c_str());
    ++errors_;
    return;
  }
  ++writes_;
  trim();
}

void DiskCache::trim() const {
  namespace fs = std::filesystem;
  struct Entry {
    fs::file_time_type time;
    std::uint64_t size;
    fs::path path;
  };
  std::vector<Entry> entries;
  std::uint64_t total = 0;
  std::error_code ec;
  const auto now = fs::file_time_type::clock::now();
  for (fs::directory_iterator it(directory_, ec), end; !ec && it != end; it.increment(ec)) {
    const fs::path& p = it->path();
    const std::string name = p.filename().string();
    std::error_code e;
    const auto time = fs::last_write_time(p, e);
    const std::uint64_t size = fs::file_size(p, e);
    if (e) continue;
    // A writer that died leaves its temporary file: gone after an hour (a live one takes ms).
    if (name.find(".bin.") != std::string::npos) {
      if (now - time > std::chrono::hours(1)) fs::remove(p, e);
      continue;
    }
    if (p.extension() != ".bin") continue;  // not ours
    entries.push_back({time, size, p});
    total += size;
  }
  if (total <= max_bytes_) return;
  std::sort(entries.begin(), entries.end(), [](const Entry& a, const Entry& b) { return a.time < b.time; });
  for (const Entry& e : entries) {
    if (total <= max_bytes_ - max_bytes_ / 5) break;  // down to 80 %: not a trim per write
    std::error_code gone;
    fs::remove(e.path, gone);  // another process may have removed it first
    total -= e.size;
  }
}

}  // namespace detail
}  // namespace layerjkr
