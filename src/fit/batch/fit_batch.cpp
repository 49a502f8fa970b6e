// Batches: a pool of threads pulls curves from a shared counter; one fit per curve. The counter
// hands out indices in order, so the curves that ran when a batch stops are a prefix of the
// input, and finished items can be passed on in input order as soon as the prefix grows.
#include <algorithm>
#include <atomic>
#include <exception>
#include <memory>
#include <mutex>
#include <optional>
#include <thread>

#include "io/read_file.hpp"
#include "layerjkr/error.hpp"
#include "layerjkr/fit.hpp"
#include "layerjkr/instrument.hpp"
#include "layerjkr/map_report.hpp"

namespace layerjkr {
namespace {

// A curve that could not be fitted keeps its samples as read (thinned; no fit, nothing
// excluded), so a report can show what failed beside why.
void keep_raw_for_display(const CurveData& data, std::size_t display_points, FitSummary* s) {
  s->delta = data.delta;
  s->P = data.P;
  s->P_fit.clear();
  s->excluded.clear();
  s->points = data.delta.size();
  thin_for_display(*s, display_points);
}

// `load(i, item)` reads item i (and may fill in its map position); `unread(i)` is told of an
// item that will not be loaded (skipped or cancelled), so that a file reader can close.
template <class Load, class Unread>
std::vector<BatchItem> run_batch(std::vector<BatchItem> items, Load load, Unread unread, const Scene& scene,
                                 const FitOptions& options, const BatchOptions& batch, bool cancelled = false) {
  if (batch.jobs < 1) throw DomainError("fit_batch", "jobs", batch.jobs, ">= 1");
  if (batch.display_points > 0 && batch.display_points < 8)
    throw DomainError("fit_batch", "display_points", static_cast<double>(batch.display_points), "0 or >= 8");
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
          unread(i);
        } else {
          const CurveData data = load(i, item);
          try {
            item.summary = fit(data, scene, options);
          } catch (const std::exception&) {
            if (batch.display_points > 0) keep_raw_for_display(data, batch.display_points, &item.summary);
            throw;
          }
          if (batch.display_points > 0) {
            // Thinned copies are moved in, so the full vectors' memory goes with them.
            thin_for_display(item.summary, batch.display_points);
          } else {
            // Move-assigned empties: `v = {}` would keep each vector's capacity, 12 bytes per
            // sample of every curve of a map (425 MB for 16 384 curves of 2 048 samples).
            item.summary.delta = std::vector<double>();
            item.summary.P = std::vector<double>();
            item.summary.P_fit = std::vector<double>();
            item.summary.excluded = std::vector<bool>();
          }
          // A fit whose answer is absurd is a failed curve, with the reason (its summary kept).
          item.ok = item.summary.failure.empty();
          if (!item.ok) item.error = "the fit failed: " + item.summary.failure;
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
    unread(i);
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
  return run_batch(
      std::move(items), [&](std::size_t i, BatchItem&) { return curves[i]; }, [](std::size_t) {}, scene, options, batch);
}

namespace {

// An instrument file of a batch: its reader while curves of it remain to be read. Opened once
// when the batch is listed and kept open or closed (kKeepOpen* below); closed, its worker
// reopens it; its last curve closes it.
class FileSlot {
 public:
  FileSlot(std::string path, std::unique_ptr<InstrumentReader> reader, std::size_t curves)
      : path_(std::move(path)), reader_(std::move(reader)), remaining_(curves) {}

  // The curve at `position`, its reader opened again if it was closed; the last curve of the
  // file closes it.
  InstrumentCurve read(std::size_t position) {
    std::shared_ptr<const InstrumentReader> reader;
    {
      const std::lock_guard<std::mutex> guard(lock_);
      if (!reader_) reader_ = std::make_shared<const InstrumentReader>(path_);
      reader = reader_;
    }
    struct Release {
      FileSlot& slot;
      ~Release() { slot.release(); }
    } release_after{*this};  // also when the curve cannot be read
    return reader->curve(position, CurveChannels{false});  // a fit needs no piezo height
  }
  // A curve of this file that will not be read (skipped, failed before reading, cancelled).
  void release() {
    const std::lock_guard<std::mutex> guard(lock_);
    if (remaining_ > 0 && --remaining_ == 0) reader_.reset();
  }

 private:
  std::string path_;
  std::mutex lock_;
  std::shared_ptr<const InstrumentReader> reader_;
  std::size_t remaining_;
};

// What a worker loads for each item: a CSV path, a curve of an instrument file, or an error
// found while listing.
struct Slot {
  std::string csv_path;
  std::shared_ptr<FileSlot> file;
  std::size_t position = 0;
  std::string error;
};

// Which files stay open between listing and reading: maps of at least kKeepOpenCurves curves
// (reopening a 65 536-curve archive costs as much as reading thousands of its curves) and the
// first kKeepOpenFiles files of any size (reopening a single curve costs 10 % of its fit);
// beyond those, small files are closed and reopened by their worker, so that a directory of
// 10 000 curves never holds 10 000 handles.
constexpr std::size_t kKeepOpenCurves = 64, kKeepOpenFiles = 256;

}  // namespace

std::vector<BatchItem> fit_files(const std::vector<std::string>& paths, const Scene& scene,
                                 const FitOptions& options, const CsvOptions& csv,
                                 const BatchOptions& batch) {
  csv.validate();
  std::vector<BatchItem> items;
  std::vector<Slot> slots;
  bool cancelled = false;
  auto add = [&](BatchItem item, Slot slot) {
    items.push_back(std::move(item));
    slots.push_back(std::move(slot));
  };
  const CurveRange& range = batch.curves;
  std::size_t kept_open = 0;
  for (const std::string& path : paths) {
    BatchItem file_item;
    file_item.source = path;
    Slot file_slot;
    // Once cancelled, the rest are not read: run_batch marks their items cancelled.
    cancelled = cancelled || (batch.cancelled && batch.cancelled());
    const bool folder_map = !cancelled && is_asylum_map_export(path);  // a directory or a glob: one map
    if (!cancelled && !folder_map) file_slot.error = detail::not_a_file(path);
    if (cancelled || !file_slot.error.empty() || (!folder_map && !is_instrument_file(path))) {
      if (file_slot.error.empty()) file_slot.csv_path = path;
      add(std::move(file_item), std::move(file_slot));
      continue;
    }
    try {
      auto reader = std::make_unique<InstrumentReader>(path);
      const std::size_t n = reader->size(), end = range.end_in(n);
      range.require_any(n, path);
      std::vector<int> numbers;
      for (std::size_t i = range.begin; i < end; ++i) numbers.push_back(reader->curve_number(i));
      if (n < kKeepOpenCurves && kept_open >= kKeepOpenFiles) reader.reset();
      kept_open += reader ? 1 : 0;
      const auto file = std::make_shared<FileSlot>(path, std::move(reader), end - range.begin);
      for (std::size_t i = range.begin; i < end; ++i) {
        BatchItem item;
        item.curve = numbers[i - range.begin];
        item.source = n > 1 ? path + "#" + std::to_string(item.curve) : path;
        add(std::move(item), Slot{"", file, i, ""});
      }
    } catch (const std::exception& e) {  // the file's own row, never the batch
      file_slot.error = e.what();
      add(std::move(file_item), std::move(file_slot));
    }
  }
  std::vector<BatchItem> done = run_batch(
      std::move(items),
      [&](std::size_t i, BatchItem& item) {
        const Slot& s = slots[i];
        if (!s.error.empty()) throw InputError(s.error);
        if (s.file) {
          const InstrumentCurve c = s.file->read(s.position);
          item.x = c.x;
          item.y = c.y;
          item.grid_x = c.grid_x;
          item.grid_y = c.grid_y;
          return to_curve_data(c, item.source, csv.spring_constant, csv.sensitivity);
        }
        // Checked again: the file may have changed since the list was made.
        const std::string why = detail::not_a_file(s.csv_path);
        if (!why.empty()) throw InputError(why);
        return read_curve_csv(s.csv_path, csv);
      },
      [&](std::size_t i) {
        if (slots[i].file) slots[i].file->release();
      },
      scene, options, batch, cancelled);
  return done;
}

std::string batch_quality(const BatchItem& item) {
  if (!item.ok) return "failed";
  if (!item.summary.converged) return "not converged";
  if (!item.summary.identifiable) return "not identifiable";
  if (!item.summary.warnings.empty()) return "warning";
  return "ok";
}

}  // namespace layerjkr
