// layerjkr: the interactive force-map report - one static, self-contained HTML page of a
// batch's results (fit-map --report DIR, Python fit_files(report=DIR)); docs/report.md.
//
//   BatchOptions b;
//   b.display_points = kDefaultDisplayPoints;  // keep a thinned copy of each fitted curve
//   std::vector<BatchItem> items = fit_files(paths, scene, options, csv, b);
//   MapReportOptions r;
//   r.free = options.free;
//   std::string html = map_report_html(items, r);  // write it as DIR/index.html
//
// The page needs no network and no server (it works from file://): the plotting library
// (plotly.js, vendored in third_party/ and compiled into the library) and the data are inline.
// It shows a heat map per field (each free parameter and its standard error, the rms residual,
// iterations, samples in contact, excluded samples, pull-off force, baseline slope), with its
// colour bar and histogram; pixels marked by status; a filter by status; and, on a click or
// the arrow keys, that curve with its fit, residuals and excluded samples and its values.
// `window.layerjkr.select(i)` shows item i (the batch's order: the fit-map CSV's data row i,
// 0-based) and returns its values as an object keyed by the CSV's column names.
//
// Layout: each instrument file with map pixels is one grid view (its pixels at grid_x,
// grid_y); every other item (CSV curves, single-curve files, curves without a pixel, failed
// files) goes to one view by index, row-major, ceil(sqrt(n)) columns wide. A selector
// switches views.
//
// Thinning (display_samples): a curve is shown by at most about `max_points` of its samples,
// chosen so that the drawn shape, its extremes and the excluded spans stay true; see there.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "layerjkr/fit.hpp"
#include "layerjkr/types.hpp"

namespace layerjkr {

/// Samples a report keeps per curve unless told otherwise: a 128 x 128 map's report is then
/// about 30 MB (docs/report.md has the measured sizes).
constexpr std::size_t kDefaultDisplayPoints = 200;

/// The samples of a fitted curve (P, P_fit and excluded aligned, `excluded` may be empty:
/// none) a display keeps, as increasing indices. With n samples and n <= max_points, all of
/// them; otherwise the samples are cut into (max_points - 2) / 4 bins of consecutive samples
/// (acquisition order), and kept are: the first and last sample; in each bin the first
/// samples where P and where the residual P - P_fit are smallest and largest (so every bin's
/// range of P and of the residual, hence every spike, is drawn); and both samples of every
/// change between included and excluded (so each excluded span starts and ends where it
/// did). At most max_points + 2 x (number of such changes) indices. NaN values are never
/// chosen as an extreme. Throws DomainError for max_points < 8 and InputError for vectors of
/// different lengths.
std::vector<std::size_t> display_samples(const std::vector<double>& P, const std::vector<double>& P_fit,
                                         const std::vector<bool>& excluded, std::size_t max_points);

/// Replaces the per-sample vectors of `s` (delta, P, P_fit, excluded) by the samples
/// display_samples keeps; the rest of the summary (excluded_count, points ...) is unchanged.
/// A summary without samples stays as it is; one without P_fit (a curve that failed, kept
/// as read) is thinned by its force alone.
void thin_for_display(FitSummary& s, std::size_t max_points);

struct MapReportOptions {
  /// The batch's free parameters (FitOptions::free), in order: their columns and maps.
  std::vector<FitParameter> free;
  /// The page's title, and a line under it (e.g. the command that made it); both plain text.
  std::string title = "layerjkr force-map report";
  std::string subtitle;
  /// Samples kept per curve (display_samples; items already thinned to this are unchanged),
  /// >= 8.
  std::size_t display_points = kDefaultDisplayPoints;
  /// Throws DomainError naming the first invalid field.
  void validate() const;
};

/// The report's data as JSON text (what the page embeds; for tests and other viewers):
/// `columns` (one array per CSV column of fit-map, the values exactly, null for none, plus
/// quality, warnings, unidentifiable, termination, points, points_in_contact, excluded_count,
/// pull_off_force, baseline_slope), `fields` (the mapped columns, with units), `views` (the
/// layout above: name, nx, ny and the item index of each cell, row-major, -1 for none) and
/// `curves` (per item null or its thinned samples: n, the original count; delta and P / P_fit
/// as 16-bit codes, base64, little-endian, between the stated lo and hi, P and P_fit sharing one
/// range; excluded as [first, last] index pairs into the kept samples).
/// quality is "failed" (not fitted: error set), "not converged", "not identifiable",
/// "warning" (fitted with warnings), or "ok", the first that applies.
std::string map_report_data(const std::vector<BatchItem>& items, const MapReportOptions& options);

/// The whole page (HTML with its CSS, script, plotting library and data inline).
std::string map_report_html(const std::vector<BatchItem>& items, const MapReportOptions& options);

/// The page's file in report directory `dir`: dir/index.html.
std::string map_report_page(const std::string& dir);

/// Makes `dir` ready for a report, before any fitting: creates it (and its parents) if
/// missing; an existing directory must be empty or hold a previous report and nothing else
/// (one entry, index.html, whose text starts as map_report_html's does), which is then
/// replaced - besides the files named in `also` (the caller's other outputs, e.g. fit-map's
/// results table, which may go beside the page); and it must take new files (checked by
/// creating and removing one). Throws InputError naming `flag` (e.g. "--report") and `dir`
/// for a path that exists and is not a directory, cannot be created or written, or holds
/// other files.
void prepare_report_dir(const std::string& dir, const std::string& flag, const std::vector<std::string>& also = {});

}  // namespace layerjkr
