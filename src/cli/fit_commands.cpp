// layerjkr fit / export: read the curves, call the library, write report, plot and CSV
// (fit-map: fit_map.cpp).
#include "fit_commands.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iterator>
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
  if (!is_instrument_file(path) && !is_asylum_map_export(path)) return read_curve_csv(path, p.csv);
  // What only a CSV needs is refused for an instrument file, which carries its own units and signs.
  if (p.csv.length_unit != 1.0 || p.csv.force_unit != 1.0 || p.csv.z_sign != 1.0 || p.csv.deflection_sign != 1.0)
    throw InputError(path + ": an instrument file gives its own units and signs: --units, --z-sign and "
                            "--deflection-sign apply to CSV files only");
  const InstrumentReader reader(path);
  if (p.csv.curve < 0 && reader.size() > 1)
    throw InputError(path + ": holds " + std::to_string(reader.size()) +
                     " curves; select one with --curve N, or fit them all with fit-map");
  for (std::size_t i = 0; i < reader.size(); ++i)
    if (p.csv.curve < 0 || reader.curve_number(i) == p.csv.curve) return to_curve_data(reader.curve(i), path, p.csv.spring_constant, p.csv.sensitivity);
  throw InputError(path + ": has no curve " + std::to_string(p.csv.curve));
}

// A small text file the CLI reads whole (a report), named by its flag in errors.
std::string read_text(const std::string& path, const std::string& flag) {
  std::ifstream f(path, std::ios::binary);
  if (!f) throw InputError(flag + ": cannot open " + path);
  std::string text((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
  if (f.bad()) throw InputError(flag + ": cannot read " + path);
  return text;
}

}  // namespace

namespace {

// A vendor's text export that fit reads as a curve file (AFM Workshop's CSV, afmformats' tab):
// export writes it as it writes an instrument file's curve, so that `export` refuses nothing
// `fit` reads from a vendor.
bool is_vendor_text(const std::string& path) {
  if (is_instrument_file(path) || is_asylum_map_export(path)) return false;
  std::ifstream in(path, std::ios::binary);
  std::string head(4096, '\0');
  in.read(head.data(), static_cast<std::streamsize>(head.size()));
  head.resize(static_cast<std::size_t>(in.gcount()));
  return is_vendor_curve_text(head);
}

int export_vendor_text(const std::string& path, const std::string& out, double spring_constant, double sensitivity) {
  CsvOptions o;
  o.spring_constant = spring_constant;
  o.sensitivity = sensitivity;
  const CurveData d = read_curve_csv(path, o);
  for (const std::string& note : d.notes) std::cerr << "export: note: " << printable(note) << "\n";
  OutputFile csv(out);
  const bool timed = !d.t.empty();
  std::string text = timed ? "curve,segment,t,force,height,tip_position\n" : "curve,segment,force,height,tip_position\n";
  for (std::size_t i = 0; i < d.size(); ++i) {
    const double tip = -d.delta[i];
    // The height the tip's position and the force imply (tip = height + F/k), where k is known.
    const double height = d.spring_constant > 0.0 ? tip - d.P[i] / d.spring_constant : std::nan("");
    text += "0," + std::to_string(d.segment[i]) + "," + (timed ? format_double(d.t[i]) + "," : std::string()) +
            format_double(d.P[i]) + "," + format_double(height) + "," + format_double(tip) + "\n";
  }
  csv.write(text);
  csv.commit();
  std::cerr << "export: 1 curve(s) of " << printable(path) << " written to " << printable(out) << "\n";
  return 0;
}

}  // namespace

int run_export(const std::string& path, const std::string& out, const std::string& curves, double spring_constant,
               double sensitivity) {
  check_not_input(out, "--out", {path});
  if (!(spring_constant >= 0.0 && std::isfinite(spring_constant)))
    throw InputError("--spring-constant = " + format_double(spring_constant) + " is invalid; valid range: finite and > 0 [N/m]");
  if (!(sensitivity >= 0.0 && std::isfinite(sensitivity)))
    throw InputError("--sensitivity = " + format_double(sensitivity) + " is invalid; valid range: finite and > 0 [m/V]");
  const CurveRange range = curves.empty() ? CurveRange{} : CurveRange::parse(curves, "--curves");
  if (is_vendor_text(path)) return export_vendor_text(path, out, spring_constant, sensitivity);
  OutputFile csv(out);
  const InstrumentReader reader(path);
  range.require_any(reader.size(), path);
  const std::size_t end = range.end_in(reader.size());
  // One curve at a time: a map is never held whole, in samples or in text. The samples' time is a
  // column where the file gives it (the first curve decides, and every curve must then have it).
  bool timed = false;
  std::vector<std::string> said;  // the reader's notes, each once: what fit reports, export says too
  for (std::size_t k = range.begin; k < end; ++k) {
    const InstrumentCurve c = reader.curve(k);
    const CurveData d = to_curve_data(c, path, spring_constant, sensitivity);
    for (const std::string& note : d.notes)
      if (std::find(said.begin(), said.end(), note) == said.end()) {
        said.push_back(note);
        std::cerr << "export: note: " << printable(note) << "\n";
      }
    if (k == range.begin) {
      timed = !d.t.empty();
      csv.write(timed ? "curve,segment,t,force,height,tip_position\n" : "curve,segment,force,height,tip_position\n");
    } else if (timed && d.t.empty()) {
      throw InputError(path + ": curve " + std::to_string(c.index) + " has no segment durations, so no time, while the "
                       "first exported curve had them; export it on its own (--curves)");
    }
    std::string text;
    std::size_t row = 0;
    for (const InstrumentSegment& seg : c.segments)  // the force as calibrated (and overridden)
      for (std::size_t i = 0; i < seg.force.size(); ++i, ++row)
        text += std::to_string(c.index) + "," + std::to_string(d.segment[row]) + "," +
                (timed ? format_double(d.t[row]) + "," : std::string()) + format_double(d.P[row]) + "," +
                format_double(seg.height[i]) + "," + format_double(-d.delta[row]) + "\n";
    csv.write(text);
  }
  csv.commit();
  std::cerr << "export: " << end - range.begin << " curve(s) of " << printable(path) << " written to " << printable(out) << "\n";
  return 0;
}

namespace {

// The fit and its outputs, from prepared options: `fit` and `fit --from-report` share it.
// `inputs` is the curve's record, taken before it is read; `extra` is added to the provenance.
int fit_and_report(const Prepared& p, const std::string& data, const std::vector<std::string>& inputs_not_outputs,
                   const std::string& report, const std::string& plot, const std::vector<std::string>& command_line,
                   const nlohmann::ordered_json& extra = nlohmann::ordered_json::object()) {
  // Both outputs are checked, and their files created, before the fit.
  check_not_input(report, "--out", inputs_not_outputs);
  check_not_input(plot, "--plot", inputs_not_outputs);
  std::optional<OutputFile> report_file, plot_file;
  if (!report.empty()) report_file.emplace(report);
  if (!plot.empty()) plot_file.emplace(plot);
  if (report_file && plot_file && report_file->is_standard_output() && plot_file->is_standard_output())
    throw InputError("--out " + report + " and --plot " + plot + " are both standard output; send one of them to a file");
  const std::vector<InputRecord> inputs{record_file(data)};
  const CurveData curve = read_fit_data(data, p);
  const FitSummary s = fit(curve, p.scene, p.options);
  if (plot_file) plot_fit(s, *plot_file);
  if (report_file) {
    nlohmann::ordered_json j = report_json(s, p.options.branch);
    j["provenance"] = provenance_record(p.scene, p.options, p.csv, inputs, command_line);
    for (const auto& item : extra.items()) j["provenance"][item.key()] = item.value();
    report_file->write(j.dump(2) + "\n");
    report_file->commit();
  }
  // The summary is for a person: on stderr when standard output carries the report or the plot.
  const bool stdout_taken = (report_file && report_file->is_standard_output()) || (plot_file && plot_file->is_standard_output());
  (stdout_taken ? std::cerr : std::cout) << printable(s.brief_report());
  return 0;
}

}  // namespace

namespace {

// Curves of one sample at several speeds, fitted jointly: the joint summary on stdout, the report
// with the joint fit, each curve fitted alone and the provenance of every input.
int joint_fit_and_report(const Prepared& p, const std::vector<std::string>& data, const std::vector<std::string>& not_outputs,
                         const std::string& report, const std::string& plot, const std::vector<std::string>& command_line,
                         const nlohmann::ordered_json& extra = nlohmann::ordered_json::object()) {
  check_not_input(report, "--out", not_outputs);
  check_not_input(plot, "--plot", not_outputs);
  std::optional<OutputFile> report_file, plot_file;
  if (!report.empty()) report_file.emplace(report);
  if (!plot.empty()) plot_file.emplace(plot);
  if (report_file && plot_file && report_file->is_standard_output() && plot_file->is_standard_output())
    throw InputError("--out " + report + " and --plot " + plot + " are both standard output; send one of them to a file");
  std::vector<InputRecord> inputs;
  std::vector<CurveData> curves;
  for (const std::string& path : data) {
    inputs.push_back(record_file(path));
    curves.push_back(read_fit_data(path, p));
  }
  const JointFitSummary j = fit_joint(curves, p.scene, p.options);
  if (plot_file) plot_joint(j, *plot_file);
  if (report_file) {
    nlohmann::ordered_json out;
    out["joint"] = report_json(j.fit, p.options.branch);
    nlohmann::ordered_json list = nlohmann::ordered_json::array();
    for (std::size_t k = 0; k < j.sources.size(); ++k)
      list.push_back({{"source", escape_bytes(j.sources[k])},
                      {"first_sample", j.curve_begin[k]},
                      {"samples", j.curve_begin[k + 1] - j.curve_begin[k]},
                      {"alone", report_json(j.alone[k], p.options.branch)}});
    out["curves"] = list;
    out["provenance"] = provenance_record(p.scene, p.options, p.csv, inputs, command_line);
    for (const auto& item : extra.items()) out["provenance"][item.key()] = item.value();
    report_file->write(out.dump(2) + "\n");
    report_file->commit();
  }
  const bool stdout_taken = (report_file && report_file->is_standard_output()) || (plot_file && plot_file->is_standard_output());
  std::ostream& o = stdout_taken ? std::cerr : std::cout;
  o << printable(j.fit.brief_report());
  for (std::size_t k = 0; k < j.sources.size(); ++k) o << "  curve " << k + 1 << ": " << printable(j.sources[k]) << "\n";
  return 0;
}

}  // namespace

int run_fit(const FitArguments& args, const std::vector<std::string>& data, bool joint, const std::string& report,
            const std::string& plot, const std::vector<std::string>& command_line) {
  if (data.size() > 1 && !joint)
    throw InputError("fit: " + std::to_string(data.size()) + " data files: give --joint to fit them together (one law "
                     "in time across speeds), or fit-map to fit each alone");
  if (joint && data.size() < 2) throw InputError("--joint fits at least 2 curves together; give more data files");
  const Prepared p = prepare(args);
  std::vector<std::string> not_outputs = data;
  not_outputs.push_back(args.scene);
  if (joint) return joint_fit_and_report(p, data, not_outputs, report, plot, command_line);
  return fit_and_report(p, data[0], not_outputs, report, plot, command_line);
}

int run_fit_from_report(const std::string& from, const std::string& report, const std::string& plot,
                        const std::vector<std::string>& command_line) {
  const std::string text = read_text(from, "--from-report");
  nlohmann::ordered_json j;
  try {
    j = nlohmann::ordered_json::parse(text);
  } catch (const nlohmann::json::parse_error& e) {
    throw InputError(from + ": not a JSON fit report (" + e.what() + ")");
  }
  if (!j.is_object() || !j.contains("provenance"))
    throw InputError(from + ": has no \"provenance\" (a fit report of layerjkr 0.1.0 or later written by fit --out)");
  const ProvenanceRecord r = parse_provenance(j["provenance"].dump(), from + ": provenance");
  if (r.version != version())
    std::cerr << "layerjkr: warning: " << from << " was written by layerjkr " << r.version << ", this is "
              << version() << ": the numbers may differ\n";
  if (!r.scene) throw InputError(from + ": cannot be rerun: its scene was " + r.scene_note);
  if (r.inputs.empty()) throw InputError(from + ": records no input");
  for (const InputRecord& in : r.inputs) verify_input(in);
  const Prepared p{*r.scene, r.options, r.csv.value_or(CsvOptions{})};
  nlohmann::ordered_json extra;
  extra["rerun_of"] = {{"report", record_file(from).path}, {"sha256", sha256_hex(text.data(), text.size())}};
  if (j.contains("joint")) {  // a joint fit: every input again
    std::vector<std::string> paths, not_outputs{from};
    for (const InputRecord& in : r.inputs) paths.push_back(in.path), not_outputs.push_back(in.path);
    return joint_fit_and_report(p, paths, not_outputs, report, plot, command_line, extra);
  }
  if (r.inputs.size() != 1)
    throw InputError(from + ": records " + std::to_string(r.inputs.size()) + " inputs; a fit report has one");
  return fit_and_report(p, r.inputs[0].path, {r.inputs[0].path, from}, report, plot, command_line, extra);
}

}  // namespace layerjkr::cli
