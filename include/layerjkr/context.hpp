// layerjkr: the shared resources behind the models, held in an explicit object (as
// ceres::Context holds Ceres' thread pool) instead of in hidden process-wide statics.
//
// What a Context owns (all of it derived data: dropping an entry only costs its rebuild):
// * the exact layer's kernel functions, one per (nu, base): Chebyshev tables of the kernel
//   transform, ~16 ms and ~50 kB each (docs/exact-layer.md); at most 64 are kept, and
//   requesting a 65th drops them all first;
// * the exact layer's power-law tables, one per (nu, base, d, discretisation): each piece of
//   ln(a/h) is built on first use (13 solves); at most 64 tables, dropped the same way;
// * the uniform layer's edge-correction lengths beta, one per nu (one exact solve, ~0.1 s).
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
#include <memory>

namespace layerjkr {
namespace detail {
struct ContextAccess;
}

/// Number of entries each cache of a Context holds (built, or being built).
struct CacheStats {
  std::size_t kernels = 0;           ///< exact-layer kernel functions, per (nu, base)
  std::size_t power_law_tables = 0;  ///< exact-layer power-law tables, per (nu, base, d, discretisation)
  std::size_t uniform_betas = 0;     ///< uniform-layer edge-correction lengths, per nu
};

class Context {
 public:
  /// An empty Context, independent of the global one (e.g. to measure cold costs, or to
  /// bound the memory of one job). Pass it as ExactLayerOptions::context or to
  /// make_uniform_layer / uniform_layer_beta.
  Context();
  ~Context();
  Context(const Context&) = delete;
  Context& operator=(const Context&) = delete;

  /// The process-wide Context the library uses when none is given. Never destroyed, so
  /// models may be used from static destructors and detached threads.
  static Context& global();

  /// Drops every cached entry. Models and solvers built before keep what they hold and give
  /// bit-identical results; later requests rebuild (with the same numbers).
  void clear();

  /// Entries per cache, for tests and diagnostics.
  CacheStats stats() const;

 private:
  friend struct detail::ContextAccess;
  struct Caches;
  std::unique_ptr<Caches> caches_;
};

}  // namespace layerjkr
