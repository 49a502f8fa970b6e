// Batches: a pool of threads pulls curves from a shared counter; one fit per curve.
#include <algorithm>
#include <atomic>
#include <mutex>
#include <optional>
#include <thread>

#include "layerjkr/error.hpp"
#include "layerjkr/fit.hpp"
#include "layerjkr/instrument.hpp"

namespace layerjkr {
namespace {

template <class Load>
std::vector<BatchItem> run_batch(std::size_t n, Load load, const Scene& scene,
                                 const FitOptions& options, const BatchOptions& batch) {
  if (batch.jobs < 1) throw DomainError("fit_batch", "jobs", batch.jobs, ">= 1");
  options.validate();
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
  csv.validate();
  // Instrument files are read here, once each (a map holds many curves); CSV files are read
  // by the workers. A slot without data and without a path carries a read error.
  struct Slot {
    BatchItem item;
    std::string csv_path;
    std::optional<CurveData> data;
    std::string error;
  };
  std::vector<Slot> slots;
  for (const std::string& path : paths) {
    if (!is_instrument_file(path)) {
      Slot s;
      s.item.source = path;
      s.csv_path = path;
      slots.push_back(std::move(s));
      continue;
    }
    try {
      const InstrumentFile file = read_instrument_file(path);
      for (const InstrumentCurve& c : file.curves) {
        Slot s;
        s.item.source = file.curves.size() > 1 ? path + "#" + std::to_string(c.index) : path;
        s.item.curve = c.index;
        s.item.x = c.x;
        s.item.y = c.y;
        s.item.grid_x = c.grid_x;
        s.item.grid_y = c.grid_y;
        try {
          s.data = to_curve_data(c, s.item.source, csv.spring_constant);
        } catch (const std::exception& e) {
          s.error = e.what();
        }
        slots.push_back(std::move(s));
      }
    } catch (const std::exception& e) {  // the file's own row, never the batch
      Slot s;
      s.item.source = path;
      s.error = e.what();
      slots.push_back(std::move(s));
    }
  }
  std::vector<BatchItem> items = run_batch(
      slots.size(),
      [&](std::size_t i, std::string* source) {
        const Slot& s = slots[i];
        *source = s.item.source;
        if (!s.error.empty()) throw InputError(s.error);
        return s.data ? *s.data : read_curve_csv(s.csv_path, csv);
      },
      scene, options, batch);
  for (std::size_t i = 0; i < items.size(); ++i) {
    items[i].curve = slots[i].item.curve;
    items[i].x = slots[i].item.x;
    items[i].y = slots[i].item.y;
    items[i].grid_x = slots[i].item.grid_x;
    items[i].grid_y = slots[i].item.grid_y;
  }
  return items;
}

}  // namespace layerjkr
