// layerjkr: the shared resources behind the models, held in an explicit object (as
// ceres::Context holds Ceres' thread pool) instead of in hidden process-wide statics.
//
// What a Context owns (all of it derived data: dropping an entry only costs its rebuild):
// * the exact layer's kernel functions, one per (nu, base): Chebyshev tables of the kernel
//   transform, ~16 ms and ~50 kB each (docs/exact-layer.md); at most 64 are kept, and
//   requesting a 65th drops them all first;
// * the exact layer's power-law tables, one per (nu, base, d, discretisation): each piece of
//   ln(a/h) is built on first use (13 solves); at most 64 tables, dropped the same way;
// * the uniform layer's edge-correction lengths beta, one per nu (one exact solve, ~0.1 s);
// * the Dugdale tables of power-law profiles, one per (medium, d, discretisation): each piece
//   of ln(c/h) is built on first use (~200 direct solves, 1-30 s; docs/theory.md s.4b);
// * optionally, a directory on disk (DiskCacheOptions) where kernels and tables are kept
//   between processes: a batch, a second run or another process of a cluster job loads them
//   instead of building them again (the cache's numbers are bit-identical to a build's).
//
// Context::global() is the one the library uses unless told otherwise. A model or solver
// holds shared pointers to what it took from a Context, so it stays valid, and keeps its
// numbers, after Context::clear() or after its Context is destroyed; models do not keep
// their Context alive.
//
// Thread safety: every member function of Context is thread-safe, and concurrent requests
// for the same entry build it once (the later callers wait for the first); requests for
// different entries build in parallel.
//
// GSL's error handler: GSL aborts the process on an error unless its handler is replaced,
// and the handler is one process-wide setting in GSL itself, so it cannot belong to a
// Context. The library checks the status of every GSL call that can fail, and switches GSL's
// handler off once per process, in one place (detail::silence_gsl_errors in
// src/core/gsl_support.cpp), called before those calls and by Context's constructor. A
// program that wants its own handler (gsl_set_error_handler) must install it after the
// library's first use, and that handler must return instead of aborting.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace layerjkr {
namespace detail {
struct ContextAccess;
}

/// Where and whether a Context keeps its kernels and tables on disk between processes.
///
/// Each entry is one file named by a hash of what it depends on (its kind, the library's
/// version, the medium's dimensionless signature and the discretisation), holding that key
/// in full and an HMAC-SHA-256 under this user's own key (32 random bytes in the folder's
/// layerjkr-cache.key, mode 0600): a file that is damaged, truncated, of another version or key,
/// or written by anyone else - even with a checksum recomputed - is ignored (and rebuilt), never
/// trusted. The folder is made private (0700); an existing one owned by another user or writable
/// by others is not used unless `shared` is set. Entries are opened without following links or
/// blocking and read only when they are this user's regular files of an entry's size (at most
/// 1 GiB). Writes go to a temporary file in the same directory that is then renamed, so
/// concurrent processes see a whole file or none. When the directory passes max_bytes, the
/// least recently used entries are removed - only files of an entry's name that start with the
/// cache's mark, never a user's own. A directory that cannot be created, read or written costs
/// the rebuild only: answers never fail because of the cache (the failures are counted in
/// CacheStats::disk_errors, the reasons in CacheStats::disk_notices).
struct DiskCacheOptions {
  /// false: nothing is read or written.
  bool enabled = false;
  /// The directory (created if absent). Empty: $XDG_CACHE_HOME/layerjkr, else
  /// $HOME/.cache/layerjkr.
  std::string directory;
  /// Size bound of the directory's entries [bytes], >= 1 MiB.
  std::uint64_t max_bytes = std::uint64_t{512} << 20;
  /// Use a directory owned by another user or writable by others (a group's cache). Entries
  /// are still authenticated by this user's key, so only this user's own are ever loaded.
  bool shared = false;

  /// The options of Context::global(): enabled unless LAYERJKR_CACHE is "off" (or "0",
  /// "false", "no"); LAYERJKR_CACHE_DIR names the directory, LAYERJKR_CACHE_MAX_MB the bound
  /// [MiB], LAYERJKR_CACHE_SHARED=on sets `shared`. Throws InputError naming the variable for a
  /// value it cannot use.
  static DiskCacheOptions from_environment();
  /// The directory after resolving an empty one; empty if neither variable is set.
  std::string resolved_directory() const;
  /// Throws DomainError naming the field if an option is out of range.
  void validate() const;
};

/// Number of entries each cache of a Context holds (built, or being built), and what its disk
/// cache did.
struct CacheStats {
  std::size_t kernels = 0;           ///< exact-layer kernel functions, per (nu, base)
  std::size_t stack_kernels = 0;     ///< kernel functions of stacks, per dimensionless signature
  std::size_t power_law_tables = 0;  ///< exact-layer power-law tables, per (nu, base, d, discretisation)
  std::size_t uniform_betas = 0;     ///< uniform-layer edge-correction lengths, per nu
  std::size_t dugdale_tables = 0;    ///< Dugdale (Maugis-Dugdale, DMT) tables, per (medium, d, discretisation)
  std::size_t disk_hits = 0;         ///< entries loaded from the disk cache
  std::size_t disk_misses = 0;       ///< entries looked for there and built
  std::size_t disk_writes = 0;       ///< entries written there
  std::size_t disk_errors = 0;       ///< reads or writes that failed (the entry was built instead)
  /// Why the disk cache is off, or which entries it refused and rebuilt (the first few, distinct).
  std::vector<std::string> disk_notices;
};

class Context {
 public:
  /// An empty Context, independent of the global one (e.g. to measure cold costs, or to
  /// bound the memory of one job). Pass it as ExactLayerOptions::context or to
  /// make_uniform_layer / uniform_layer_beta.
  Context();
  /// An empty Context whose kernels and tables are also kept in a directory on disk.
  /// Throws DomainError for invalid options.
  explicit Context(const DiskCacheOptions& disk);
  ~Context();
  Context(const Context&) = delete;
  Context& operator=(const Context&) = delete;

  /// The process-wide Context the library uses when none is given, with the disk cache of
  /// DiskCacheOptions::from_environment() (one that the environment misconfigures is off, and
  /// says why in CacheStats::disk_errors). Never destroyed, so models may be used from static
  /// destructors and detached threads.
  static Context& global();
  /// The global Context if something has used it, else nullptr: nothing is made (the CLI asks
  /// at exit for the disk cache's notices).
  static const Context* global_if_made();

  /// Drops every cached entry in memory (not on disk). Models and solvers built before keep
  /// what they hold and give bit-identical results; later requests rebuild or load (with the
  /// same numbers).
  void clear();

  /// Entries per cache, for tests and diagnostics.
  CacheStats stats() const;

 private:
  friend struct detail::ContextAccess;
  struct Caches;
  std::unique_ptr<Caches> caches_;
};

}  // namespace layerjkr
