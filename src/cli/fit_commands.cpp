// layerjkr fit / fit-map / export: read the curves, call the library, write report, plot and CSV.
#include "fit_commands.hpp"

#include <chrono>
#include <cmath>
#include <iostream>
#include <sstream>

#include "files.hpp"
#include "layerjkr/layerjkr.hpp"
#include "plots.hpp"
#include "reports.hpp"

namespace layerjkr::cli {
namespace {

std::string csv_cell(const std::string& s) {
  if (s.find_first_of(",\"\n") == std::string::npos) return s;
  std::string q = "\"";
  for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c == '\n' ? ' ' : c);
  return q + "\"";
}

std::string num(double v) { return std::isfinite(v) ? format_double(v) : ""; }

// The curve `fit` reads: a CSV file, or one curve of an instrument file.
CurveData read_fit_data(const std::string& path, const Prepared& p) {
  if (!is_instrument_file(path)) return read_curve_csv(path, p.csv);
  const InstrumentFile file = read_instrument_file(path);
  if (p.csv.curve < 0 && file.curves.size() > 1)
    throw InputError(path + ": holds " + std::to_string(file.curves.size()) +
                     " curves; select one with --curve N, or fit them all with fit-map");
  for (const InstrumentCurve& c : file.curves)
    if (p.csv.curve < 0 || c.index == p.csv.curve) return to_curve_data(c, path, p.csv.spring_constant);
  throw InputError(path + ": has no curve " + std::to_string(p.csv.curve));
}

}  // namespace

int run_export(const std::string& path, const std::string& out) {
  const InstrumentFile file = read_instrument_file(path);
  std::string text = "curve,segment,force,height,tip_position\n";
  for (const InstrumentCurve& c : file.curves) {
    const CurveData d = to_curve_data(c, path);
    std::size_t row = 0;
    for (const InstrumentSegment& seg : c.segments)
      for (std::size_t i = 0; i < seg.force.size(); ++i, ++row)
        text += std::to_string(c.index) + "," + std::to_string(d.segment[row]) + "," + format_double(seg.force[i]) +
                "," + format_double(seg.height[i]) + "," + format_double(-d.delta[row]) + "\n";
  }
  write_atomically(out, text);
  std::cerr << "export: " << file.curves.size() << " curve(s) of " << path << " written to " << out << "\n";
  return 0;
}

int run_fit(const FitArguments& args, const std::string& data, const std::string& report,
            const std::string& plot) {
  const Prepared p = prepare(args);
  const CurveData curve = read_fit_data(data, p);
  const FitSummary s = fit(curve, p.scene, p.options);
  if (!plot.empty()) plot_fit(s, plot);
  if (!report.empty()) write_atomically(report, report_json(s, p.options.branch).dump(2) + "\n");
  std::cout << s.brief_report();
  return 0;
}

int run_fit_map(const FitArguments& args, const std::vector<std::string>& inputs, int jobs,
                const std::string& out, const std::string& plot_dir) {
  const Prepared p = prepare(args);
  if (jobs < 1) throw InputError("--jobs = " + std::to_string(jobs) + " must be >= 1");
  const std::vector<std::string> files = expand_inputs(inputs);
  BatchOptions b;
  b.jobs = jobs;
  const auto t0 = std::chrono::steady_clock::now();
  auto last = t0 - std::chrono::seconds(1);
  b.progress = [&](std::size_t done, std::size_t total) {
    const auto now = std::chrono::steady_clock::now();
    if (done != total && now - last < std::chrono::milliseconds(200)) return;
    last = now;
    const int width = 30, filled = static_cast<int>(width * done / total);
    std::cerr << "\rfit-map [" << std::string(filled, '#') << std::string(width - filled, ' ') << "] "
              << done << "/" << total << "  "
              << std::chrono::duration<double>(now - t0).count() << " s" << std::flush;
    if (done == total) std::cerr << "\n";
  };
  const std::vector<BatchItem> items = fit_files(files, p.scene, p.options, p.csv, b);
  std::ostringstream csv;
  csv << "file,curve,x,y,grid_x,grid_y,status,error,model,converged,iterations,rms_residual,identifiable";
  for (FitParameter q : p.options.free) csv << "," << to_string(q) << "," << to_string(q) << "_stderr";
  csv << "\n";
  std::size_t failed = 0;
  for (const auto& it : items) {
    auto index = [](int v) { return v >= 0 ? std::to_string(v) : std::string(); };
    csv << csv_cell(it.source) << "," << index(it.curve) << "," << num(it.x) << "," << num(it.y) << ","
        << index(it.grid_x) << "," << index(it.grid_y) << "," << (it.ok ? "ok" : "error") << "," << csv_cell(it.error);
    if (it.ok) {
      const FitSummary& s = it.summary;
      csv << "," << s.model << "," << (s.converged ? 1 : 0) << "," << s.iterations << ","
          << format_double(s.rms_residual) << "," << (s.identifiable ? 1 : 0);
      for (const auto& e : s.parameters) csv << "," << num(e.value) << "," << num(e.standard_error);
    } else {
      ++failed;
      csv << ",,,,,";
      for (std::size_t k = 0; k < p.options.free.size(); ++k) csv << ",,";
    }
    csv << "\n";
  }
  write_atomically(out, csv.str());
  if (!plot_dir.empty()) plot_map_fields(items, p.options.free, plot_dir);
  std::cerr << "fit-map: " << items.size() - failed << " of " << items.size() << " curves fitted";
  if (failed) std::cerr << "; " << failed << " failed (see the error column of " << out << ")";
  std::cerr << "\n";
  return 0;
}

}  // namespace layerjkr::cli
