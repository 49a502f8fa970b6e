// Batches: a pool of threads pulls curves from a shared counter; one fit per curve. The counter
// hands out indices in order, so the curves that ran when a batch stops are a prefix of the
// input, and finished items can be passed on in input order as soon as the prefix grows.
#include <algorithm>
#include <atomic>
#include <exception>
#include <filesystem>
#include <mutex>
#include <optional>
#include <thread>

#include "layerjkr/error.hpp"
#include "layerjkr/fit.hpp"
#include "layerjkr/instrument.hpp"

namespace layerjkr {
namespace {

namespace fs = std::filesystem;

// Why `path` is not a regular file the readers may open, or "" when it is one. Checked before
// opening: opening a FIFO blocks until someone writes to it.
std::string not_a_file(const std::string& path) {
  std::error_code ec;
  const fs::file_status st = fs::status(path, ec);
  if (fs::is_regular_file(st)) return {};
  if (fs::is_directory(st)) return path + ": is a directory, not a curve file";
  if (fs::is_fifo(st)) return path + ": is a FIFO (named pipe), not a regular file; not opened, reading it could block";
  if (fs::is_socket(st)) return path + ": is a socket, not a regular file";
  if (fs::is_block_file(st) || fs::is_character_file(st)) return path + ": is a device, not a regular file";
  if (ec == std::errc::too_many_symbolic_link_levels) return path + ": is a symbolic link loop";
  std::error_code lec;
  if (fs::is_symlink(fs::symlink_status(path, lec))) return path + ": is a dangling symbolic link (its target does not exist)";
  if (ec) return path + ": cannot be read (" + ec.message() + ")";
  return path + ": is not a regular file";
}

template <class Load>
std::vector<BatchItem> run_batch(std::vector<BatchItem> items, Load load, const Scene& scene,
                                 const FitOptions& options, const BatchOptions& batch, bool cancelled = false) {
  if (batch.jobs < 1) throw DomainError("fit_batch", "jobs", batch.jobs, ">= 1");
  options.validate();
  const std::size_t n = items.size();
  std::atomic<std::size_t> next{0};
  std::atomic<bool> stop{cancelled};
  // Under `lock`: which items finished, how many were passed to on_item, the first hook error.
  std::mutex lock;
  std::vector<char> finished(n, 0);
  std::size_t done = 0, emitted = 0;
  std::exception_ptr hook_error;
  auto finish = [&](std::size_t i) {
    const std::lock_guard<std::mutex> guard(lock);
    finished[i] = 1;
    ++done;
    if (hook_error) return;
    try {
      for (; emitted < n && finished[emitted]; ++emitted)
        if (batch.on_item) batch.on_item(emitted, items[emitted]);
      if (batch.progress) batch.progress(done, n);
    } catch (...) {  // a caller's hook: stop the batch, rethrow after the join
      hook_error = std::current_exception();
      stop = true;
    }
  };
  auto worker = [&] {
    for (;;) {
      if (stop || (batch.cancelled && batch.cancelled())) {
        stop = true;
        return;
      }
      const std::size_t i = next++;
      if (i >= n) return;
      BatchItem& item = items[i];
      try {
        if (batch.skip && batch.skip(item)) {
          item.skipped = true;
        } else {
          item.summary = fit(load(i), scene, options);
          item.summary.delta = {};
          item.summary.P = {};
          item.summary.P_fit = {};
          item.ok = true;
        }
      } catch (const std::exception& e) {  // one bad curve never stops the batch
        item.ok = false;
        item.error = e.what();
      }
      finish(i);
    }
  };
  const int threads = static_cast<int>(std::min<std::size_t>(static_cast<std::size_t>(batch.jobs), std::max<std::size_t>(n, 1)));
  std::vector<std::thread> pool;
  for (int t = 1; t < threads; ++t) pool.emplace_back(worker);
  worker();
  for (auto& t : pool) t.join();
  if (hook_error) std::rethrow_exception(hook_error);
  for (std::size_t i = std::min(next.load(), n); i < n; ++i) {
    items[i].cancelled = true;
    items[i].error = "cancelled before it was fitted";
  }
  return items;
}

}  // namespace

std::vector<BatchItem> fit_batch(const std::vector<CurveData>& curves, const Scene& scene,
                                 const FitOptions& options, const BatchOptions& batch) {
  std::vector<BatchItem> items(curves.size());
  for (std::size_t i = 0; i < curves.size(); ++i) items[i].source = curves[i].source;
  return run_batch(std::move(items), [&](std::size_t i) { return curves[i]; }, scene, options, batch);
}

std::vector<BatchItem> fit_files(const std::vector<std::string>& paths, const Scene& scene,
                                 const FitOptions& options, const CsvOptions& csv,
                                 const BatchOptions& batch) {
  csv.validate();
  // Instrument files are read here, once each (a map holds many curves); CSV files are read
  // by the workers. A slot without data and without a path carries a read error.
  struct Slot {
    std::string csv_path;
    std::optional<CurveData> data;
    std::string error;
  };
  std::vector<BatchItem> items;
  std::vector<Slot> slots;
  bool cancelled = false;
  auto add = [&](BatchItem item, Slot slot) {
    items.push_back(std::move(item));
    slots.push_back(std::move(slot));
  };
  for (const std::string& path : paths) {
    BatchItem file_item;
    file_item.source = path;
    Slot file_slot;
    // Once cancelled, the rest are not read: run_batch marks their items cancelled.
    cancelled = cancelled || (batch.cancelled && batch.cancelled());
    if (!cancelled) file_slot.error = not_a_file(path);
    if (cancelled || !file_slot.error.empty() || !is_instrument_file(path)) {
      if (file_slot.error.empty()) file_slot.csv_path = path;
      add(std::move(file_item), std::move(file_slot));
      continue;
    }
    try {
      const InstrumentFile file = read_instrument_file(path);
      for (const InstrumentCurve& c : file.curves) {
        BatchItem item;
        item.source = file.curves.size() > 1 ? path + "#" + std::to_string(c.index) : path;
        item.curve = c.index;
        item.x = c.x;
        item.y = c.y;
        item.grid_x = c.grid_x;
        item.grid_y = c.grid_y;
        Slot s;
        try {
          s.data = to_curve_data(c, item.source, csv.spring_constant);
        } catch (const std::exception& e) {
          s.error = e.what();
        }
        add(std::move(item), std::move(s));
      }
    } catch (const std::exception& e) {  // the file's own row, never the batch
      file_slot.error = e.what();
      add(std::move(file_item), std::move(file_slot));
    }
  }
  return run_batch(
      std::move(items),
      [&](std::size_t i) {
        const Slot& s = slots[i];
        if (!s.error.empty()) throw InputError(s.error);
        // Checked again: the file may have changed since the list was made.
        if (!s.data) {
          const std::string why = not_a_file(s.csv_path);
          if (!why.empty()) throw InputError(why);
        }
        return s.data ? *s.data : read_curve_csv(s.csv_path, csv);
      },
      scene, options, batch, cancelled);
}

}  // namespace layerjkr
