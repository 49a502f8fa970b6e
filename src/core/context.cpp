#include "layerjkr/context.hpp"

#include <atomic>

#include "core/context_caches.hpp"
#include "core/gsl_support.hpp"
#include "layerjkr/error.hpp"

namespace layerjkr {

Context::Context() : caches_(std::make_unique<Caches>(DiskCacheOptions{})) { detail::silence_gsl_errors(); }

Context::Context(const DiskCacheOptions& disk) : caches_(std::make_unique<Caches>(disk)) {
  detail::silence_gsl_errors();
}

Context::~Context() = default;

namespace {
std::atomic<const Context*> g_global{nullptr};
}

Context& Context::global() {
  // Leaked on purpose: models built from it may still be used by static destructors or
  // detached threads after main returns.
  static Context* const instance = [] {
    try {
      return new Context(DiskCacheOptions::from_environment());
    } catch (const Error&) {  // a bad LAYERJKR_CACHE*: no disk cache (the CLI refuses it up front)
      auto* c = new Context();
      c->caches_->disk->count_error();
      return c;
    }
  }();
  g_global.store(instance);
  return *instance;
}

void Context::clear() {
  caches_->kernels.clear();
  caches_->stack_kernels.clear();
  caches_->power_law_tables.clear();
  caches_->dugdale_tables.clear();
  caches_->uniform_betas.clear();
}

const Context* Context::global_if_made() { return g_global.load(); }

CacheStats Context::stats() const {
  CacheStats s;
  s.kernels = caches_->kernels.size();
  s.stack_kernels = caches_->stack_kernels.size();
  s.power_law_tables = caches_->power_law_tables.size();
  s.dugdale_tables = caches_->dugdale_tables.size();
  s.uniform_betas = caches_->uniform_betas.size();
  s.disk_hits = caches_->disk->hits();
  s.disk_misses = caches_->disk->misses();
  s.disk_writes = caches_->disk->writes();
  s.disk_errors = caches_->disk->errors();
  s.disk_notices = caches_->disk->notices();
  return s;
}

}  // namespace layerjkr
