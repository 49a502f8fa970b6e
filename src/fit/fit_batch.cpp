// Batches: a pool of threads pulls curves from a shared counter; one fit per curve.
#include <algorithm>
#include <atomic>
#include <mutex>
#include <thread>

#include "layerjkr/error.hpp"
#include "layerjkr/fit.hpp"

namespace layerjkr {
namespace {

template <class Load>
std::vector<BatchItem> run_batch(std::size_t n, Load load, const Scene& scene,
                                 const FitOptions& options, const BatchOptions& batch) {
  if (batch.jobs < 1) throw DomainError("fit_batch", "jobs", batch.jobs, ">= 1");
  options.Validate();
  std::vector<BatchItem> items(n);
  std::atomic<std::size_t> next{0}, done{0};
  std::mutex progress_mutex;
  auto worker = [&] {
    for (std::size_t i = next++; i < n; i = next++) {
      BatchItem& item = items[i];
      try {
        const CurveData curve = load(i, &item.source);
        item.summary = fit(curve, scene, options);
        item.summary.delta = {};
        item.summary.P = {};
        item.summary.P_fit = {};
        item.ok = true;
      } catch (const std::exception& e) {  // one bad curve never stops the batch
        item.ok = false;
        item.error = e.what();
      }
      const std::size_t d = ++done;
      if (batch.progress) {
        const std::lock_guard<std::mutex> lock(progress_mutex);
        batch.progress(d, n);
      }
    }
  };
  const int threads = static_cast<int>(std::min<std::size_t>(static_cast<std::size_t>(batch.jobs), std::max<std::size_t>(n, 1)));
  std::vector<std::thread> pool;
  for (int t = 1; t < threads; ++t) pool.emplace_back(worker);
  worker();
  for (auto& t : pool) t.join();
  return items;
}

}  // namespace

std::vector<BatchItem> fit_batch(const std::vector<CurveData>& curves, const Scene& scene,
                                 const FitOptions& options, const BatchOptions& batch) {
  return run_batch(
      curves.size(),
      [&](std::size_t i, std::string* source) {
        *source = curves[i].source;
        return curves[i];
      },
      scene, options, batch);
}

std::vector<BatchItem> fit_files(const std::vector<std::string>& paths, const Scene& scene,
                                 const FitOptions& options, const CsvOptions& csv,
                                 const BatchOptions& batch) {
  csv.Validate();
  return run_batch(
      paths.size(),
      [&](std::size_t i, std::string* source) {
        *source = paths[i];
        return read_curve_csv(paths[i], csv);
      },
      scene, options, batch);
}

}  // namespace layerjkr
