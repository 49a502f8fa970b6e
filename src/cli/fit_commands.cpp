// layerjkr fit / export: read the curves, call the library, write report, plot and CSV
// (fit-map: fit_map.cpp).
#include "fit_commands.hpp"

#include <algorithm>
#include <iostream>
#include <optional>

#include "files.hpp"
#include "layerjkr/layerjkr.hpp"
#include "plots.hpp"
#include "reports.hpp"

namespace layerjkr::cli {
namespace {

// The curve `fit` reads: a CSV file, or one curve of an instrument file (only that one is read).
CurveData read_fit_data(const std::string& path, const Prepared& p) {
  if (!is_instrument_file(path)) return read_curve_csv(path, p.csv);
  const InstrumentReader reader(path);
  if (p.csv.curve < 0 && reader.size() > 1)
    throw InputError(path + ": holds " + std::to_string(reader.size()) +
                     " curves; select one with --curve N, or fit them all with fit-map");
  for (std::size_t i = 0; i < reader.size(); ++i)
    if (p.csv.curve < 0 || reader.curve_number(i) == p.csv.curve) return to_curve_data(reader.curve(i), path, p.csv.spring_constant);
  throw InputError(path + ": has no curve " + std::to_string(p.csv.curve));
}

}  // namespace

int run_export(const std::string& path, const std::string& out, const std::string& curves) {
  check_not_input(out, "--out", {path});
  const CurveRange range = curves.empty() ? CurveRange{} : CurveRange::parse(curves, "--curves");
  OutputFile csv(out);
  const InstrumentReader reader(path);
  range.require_any(reader.size(), path);
  const std::size_t end = range.end_in(reader.size());
  csv.write("curve,segment,force,height,tip_position\n");
  // One curve at a time: a map is never held whole, in samples or in text.
  for (std::size_t k = range.begin; k < end; ++k) {
    const InstrumentCurve c = reader.curve(k);
    const CurveData d = to_curve_data(c, path);
    std::string text;
    std::size_t row = 0;
    for (const InstrumentSegment& seg : c.segments)
      for (std::size_t i = 0; i < seg.force.size(); ++i, ++row)
        text += std::to_string(c.index) + "," + std::to_string(d.segment[row]) + "," + format_double(seg.force[i]) +
                "," + format_double(seg.height[i]) + "," + format_double(-d.delta[row]) + "\n";
    csv.write(text);
  }
  csv.commit();
  std::cerr << "export: " << end - range.begin << " curve(s) of " << path << " written to " << out << "\n";
  return 0;
}

int run_fit(const FitArguments& args, const std::string& data, const std::string& report,
            const std::string& plot) {
  const Prepared p = prepare(args);
  // Both outputs are checked, and their files created, before the fit.
  check_not_input(report, "--out", {data, args.scene});
  check_not_input(plot, "--plot", {data, args.scene});
  std::optional<OutputFile> report_file, plot_file;
  if (!report.empty()) report_file.emplace(report);
  if (!plot.empty()) plot_file.emplace(plot);
  const CurveData curve = read_fit_data(data, p);
  const FitSummary s = fit(curve, p.scene, p.options);
  if (plot_file) plot_fit(s, *plot_file);
  if (report_file) {
    report_file->write(report_json(s, p.options.branch).dump(2) + "\n");
    report_file->commit();
  }
  std::cout << s.brief_report();
  return 0;
}

}  // namespace layerjkr::cli
