// The on-disk store of a Context's kernels and tables (disk_cache.hpp).
#include "core/disk_cache.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <openssl/crypto.h>
#include <openssl/evp.h>
#include <openssl/hmac.h>
#include <openssl/rand.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <mutex>
#include <string>
#include <system_error>
#include <vector>

#include "layerjkr/error.hpp"
#include "layerjkr/provenance.hpp"

namespace layerjkr {
namespace {

constexpr char kMagic[16] = "layerjkr-cache\n";  // 15 characters and the NUL
// 2: entries end in an HMAC-SHA-256 under this user's key instead of a CRC-32, which anyone who
// can write the folder could recompute over numbers of their choosing.
constexpr std::uint32_t kFormat = 2;
constexpr std::size_t kKeyBytes = 32, kMacBytes = 32;
constexpr char kKeyName[] = "layerjkr-cache.key";
// No entry is larger (the biggest, a stack's kernel, is a few MB): a file beyond it at an
// entry's name (a sparse 8 GiB file) is refused by its size, before any byte is read.
constexpr std::uint64_t kMaxEntryBytes = std::uint64_t{1} << 30;
constexpr std::size_t kMaxNotices = 8;
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
  std::string shared = env("LAYERJKR_CACHE_SHARED");
  std::transform(shared.begin(), shared.end(), shared.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (shared == "on" || shared == "1" || shared == "true" || shared == "yes") o.shared = true;
  else if (!shared.empty() && shared != "off" && shared != "0" && shared != "false" && shared != "no")
    throw InputError("LAYERJKR_CACHE_SHARED = '" + env("LAYERJKR_CACHE_SHARED") + "': expected on or off (1/0, true/false, yes/no)");
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

// Why the file at `path` cannot be an entry of this user's cache, or "" with its bytes in `out`.
// Opened without following a link and without blocking (a FIFO at the name would hang the
// open), then only a regular file of this user's, of an entry's size, is read.
std::string read_entry(const std::string& path, std::uint64_t max_size, std::string& out, bool* absent) {
  *absent = false;
  const int fd = ::open(path.c_str(), O_RDONLY | O_NOFOLLOW | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) {
    *absent = errno == ENOENT;
    return errno == ELOOP ? "is a symbolic link" : std::strerror(errno);
  }
  struct stat st {};
  std::string why;
  if (::fstat(fd, &st) != 0) why = std::strerror(errno);
  else if (!S_ISREG(st.st_mode)) why = "is not a regular file";
  else if (st.st_uid != ::geteuid()) why = "belongs to uid " + std::to_string(st.st_uid) + ", not this user";
  else if (static_cast<std::uint64_t>(st.st_size) > max_size)
    why = "holds " + std::to_string(st.st_size) + " bytes, more than an entry's " + std::to_string(max_size);
  if (why.empty()) {
    out.resize(static_cast<std::size_t>(st.st_size));
    std::size_t done = 0;
    while (why.empty() && done < out.size()) {
      const ssize_t n = ::pread(fd, out.data() + done, out.size() - done, static_cast<off_t>(done));
      if (n < 0 && errno == EINTR) continue;
      if (n <= 0) why = n < 0 ? std::strerror(errno) : "was truncated while read";
      else done += static_cast<std::size_t>(n);
    }
  }
  ::close(fd);
  return why;
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

std::string mode_text(mode_t m) {
  char buf[8];
  std::snprintf(buf, sizeof buf, "%04o", static_cast<unsigned>(m & 07777));
  return buf;
}

}  // namespace

DiskCache::DiskCache(const DiskCacheOptions& options) : max_bytes_(options.max_bytes) {
  if (!options.enabled) return;
  options.validate();
  directory_ = options.resolved_directory();
  if (directory_.empty()) return;
  if (!prepare_directory(options.shared) || !load_key()) {
    directory_.clear();
    ++errors_;
  }
}

bool DiskCache::prepare_directory(bool shared) {
  namespace fs = std::filesystem;
  const fs::path dir(directory_);
  std::error_code ec;
  if (dir.has_parent_path()) fs::create_directories(dir.parent_path(), ec);
  // Private unless the folder exists already: 0700, so that no one else can place entries.
  if (::mkdir(directory_.c_str(), 0700) != 0 && errno != EEXIST) {
    note("disk cache off: cannot create " + directory_ + ": " + std::strerror(errno));
    return false;
  }
  struct stat st {};
  if (::stat(directory_.c_str(), &st) != 0 || !S_ISDIR(st.st_mode)) {
    note("disk cache off: " + directory_ + " is not a directory");
    return false;
  }
  if (shared) return true;  // entries are still checked against this user's own key
  const std::string opt_in = " (LAYERJKR_CACHE_SHARED=1, DiskCacheOptions::shared, uses it anyway: entries stay "
                             "authenticated by this user's own key, so no one else's are trusted)";
  if (st.st_uid != ::geteuid()) {
    note("disk cache off: " + directory_ + " belongs to uid " + std::to_string(st.st_uid) + ", not this user (uid " +
         std::to_string(::geteuid()) + ")" + opt_in);
    return false;
  }
  if ((st.st_mode & (S_IWGRP | S_IWOTH)) != 0) {
    note("disk cache off: " + directory_ + " is writable by others (mode " + mode_text(st.st_mode) + ")" + opt_in);
    return false;
  }
  return true;
}

// The key that authenticates this user's entries: 32 random bytes in a 0600 file of the
// user's in the folder, made once (linked into place, so concurrent first runs agree on one).
bool DiskCache::load_key() {
  const std::string path = directory_ + "/" + kKeyName;
  for (int attempt = 0; attempt < 2; ++attempt) {
    std::string key;
    bool absent = false;
    const std::string why = read_entry(path, kKeyBytes, key, &absent);
    if (why.empty() && key.size() == kKeyBytes) {
      struct stat st {};
      if (::lstat(path.c_str(), &st) == 0 && (st.st_mode & 077) == 0) {
        key_ = key;
        return true;
      }
    }
    if (!absent) {
      note("disk cache off: its key " + path + (why.empty() ? " is not a private 32-byte file (mode 0600)" : " " + why));
      return false;
    }
    unsigned char bytes[kKeyBytes];
    if (RAND_bytes(bytes, static_cast<int>(kKeyBytes)) != 1) {
      note("disk cache off: no random bytes for its key");
      return false;
    }
    std::string temp = path + ".XXXXXX";
    const int fd = ::mkstemp(temp.data());  // 0600
    if (fd < 0) {
      note("disk cache off: cannot write its key in " + directory_ + ": " + std::strerror(errno));
      return false;
    }
    const bool written = write_all(fd, std::string(reinterpret_cast<const char*>(bytes), kKeyBytes));
    ::close(fd);
    if (written) (void)::link(temp.c_str(), path.c_str());  // EEXIST: another process made it first
    ::unlink(temp.c_str());
  }
  note("disk cache off: its key " + path + " could not be made");
  return false;
}

std::string DiskCache::mac(const std::string& bytes) const {
  unsigned char out[EVP_MAX_MD_SIZE];
  unsigned int len = 0;
  if (!HMAC(EVP_sha256(), key_.data(), static_cast<int>(key_.size()), reinterpret_cast<const unsigned char*>(bytes.data()),
            bytes.size(), out, &len) ||
      len != kMacBytes)
    return {};
  return std::string(reinterpret_cast<const char*>(out), len);
}

void DiskCache::note(const std::string& message) const {
  const std::lock_guard<std::mutex> lock(notes_mutex_);
  if (notes_.size() < kMaxNotices && std::find(notes_.begin(), notes_.end(), message) == notes_.end())
    notes_.push_back(message);
}

std::vector<std::string> DiskCache::notices() const {
  const std::lock_guard<std::mutex> lock(notes_mutex_);
  return notes_;
}

std::string DiskCache::path_of(std::string_view kind, const std::vector<double>& key) const {
  char hex[17];
  std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(fnv1a(identity(kind, key))));
  return directory_ + "/" + std::string(kind) + "-" + hex + ".bin";
}

std::optional<std::vector<double>> DiskCache::load(std::string_view kind, const std::vector<double>& key) const {
  const std::string path = path_of(kind, key);
  std::string bytes;
  bool absent = false;
  const std::string unreadable = read_entry(path, std::min(max_bytes_, kMaxEntryBytes), bytes, &absent);
  if (!unreadable.empty()) {
    if (!absent) note("disk cache: " + path + " " + unreadable + ": not used, the entry is rebuilt");
    ++misses_;
    return std::nullopt;
  }
  const std::string id = identity(kind, key);
  std::uint64_t n = 0;
  const std::size_t head = id.size() + sizeof n;
  bool ok = bytes.size() >= head + kMacBytes && bytes.compare(0, id.size(), id) == 0;
  if (ok) {
    std::memcpy(&n, bytes.data() + id.size(), sizeof n);
    ok = n <= (bytes.size() - head) / sizeof(double) && bytes.size() == head + n * sizeof(double) + kMacBytes;
  }
  if (ok) {
    const std::string expected = mac(bytes.substr(0, bytes.size() - kMacBytes));
    ok = expected.size() == kMacBytes && CRYPTO_memcmp(expected.data(), bytes.data() + bytes.size() - kMacBytes, kMacBytes) == 0;
  }
  if (!ok) {  // damaged, another version's or key's, or not written under this user's key: rebuilt
    note("disk cache: " + path + " is damaged or was not written by this user's cache (its authentication "
         "failed): not used, the entry is rebuilt");
    ++misses_;
    return std::nullopt;
  }
  std::vector<double> payload(static_cast<std::size_t>(n));
  std::memcpy(payload.data(), bytes.data() + head, payload.size() * sizeof(double));
  ::utimensat(AT_FDCWD, path.c_str(), nullptr, AT_SYMLINK_NOFOLLOW);  // recently used: trimmed last
  ++hits_;
  return payload;
}

void DiskCache::store(std::string_view kind, const std::vector<double>& key, const std::vector<double>& payload) const {
  std::string bytes = identity(kind, key);
  put_doubles(bytes, payload);
  const std::string tag = mac(bytes);
  if (tag.size() != kMacBytes) {
    ++errors_;
    return;
  }
  bytes += tag;
  const std::string path = path_of(kind, key);
  std::string temp = path + ".XXXXXX";
  const int fd = ::mkstemp(temp.data());  // 0600: only this user reads what only this user can verify
  if (fd < 0) {
    ++errors_;
    return;
  }
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

namespace {

// <kind>-<16 hex digits>.bin, the kind in [a-z0-9-]; with `temporary`, followed by mkstemp's
// ".XXXXXX". Only such names are the cache's to remove.
bool entry_name(const std::string& name, bool temporary) {
  std::size_t end = name.size();
  if (temporary) {
    if (end < 7 || name[end - 7] != '.') return false;
    for (std::size_t i = end - 6; i < end; ++i)
      if (!std::isalnum(static_cast<unsigned char>(name[i]))) return false;
    end -= 7;
  }
  const std::string tail = ".bin";
  if (end < 1 + 1 + 16 + tail.size() || name.compare(end - tail.size(), tail.size(), tail) != 0) return false;
  const std::size_t hex = end - tail.size() - 16;
  if (name[hex - 1] != '-') return false;
  for (std::size_t i = hex; i < hex + 16; ++i)
    if (!std::isxdigit(static_cast<unsigned char>(name[i])) || std::isupper(static_cast<unsigned char>(name[i]))) return false;
  for (std::size_t i = 0; i + 1 < hex; ++i) {
    const auto c = static_cast<unsigned char>(name[i]);
    if (!(std::islower(c) || std::isdigit(c) || c == '-')) return false;
  }
  return true;
}

// The cache's mark: the file starts with the magic (an empty temporary file is a writer that
// died before writing). Opened as load() opens entries.
bool marked(const std::string& path, bool empty_ok) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_NOFOLLOW | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) return false;
  struct stat st {};
  char head[sizeof kMagic];
  bool ok = ::fstat(fd, &st) == 0 && S_ISREG(st.st_mode) && st.st_uid == ::geteuid();
  if (ok) ok = (empty_ok && st.st_size == 0) ||
               (::pread(fd, head, sizeof head, 0) == static_cast<ssize_t>(sizeof head) && std::memcmp(head, kMagic, sizeof head) == 0);
  ::close(fd);
  return ok;
}

}  // namespace

// Removes only what the cache wrote: files of an entry's name, this user's, regular (links are
// not followed), starting with the cache's magic - never a user's own *.bin or *.bin.* file in
// the folder LAYERJKR_CACHE_DIR names.
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
    const bool temporary = entry_name(name, true);
    if (!temporary && !entry_name(name, false)) continue;  // not ours
    std::error_code e;
    if (!fs::is_regular_file(fs::symlink_status(p, e)) || e) continue;
    const auto time = fs::last_write_time(p, e);
    const std::uint64_t size = fs::file_size(p, e);
    if (e) continue;
    // A writer that died leaves its temporary file: gone after an hour (a live one takes ms).
    if (temporary) {
      if (now - time > std::chrono::hours(1) && marked(p.string(), true)) fs::remove(p, e);
      continue;
    }
    entries.push_back({time, size, p});
    total += size;
  }
  if (total <= max_bytes_) return;
  std::sort(entries.begin(), entries.end(), [](const Entry& a, const Entry& b) { return a.time < b.time; });
  for (const Entry& e : entries) {
    if (total <= max_bytes_ - max_bytes_ / 5) break;  // down to 80 %: not a trim per write
    if (!marked(e.path.string(), false)) continue;
    std::error_code gone;
    fs::remove(e.path, gone);  // another process may have removed it first
    total -= e.size;
  }
}

}  // namespace detail
}  // namespace layerjkr
