#include "layerjkr/context.hpp"

#include "core/context_caches.hpp"
#include "core/gsl_support.hpp"

namespace layerjkr {

Context::Context() : caches_(std::make_unique<Caches>()) { detail::silence_gsl_errors(); }

Context::~Context() = default;

Context& Context::global() {
  // Leaked on purpose: models built from it may still be used by static destructors or
  // detached threads after main returns.
  static Context* const instance = new Context();
  return *instance;
}

void Context::clear() {
  caches_->kernels.clear();
  caches_->power_law_tables.clear();
  caches_->uniform_betas.clear();
}

CacheStats Context::stats() const {
  CacheStats s;
  s.kernels = caches_->kernels.size();
  s.power_law_tables = caches_->power_law_tables.size();
  s.uniform_betas = caches_->uniform_betas.size();
  return s;
}

}  // namespace layerjkr
