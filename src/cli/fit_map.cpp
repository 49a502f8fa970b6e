// layerjkr fit-map: the results table, written row by row in input order as curves finish, so an
// interrupted run (SIGINT, SIGTERM) leaves a valid partial table that --resume completes.
#include <atomic>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <iterator>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <sstream>
#include <utility>

#include <unistd.h>

#include "files.hpp"
#include "fit_commands.hpp"
#include "layerjkr/layerjkr.hpp"
#include "limits.hpp"
#include "map_resume.hpp"
#include "plots.hpp"
#include "map_tiffs.hpp"
#include "reports.hpp"
#include "results_table.hpp"

namespace layerjkr::cli {
namespace {

using json = nlohmann::ordered_json;

std::string num(double v) { return std::isfinite(v) ? format_double(v) : ""; }
std::string index(int v) { return v >= 0 ? std::to_string(v) : std::string(); }

// A message as one printable line of a cell.
std::string message_cell(std::string s) {
  for (char& c : s)
    if (c == '\n' || c == '\r') c = ' ';
  return csv_cell(printable(s));
}

std::string header(const std::vector<FitParameter>& free) {
  std::string h = "file,curve,x,y,grid_x,grid_y,status,error,model,converged,iterations,rms_residual,identifiable,"
                  "identifiability,contact_point,contact_point_err,range_samples";
  for (FitParameter q : free) h += std::string(",") + to_string(q) + "," + to_string(q) + "_stderr";
  return h + ",quality,warnings,notices\n";
}

// Messages in one cell, separated by " | ".
std::string messages_cell(const std::vector<std::string>& messages) {
  std::string joined;
  for (const std::string& m : messages) joined += (joined.empty() ? "" : " | ") + m;
  return message_cell(joined);
}

// The file cell is the name as given, escaped reversibly (text.hpp): a name with a line break
// stays one quoted cell, bytes that are not UTF-8 become \xNN.
std::string row(const BatchItem& it, std::size_t free) {
  std::ostringstream csv;
  csv << csv_cell(escape_bytes(it.source)) << "," << index(it.curve) << "," << num(it.x) << "," << num(it.y) << ","
      << index(it.grid_x) << "," << index(it.grid_y) << "," << (it.ok ? "ok" : "error") << "," << message_cell(it.error);
  if (it.ok) {
    const FitSummary& s = it.summary;
    csv << "," << s.model << "," << (s.converged ? 1 : 0) << "," << s.iterations << ","
        << format_double(s.rms_residual) << "," << (s.identifiable ? 1 : 0) << "," << message_cell(s.identifiability())
        << "," << num(s.contact_point.value) << "," << num(s.contact_point.standard_error) << ","
        << s.contact_point.samples_in_range;
    for (const auto& e : s.parameters) csv << "," << num(e.value) << "," << num(e.standard_error);
    csv << "," << batch_quality(it) << "," << messages_cell(s.warnings) << "," << messages_cell(s.notices);
  } else {
    csv << ",,,,,,,,,";
    for (std::size_t k = 0; k < free; ++k) csv << ",,";
    csv << "," << batch_quality(it) << ",,";
  }
  csv << "\n";
  return csv.str();
}

// SIGINT / SIGTERM: the batch polls the flag between curves. The handler resets itself, so a
// second signal stops the process at once.
std::atomic<int> stop_signal{0};
static_assert(std::atomic<int>::is_always_lock_free, "the signal handler writes an atomic");
extern "C" void on_stop_signal(int sig) { stop_signal.store(sig); }

class StopOnSignals {
 public:
  StopOnSignals() {
    struct sigaction sa {};
    sa.sa_handler = on_stop_signal;
    sigemptyset(&sa.sa_mask);
    sa.sa_flags = SA_RESETHAND | SA_RESTART;
    sigaction(SIGINT, &sa, &old_int_);
    sigaction(SIGTERM, &sa, &old_term_);
  }
  ~StopOnSignals() {
    sigaction(SIGINT, &old_int_, nullptr);
    sigaction(SIGTERM, &old_term_, nullptr);
  }
  StopOnSignals(const StopOnSignals&) = delete;
  StopOnSignals& operator=(const StopOnSignals&) = delete;

 private:
  struct sigaction old_int_ {}, old_term_ {};
};

// The record at `path` as JSON, or nullopt if it is missing or not a fit-map record: an object
// with the version that wrote it and its table (every record layerjkr 0.1 and later wrote).
std::optional<json> read_record(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  if (!f) return std::nullopt;
  try {
    json j = json::parse(f);
    if (j.is_object() && j.contains("layerjkr_version") && j.contains("table")) return j;
  } catch (const nlohmann::json::exception&) {
  }
  return std::nullopt;
}

// The record beside a table is derived from --out: it may replace only a record layerjkr wrote.
void check_record_replaceable(const std::string& sidecar, bool force) {
  std::error_code ec;
  const auto st = std::filesystem::symlink_status(sidecar, ec);
  if (force || !std::filesystem::exists(st) || std::filesystem::is_directory(std::filesystem::status(sidecar, ec)))
    return;  // a directory is refused when the record is opened, with its own message
  if (!read_record(sidecar))
    throw InputError("--out's record " + sidecar +
                     " exists and is not a fit-map record; it is not replaced (choose another --out, move the file, "
                     "or give --force to replace it)");
}

// --resume keeps rows made earlier: only if they were made from the same scene and options, and
// every input both runs name still has the bytes it had (the sidecar says what they were made from).
// Returns the earlier record.
json check_resumable(const std::string& sidecar, const json& now) {
  if (!std::filesystem::exists(sidecar))
    throw InputError("--resume: " + sidecar + ", the record of how the earlier table was made, is missing; "
                     "without it its rows cannot be checked against this run (rerun without --resume)");
  const std::optional<json> read = read_record(sidecar);
  if (!read) throw InputError("--resume: " + sidecar + " is not a fit-map record");
  const json& earlier = *read;
  const auto differs = [&](const char* key, const char* sub = nullptr) {
    if (!earlier.contains(key)) return true;
    return sub ? !earlier[key].contains(sub) || earlier[key][sub] != now[key][sub] : earlier[key] != now[key];
  };
  if (differs("scene", "json") || differs("scene", "description"))
    throw InputError("--resume: the earlier table was made with another scene (" + sidecar + "); it is not resumed");
  if (differs("options") || differs("csv"))
    throw InputError("--resume: the earlier table was made with other fit options (" + sidecar + ": " +
                     (earlier.contains("options") ? earlier["options"].dump() : std::string("none")) +
                     "); it is not resumed");
  std::map<std::string, std::string> hashes;
  if (earlier.contains("inputs") && earlier["inputs"].is_array())
    for (const auto& in : earlier["inputs"])
      if (in.contains("path") && in["path"].is_string()) hashes[in["path"].get<std::string>()] = in.value("sha256", json()).dump();
  for (const auto& in : now["inputs"]) {
    const auto found = hashes.find(in["path"].get<std::string>());
    if (found != hashes.end() && found->second != in["sha256"].dump())
      throw InputError("--resume: " + in["path"].get<std::string>() + " changed since the earlier table was made: SHA-256 " +
                       in["sha256"].dump() + ", " + sidecar + " says " + found->second + "; it is not resumed");
  }
  if (earlier.value("layerjkr_version", std::string()) != version())
    std::cerr << "layerjkr: warning: --resume: the earlier rows were made by layerjkr "
              << printable(earlier.value("layerjkr_version", std::string("(unknown)"))) << ", the new ones by "
              << version() << "\n";
  return earlier;
}

// A progress bar on stderr, only for a person watching: logs and pipes get the summary line.
std::function<void(std::size_t, std::size_t)> progress_bar(bool* drawn) {
  if (!isatty(STDERR_FILENO)) return {};
  const auto t0 = std::chrono::steady_clock::now();
  auto last = std::make_shared<std::chrono::steady_clock::time_point>(t0 - std::chrono::seconds(1));
  return [t0, last, drawn](std::size_t done, std::size_t total) {
    const auto now = std::chrono::steady_clock::now();
    if (done != total && now - *last < std::chrono::milliseconds(200)) return;
    *last = now;
    *drawn = true;
    const double seconds = std::chrono::duration<double>(now - t0).count();
    const double rate = seconds > 0.0 ? static_cast<double>(done) / seconds : 0.0;
    const int width = 30, filled = static_cast<int>(width * done / total);
    char line[160];
    std::snprintf(line, sizeof line, "\rfit-map [%s%s] %zu/%zu  %.0f curves/s  %.0f s left  ",
                  std::string(static_cast<std::size_t>(filled), '#').c_str(),
                  std::string(static_cast<std::size_t>(width - filled), ' ').c_str(), done, total, rate,
                  rate > 0.0 ? static_cast<double>(total - done) / rate : 0.0);
    std::cerr << line << std::flush;
  };
}

}  // namespace

std::string sidecar_path(const std::string& out) {
  const std::string ext = ".csv";
  if (out.size() > ext.size() && out.compare(out.size() - ext.size(), ext.size(), ext) == 0)
    return out.substr(0, out.size() - ext.size()) + ".json";
  return out + ".json";
}

namespace {

// fit-map from prepared options and expanded inputs: the command and its --from-report share it.
// `all_inputs`: every file the outputs must not be; `extra`: added to the sidecar.
// `not_read`: what the input folders held besides curves, said once the outputs are checked.
int map_and_record(const Prepared& p, const std::vector<std::string>& files, const std::vector<std::string>& all_inputs,
                   const std::string& curves, const MapOutputs& o, const std::vector<std::string>& command_line,
                   const json& extra, const std::vector<std::string>& not_read = {}) {
  check_count("--jobs", o.jobs, 1, kMaxJobs);
  if (o.resume && !o.plot_dir.empty())
    throw InputError("--plot-dir needs every fit, and --resume does not redo the earlier ones: run them apart");
  if (o.resume && !o.report_dir.empty())
    throw InputError("--report needs every fit, and --resume does not redo the earlier ones: run them apart");
  if (o.resume && !o.tiff_dir.empty())
    throw InputError("--tiff needs every fit, and --resume does not redo the earlier ones: run them apart");
  check_not_input(o.out, "--out", all_inputs);
  // Every output is opened, and every derived one checked, before the first fit: a bad path fails
  // now, not after the work. The report's directory first: the table and its record may go into it.
  if (!o.report_dir.empty()) prepare_report_dir(o.report_dir, "--report", {o.out, sidecar_path(o.out)});
  OutputFile table(o.out);
  if (o.resume && table.is_stream())
    throw InputError("--resume reads the earlier table from --out, and " + o.out + " is a stream, not a file");
  // A table that is a stream (standard output, a FIFO, a device) has no record beside it.
  const std::string sidecar = table.is_stream() ? std::string() : sidecar_path(o.out);
  std::optional<OutputFile> record;
  if (!sidecar.empty()) {
    check_not_input(sidecar, "--out's record", all_inputs);
    check_record_replaceable(sidecar, o.force);
    record.emplace(sidecar);
  }
  // Curve files carry no map position: --plot-dir is refused now, before anything is written (the
  // table, its record or the directory), as --tiff is.
  if (!o.plot_dir.empty() && !may_carry_map_positions(files))
    throw InputError("--plot-dir: no input carries map positions (CSV curve files do not; instrument force maps and QI "
                     "files do)");
  if (!o.plot_dir.empty()) prepare_plot_dir(o.plot_dir, map_plot_names(p.options.free), o.force);
  if (!o.tiff_dir.empty()) prepare_tiff_dir(o.tiff_dir, files, map_tiff_names(files, p.options.free), o.force);
  for (const std::string& line : not_read) std::cerr << "fit-map: " << printable(line) << "\n";
  // What the rows are made from, hashed before any is read (docs/provenance.md has the cost).
  std::vector<InputRecord> hashed;
  hashed.reserve(files.size());
  for (const std::string& f : files) hashed.push_back(record_file(f));
  json made_from = provenance_record(p.scene, p.options, p.csv, hashed, command_line);
  // Each input also as it was named (the table's file column), so a rerun can name it the same way.
  for (std::size_t k = 0; k < files.size(); ++k) made_from["inputs"][k]["named"] = escape_bytes(files[k]);
  made_from["table"] = escape_bytes(o.out);
  made_from["curves"] = curves.empty() ? json(nullptr) : json(curves);
  for (const auto& item : extra.items()) made_from[item.key()] = item.value();
  EarlierRows earlier;
  earlier.set_inputs(files, hashed);
  const json earlier_record =
      o.resume ? earlier.read(o.out, header(p.options.free), [&] { return check_resumable(sidecar, made_from); })
               : json();
  if (!earlier_record.is_null()) {
    // The earlier inputs this run does not name keep their rows, so their records stay too.
    std::set<std::string> named;
    for (const auto& in : made_from["inputs"]) named.insert(in.value("path", std::string()));
    for (const auto& in : earlier_record.value("inputs", json::array()))
      if (!named.count(in.value("path", std::string()))) made_from["inputs"].push_back(in);
  }
  if (record) record->write(made_from.dump(2) + "\n");
  std::optional<OutputFile> page;
  if (!o.report_dir.empty()) page.emplace(map_report_page(o.report_dir));
  table.write(header(p.options.free));

  std::size_t rows = 0, failed = 0, skipped = 0;
  BatchOptions b;
  b.jobs = o.jobs;
  if (!curves.empty()) b.curves = CurveRange::parse(curves, "--curves");
  b.cancelled = [] { return stop_signal.load() != 0; };
  if (page) b.display_points = kDefaultDisplayPoints;
  if (!earlier.empty()) b.skip = [&](const BatchItem& it) { return earlier.claim(it.source, it.curve); };
  b.on_item = [&](std::size_t, const BatchItem& it) {
    if (it.skipped) {
      bool was_failed = false;
      table.write(earlier.take(it.source, it.curve, &was_failed));
      failed += was_failed ? 1 : 0;
      ++skipped;
    } else {
      table.write(row(it, p.options.free.size()));
      failed += it.ok ? 0 : 1;
    }
    ++rows;
  };
  bool drawn = false;
  b.progress = progress_bar(&drawn);
  std::vector<BatchItem> items;
  {
    const StopOnSignals stop;
    items = fit_files(files, p.scene, p.options, p.csv, b);
  }
  // Rows of the earlier table that this run's inputs did not name are kept, after the others.
  std::size_t kept_failed = 0;
  const std::vector<std::string> kept = earlier.leftover(&kept_failed);
  for (const std::string& line : kept) table.write(line);
  table.commit();
  if (record) record->commit();
  if (drawn) std::cerr << "\n";
  const std::string what = table.is_standard_output() ? std::string("standard output") : printable(o.out);
  const std::string kept_note =
      kept.empty() ? "" : "; " + std::to_string(kept.size()) + " earlier row(s) for other inputs kept at the end";
  if (const int sig = stop_signal.load()) {
    std::cerr << "fit-map: stopped by " << (sig == SIGINT ? "SIGINT" : "SIGTERM") << ": " << rows << " of "
              << items.size() << " rows written to " << what << kept_note << "; --resume finishes the table"
              << (page ? " (no report written)" : "") << "\n";
    return 128 + sig;
  }
  // Instrument files whose curves turned out to hold no map position (single curves): the table
  // stands and the maps are said to be impossible, not an error after the work.
  const bool placed = std::any_of(items.begin(), items.end(), [](const BatchItem& it) { return it.grid_x >= 0 && it.grid_y >= 0; });
  if ((!o.plot_dir.empty() || !o.tiff_dir.empty()) && !placed)
    std::cerr << "fit-map: warning: no fitted curve carries a map position (single curves, not a map): no map "
                 "drawn" << (o.plot_dir.empty() ? "" : " in --plot-dir") << (o.tiff_dir.empty() ? "" : " or --tiff") << "\n";
  if (!o.plot_dir.empty() && placed) plot_map_fields(items, p.options.free, o.plot_dir, o.force);
  if (!o.tiff_dir.empty() && placed) {
    const std::size_t n = write_map_tiffs(items, files, p.options.free, o.tiff_dir);
    std::cerr << "fit-map: " << n << " TIFF image(s) written to " << printable(o.tiff_dir) << "\n";
  }
  if (page) {
    MapReportOptions r;
    r.free = p.options.free;
    r.subtitle = "scene " + (p.scene.origin.file.empty() ? std::string("(recorded)") : p.scene.origin.file) + "; " +
                 std::to_string(files.size()) + " input file(s); results " + o.out +
                 (sidecar.empty() ? std::string() : "; its record " + sidecar);
    page->write(map_report_html(items, r));
    page->commit();
    std::cerr << "fit-map: report written to " << printable(page->target()) << "\n";
  }
  const std::size_t all_rows = rows + kept.size(), all_failed = failed + kept_failed;
  std::cerr << "fit-map: " << all_rows - all_failed << " of " << all_rows << " curves fitted";
  if (skipped) std::cerr << " (" << skipped << " rows kept from the earlier run)";
  if (all_failed) std::cerr << "; " << all_failed << " failed (see the error column of " << what << ")";
  std::cerr << kept_note;
  if (sidecar.empty()) std::cerr << "; no record written (the table is a stream: give --out FILE for one)";
  std::cerr << "\n";
  if (all_failed == 0 && all_rows > 0) return 0;
  return all_failed < all_rows ? kExitSomeFailed : kExitNoneFitted;
}

}  // namespace

int run_fit_map(const FitArguments& args, const std::vector<std::string>& inputs, const std::string& curves,
                const MapOutputs& outputs, const std::vector<std::string>& command_line) {
  const Prepared p = prepare(args);
  std::vector<std::string> skipped;
  const std::vector<std::string> files = expand_inputs(inputs, &skipped);
  // --curve picks one curve of a CSV export that holds several; fit-map fits every curve of an
  // instrument file, so there it would be ignored: refused, pointing at --curves.
  if (p.csv.curve >= 0)
    for (const std::string& f : files)
      if (is_instrument_file(f) || is_asylum_map_export(f))
        throw InputError("--curve " + std::to_string(p.csv.curve) + " does not apply to " + printable(f) +
                         ": fit-map fits every curve of an instrument file; select positions with --curves A:B");
  std::vector<std::string> all_inputs = files;
  all_inputs.push_back(args.scene);
  return map_and_record(p, files, all_inputs, curves, outputs, command_line, json::object(), skipped);
}

int run_fit_map_from_report(const std::string& from, const MapOutputs& outputs,
                            const std::vector<std::string>& command_line) {
  std::ifstream f(from, std::ios::binary);
  if (!f) throw InputError("--from-report: cannot open " + from);
  const std::string text((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
  json j;
  try {
    j = json::parse(text);
  } catch (const nlohmann::json::parse_error& e) {
    throw InputError(from + ": not a fit-map record (" + e.what() + ")");
  }
  if (!j.is_object() || !j.contains("table"))
    throw InputError(from + ": is not a fit-map record (the OUT.json fit-map writes beside its table)");
  const ProvenanceRecord r = parse_provenance(text, from);
  if (r.version != version())
    std::cerr << "layerjkr: warning: " << printable(from) << " was written by layerjkr " << printable(r.version)
              << ", this is " << version() << ": the numbers may differ\n";
  if (!r.scene) throw InputError(from + ": cannot be rerun: its scene was " + r.scene_note);
  std::vector<std::string> files;
  for (std::size_t k = 0; k < r.inputs.size(); ++k) {
    const InputRecord& in = r.inputs[k];
    // An input recorded as not a file (a FIFO, a directory) gave a failed row; it is named again.
    if (in.error.empty()) verify_input(in);
    // As the first run named it where that still names the same file (from the same directory):
    // the table's file column is then the same too.
    const std::string named = unescape_bytes(j["inputs"][k].value("named", std::string()));
    std::error_code ec;
    const bool same = !named.empty() && std::filesystem::absolute(named, ec).lexically_normal().string() == in.path;
    files.push_back(same && !ec ? named : in.path);
  }
  const std::string curves = j.value("curves", json()).is_string() ? j["curves"].get<std::string>() : std::string();
  std::vector<std::string> all_inputs = files;
  all_inputs.push_back(from);
  json extra;
  extra["rerun_of"] = {{"record", escape_bytes(record_file(from).path)}, {"sha256", sha256_hex(text.data(), text.size())}};
  const Prepared p{*r.scene, r.options, r.csv.value_or(CsvOptions{})};
  MapOutputs o = outputs;
  o.resume = false;
  return map_and_record(p, files, all_inputs, curves, o, command_line, extra);
}

}  // namespace layerjkr::cli
