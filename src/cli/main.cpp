// layerjkr command-line tool: a thin layer over the public API.
//   layerjkr curve SCENE.json (--at a1,a2,... | --a-max A --points N)
//   layerjkr summary SCENE.json
//   layerjkr fit DATA.csv --scene S.json --free E,w,delta0 [--out R.json] [--plot F.png] ...
//   layerjkr fit --from-report R.json [--out R2.json] [--plot F.png]
//   layerjkr fit-map DIR_OR_GLOB... --scene S.json --free ... --jobs N --out RESULTS.csv [--report DIR] [--resume]
//   layerjkr fit-map --from-report RESULTS.json --out AGAIN.csv [--jobs N] [--report DIR]
//   layerjkr export FILE.jpk-force|.jpk-force-map|.jpk-qi-data|.ibw|.spm|.000 --out OUT.csv [--curves A:B]
//   layerjkr simulate SCENE.json --max-indentation D [--speed V ...] [--out CURVE.csv]
// Exit codes (kExitCodes below, printed by --help): 0 success, 1 internal or numerical failure, 2
// invalid scene, data or arguments (nothing written), 3 / 4 fit-map wrote its table but some / all of
// its curves failed, 130 / 143 fit-map stopped by SIGINT / SIGTERM. Every error is one line on stderr,
// printable (text.hpp): a value echoed from a file cannot drive the terminal.
#include <algorithm>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <string>
#include <thread>
#include <vector>

#include <CLI/CLI.hpp>
#include <glog/logging.h>
#include <nlohmann/json.hpp>

#include "discrete_command.hpp"
#include "fit_commands.hpp"
#include "limits.hpp"
#include "reports.hpp"
#include "simulate_command.hpp"
#include "layerjkr/layerjkr.hpp"

namespace {

using layerjkr::format_double;

constexpr const char* kExitCodes =
    "Exit codes: 0 success; 1 internal or numerical failure; 2 invalid scene, data or arguments (one line on "
    "stderr, nothing written); fit-map: 3 some curves failed (the table has their rows and errors), 4 no curve was "
    "fitted; 130 / 143 fit-map stopped by SIGINT / SIGTERM (the table so far is kept; --resume finishes it).";

// One printable line on stderr, whatever the message holds (CLI11's messages can span lines; a
// value echoed from a file can hold escape sequences).
int fail(int code, const std::string& message) {
  std::string line = "layerjkr: " + message;
  for (char& c : line)
    if (c == '\n' || c == '\r') c = ' ';
  std::cerr << layerjkr::printable(line) << "\n";
  return code;
}

void print_warnings(const std::vector<std::string>& warnings, const std::vector<std::string>& notices) {
  for (const auto& w : warnings) std::cerr << "layerjkr: warning: " << layerjkr::printable(w) << "\n";
  for (const auto& n : notices) std::cerr << "layerjkr: note: " << layerjkr::printable(n) << "\n";
}

void print_choice(const std::optional<layerjkr::AutoChoice>& choice) {
  if (choice) std::cerr << "layerjkr: " << layerjkr::printable(choice->brief_report()) << "\n";
}

int run_curve(const std::string& path, const std::string& at, double a_max, int points) {
  const layerjkr::Scene scene = layerjkr::load_scene(path);
  std::vector<double> radii;
  if (!at.empty()) {
    radii = layerjkr::cli::parse_radii(at);
  } else {
    if (!(a_max > 0.0) || !std::isfinite(a_max))
      throw layerjkr::InputError("--a-max = " + format_double(a_max) + " must be finite and > 0");
    layerjkr::cli::check_count("--points", points, 1, layerjkr::cli::kMaxPoints);
    for (int i = 1; i <= points; ++i) radii.push_back(a_max * i / points);
  }
  // Compute everything before printing so a failure never leaves partial output.
  const layerjkr::CurveAnswer answer = layerjkr::solve_curve(scene, radii);
  print_warnings(answer.warnings, answer.notices);
  print_choice(answer.choice);
  std::cout << layerjkr::cli::curve_csv(answer);
  return 0;
}

// summary's retract, for a scene with adhesion kinetics: a speed (fixed grips, or a cantilever with
// --stiffness) or a load rate.
struct RetractArguments {
  double speed = 0.0, load_rate = 0.0, stiffness = 0.0, start_force = 0.0;
  CLI::Option *speed_opt = nullptr, *load_rate_opt = nullptr, *stiffness_opt = nullptr;
};

layerjkr::AnswerOptions summary_options(const RetractArguments& r) {
  layerjkr::AnswerOptions o;
  o.retract_start_force = r.start_force;
  if (r.speed_opt->count() > 0) {
    layerjkr::RetractDrive d;
    d.control = r.stiffness_opt->count() > 0 ? layerjkr::RetractControl::cantilever : layerjkr::RetractControl::fixed_grips;
    d.rate = r.speed;
    d.stiffness = r.stiffness;
    o.retract = d;
  } else if (r.load_rate_opt->count() > 0) {
    o.retract = layerjkr::RetractDrive{layerjkr::RetractControl::load, r.load_rate, 0.0};
  }
  if (o.retract) {
    try {
      o.retract->validate();
    } catch (const layerjkr::DomainError& e) {
      const std::string flag = e.parameter() == "stiffness" ? "--stiffness" : o.retract->control == layerjkr::RetractControl::load ? "--load-rate" : "--retract-speed";
      throw layerjkr::InputError(flag + " = " + format_double(e.value()) + " must be finite and > 0 (" +
                                 (flag == "--load-rate" ? "N/s)" : flag == "--stiffness" ? "N/m)" : "m/s)"));
    }
  }
  return o;
}

int run_summary(const std::string& path, const RetractArguments& retract) {
  const layerjkr::SummaryAnswer answer = layerjkr::solve_summary(layerjkr::load_scene(path), summary_options(retract));
  print_warnings(answer.warnings, answer.notices);
  print_choice(answer.choice);
  std::cout << layerjkr::cli::summary_json(answer).dump(2) << "\n";
  return 0;
}

}  // namespace

static int run_main(int argc, char** argv) {
  // Ceres logs internal diagnostics through glog; the CLI reports through its own messages.
  FLAGS_minloglevel = google::GLOG_FATAL;
  CLI::App app{"layerjkr: adhesive (JKR) contact of thin elastic layers"};
  app.set_version_flag("--version", std::string("layerjkr ") + layerjkr::version());
  app.footer(kExitCodes);
  app.require_subcommand(1);
  std::string scene_path, at;
  double a_max = 0.0;
  int points = 0;

  CLI::App* curve = app.add_subcommand(
      "curve", "Adhesive curve at given contact radii: CSV a,P,delta,P_H,delta_H,S,error_est,c (SI; c: the adhesive zone's outer radius; error_est: "
               "estimated relative model error)");
  curve->add_option("scene", scene_path, "Scene JSON file")->required();
  auto* at_opt = curve->add_option("--at", at, "Comma-separated contact radii [m]");
  auto* max_opt = curve->add_option("--a-max", a_max, "Largest contact radius of an even grid [m]");
  auto* points_opt = curve->add_option("--points", points, "Number of grid points a_max*i/N, i=1..N");
  max_opt->needs(points_opt);
  points_opt->needs(max_opt);
  at_opt->excludes(max_opt);

  CLI::App* summary = app.add_subcommand(
      "summary", "JSON summary: pull-off, zero-load radius, fixed-grips critical point, model error estimate, K, G");
  summary->add_option("scene", scene_path, "Scene JSON file")->required();
  RetractArguments retract;
  retract.speed_opt = summary->add_option("--retract-speed", retract.speed,
                                          "With adhesion kinetics: the retract's speed [m/s] (fixed grips, or the "
                                          "cantilever's base with --stiffness): its rate-dependent pull-off and a sweep of speeds");
  retract.load_rate_opt = summary->add_option("--load-rate", retract.load_rate,
                                              "With adhesion kinetics: a load-controlled retract at this rate [N/s]");
  retract.stiffness_opt = summary->add_option("--stiffness", retract.stiffness, "The cantilever's stiffness [N/m]");
  summary->add_option("--start-force", retract.start_force,
                      "The retract starts from the equilibrium contact at this force [N] (default 0)");
  retract.speed_opt->excludes(retract.load_rate_opt);
  retract.stiffness_opt->needs(retract.speed_opt);

  layerjkr::cli::FitArguments fit_args;
  std::vector<std::string> data_paths;
  bool joint = false;
  std::string report_path, plot_path;
  std::vector<std::string> map_inputs;
  layerjkr::cli::MapOutputs map;
  map.jobs = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  CLI::App* fit = app.add_subcommand(
      "fit", "Fit a measured curve (CSV or instrument file) with a scene's model: estimates, errors, identifiability");
  fit->add_option("data", data_paths, "Curve CSV (delta,P[,a][,weight][,segment][,t] | tip_position,force | z,deflection | "
                                      "an export; columns, units and signs: docs/fitting.md) or an instrument file (JPK, Igor, "
                                      "Bruker NanoScope); several with --joint")
      ->required();
  fit->add_flag("--joint", joint,
                "Fit several curves of one sample together (a relaxing medium or crack kinetics at several speeds): "
                "every parameter shared but each curve's delta0 and P0");
  layerjkr::cli::add_fit_options(*fit, fit_args);
  fit->add_option("--out", report_path, "Write the JSON report here (with its provenance: version, scene, options, "
                                        "the input's SHA-256, the command line); - for standard output (the summary "
                                        "then goes to stderr)");
  fit->add_option("--plot", plot_path, "Write a PNG of data, fit and residuals (gnuplot); - for standard output");
  std::string from_report;
  fit->add_option("--from-report", from_report,
                  "Rerun the fit a JSON report records (its scene, options and input, whose SHA-256 must match) "
                  "instead of DATA, --scene and the fit flags; --out and --plot as usual");
  // With --from-report the report gives the data, scene and flags: they are required only without it
  // (checked after parsing, with CLI11's own message).
  const std::vector<std::string> fit_required{"data", "--scene", "--free"};
  for (const std::string& name : fit_required) {
    CLI::Option* o = fit->get_option(name);
    o->required(false)->description(o->get_description() + " (REQUIRED unless --from-report)");
  }

  CLI::App* fit_map = app.add_subcommand(
      "fit-map", "Fit many curves in parallel; one CSV row per curve (failures included)");
  fit_map->add_option("inputs", map_inputs,
                      "Directories (all *.csv and instrument files), glob patterns or files; maps give a row per curve")
      ->required();
  layerjkr::cli::add_fit_options(*fit_map, fit_args);
  fit_map->add_option("--jobs", map.jobs, "Worker threads (default: all cores)");
  fit_map->add_option("--out", map.out,
                      "Results CSV (- for standard output); beside a file, its record OUT.json (OUT.csv with .json "
                      "for .csv, else OUT + .json): version, scene, options, every input's SHA-256, the command line")
      ->required();
  fit_map->add_option("--plot-dir", map.plot_dir,
                      "Draw each fitted field (parameters, rms, status) as a heat-map PNG over the map grid (gnuplot); "
                      "pictures there that layerjkr did not draw are not replaced");
  fit_map->add_option("--tiff", map.tiff_dir,
                      "Write each fitted field of each map (parameters, their _stderr, pull_off, rms_residual) as a "
                      "32-bit float TIFF for ImageJ or Gwyddion: DIR/FIELD.tiff (DIR/STEM.FIELD.tiff for several inputs), "
                      "NaN where no fit; TIFFs there that layerjkr did not write are not replaced");
  fit_map->add_flag("--force", map.force,
                    "Replace derived files that layerjkr did not write: a file at the record's name that is not a "
                    "fit-map record, pictures in --plot-dir, TIFFs in --tiff");
  std::string map_curves, export_curves;
  fit_map->add_option("--report", map.report_dir,
                      "Write an interactive report (one self-contained HTML page: maps, histograms, each curve and its "
                      "fit) as DIR/index.html; DIR must be new, empty or an earlier report (the --out table may go in it)");
  fit_map->add_option("--curves", map_curves,
                      "Fit only the curves at positions A to B - 1 of each map (A:B, A: or :B; 0-based, file order); "
                      "the rest are not read");
  std::string map_from_report;
  fit_map->add_option("--from-report", map_from_report,
                      "Rerun the map a record (OUT.json) describes: its scene, options, inputs (SHA-256 checked) and "
                      "--curves, instead of INPUTS, --scene and the fit flags; give --out, and --jobs, --plot-dir");
  for (const char* name : {"inputs", "--scene", "--free"}) {
    CLI::Option* o = fit_map->get_option(name);
    o->required(false)->description(o->get_description() + " (REQUIRED unless --from-report)");
  }
  fit_map->add_flag("--resume", map.resume,
                    "Keep the rows of an existing --out table (same header) and fit only the curves it lacks; refused when its "
                    "record names another scene or options, or an input whose SHA-256 changed");

  std::string export_path, export_out;
  CLI::App* export_cmd = app.add_subcommand(
      "export", "Write every curve of an instrument file (JPK, Igor, Bruker) as CSV: curve,segment,t,force,height,tip_position (t where the file gives segment durations; segment 0 approach, 1 retract, 2 dwell)");
  export_cmd->add_option("file", export_path, "Instrument file (" + layerjkr::known_instrument_formats() + ")")
      ->required();
  export_cmd->add_option("--curves", export_curves, "Only the curves at positions A to B - 1 (A:B, A: or :B)");
  double export_k = 0.0, export_sensitivity = 0.0;
  export_cmd->add_option("--spring-constant", export_k,
                         "The cantilever's spring constant [N/m]: replaces the file's, or gives one it lacks");
  export_cmd->add_option("--sensitivity", export_sensitivity,
                         "The deflection sensitivity [m/V]: replaces the file's (the deflection rescales)");
  export_cmd->add_option("--out", export_out, "CSV file to write (- for standard output)")->required();

  layerjkr::cli::DiscreteArguments discrete_args;
  CLI::App* discrete = app.add_subcommand(
      "discrete", "JKR from discrete data (paper s.5): flat-punch steps + convex-indenter curve -> curve CSV or summary");
  layerjkr::cli::add_discrete_options(*discrete, discrete_args);

  layerjkr::cli::SimulateArguments simulate_args;
  CLI::App* simulate = app.add_subcommand(
      "simulate", "A synthetic curve of a scene as CSV t,delta,P[,a],segment (t with --speed): at equilibrium, or in time "
                  "for a relaxing medium (Lee-Radok, Ting) and crack kinetics");
  layerjkr::cli::add_simulate_options(*simulate, simulate_args);

  const std::vector<std::string> commands = {"curve", "summary", "fit", "fit-map", "export", "discrete", "simulate"};
  if (argc > 1 && argv[1][0] != '-' &&
      std::find(commands.begin(), commands.end(), std::string(argv[1])) == commands.end()) {
    return fail(2, "unknown command '" + std::string(argv[1]) +
                       "' (known: curve, summary, fit, fit-map, export, discrete, simulate; see --help)");
  }
  try {
    app.parse(argc, argv);
    if (*curve && at.empty() && !*max_opt)
      throw CLI::RequiredError("curve needs --at or --a-max with --points");
    // With --from-report the report gives the inputs, scene and fit flags; without it they are required.
    const auto check_from_report = [&](CLI::App* command, const std::string& report, const std::vector<std::string>& required,
                                       const std::vector<std::string>& allowed) {
      if (report.empty()) {
        for (const std::string& name : required)
          if (command->get_option(name)->count() == 0) throw CLI::RequiredError(name);
        return;
      }
      std::string list;
      for (const std::string& name : allowed) list += (list.empty() ? "" : ", ") + name;
      for (const CLI::Option* o : command->get_options())
        if (o->count() > 0 && o->get_name() != "--from-report" &&
            std::find(allowed.begin(), allowed.end(), o->get_name()) == allowed.end())
          throw CLI::ValidationError("--from-report takes the inputs, scene and every fit option from the report; "
                                     "give only " + list + " with it, not " + o->get_name());
    };
    if (*fit) check_from_report(fit, from_report, fit_required, {"--out", "--plot"});
    if (*fit_map) check_from_report(fit_map, map_from_report, {"inputs", "--scene", "--free"},
                        {"--out", "--jobs", "--plot-dir", "--report", "--tiff", "--force"});
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    return fail(2, std::string(e.what()) + " (see --help)");
  }

  try {
    // A misspelt LAYERJKR_CACHE* is refused here, not left to switch the cache off quietly.
    layerjkr::DiskCacheOptions::from_environment();
    if (*curve) return run_curve(scene_path, at, a_max, points);
    const std::vector<std::string> command_line(argv, argv + argc);
    if (*fit && !from_report.empty())
      return layerjkr::cli::run_fit_from_report(from_report, report_path, plot_path, command_line);
    if (*fit) return layerjkr::cli::run_fit(fit_args, data_paths, joint, report_path, plot_path, command_line);
    if (*fit_map && !map_from_report.empty())
      return layerjkr::cli::run_fit_map_from_report(map_from_report, map, command_line);
    if (*fit_map) return layerjkr::cli::run_fit_map(fit_args, map_inputs, map_curves, map, command_line);
    if (*export_cmd)
      return layerjkr::cli::run_export(export_path, export_out, export_curves, export_k, export_sensitivity);
    if (*discrete) return layerjkr::cli::run_discrete(discrete_args);
    if (*simulate) {
      std::string line = "layerjkr";  // what made the file, in its first line
      for (std::size_t i = 1; i < command_line.size(); ++i) line += " " + command_line[i];
      return layerjkr::cli::run_simulate(simulate_args, line);
    }
    return run_summary(scene_path, retract);
  } catch (const layerjkr::NumericalError& e) {
    return fail(1, std::string("numerical failure: ") + e.what());
  } catch (const layerjkr::Error& e) {
    return fail(2, e.what());
  } catch (const std::exception& e) {
    return fail(1, std::string("internal error: ") + e.what());
  }
}

int main(int argc, char** argv) {
  // Past RLIMIT_FSIZE a write fails with EFBIG, which the writers report, instead of a core dump.
  std::signal(SIGXFSZ, SIG_IGN);
  layerjkr::enable_hdf5_reading();  // the CLI links libhdf5; the library alone does not
  try {
    const int rc = run_main(argc, argv);
    // Why the disk cache was off, or which entries it refused (a folder others can write, a
    // forged entry): the user's to know, after the answer and only with one (exit 0).
    if (const layerjkr::Context* c = layerjkr::Context::global_if_made(); c && rc == 0)
      for (const std::string& note : c->stats().disk_notices) std::fprintf(stderr, "layerjkr: note: %s\n", note.c_str());
    return rc;
  } catch (const std::exception& e) {  // setting up the parser itself failed
    return fail(1, std::string("internal error: ") + e.what());
  }
}
