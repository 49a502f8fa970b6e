// The disk cache of kernels and tables (DiskCacheOptions, context.hpp): what a second process
// loads is bit for bit what the first built; damaged, truncated or foreign files are rebuilt,
// never trusted; concurrent writers leave whole files; the size bound holds, least recently
// used first; a directory that cannot be written costs the rebuild only; the environment's
// switches. Oracles: the same answers with the cache off, and the files themselves.
#include <catch2/catch.hpp>

#include <fcntl.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

#include "core/disk_cache.hpp"
#include "layerjkr/context.hpp"
#include "layerjkr/error.hpp"
#include "layerjkr/exact_layer.hpp"
#include "layerjkr/layered_medium.hpp"
#include "layerjkr/model.hpp"
#include "layerjkr/provenance.hpp"
#include "support/stack_media.hpp"
#include "support/temp_dir.hpp"
#include "support/catch_after_glog.hpp"  // after the internal headers: Catch's CHECK, not glog's

using namespace layerjkr;
namespace fs = std::filesystem;

namespace {

DiskCacheOptions in(const fs::path& dir, std::uint64_t max_bytes = std::uint64_t{512} << 20) {
  DiskCacheOptions o;
  o.enabled = true;
  o.directory = dir.string();
  o.max_bytes = max_bytes;
  return o;
}

ExactLayerOptions with(std::shared_ptr<Context> context) {
  ExactLayerOptions o;
  o.context = std::move(context);
  o.max_a_over_h = 20.0;
  return o;
}

const LayeredMedium kBilayer = test::stack({{3e6, 0.3, 0.1e-3}, {300e6, 0.3, 1.9e-3}});

// A sphere (solved on the kernel) and a paraboloid (from the power-law table) on the stack.
std::vector<NonAdhesiveState> answers(const std::shared_ptr<Context>& context) {
  std::vector<NonAdhesiveState> out;
  const auto sphere = make_exact_layer(make_sphere(5e-3), kBilayer, with(context));
  const auto paraboloid = make_exact_layer(make_paraboloid(5e-3), kBilayer, with(context));
  for (double a : {2e-5, 1e-4, 4e-4}) {
    out.push_back(sphere->state(a));
    out.push_back(paraboloid->state(a));
  }
  return out;
}

bool identical(const std::vector<NonAdhesiveState>& x, const std::vector<NonAdhesiveState>& y) {
  if (x.size() != y.size()) return false;
  for (std::size_t i = 0; i < x.size(); ++i)
    if (!(x[i].P_H == y[i].P_H && x[i].delta_H == y[i].delta_H && x[i].S == y[i].S && x[i].dS_da == y[i].dS_da))
      return false;
  return true;
}

std::vector<fs::path> files(const fs::path& dir) {
  std::vector<fs::path> out;
  for (const auto& e : fs::directory_iterator(dir)) out.push_back(e.path());
  return out;
}

}  // namespace

TEST_CASE("disk cache: a second Context loads the stack's kernel and table pieces, bit for bit", "[disk_cache]") {
  const test::TempDir dir;
  const std::vector<NonAdhesiveState> uncached = answers(std::make_shared<Context>());
  const auto first = std::make_shared<Context>(in(dir.path()));
  CHECK(identical(answers(first), uncached));
  const CacheStats s1 = first->stats();
  CHECK(s1.disk_hits == 0);
  CHECK(s1.disk_writes >= 3);  // the stack's kernel and at least two table pieces
  CHECK(s1.disk_errors == 0);
  const auto second = std::make_shared<Context>(in(dir.path()));
  CHECK(identical(answers(second), uncached));
  const CacheStats s2 = second->stats();
  CHECK(s2.disk_hits == s1.disk_writes);
  CHECK(s2.disk_writes == 0);
  for (const fs::path& p : files(dir.path()))  // no temporary file left: entries and the key
    CHECK((p.extension() == ".bin" || p.filename() == "layerjkr-cache.key"));
}

TEST_CASE("disk cache: damaged, truncated and foreign entries are rebuilt, never trusted", "[disk_cache]") {
  const test::TempDir dir;
  const detail::DiskCache cache(in(dir.path()));
  const std::vector<double> key{0.3, 1.0}, payload{1.0, 2.0, 3.0, -0.0, 1e-300};
  cache.store("test-kind", key, payload);
  REQUIRE(cache.load("test-kind", key) == payload);
  CHECK_FALSE(cache.load("test-kind", {0.3, 0.0}));
  CHECK_FALSE(cache.load("other-kind", key));
  const std::string path = cache.path_of("test-kind", key);
  std::string bytes;
  {
    std::ifstream f(path, std::ios::binary);
    bytes.assign(std::istreambuf_iterator<char>(f), {});
  }
  const auto rewrite = [&](const std::string& b) { std::ofstream(path, std::ios::binary | std::ios::trunc) << b; };
  for (std::size_t i : {std::size_t{3}, std::size_t{20}, bytes.size() - 30, bytes.size() - 1}) {
    std::string damaged = bytes;
    damaged[i] = static_cast<char>(damaged[i] ^ 0x10);
    rewrite(damaged);
    INFO("byte " << i);
    CHECK_FALSE(cache.load("test-kind", key));
  }
  rewrite(bytes.substr(0, bytes.size() / 2));
  CHECK_FALSE(cache.load("test-kind", key));
  rewrite("");
  CHECK_FALSE(cache.load("test-kind", key));
  // Another library version's entry under this name (a hash collision, or a copied cache).
  std::string foreign = bytes;
  const std::size_t v = foreign.find(version());
  REQUIRE(v != std::string::npos);
  foreign[v] = foreign[v] == '9' ? '8' : '9';
  rewrite(foreign);
  CHECK_FALSE(cache.load("test-kind", key));
  rewrite(bytes);
  CHECK(cache.load("test-kind", key) == payload);
}

TEST_CASE("disk cache: a damaged kernel file gives the same answers, rebuilt and rewritten", "[disk_cache]") {
  const test::TempDir dir;
  const std::vector<NonAdhesiveState> uncached = answers(std::make_shared<Context>());
  (void)answers(std::make_shared<Context>(in(dir.path())));
  for (const fs::path& p : files(dir.path())) {  // every entry's payload damaged behind a valid-looking header
    if (p.extension() != ".bin") continue;
    std::fstream f(p, std::ios::in | std::ios::out | std::ios::binary);
    f.seekp(static_cast<std::streamoff>(fs::file_size(p) / 2));
    f.put('\x7f');
  }
  const auto context = std::make_shared<Context>(in(dir.path()));
  CHECK(identical(answers(context), uncached));
  CHECK(context->stats().disk_hits == 0);
  CHECK(context->stats().disk_writes >= 3);
}

TEST_CASE("disk cache: concurrent processes and threads writing the same entries leave whole files", "[disk_cache]") {
  const test::TempDir dir;
  const std::vector<NonAdhesiveState> uncached = answers(std::make_shared<Context>());
  std::vector<pid_t> children;
  for (int k = 0; k < 3; ++k) {
    const pid_t pid = fork();
    REQUIRE(pid >= 0);
    if (pid == 0) {  // a process of its own: its own Context, the same directory
      bool ok = false;
      try {
        ok = identical(answers(std::make_shared<Context>(in(dir.path()))), uncached);
      } catch (...) {
      }
      std::_Exit(ok ? 0 : 1);
    }
    children.push_back(pid);
  }
  std::vector<std::thread> threads;
  std::vector<char> ok(2, 0);
  for (std::size_t k = 0; k < ok.size(); ++k)
    threads.emplace_back([&, k] { ok[k] = identical(answers(std::make_shared<Context>(in(dir.path()))), uncached); });
  for (std::thread& t : threads) t.join();
  for (pid_t pid : children) {
    int status = 0;
    REQUIRE(waitpid(pid, &status, 0) == pid);
    CHECK((WIFEXITED(status) && WEXITSTATUS(status) == 0));
  }
  CHECK((ok[0] && ok[1]));
  const auto after = std::make_shared<Context>(in(dir.path()));
  CHECK(identical(answers(after), uncached));
  CHECK(after->stats().disk_writes == 0);
  for (const fs::path& p : files(dir.path())) CHECK((p.extension() == ".bin" || p.filename() == "layerjkr-cache.key"));
}

TEST_CASE("disk cache: the size bound holds, the least recently used entries go first", "[disk_cache]") {
  const test::TempDir dir;
  const detail::DiskCache cache(in(dir.path(), std::uint64_t{1} << 20));
  const std::vector<double> payload(20000, 1.5);  // 160 kB an entry
  cache.store("bound", {0.0}, payload);
  for (int k = 1; k < 12; ++k) {
    cache.store("bound", {static_cast<double>(k)}, payload);
    // Entry 0 is used between writes: it stays; the others age out in order.
    timespec old[2] = {{0, 0}, {0, 0}};
    for (int j = 1; j <= k; ++j) {  // older mtimes for older entries (a second apart: coarse filesystems)
      old[0] = old[1] = timespec{1000000 + j, 0};
      ::utimensat(AT_FDCWD, cache.path_of("bound", {static_cast<double>(j)}).c_str(), old, 0);
    }
    CHECK(cache.load("bound", {0.0}));
  }
  std::uint64_t total = 0;
  for (const fs::path& p : files(dir.path())) total += fs::file_size(p);  // the key's 32 bytes included
  CHECK(total <= (std::uint64_t{1} << 20));
  CHECK(cache.load("bound", {0.0}));
  CHECK(cache.load("bound", {11.0}));
  CHECK_FALSE(cache.load("bound", {1.0}));
  CHECK_THROWS_AS(detail::DiskCache(in(dir.path(), 1000)), DomainError);
}

TEST_CASE("disk cache: a directory that cannot be written costs the rebuild, not the answer", "[disk_cache]") {
  const test::TempDir dir;
  const fs::path blocked = dir.path() / "file_not_dir";
  std::ofstream(blocked.string()) << "x";  // a file where the directory should be
  const std::vector<NonAdhesiveState> uncached = answers(std::make_shared<Context>());
  const auto context = std::make_shared<Context>(in(blocked / "cache"));
  CHECK(identical(answers(context), uncached));
  CHECK(context->stats().disk_errors >= 1);
  CHECK(context->stats().disk_writes == 0);
}

TEST_CASE("disk cache: LAYERJKR_CACHE, LAYERJKR_CACHE_DIR and LAYERJKR_CACHE_MAX_MB", "[disk_cache]") {
  const auto with_env = [](const char* name, const char* value) {
    if (value) ::setenv(name, value, 1);
    else ::unsetenv(name);
  };
  with_env("LAYERJKR_CACHE", nullptr);
  with_env("LAYERJKR_CACHE_DIR", "/some/where");
  with_env("LAYERJKR_CACHE_MAX_MB", "64");
  DiskCacheOptions o = DiskCacheOptions::from_environment();
  CHECK(o.enabled);
  CHECK(o.resolved_directory() == "/some/where");
  CHECK(o.max_bytes == (std::uint64_t{64} << 20));
  for (const char* off : {"off", "OFF", "0", "false", "no"}) {
    with_env("LAYERJKR_CACHE", off);
    CHECK_FALSE(DiskCacheOptions::from_environment().enabled);
  }
  with_env("LAYERJKR_CACHE", "maybe");
  CHECK_THROWS_WITH(DiskCacheOptions::from_environment(), Catch::Contains("LAYERJKR_CACHE = 'maybe'"));
  with_env("LAYERJKR_CACHE", "on");
  for (const char* bad : {"0", "-5", "1.5", "lots", "99999999999999999999"}) {
    with_env("LAYERJKR_CACHE_MAX_MB", bad);
    CHECK_THROWS_WITH(DiskCacheOptions::from_environment(),
                      Catch::Contains("LAYERJKR_CACHE_MAX_MB = '" + std::string(bad) + "'") && Catch::Contains("[1, "));
  }
  with_env("LAYERJKR_CACHE_MAX_MB", nullptr);
  with_env("LAYERJKR_CACHE_DIR", nullptr);
  with_env("XDG_CACHE_HOME", "/xdg");
  CHECK(DiskCacheOptions::from_environment().resolved_directory() == "/xdg/layerjkr");
  with_env("XDG_CACHE_HOME", nullptr);
  with_env("HOME", "/home/someone");
  CHECK(DiskCacheOptions::from_environment().resolved_directory() == "/home/someone/.cache/layerjkr");
  CHECK_FALSE(DiskCacheOptions{}.enabled);  // a Context made without options keeps nothing on disk
}

namespace {

std::string read_bytes(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(f), {});
}

bool has_notice(const detail::DiskCache& cache, const std::string& part) {
  for (const std::string& n : cache.notices())
    if (n.find(part) != std::string::npos) return true;
  return false;
}

}  // namespace

TEST_CASE("disk cache: an entry someone else wrote or edited is rebuilt, even with its checksum recomputed",
          "[disk_cache][trust]") {
  // Issue 41: with a CRC-32 anyone who could write the folder changed everyone's answers (a
  // pull-off's delta changed sign). Entries now carry an HMAC under this user's own key.
  const test::TempDir dir, other;
  const detail::DiskCache cache(in(dir.path()));
  REQUIRE(cache.enabled());
  const std::vector<double> key{0.49, 2.0}, payload{1.0, 2.0, 3.0};
  cache.store("test-kind", key, payload);
  REQUIRE(cache.load("test-kind", key) == payload);
  const std::string path = cache.path_of("test-kind", key);
  // Edited: a payload double changed, and the old format's CRC-32 of everything before the tail
  // recomputed over it (what an attacker could do to the old format).
  std::string forged = read_bytes(path);
  const double evil = -2.0;
  std::memcpy(forged.data() + forged.size() - 32 - 2 * sizeof(double), &evil, sizeof evil);
  std::ofstream(path, std::ios::binary | std::ios::trunc) << forged;
  CHECK_FALSE(cache.load("test-kind", key));
  CHECK(has_notice(cache, "its authentication failed"));
  // Written whole by another cache (another user's key), copied in under the same name.
  const detail::DiskCache theirs(in(other.path()));
  theirs.store("test-kind", key, {9.0, 9.0, 9.0});
  fs::copy_file(theirs.path_of("test-kind", key), path, fs::copy_options::overwrite_existing);
  CHECK_FALSE(cache.load("test-kind", key));
  cache.store("test-kind", key, payload);
  CHECK(cache.load("test-kind", key) == payload);
}

TEST_CASE("disk cache: a folder others can write or another user owns is not used unless shared",
          "[disk_cache][trust]") {
  const test::TempDir dir;
  const fs::path open_dir = dir.path() / "open";
  fs::create_directory(open_dir);
  fs::permissions(open_dir, fs::perms::all);  // 0777
  const detail::DiskCache refused(in(open_dir));
  CHECK_FALSE(refused.enabled());
  CHECK(has_notice(refused, "is writable by others (mode 0777)"));
  CHECK(has_notice(refused, "LAYERJKR_CACHE_SHARED=1"));
  DiskCacheOptions shared = in(open_dir);
  shared.shared = true;
  const detail::DiskCache opted_in(shared);
  CHECK(opted_in.enabled());
  // A new folder is made private.
  const detail::DiskCache made(in(dir.path() / "new" / "cache"));
  REQUIRE(made.enabled());
  CHECK((fs::status(dir.path() / "new" / "cache").permissions() & fs::perms::all) == fs::perms::owner_all);
  CHECK((fs::status(dir.path() / "new" / "cache" / "layerjkr-cache.key").permissions() & fs::perms::all) ==
        (fs::perms::owner_read | fs::perms::owner_write));
  // A key others can read is no key.
  fs::permissions(dir.path() / "new" / "cache" / "layerjkr-cache.key", fs::perms::others_read, fs::perm_options::add);
  const detail::DiskCache exposed(in(dir.path() / "new" / "cache"));
  CHECK_FALSE(exposed.enabled());
  CHECK(has_notice(exposed, "is not a private 32-byte file"));
  if (::geteuid() == 0) {  // only root can give a folder to another user
    const fs::path theirs = dir.path() / "theirs";
    fs::create_directory(theirs);
    fs::permissions(theirs, fs::perms::owner_all, fs::perm_options::replace);
    REQUIRE(::chown(theirs.c_str(), 65534, 65534) == 0);
    const detail::DiskCache foreign(in(theirs));
    CHECK_FALSE(foreign.enabled());
    CHECK(has_notice(foreign, "belongs to uid 65534, not this user"));
  }
}

TEST_CASE("disk cache: a FIFO, a link or a sparse 8 GiB file at an entry's name is neither waited on nor read",
          "[disk_cache][trust]") {
  const test::TempDir dir;
  const detail::DiskCache cache(in(dir.path()));
  const std::vector<double> key{1.0};
  const std::string path = cache.path_of("test-kind", key);
  REQUIRE(::mkfifo(path.c_str(), 0600) == 0);  // opened before its type was checked: every run hung
  CHECK_FALSE(cache.load("test-kind", key));
  CHECK(has_notice(cache, "is not a regular file"));
  fs::remove(path);
  {
    const int fd = ::open(path.c_str(), O_CREAT | O_WRONLY, 0600);
    REQUIRE(fd >= 0);
    REQUIRE(::ftruncate(fd, static_cast<off_t>(std::int64_t{8} << 30)) == 0);  // sparse: no disk used
    ::close(fd);
  }
  CHECK_FALSE(cache.load("test-kind", key));  // read whole before: bad_alloc under a 2 GiB limit
  CHECK(has_notice(cache, "holds 8589934592 bytes"));
  fs::remove(path);
  const test::TempDir elsewhere;
  cache.store("test-kind", key, {1.0});
  fs::rename(path, elsewhere.path() / "real.bin");
  fs::create_symlink(elsewhere.path() / "real.bin", path);
  CHECK_FALSE(cache.load("test-kind", key));
  CHECK(has_notice(cache, "is a symbolic link"));
  if (::geteuid() == 0) {
    fs::remove(path);
    cache.store("test-kind", key, {1.0});
    REQUIRE(::chown(path.c_str(), 65534, 65534) == 0);
    CHECK_FALSE(cache.load("test-kind", key));
    CHECK(has_notice(cache, "belongs to uid 65534"));
  }
}

TEST_CASE("disk cache: trimming removes only the cache's own files", "[disk_cache][trust]") {
  // Before, trimming deleted any *.bin.* older than an hour and the user's own *.bin files over
  // the bound, in whatever folder LAYERJKR_CACHE_DIR named.
  const test::TempDir dir;
  const detail::DiskCache cache(in(dir.path(), std::uint64_t{1} << 20));
  const auto user_file = [&](const std::string& name, std::size_t bytes) {
    std::ofstream(dir.path() / name, std::ios::binary) << std::string(bytes, 'u');
    const timespec old[2] = {{1000, 0}, {1000, 0}};  // older than every entry and than an hour
    ::utimensat(AT_FDCWD, (dir.path() / name).c_str(), old, 0);
  };
  const std::vector<std::string> users{"thesis.bin", "notes.bin.backup", "layer-kernel-0123456789abcdef.bin",
                                       "layer-kernel-0123456789abcdef.bin.AbCdEf"};
  for (const std::string& name : users) user_file(name, 300000);
  // A writer of ours that died an hour ago: its temporary file carries the magic.
  const std::string dead = cache.path_of("test-kind", {42.0}) + ".Zz0000";
  std::ofstream(dead, std::ios::binary) << std::string("layerjkr-cache\n", 16) << "partial";
  const timespec old[2] = {{1000, 0}, {1000, 0}};
  ::utimensat(AT_FDCWD, dead.c_str(), old, 0);
  const std::vector<double> payload(20000, 1.5);  // 160 kB an entry
  for (int k = 0; k < 12; ++k) cache.store("bound", {static_cast<double>(k)}, payload);
  for (const std::string& name : users) {
    INFO(name);
    CHECK(fs::exists(dir.path() / name));
  }
  CHECK_FALSE(fs::exists(dead));
  std::uint64_t ours = 0;
  for (const fs::path& p : files(dir.path()))
    if (std::find(users.begin(), users.end(), p.filename().string()) == users.end()) ours += fs::file_size(p);
  CHECK(ours <= (std::uint64_t{1} << 20));
}

TEST_CASE("disk cache: LAYERJKR_CACHE_SHARED, and the Context's notices", "[disk_cache][trust]") {
  ::setenv("LAYERJKR_CACHE_SHARED", "on", 1);
  CHECK(DiskCacheOptions::from_environment().shared);
  ::setenv("LAYERJKR_CACHE_SHARED", "sometimes", 1);
  CHECK_THROWS_WITH(DiskCacheOptions::from_environment(), Catch::Contains("LAYERJKR_CACHE_SHARED = 'sometimes'"));
  ::unsetenv("LAYERJKR_CACHE_SHARED");
  CHECK_FALSE(DiskCacheOptions::from_environment().shared);
  const test::TempDir dir;
  fs::permissions(dir.path(), fs::perms::all);
  const Context context(in(dir.path()));
  const CacheStats s = context.stats();
  CHECK(s.disk_errors >= 1);
  REQUIRE_FALSE(s.disk_notices.empty());
  CHECK_THAT(s.disk_notices.front(), Catch::Contains("disk cache off") && Catch::Contains("writable by others"));
}
