// The fit and fit-map pictures (plots.hpp), drawn by gnuplot from temporary data files.
#include "plots.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <functional>
#include <sstream>

#include "gnuplot.hpp"
#include "layerjkr/error.hpp"

namespace layerjkr::cli {
namespace {

namespace fs = std::filesystem;

std::string num(double v) { return std::isfinite(v) ? format_double(v) : ""; }

}  // namespace

namespace {

// The SI prefix for values up to `largest` in magnitude: (factor to multiply by, label such as
// "µm"); the axes then carry plain numbers and the unit in their titles.
std::pair<double, std::string> si_scale(double largest, const std::string& unit) {
  static const std::pair<double, const char*> prefixes[] = {{1e-15, "f"}, {1e-12, "p"}, {1e-9, "n"}, {1e-6, "\u00b5"},
                                                           {1e-3, "m"},   {1.0, ""},     {1e3, "k"},  {1e6, "M"},
                                                           {1e9, "G"}};
  std::pair<double, const char*> chosen = prefixes[5];
  if (std::isfinite(largest) && largest > 0.0)
    for (const auto& p : prefixes)
      if (largest >= 0.999 * p.first) chosen = p;
  return {1.0 / chosen.first, chosen.second + unit};
}

double largest_magnitude(const std::vector<double>& v) {
  double m = 0.0;
  for (double x : v)
    if (std::isfinite(x)) m = std::max(m, std::fabs(x));
  return m;
}

}  // namespace

// Data, fitted curve and residuals with gnuplot, through a temporary file: force against the
// indentation from the model's contact point (FitSummary::model_delta0), the fit as a line, units
// scaled to a prefix. The data go to a private scratch file that gnuplot reads by name, removed
// whether gnuplot succeeds or not.
void plot_fit(const FitSummary& s, OutputFile& png) {
  const double d0 = s.model_delta0();
  const bool in_time = !s.t.empty();
  std::vector<double> indentation(s.delta.size()), residual(s.delta.size());
  for (std::size_t i = 0; i < s.delta.size(); ++i) {
    indentation[i] = in_time ? s.t[i] : s.delta[i] - d0;
    residual[i] = s.P[i] - s.P_fit[i];
  }
  const auto x = in_time ? std::pair<double, std::string>{1.0, "s"} : si_scale(largest_magnitude(indentation), "m");
  const auto y = si_scale(std::max(largest_magnitude(s.P), largest_magnitude(s.P_fit)), "N");
  const auto r = si_scale(largest_magnitude(residual), "N");
  ScratchFile data("plot-data");
  {
    std::ostringstream f;
    f.precision(17);
    for (std::size_t i = 0; i < s.delta.size(); ++i)
      f << indentation[i] * x.first << " " << s.P[i] * y.first << " " << s.P_fit[i] * y.first << " "
        << residual[i] * r.first << " " << (!s.excluded.empty() && s.excluded[i] ? 1 : 0) << "\n";
    data.write(f.str());
  }
  const std::string dat = gnuplot_quoted(data.path());
  std::ostringstream g;
  std::ostringstream rms;
  rms.precision(4);
  rms << s.rms_residual;
  g << "set terminal pngcairo size 900,750 font ',10' noenhanced\n"
    << "set output " << gnuplot_quoted(png.temporary()) << "\n"
    << "set multiplot layout 2,1 title 'layerjkr fit: " << s.model << " (rms " << rms.str() << " N)'\n"
    << "set grid\n"
    << "set ylabel 'force [" << y.second << "]'\nset key top left\n"
    << "plot " << dat << " using 1:($5 == 0 ? $2 : 1/0) with points pt 7 ps 0.4 lc rgb '#3b6ea8' title 'data', "
    << "'' using 1:($5 == 1 ? $2 : 1/0) with points pt 7 ps 0.4 lc rgb '#e67e22' title '"
    << (in_time ? "not fitted (history only, or excluded)" : "excluded (not JKR)") << "', "
    << "'' using 1:3 with lines lw 2 lc rgb '#c0392b' title 'fit'\n"
    << "set xlabel '" << (in_time ? "time" : "indentation delta - delta0") << " [" << x.second
    << "]'\nset ylabel 'residual [" << r.second
    << "]'\nunset key\n"
    << "plot " << dat << " using 1:4 with points pt 7 ps 0.3 lc rgb '#3b6ea8', 0 lc rgb '#c0392b'\n"
    << "unset multiplot\n";
  run_gnuplot(g.str(), png.temporary(), "--plot");
  png.commit();
}

void plot_joint(const JointFitSummary& j, OutputFile& png) {
  // The curves in turn on one time axis: each shifted to start a tenth of the longest after the
  // one before ends.
  FitSummary s = j.fit;
  double longest = 0.0;
  for (std::size_t k = 0; k + 1 < j.curve_begin.size(); ++k)
    if (j.curve_begin[k + 1] > j.curve_begin[k])
      longest = std::max(longest, s.t[j.curve_begin[k + 1] - 1] - s.t[j.curve_begin[k]]);
  double offset = 0.0;
  for (std::size_t k = 0; k + 1 < j.curve_begin.size(); ++k) {
    if (j.curve_begin[k + 1] == j.curve_begin[k]) continue;
    const double start = s.t[j.curve_begin[k]], end = s.t[j.curve_begin[k + 1] - 1];
    for (std::size_t i = j.curve_begin[k]; i < j.curve_begin[k + 1]; ++i) s.t[i] = s.t[i] - start + offset;
    offset += end - start + 0.1 * longest;
  }
  s.model += ", " + std::to_string(j.sources.size()) + " curves in turn";
  plot_fit(s, png);
}

std::vector<std::string> map_plot_names(const std::vector<FitParameter>& free) {
  std::vector<std::string> names;
  names.reserve(free.size() + 3);
  for (FitParameter q : free) names.push_back(std::string(to_string(q)) + ".png");
  for (const char* n : {"pull_off", "rms_residual", "status"}) names.push_back(std::string(n) + ".png");
  return names;
}

void prepare_plot_dir(const std::string& dir, const std::vector<std::string>& names, bool force) {
  prepare_derived_dir(dir, "--plot-dir", names, force, is_marked_png, "a picture layerjkr drew");
}

void plot_map_fields(const std::vector<BatchItem>& items, const std::vector<FitParameter>& free,
                     const std::string& dir, bool force) {
  int nx = 0, ny = 0;
  std::size_t placed = 0;
  for (const auto& it : items) {
    nx = std::max(nx, it.grid_x + 1);
    ny = std::max(ny, it.grid_y + 1);
    placed += it.grid_x >= 0 && it.grid_y >= 0 ? 1 : 0;
  }
  // The grid a header announces is bounded by the curves present: a grid mostly empty (a header's
  // 1e6 x 1e6 over 4 curves) is drawn as its pixels alone, never allocated.
  const bool sparse = static_cast<double>(nx) * ny > std::max(16.0 * static_cast<double>(placed), 4096.0);
  if (nx == 0 || ny == 0)
    throw InputError("--plot-dir: no input carries map positions (instrument force maps and QI files do)");
  prepare_plot_dir(dir, map_plot_names(free), force);
  struct Field {
    std::string name, label;
    std::function<double(const BatchItem&)> value;
  };
  std::vector<Field> fields;
  for (FitParameter q : free) {
    const std::string n = to_string(q);
    const std::string unit = unit_of(q);
    const std::string label = (q == FitParameter::delta0 ? "contact point delta0" : q == FitParameter::P0 ? "baseline P0" : n) +
                              (unit.empty() ? std::string() : " [" + unit + "]");
    fields.push_back({n, label, [q](const BatchItem& it) {
                        for (const auto& e : it.summary.parameters)
                          if (e.parameter == q) return e.value;
                        return std::nan("");
                      }});
  }
  fields.push_back({"pull_off", "measured pull-off force [N]", [](const BatchItem& it) { return it.summary.pull_off_force; }});
  fields.push_back({"rms_residual", "rms residual [N]", [](const BatchItem& it) { return it.summary.rms_residual; }});
  fields.push_back({"status", "status (1 fitted, 0 failed)", [](const BatchItem& it) { return it.ok ? 1.0 : 0.0; }});
  for (const Field& f : fields) {
    OutputFile png((fs::path(dir) / (f.name + ".png")).string());
    ScratchFile data("plot-data");
    if (sparse) {
      std::ostringstream d;
      d.precision(17);
      for (const auto& it : items)
        if (it.grid_x >= 0 && it.grid_y >= 0) {
          const double v = f.name == "status" || it.ok ? f.value(it) : std::nan("");
          d << it.grid_x << " " << it.grid_y << " " << (std::isfinite(v) ? num(v) : std::string("NaN")) << "\n";
        }
      data.write(d.str());
    } else {
      std::ostringstream d;
      d.precision(17);
      // gnuplot's image needs every pixel of the grid: NaN where there is no value.
      std::vector<double> grid(static_cast<std::size_t>(nx) * static_cast<std::size_t>(ny), std::nan(""));
      for (const auto& it : items)
        if (it.grid_x >= 0 && it.grid_y >= 0)
          grid[static_cast<std::size_t>(it.grid_y) * static_cast<std::size_t>(nx) + static_cast<std::size_t>(it.grid_x)] =
              f.name == "status" || it.ok ? f.value(it) : std::nan("");
      for (int y = 0; y < ny; ++y)
        for (int x = 0; x < nx; ++x) {
          const double v = grid[static_cast<std::size_t>(y) * static_cast<std::size_t>(nx) + static_cast<std::size_t>(x)];
          d << x << " " << y << " " << (std::isfinite(v) ? num(v) : std::string("NaN")) << "\n";
        }
      data.write(d.str());
    }
    std::ostringstream g;
    g << "set terminal pngcairo size 640,560 font ',10' noenhanced\nset output " << gnuplot_quoted(png.temporary()) << "\n"
      << "set title 'fit-map: " << f.label << "'\nset xlabel 'grid x'\nset ylabel 'grid y'\n"
      << "set xrange [-0.5:" << nx - 0.5 << "]\nset yrange [-0.5:" << ny - 0.5 << "]\n"
      << "set size ratio -1\nset palette rgb 33,13,10\nset colorbox\n"
      << (f.name == "status" ? "set cbrange [0:1]\n" : "")
      << "plot " << gnuplot_quoted(data.path())
      << (sparse ? " using 1:2:3 with points pt 5 ps 1.5 palette notitle\n" : " using 1:2:3 with image notitle\n");
    run_gnuplot(g.str(), png.temporary(), "--plot-dir");
    png.commit();
  }
}

}  // namespace layerjkr::cli
