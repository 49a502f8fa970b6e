// layerjkr fit / fit-map: parse options, call the library, write report, plot and CSV.
#include "fit_commands.hpp"

#include <glob.h>
#include <sys/wait.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <limits>
#include <sstream>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "layerjkr/layerjkr.hpp"

namespace layerjkr::cli {
namespace {

namespace fs = std::filesystem;
using json = nlohmann::ordered_json;

json number_or_null(double v) { return std::isfinite(v) ? json(v) : json(nullptr); }

void parse_loss(const std::string& text, FitOptions& o) {
  if (text == "none") return;
  const auto colon = text.find(':');
  const std::string kind = text.substr(0, colon);
  if ((kind != "huber" && kind != "cauchy") || colon == std::string::npos)
    throw InputError("--loss = \"" + text + "\" is invalid; use none, huber:SCALE or cauchy:SCALE (SCALE in N)");
  const std::string scale = text.substr(colon + 1);
  char* end = nullptr;
  const double s = std::strtod(scale.c_str(), &end);
  if (scale.empty() || *end != '\0' || !(s > 0.0) || !std::isfinite(s))
    throw InputError("--loss: scale '" + scale + "' must be a finite number > 0 [N]");
  o.loss = kind == "huber" ? LossType::huber : LossType::cauchy;
  o.loss_scale = s;
}

}  // namespace

Prepared prepare_options(const FitArguments& a) {
  Prepared p;
  p.options.free = parse_fit_parameters(a.free, "--free");
  p.options.branch = parse_branch(a.branch, "--branch");
  parse_loss(a.loss, p.options);
  p.options.extra_starts = a.extra_starts;
  p.options.max_iterations = a.max_iterations;
  parse_units(a.units, p.csv);
  p.csv.spring_constant = a.spring_constant;
  p.csv.z_sign = a.z_sign;
  p.csv.deflection_sign = a.deflection_sign;
  p.csv.curve = a.curve;
  // The retract's control: a known spring constant (instrument file, --spring-constant) means
  // a cantilever let go; without one, load control.
  if (a.control == "auto" || a.control == "cantilever") p.options.cantilever_stiffness = std::nan("");
  else if (a.control == "load") p.options.cantilever_stiffness = 0.0;
  else if (a.control == "grips") p.options.cantilever_stiffness = std::numeric_limits<double>::infinity();
  else throw InputError("--control = \"" + a.control + "\" is invalid; use auto, load, cantilever or grips");
  p.cantilever_required = a.control == "cantilever";
  if (a.baseline != "constant" && a.baseline != "tilt")
    throw InputError("--baseline = \"" + a.baseline + "\" is invalid; use constant or tilt");
  p.options.baseline_tilt = a.baseline == "tilt";
  if (a.window == "all") {
    p.options.retract_window = FitOptions::RetractWindow::all;
  } else if (a.window == "pull-off") {
    p.options.retract_window = FitOptions::RetractWindow::to_pull_off;
  } else if (a.window.rfind("fraction:", 0) == 0) {
    const std::string f = a.window.substr(9);
    char* end = nullptr;
    const double v = std::strtod(f.c_str(), &end);
    if (f.empty() || *end != '\0' || !(v > 0.0 && v <= 1.0))
      throw InputError("--window fraction:" + f + " is invalid; the fraction must be in (0, 1]");
    p.options.retract_window = FitOptions::RetractWindow::force_fraction;
    p.options.window_fraction = v;
  } else {
    throw InputError("--window = \"" + a.window + "\" is invalid; use all, pull-off or fraction:F");
  }
  try {
    p.options.validate();
    p.csv.validate();
  } catch (const DomainError& e) {
    throw InputError(std::string("invalid option: ") + e.what());
  }
  return p;
}

Prepared prepare(const FitArguments& a) {
  Prepared p = prepare_options(a);
  p.scene = load_scene(a.scene);
  return p;
}

nlohmann::ordered_json report_json(const FitSummary& s, Branch branch) {
  json j;
  j["converged"] = s.converged;
  j["termination"] = s.termination;
  j["iterations"] = s.iterations;
  j["model"] = s.model;
  j["family"] = s.family;
  j["branch"] = to_string(branch);
  json params = json::object();
  for (const auto& e : s.parameters)
    params[to_string(e.parameter)] = {{"value", e.value},
                                      {"stderr", number_or_null(e.standard_error)},
                                      {"initial", e.initial},
                                      {"at_bound", e.at_bound},
                                      {"identifiable", e.identifiable}};
  j["parameters"] = params;
  json corr = json::object();
  for (std::size_t i = 0; i < s.parameters.size(); ++i) {
    json row = json::object();
    for (std::size_t k = 0; k < s.parameters.size(); ++k)
      row[to_string(s.parameters[k].parameter)] = number_or_null(s.correlation[i][k]);
    corr[to_string(s.parameters[i].parameter)] = row;
  }
  j["correlation"] = corr;
  j["rms_residual"] = s.rms_residual;
  j["excluded"] = s.excluded_count;
  j["pull_off_force"] = number_or_null(s.pull_off_force);
  j["baseline_slope"] = s.baseline_slope;
  j["baseline_slope_stderr"] = s.baseline_slope_stderr;
  j["points"] = s.points;
  j["points_in_contact"] = s.points_in_contact;
  j["identifiable"] = s.identifiable;
  j["unidentifiable"] = s.unidentifiable;
  j["warnings"] = s.warnings;
  return j;
}

namespace {

// Writes via a temporary name so a failure never leaves a partial file.
void write_atomically(const std::string& path, const std::string& text) {
  const std::string tmp = path + ".tmp";
  {
    std::ofstream f(tmp, std::ios::binary);
    f << text;
    if (!f) throw InputError(path + ": cannot write the file");
  }
  fs::rename(tmp, path);
}

// Data, fitted curve and residuals with gnuplot (pngcairo), through a temporary file.
void plot_fit(const FitSummary& s, const std::string& path) {
  const std::string dat = path + ".dat.tmp", png = path + ".tmp.png";
  {
    std::ofstream f(dat);
    f.precision(17);
    for (std::size_t i = 0; i < s.delta.size(); ++i)
      f << s.delta[i] << " " << s.P[i] << " " << s.P_fit[i] << " " << s.P[i] - s.P_fit[i] << " "
        << (!s.excluded.empty() && s.excluded[i] ? 1 : 0) << "\n";
    if (!f) throw InputError(path + ": cannot write the plot data");
  }
  std::ostringstream g;
  g << "set terminal pngcairo size 900,750 font ',10' noenhanced\n"
    << "set output '" << png << "'\n"
    << "set multiplot layout 2,1 title 'layerjkr fit: " << s.model << " (rms " << s.rms_residual << " N)'\n"
    << "set format x '%.3s%c'\nset format y '%.1s%c'\nset grid\n"
    << "set ylabel 'force P [N]'\nset key top left\n"
    << "plot '" << dat << "' using 1:($5 == 0 ? $2 : 1/0) with points pt 7 ps 0.4 lc rgb '#777777' title 'data', "
    << "'' using 1:($5 == 1 ? $2 : 1/0) with points pt 7 ps 0.4 lc rgb '#e67e22' title 'excluded (not JKR)', "
    << "'' using 1:3 with points pt 7 ps 0.3 lc rgb '#c0392b' title 'fit'\n"
    << "set xlabel 'delta [m]'\nset ylabel 'residual [N]'\nunset key\n"
    << "plot '" << dat << "' using 1:4 with points pt 7 ps 0.3 lc rgb '#2c3e50', 0 lc rgb '#c0392b'\n"
    << "unset multiplot\n";
  FILE* pipe = popen("gnuplot 2>&1", "w");
  if (!pipe) throw Error("--plot: cannot start gnuplot");
  std::fputs(g.str().c_str(), pipe);
  const int status = pclose(pipe);
  std::remove(dat.c_str());
  if (status != 0 || !fs::exists(png)) {
    std::remove(png.c_str());
    throw Error("--plot: gnuplot failed (is it installed? apt-get install gnuplot-nox)");
  }
  fs::rename(png, path);
}

std::string csv_cell(const std::string& s) {
  if (s.find_first_of(",\"\n") == std::string::npos) return s;
  std::string q = "\"";
  for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c == '\n' ? ' ' : c);
  return q + "\"";
}

std::string num(double v) { return std::isfinite(v) ? format_double(v) : ""; }

std::vector<std::string> expand_inputs(const std::vector<std::string>& inputs) {
  std::vector<std::string> files;
  for (const auto& in : inputs) {
    std::error_code ec;
    if (fs::is_directory(in, ec)) {
      std::vector<std::string> found;
      for (const auto& e : fs::directory_iterator(in))
        if (e.is_regular_file() && (e.path().extension() == ".csv" || is_instrument_file(e.path().string())))
          found.push_back(e.path().string());
      std::sort(found.begin(), found.end());
      if (found.empty()) throw InputError(in + ": the directory holds no .csv or instrument files");
      files.insert(files.end(), found.begin(), found.end());
    } else if (in.find_first_of("*?[") != std::string::npos) {
      glob_t g{};
      const int rc = glob(in.c_str(), 0, nullptr, &g);
      std::vector<std::string> found(g.gl_pathv, g.gl_pathv + (rc == 0 ? g.gl_pathc : 0));
      globfree(&g);
      if (found.empty()) throw InputError(in + ": the pattern matches no files");
      files.insert(files.end(), found.begin(), found.end());
    } else if (fs::is_regular_file(in, ec)) {
      files.push_back(in);
    } else {
      throw InputError(in + ": no such file or directory");
    }
  }
  return files;
}

// One PNG per field over the map grid (pixels from the files' positions); a pixel with no
// curve or a failed fit is left blank, and status shows which ones failed.
void plot_map_fields(const std::vector<BatchItem>& items, const std::vector<FitParameter>& free,
                     const std::string& dir) {
  int nx = 0, ny = 0;
  for (const auto& it : items) {
    nx = std::max(nx, it.grid_x + 1);
    ny = std::max(ny, it.grid_y + 1);
  }
  if (nx == 0 || ny == 0)
    throw InputError("--plot-dir: no input carries map positions (instrument force maps and QI files do)");
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) throw InputError("--plot-dir " + dir + ": cannot create the directory (" + ec.message() + ")");
  struct Field {
    std::string name, label;
    std::function<double(const BatchItem&)> value;
  };
  std::vector<Field> fields;
  for (FitParameter q : free) {
    const std::string n = to_string(q);
    const std::string label = q == FitParameter::delta0 ? "contact point delta0 [m]"
                              : q == FitParameter::E    ? "E [Pa]"
                              : q == FitParameter::K    ? "K [N/m^3]"
                              : q == FitParameter::w    ? "w [J/m^2]"
                              : q == FitParameter::P0   ? "baseline P0 [N]"
                                                        : n;
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
    const std::string dat = (fs::path(dir) / (f.name + ".dat.tmp")).string();
    const std::string png = (fs::path(dir) / (f.name + ".png")).string();
    {
      std::ofstream d(dat);
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
      if (!d) throw InputError("--plot-dir: cannot write " + dat);
    }
    std::ostringstream g;
    g << "set terminal pngcairo size 640,560 font ',10' noenhanced\nset output '" << png << "'\n"
      << "set title 'fit-map: " << f.label << "'\nset xlabel 'grid x'\nset ylabel 'grid y'\n"
      << "set xrange [-0.5:" << nx - 0.5 << "]\nset yrange [-0.5:" << ny - 0.5 << "]\n"
      << "set size ratio -1\nset palette rgb 33,13,10\nset colorbox\n"
      << (f.name == "status" ? "set cbrange [0:1]\n" : "")
      << "plot '" << dat << "' using 1:2:3 with image notitle\n";
    FILE* pipe = popen("gnuplot 2>&1", "w");
    if (!pipe) throw Error("--plot-dir: cannot start gnuplot");
    std::fputs(g.str().c_str(), pipe);
    const int status = pclose(pipe);
    std::remove(dat.c_str());
    if (status != 0 || !fs::exists(png))
      throw Error("--plot-dir: gnuplot failed (is it installed? apt-get install gnuplot-nox)");
  }
}

}  // namespace

void add_fit_options(CLI::App& c, FitArguments& a) {
  c.add_option("--scene", a.scene, "Scene JSON: indenter, medium, model; starting values")->required();
  c.add_option("--free", a.free, "Parameters to fit, comma-separated: K,G (or T),w,delta0,P0,E,R")->required();
  c.add_option("--loss", a.loss, "Robust loss: none | huber:SCALE | cauchy:SCALE (SCALE in N)");
  c.add_option("--branch", a.branch, "approach | retract | all (default approach)");
  c.add_option("--units", a.units, "Units of the CSV: LENGTH,FORCE, e.g. nm,nN (default m,N)");
  c.add_option("--spring-constant", a.spring_constant, "Cantilever stiffness [N/m] for z,deflection data");
  c.add_option("--z-sign", a.z_sign, "+1 if z grows towards the sample, -1 if it decreases");
  c.add_option("--deflection-sign", a.deflection_sign, "+1 if deflection > 0 means repulsion, else -1");
  c.add_option("--starts", a.extra_starts, "Extra starts around the data-driven guess (default 0)");
  c.add_option("--max-iterations", a.max_iterations, "Ceres iteration limit (default 200)");
  c.add_option("--curve", a.curve, "Which curve of a file holding several (instrument map or export)");
  c.add_option("--baseline", a.baseline, "constant | tilt (a linear baseline from the samples off contact)");
  c.add_option("--window", a.window,
               "Retract samples used: all | pull-off (largest force to the force minimum) | fraction:F (the top F "
               "of the unloading force range)");
  c.add_option("--control", a.control,
               "Retract control: auto (cantilever when the spring constant is known, else load) | load | "
               "cantilever | grips");
}

namespace {

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
  if (p.cantilever_required && !(curve.spring_constant > 0.0))
    throw InputError("--control cantilever needs the spring constant: an instrument file, or --spring-constant k [N/m]");
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
