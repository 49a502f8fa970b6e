// What this measures (issue #22): reading big instrument maps on 2 threads - a 256 x 256 JPK
// QI archive (65 536 curves) and a 128 x 128 NanoScope force volume (16 384 curves) - as
// curves per second, against the floor of just unpacking the bytes the reader needs:
//   floor    every entry InstrumentReader reads (header.properties, shared-data/
//            header.properties, each curve's header, segment headers, and the channels
//            vDeflection, the measured height and height), inflated with libzip into a reused
//            buffer, the entries shared by 2 threads through an atomic counter, each thread
//            with its own zip_t opened before the clock starts (the floor is inflating, not
//            indexing the archive); beside it the same for every entry of the archive.
//            NanoScope: the force data block read with pread in 1 MiB chunks by 2 threads.
//   read     InstrumentReader(path).curve(i) for every i on 2 threads (atomic counter).
//   Hertz    fit_files({path}, ...) with BatchOptions::jobs = 2: a paraboloid on a half-space,
//            E, delta0 and P0 free, approach branch (the CLI's default).
//   JKR      the same with w free too, both branches.
//   CLI      `layerjkr fit-map --jobs 2 --scene hertz.json --free E,delta0,P0 --out T MAP`,
//            end to end (process start to exit).
// Each measurement runs 3 times (--repeat) in its own child process (this program again,
// with --phase): the median time is reported, and the largest peak RSS (ru_maxrss from
// wait4), so every phase has its own peak. The maps are made first by tools/
// make_instrument_map in a fresh temporary directory (not timed here; their generation time
// and peak RSS are printed apart), synced to disk, and removed at the end. The maps are read
// warm: they were just written, so they sit in the page cache.
//
// The scene is built here: data/scenes has no half-space scene, and neither file says its
// tip's radius (the QI header's probe field is empty; the NanoScope header says Tip Radius:
// 20 nm), so both are fitted with a 20 nm paraboloid. The radius only scales E; the cost
// of a fit is the Hertz family's either way.
//
// Run: build/bin/map_reading [QI_SIDE = 256] [NANOSCOPE_SIDE = 128] [--repeat N = 3] [--strict]
// --strict: exit 1 if any measurement could not be made (each is otherwise a numbered note
// under the table). The QI map is made from the bundled QI file; the NanoScope one needs
// ../shared and is skipped, said, without it. Exit 77 if no map could be made. The ctest
// map_reading_runs is the quick check that it all runs - `map_reading 8 4 --repeat 1
// --strict`, nothing timed or compared with a target (timings belong to this table, not to
// a test).
// Run it while nothing else builds: flock /tmp/layerjkr-build.lock build/bin/map_reading
#include <fcntl.h>
#include <stdlib.h>  // mkdtemp
#include <sys/resource.h>
#include <sys/statfs.h>
#include <sys/wait.h>
#include <unistd.h>
#include <zip.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <exception>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "layerjkr/layerjkr.hpp"

namespace {

using Clock = std::chrono::steady_clock;
constexpr int kJobs = 2;
constexpr int kSkipped = 77;  // the sources are absent (../shared)

const char* const kHertzScene = R"({"indenter": {"shape": "paraboloid", "R": 2e-8},
  "medium": {"type": "half_space", "E": 1e5, "nu": 0.5}})";
const char* const kJkrScene = R"({"indenter": {"shape": "paraboloid", "R": 2e-8},
  "medium": {"type": "half_space", "E": 1e5, "nu": 0.5}, "w": 1e-3})";

double since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

bool ends_with(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

// What one phase reports: its wall time, the curves it covered, how many were read or
// fitted, the bytes it unpacked (floors).
struct Outcome {
  double seconds = 0.0;
  std::size_t curves = 0, ok = 0, bytes = 0;
};

// ---------------------------------------------------------------------------------------
// Phases (run in a child process)

// Runs body(thread) on kJobs threads; the first exception one throws is rethrown here.
template <class F>
void on_threads(F body) {
  std::vector<std::thread> threads;
  std::vector<std::exception_ptr> errors(kJobs);
  for (int t = 0; t < kJobs; ++t)
    threads.emplace_back([&, t] {
      try {
        body(t);
      } catch (...) {
        errors[static_cast<std::size_t>(t)] = std::current_exception();
      }
    });
  for (auto& th : threads) th.join();
  for (const auto& e : errors)
    if (e) std::rethrow_exception(e);
}

zip_t* open_zip(const std::string& path) {
  int err = 0;
  zip_t* z = zip_open(path.c_str(), ZIP_RDONLY, &err);
  if (!z) throw std::runtime_error(path + ": cannot open (libzip error " + std::to_string(err) + ")");
  return z;
}

// The entries InstrumentReader reads: the two archive headers, and per curve its header,
// its segment headers and the channels it decodes (the measured height is the first of
// strainGaugeHeight, capacitiveSensorHeight, measuredHeight a segment has; these maps have
// one of them per segment, so every one present is counted).
bool needed(const std::string& name) {
  if (name == "header.properties" || name == "shared-data/header.properties") return true;
  if (name.rfind("index/", 0) != 0) return false;
  for (const char* suffix :
       {"/header.properties", "/segment-header.properties", "/channels/vDeflection.dat", "/channels/height.dat",
        "/channels/measuredHeight.dat", "/channels/strainGaugeHeight.dat", "/channels/capacitiveSensorHeight.dat"})
    if (ends_with(name, suffix)) return true;
  return false;
}

Outcome floor_jpk(const std::string& path, bool all_entries) {
  // Opening and listing are not the floor (a reader's index of the archive is its own
  // business): both handles are opened and the entries listed before the clock starts.
  std::vector<zip_t*> handles;
  for (int t = 0; t < kJobs; ++t) handles.push_back(open_zip(path));
  std::vector<zip_uint64_t> entries;
  std::size_t curves = 0;
  const zip_int64_t count = zip_get_num_entries(handles[0], 0);
  for (zip_uint64_t i = 0; i < static_cast<zip_uint64_t>(count); ++i) {
    const std::string name = zip_get_name(handles[0], i, 0);
    if (name.rfind("index/", 0) == 0 && std::count(name.begin(), name.end(), '/') == 2 &&
        ends_with(name, "/header.properties"))
      ++curves;
    if (!ends_with(name, "/") && (all_entries || needed(name))) entries.push_back(i);
  }
  std::atomic<std::size_t> next{0}, bytes{0};
  constexpr std::size_t kChunk = 64;  // entries taken at a time: neighbours, as a reader reads them
  const auto t0 = Clock::now();
  on_threads([&](int t) {
    zip_t* z = handles[static_cast<std::size_t>(t)];
    std::vector<char> buffer;
    std::size_t mine = 0;
    for (std::size_t b; (b = next.fetch_add(kChunk)) < entries.size();)
      for (std::size_t k = b; k < std::min(b + kChunk, entries.size()); ++k) {
        zip_stat_t st;
        if (zip_stat_index(z, entries[k], 0, &st) != 0) throw std::runtime_error(zip_strerror(z));
        buffer.resize(std::max(buffer.size(), static_cast<std::size_t>(st.size)));
        zip_file_t* f = zip_fopen_index(z, entries[k], 0);
        if (!f) throw std::runtime_error(zip_strerror(z));
        const zip_int64_t n = zip_fread(f, buffer.data(), st.size);
        zip_fclose(f);
        if (n != static_cast<zip_int64_t>(st.size)) throw std::runtime_error("short read");
        mine += static_cast<std::size_t>(n);
      }
    bytes += mine;
  });
  const double seconds = since(t0);
  for (zip_t* z : handles) zip_discard(z);
  return {seconds, curves, curves, bytes};
}

// The NanoScope header's value of `key` in the first section named `section`.
std::string nanoscope_value(const std::string& header, const std::string& section, const std::string& key) {
  std::size_t at = header.find(section + "\r\n");
  if (at == std::string::npos) throw std::runtime_error("no " + section);
  const std::size_t end = header.find("\r\n\\*", at + section.size());
  at = header.find("\r\n" + key + ": ", at);
  if (at == std::string::npos || at > end) throw std::runtime_error("no " + key + " in " + section);
  const std::size_t v = at + 2 + key.size() + 2;
  return header.substr(v, header.find("\r\n", v) - v);
}

Outcome floor_nanoscope(const std::string& path) {
  const auto t0 = Clock::now();
  const int fd = ::open(path.c_str(), O_RDONLY);
  if (fd < 0) throw std::runtime_error(path + ": cannot open");
  std::string header(std::size_t{256} << 10, '\0');  // NanoScope headers are 20-80 KB
  const ssize_t got = ::pread(fd, header.data(), header.size(), 0);
  header.resize(got > 0 ? static_cast<std::size_t>(got) : 0);
  header.resize(std::min(header.size(), header.find("\\*File list end")));
  const std::size_t offset = std::stoull(nanoscope_value(header, "\\*Ciao force image list", "\\Data offset"));
  const std::size_t length = std::stoull(nanoscope_value(header, "\\*Ciao force image list", "\\Data length"));
  const std::size_t curves = std::stoull(nanoscope_value(header, "\\*Ciao scan list", "\\Lines")) *
                             std::stoull(nanoscope_value(header, "\\*Ciao scan list", "\\Samps/line"));
  constexpr std::size_t kChunk = std::size_t{1} << 20;
  std::atomic<std::size_t> next{0}, bytes{0};
  on_threads([&](int) {
    std::vector<char> buffer(kChunk);
    std::size_t mine = 0;
    for (std::size_t b; (b = next.fetch_add(kChunk)) < length;) {
      const ssize_t n = ::pread(fd, buffer.data(), std::min(kChunk, length - b), static_cast<off_t>(offset + b));
      if (n <= 0) throw std::runtime_error(path + ": read failed");
      mine += static_cast<std::size_t>(n);
    }
    bytes += mine;
  });
  ::close(fd);
  return {since(t0), curves, curves, bytes};
}

Outcome read_only(const std::string& path) {
  const auto t0 = Clock::now();
  const layerjkr::InstrumentReader reader(path);
  const std::size_t n = reader.size();
  std::atomic<std::size_t> next{0}, ok{0}, samples{0};
  on_threads([&](int) {
    std::size_t mine = 0, read = 0;
    for (std::size_t i; (i = next++) < n;) {
      try {
        const layerjkr::InstrumentCurve c = reader.curve(i);
        for (const auto& s : c.segments) mine += s.force.size();
        ++read;
      } catch (const std::exception&) {
        // counted as not read
      }
    }
    ok += read;
    samples += mine;  // used, so that no read is optimised away
  });
  return {since(t0), n, ok, samples * sizeof(double)};
}

Outcome fit_map(const std::string& path, bool jkr) {
  const auto t0 = Clock::now();
  const layerjkr::Scene scene = layerjkr::parse_scene(jkr ? kJkrScene : kHertzScene);
  layerjkr::FitOptions o;
  using layerjkr::FitParameter;
  o.free = jkr ? std::vector<FitParameter>{FitParameter::E, FitParameter::w, FitParameter::delta0, FitParameter::P0}
               : std::vector<FitParameter>{FitParameter::E, FitParameter::delta0, FitParameter::P0};
  o.branch = jkr ? layerjkr::Branch::all : layerjkr::Branch::approach;
  layerjkr::BatchOptions b;
  b.jobs = kJobs;
  const std::vector<layerjkr::BatchItem> items = layerjkr::fit_files({path}, scene, o, layerjkr::CsvOptions{}, b);
  Outcome r;
  r.seconds = since(t0);
  r.curves = items.size();
  for (const auto& it : items) r.ok += (it.ok && it.summary.converged) ? 1 : 0;
  // The first failure, for the log (and for the table when the file could not be read).
  for (const auto& it : items)
    if (!it.ok) {
      std::fprintf(stderr, "%s\n", it.error.c_str());
      break;
    }
  return r;
}

int run_phase(const std::string& phase, const std::string& path) {
  Outcome r;
  if (phase == "floor-needed")
    r = floor_jpk(path, false);
  else if (phase == "floor-all")
    r = floor_jpk(path, true);
  else if (phase == "floor-pread")
    r = floor_nanoscope(path);
  else if (phase == "read")
    r = read_only(path);
  else if (phase == "hertz")
    r = fit_map(path, false);
  else if (phase == "jkr")
    r = fit_map(path, true);
  else
    throw std::runtime_error("unknown phase " + phase);
  std::printf("%.6f %zu %zu %zu\n", r.seconds, r.curves, r.ok, r.bytes);
  return 0;
}

// ---------------------------------------------------------------------------------------
// The parent: children, medians, the table

struct Child {
  int code = -1;
  double wall = 0.0;  // seen from here, process start to exit
  long rss_kb = 0;
  std::string out;
};

// Runs argv with stdout captured (stderr to `err_file`, if given) and returns its exit
// status, wall time and peak RSS.
Child spawn(const std::vector<std::string>& argv, const std::string& err_file = "/dev/null") {
  int pipe_fds[2];
  if (::pipe(pipe_fds) != 0) throw std::runtime_error("pipe failed");
  std::vector<char*> args;
  for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  const auto t0 = Clock::now();
  const pid_t pid = ::fork();
  if (pid < 0) throw std::runtime_error("fork failed");
  if (pid == 0) {
    ::dup2(pipe_fds[1], 1);
    const int err = ::open(err_file.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (err >= 0) ::dup2(err, 2);
    ::close(pipe_fds[0]);
    ::close(pipe_fds[1]);
    ::execv(args[0], args.data());
    ::_exit(127);
  }
  ::close(pipe_fds[1]);
  Child c;
  char buf[4096];
  for (ssize_t n; (n = ::read(pipe_fds[0], buf, sizeof buf)) > 0;) c.out.append(buf, static_cast<std::size_t>(n));
  ::close(pipe_fds[0]);
  int status = 0;
  rusage ru{};
  ::wait4(pid, &status, 0, &ru);
  c.wall = since(t0);
  c.code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  c.rss_kb = ru.ru_maxrss;
  return c;
}

std::string self_path() { return std::filesystem::read_symlink("/proc/self/exe").string(); }

// A phase run `repeat` times: the median outcome (by time) and the largest peak RSS.
struct Measured {
  Outcome median;
  long rss_kb = 0;
  std::string error;  // why the phase could not run (empty: it ran)
};

std::string first_line(const std::string& file) {
  std::ifstream in(file);
  std::string line;
  std::getline(in, line);
  return line;
}

Measured measure(const std::string& phase, const std::string& path, std::size_t curves, int repeat,
                 const std::string& dir) {
  std::vector<Outcome> runs;
  Measured m;
  for (int k = 0; k < repeat; ++k) {
    const Child c = spawn({self_path(), "--phase", phase, path}, dir + "/phase.err");
    if (c.code != 0) {  // reported in the table, and the other phases still run
      m.error = first_line(dir + "/phase.err");
      std::fprintf(stderr, "  %-12s failed (exit %d): %s\n", phase.c_str(), c.code, m.error.c_str());
      return m;
    }
    Outcome o;
    std::istringstream(c.out) >> o.seconds >> o.curves >> o.ok >> o.bytes;
    if (o.curves != curves) {  // fit_files makes one failed item of a file it cannot read
      m.error = std::to_string(o.curves) + " items for " + std::to_string(curves) +
                " curves: " + first_line(dir + "/phase.err");
      std::fprintf(stderr, "  %-12s failed: %s\n", phase.c_str(), m.error.c_str());
      return m;
    }
    runs.push_back(o);
    m.rss_kb = std::max(m.rss_kb, c.rss_kb);
    std::fprintf(stderr, "  %-12s %s: %.3f s, %zu of %zu, %.0f MB peak\n", phase.c_str(),
                 std::filesystem::path(path).filename().c_str(), o.seconds, o.ok, o.curves, c.rss_kb / 1024.0);
  }
  std::sort(runs.begin(), runs.end(), [](const Outcome& a, const Outcome& b) { return a.seconds < b.seconds; });
  m.median = runs[runs.size() / 2];
  return m;
}

// The CLI, end to end: median wall time, largest peak RSS, and its closing line.
struct CliRun {
  double seconds = 0.0;
  long rss_kb = 0;
  std::string summary, error;
};

CliRun measure_cli(const std::string& map, std::size_t curves, const std::string& scene, int repeat,
                   const std::string& dir) {
  std::vector<double> times;
  CliRun r;
  for (int k = 0; k < repeat; ++k) {
    const std::string out = dir + "/fit-map.csv", err = dir + "/fit-map.err";
    std::filesystem::remove(out);
    const Child c = spawn({LAYERJKR_CLI_PATH, "fit-map", "--jobs", std::to_string(kJobs), "--scene", scene, "--free",
                           "E,delta0,P0", "--out", out, map},
                          err);
    std::ifstream e(err);
    std::string last;
    for (std::string line; std::getline(e, line);)
      if (!line.empty()) last = line;
    if (c.code != 0 && c.code != 3) {  // 3: some curves failed, which the row count below checks
      r.error = last;
      std::fprintf(stderr, "  %-12s failed (exit %d): %s\n", "cli", c.code, last.c_str());
      return r;
    }
    r.summary = last;
    // "fit-map: F of N curves fitted..." (N: the rows; one failed row for a file it cannot read)
    const std::size_t of = last.find(" of "), space = last.find(' ', of + 4);
    if (of == std::string::npos || last.substr(of + 4, space - of - 4) != std::to_string(curves)) {
      r.error = "not " + std::to_string(curves) + " rows: " + last;
      std::fprintf(stderr, "  %-12s failed: %s\n", "cli", r.error.c_str());
      return r;
    }
    times.push_back(c.wall);
    r.rss_kb = std::max(r.rss_kb, c.rss_kb);
    std::fprintf(stderr, "  %-12s %s: %.3f s, %.0f MB peak (%s)\n", "cli",
                 std::filesystem::path(map).filename().c_str(), c.wall, c.rss_kb / 1024.0, last.c_str());
  }
  std::sort(times.begin(), times.end());
  r.seconds = times[times.size() / 2];
  return r;
}

// A fresh directory under the system's temporary directory, removed with its contents.
class TempDir {
 public:
  TempDir() {
    std::string pattern = (std::filesystem::temp_directory_path() / "layerjkr_map_reading_XXXXXX").string();
    if (!::mkdtemp(pattern.data())) throw std::runtime_error("cannot create " + pattern);
    path_ = pattern;
  }
  ~TempDir() {
    std::error_code ignored;
    std::filesystem::remove_all(path_, ignored);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  std::string file(const std::string& name) const { return path_ + "/" + name; }
  const std::string& path() const { return path_; }

 private:
  std::string path_;
};

std::string cpu_model() {
  std::ifstream in("/proc/cpuinfo");
  for (std::string line; std::getline(in, line);)
    if (line.rfind("model name", 0) == 0) return line.substr(line.find(':') + 2);
  return "unknown";
}

std::string filesystem_of(const std::string& path) {
  struct statfs s {};
  if (::statfs(path.c_str(), &s) != 0) return "unknown";
  switch (static_cast<unsigned long>(s.f_type)) {
    case 0x01021994UL:
      return "tmpfs (memory)";
    case 0xEF53UL:
      return "ext2/3/4 (disk)";
    case 0x58465342UL:
      return "xfs (disk)";
    case 0x9123683EUL:
      return "btrfs (disk)";
    case 0x794C7630UL:
      return "overlayfs";
    default: {
      char hex[32];
      std::snprintf(hex, sizeof hex, "0x%lx", static_cast<unsigned long>(s.f_type));
      return std::string("filesystem type ") + hex;
    }
  }
}

std::string rate(const Outcome& o) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.2f s (%.0f/s)", o.seconds, static_cast<double>(o.curves) / o.seconds);
  return buf;
}
std::string fitted(const Outcome& o) {
  char buf[96];
  std::snprintf(buf, sizeof buf, "%.2f s (%.0f/s; %.1f %% fitted)", o.seconds,
                static_cast<double>(o.curves) / o.seconds,
                100.0 * static_cast<double>(o.ok) / static_cast<double>(std::max<std::size_t>(o.curves, 1)));
  return buf;
}
double mb(long kb) { return static_cast<double>(kb) / 1024.0; }

int run(int qi_side, int nanoscope_side, int repeat, bool strict) {
  const TempDir dir;
  std::printf("Machine: %u threads (nproc), %s; maps in %s on %s; %d threads, median of %d runs.\n\n",
              std::thread::hardware_concurrency(), cpu_model().c_str(), dir.path().c_str(),
              filesystem_of(dir.path()).c_str(), kJobs, repeat);
  struct Map {
    std::string label, kind, path;
    int side;
    std::size_t curves() const { return static_cast<std::size_t>(side) * static_cast<std::size_t>(side); }
  };
  const std::vector<Map> all_maps = {
      {"QI " + std::to_string(qi_side) + " x " + std::to_string(qi_side), "qi", dir.file("map.jpk-qi-data"), qi_side},
      {"NanoScope " + std::to_string(nanoscope_side) + " x " + std::to_string(nanoscope_side), "nanoscope",
       dir.file("map.spm"), nanoscope_side}};
  std::vector<Map> maps;
  for (const Map& m : all_maps) {
    const Child c = spawn({LAYERJKR_MAKE_INSTRUMENT_MAP, m.kind, std::to_string(m.side), m.path}, dir.file("make.err"));
    if (c.code != 0) {
      std::ifstream e(dir.file("make.err"));
      std::string line;
      std::getline(e, line);
      // The QI source is bundled; the NanoScope one is in ../shared: without it that map is
      // skipped, said, and the rest measured.
      if (line.find("is absent") != std::string::npos) {
        std::printf("Skipped %s: %s (needs ../shared)\n", m.label.c_str(), line.c_str());
        continue;
      }
      std::fprintf(stderr, "map_reading: %s\n", line.c_str());
      return 1;
    }
    maps.push_back(m);
    // Written to disk before anything is timed: the kernel's writeback of a fresh 0.9 GB
    // file otherwise overlaps the first phases (it doubled the QI floor's time).
    const auto t0 = Clock::now();
    const int fd = ::open(m.path.c_str(), O_RDONLY);
    if (fd < 0 || ::fsync(fd) != 0) throw std::runtime_error(m.path + ": fsync failed");
    ::close(fd);
    std::printf(
        "Generated %s (%zu curves): %.0f MB in %.2f s, peak RSS %.0f MB (tools/make_instrument_map); "
        "fsync %.2f s\n",
        m.label.c_str(), m.curves(), static_cast<double>(std::filesystem::file_size(m.path)) / 1e6, c.wall,
        mb(c.rss_kb), since(t0));
  }
  // Nothing to measure at all: ctest counts exit 77 as skipped.
  if (maps.empty()) return kSkipped;
  std::ofstream(dir.file("hertz.json")) << kHertzScene;

  std::printf(
      "\n| map | curves | floor: needed / all entries | read-only | read / floor | read + Hertz | read + JKR "
      "| peak RSS: floor / read / Hertz / JKR | CLI fit-map, Hertz (peak RSS) |\n");
  std::printf("|---|---|---|---|---|---|---|---|---|\n");
  std::vector<std::string> all_notes;
  for (const Map& m : maps) {
    const bool qi = m.kind == "qi";
    const Measured floor = measure(qi ? "floor-needed" : "floor-pread", m.path, m.curves(), repeat, dir.path());
    Measured floor_all;
    if (qi) floor_all = measure("floor-all", m.path, m.curves(), repeat, dir.path());
    const Measured read = measure("read", m.path, m.curves(), repeat, dir.path());
    const Measured hertz = measure("hertz", m.path, m.curves(), repeat, dir.path());
    const Measured jkr = measure("jkr", m.path, m.curves(), repeat, dir.path());
    const CliRun cli = measure_cli(m.path, m.curves(), dir.file("hertz.json"), repeat, dir.path());
    std::vector<std::string> notes;
    auto cell = [&](const Measured& x, const std::string& what, const std::string& text) {
      if (x.error.empty()) return text;
      notes.push_back(m.label + ", " + what + ": " + x.error);
      return "n/a [" + std::to_string(all_notes.size() + notes.size()) + "]";
    };
    auto secs = [](double t) {
      char buf[32];
      std::snprintf(buf, sizeof buf, "%.2f s", t);
      return std::string(buf);
    };
    auto peak = [](const Measured& x) {
      return x.error.empty() ? std::to_string(static_cast<long>(mb(x.rss_kb))) : "-";
    };
    std::string floors = cell(floor, qi ? "floor" : "pread floor", secs(floor.median.seconds));
    if (qi)
      floors += " / " + cell(floor_all, "whole-archive floor", secs(floor_all.median.seconds));
    else
      floors += " (pread)";
    char ratio[32] = "-";
    if (floor.error.empty() && read.error.empty())
      std::snprintf(ratio, sizeof ratio, "%.1f", read.median.seconds / floor.median.seconds);
    const std::string rss = peak(floor) + " / " + peak(read) + " / " + peak(hertz) + " / " + peak(jkr) + " MB";
    const std::string read_cell = cell(read, "read", rate(read.median));
    const std::string hertz_cell = cell(hertz, "read + Hertz", fitted(hertz.median));
    const std::string jkr_cell = cell(jkr, "read + JKR", fitted(jkr.median));
    std::string cli_cell;
    if (cli.error.empty()) {
      char buf[64];
      std::snprintf(buf, sizeof buf, "%.2f s (%.0f MB)", cli.seconds, mb(cli.rss_kb));
      cli_cell = buf;
    } else {
      notes.push_back(m.label + ", CLI: " + cli.error);
      cli_cell = "n/a [" + std::to_string(all_notes.size() + notes.size()) + "]";
    }
    std::printf("| %s | %zu | %s | %s | %s | %s | %s | %s | %s |\n", m.label.c_str(), m.curves(), floors.c_str(),
                read_cell.c_str(), ratio, hertz_cell.c_str(), jkr_cell.c_str(), rss.c_str(), cli_cell.c_str());
    std::fflush(stdout);
    if (read.error.empty() && read.median.ok != read.median.curves)
      notes.push_back(m.label + ": " + std::to_string(read.median.curves - read.median.ok) + " of " +
                      std::to_string(read.median.curves) + " curves could not be read");
    all_notes.insert(all_notes.end(), notes.begin(), notes.end());
  }
  for (std::size_t k = 0; k < all_notes.size(); ++k) std::printf("\n[%zu] %s", k + 1, all_notes[k].c_str());
  if (!all_notes.empty()) std::printf("\n");
  if (strict && !all_notes.empty()) {
    std::fprintf(stderr, "map_reading: %zu measurements could not be made (--strict)\n", all_notes.size());
    return 1;
  }
  std::printf(
      "\nTargets (QI): read >= 20 000 curves/s and within 2x of the floor; read + Hertz >= 5 000 curves/s; "
      "peak RSS < 500 MB.\n");
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    if (argc == 4 && std::string(argv[1]) == "--phase") return run_phase(argv[2], argv[3]);
    std::vector<int> sides;
    int repeat = 3;
    bool strict = false;
    for (int i = 1; i < argc; ++i) {
      const std::string a = argv[i];
      if (a == "--repeat" && i + 1 < argc)
        repeat = std::atoi(argv[++i]);
      else if (a == "--strict")
        strict = true;
      else
        sides.push_back(std::atoi(a.c_str()));
    }
    const int qi_side = sides.size() > 0 ? sides[0] : 256, nanoscope_side = sides.size() > 1 ? sides[1] : 128;
    if (qi_side < 1 || nanoscope_side < 1 || repeat < 1 || sides.size() > 2) {
      std::fprintf(stderr, "usage: map_reading [QI_SIDE = 256] [NANOSCOPE_SIDE = 128] [--repeat N = 3] [--strict]\n");
      return 2;
    }
    return run(qi_side, nanoscope_side, repeat, strict);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "map_reading: %s\n", e.what());
    return 1;
  }
}
