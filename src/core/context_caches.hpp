// Internal: the caches a layerjkr::Context owns (include/layerjkr/context.hpp), and how the
// models reach them. Each model builds its own entries (layer_kernel.cpp,
// exact_power_law_table.cpp, uniform_layer.cpp); the Context only stores them.
#pragma once

#include <cstddef>
#include <map>
#include <memory>
#include <mutex>
#include <tuple>
#include <utility>
#include <vector>

#include "core/disk_cache.hpp"
#include "layerjkr/context.hpp"

namespace layerjkr {
namespace detail {

class LayerKernelFunction;
class ExactPowerLawTable;
class DugdaleTable;

// Shared, immutable values per key, each built once: a request for a key being built waits
// for that build (so two threads never build the same entry twice) while requests for other
// keys proceed. A build that throws leaves no entry, so the next request tries again. With
// max_entries > 0, adding a key to a full cache first drops every entry (holders keep theirs).
template <class Key, class Value>
class BuildOnceCache {
 public:
  explicit BuildOnceCache(std::size_t max_entries = 0) : max_entries_(max_entries) {}

  template <class Build>
  std::shared_ptr<const Value> get(const Key& key, Build build) {
    std::shared_ptr<Slot> slot;
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      auto it = slots_.find(key);
      if (it == slots_.end()) {
        if (max_entries_ > 0 && slots_.size() >= max_entries_) slots_.clear();
        it = slots_.emplace(key, std::make_shared<Slot>()).first;
      }
      slot = it->second;
    }
    const std::lock_guard<std::mutex> building(slot->mutex);
    if (!slot->value) {
      try {
        slot->value = build();
      } catch (...) {
        const std::lock_guard<std::mutex> lock(mutex_);
        if (const auto it = slots_.find(key); it != slots_.end() && it->second == slot) slots_.erase(it);
        throw;
      }
    }
    return slot->value;
  }

  void clear() {
    const std::lock_guard<std::mutex> lock(mutex_);
    slots_.clear();
  }

  std::size_t size() const {
    const std::lock_guard<std::mutex> lock(mutex_);
    return slots_.size();
  }

 private:
  struct Slot {
    std::mutex mutex;  // held while the value is built
    std::shared_ptr<const Value> value;
  };
  std::size_t max_entries_;
  mutable std::mutex mutex_;  // guards slots_, never held during a build
  std::map<Key, std::shared_ptr<Slot>> slots_;
};

using KernelKey = std::pair<double, bool>;  // nu, bonded
using StackKernelKey = std::vector<double>;  // StackSymbol::signature()
// the medium's signature (StackSymbol: nu and the base for one layer), d, points_per_panel,
// panel_width, min_panels: what the table's numbers depend on
using PowerLawTableKey = std::tuple<std::vector<double>, double, int, double, int>;

}  // namespace detail

struct Context::Caches {
  explicit Caches(const DiskCacheOptions& options) : disk(std::make_shared<detail::DiskCache>(options)) {}
  // Kernels and tables between processes (disabled unless the Context was given a directory).
  // Shared: a table holds it to store the pieces it builds later, after its Context is gone.
  std::shared_ptr<const detail::DiskCache> disk;
  // ~50 kB a kernel; a session rarely needs more layers.
  detail::BuildOnceCache<detail::KernelKey, detail::LayerKernelFunction> kernels{64};
  detail::BuildOnceCache<detail::StackKernelKey, detail::LayerKernelFunction> stack_kernels{64};
  detail::BuildOnceCache<detail::PowerLawTableKey, detail::ExactPowerLawTable> power_law_tables{64};
  // the medium's signature, d and the discretisation: Dugdale states of r^d (dugdale_table.hpp)
  detail::BuildOnceCache<std::vector<double>, detail::DugdaleTable> dugdale_tables{64};
  // nu -> beta: a handful of entries per process.
  detail::BuildOnceCache<double, double> uniform_betas;
};

namespace detail {

struct ContextAccess {
  static Context::Caches& caches(Context& context) { return *context.caches_; }
};

// The caches of `context`, or of Context::global() when it is null.
inline auto& context_caches(const std::shared_ptr<Context>& context) {
  return ContextAccess::caches(context ? *context : Context::global());
}

}  // namespace detail
}  // namespace layerjkr
