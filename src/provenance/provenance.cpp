// Provenance records (provenance.hpp): options and scenes as JSON and back, exactly.
//
// Each options struct has ONE field table below (fit_fields, csv_fields): writing and reading
// both walk it, so a new option is one line there. The static_asserts on the structs' sizes are
// tripwires: a field added to FitOptions or CsvOptions without a line in its table stops the
// build here instead of going unrecorded.
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <set>
#include <type_traits>

#include <nlohmann/json.hpp>

#include "layerjkr/error.hpp"
#include "layerjkr/text.hpp"
#include "layerjkr/provenance.hpp"
#include "layerjkr/types.hpp"
#include "provenance/scene_description.hpp"

#ifndef LAYERJKR_VERSION
#error "LAYERJKR_VERSION (the CMake project version) must be defined"
#endif

namespace layerjkr {
namespace {

using json = nlohmann::ordered_json;

// ---- The field tables: one line per option. ----
template <class Options, class Visit>
void fit_fields(Options& o, Visit&& v) {
  v("free", o.free);
  v("branch", o.branch);
  v("retract_control", o.retract_control);
  v("cantilever_stiffness", o.cantilever_stiffness);
  v("exclusion_sigmas", o.exclusion_sigmas);
  v("force_noise", o.force_noise);
  v("radius_noise", o.radius_noise);
  v("errors_in_displacement", o.errors_in_displacement);
  v("displacement_noise", o.displacement_noise);
  v("baseline", o.baseline);
  v("remove_offset", o.remove_offset);
  v("retract_window", o.retract_window);
  v("window_fraction", o.window_fraction);
  v("loss", o.loss);
  v("loss_scale", o.loss_scale);
  v("max_iterations", o.max_iterations);
  v("function_tolerance", o.function_tolerance);
  v("parameter_tolerance", o.parameter_tolerance);
  v("gradient_tolerance", o.gradient_tolerance);
  v("extra_starts", o.extra_starts);
  v("compute_covariance", o.compute_covariance);
  v("correlation_limit", o.correlation_limit);
  v("table_points_per_decade", o.table_points_per_decade);
  v("trace", o.trace);
  v("contact_point", o.contact_point);
  v("indentation_range", o.indentation_range);
  v("force_range", o.force_range);
  v("baseline_window", o.baseline_window);
  v("bounds", o.bounds);
}

template <class Options, class Visit>
void csv_fields(Options& o, Visit&& v) {
  v("length_unit", o.length_unit);
  v("force_unit", o.force_unit);
  v("spring_constant", o.spring_constant);
  v("sensitivity", o.sensitivity);
  v("z_sign", o.z_sign);
  v("deflection_sign", o.deflection_sign);
  v("curve", o.curve);
  v("max_bytes", o.max_bytes);
  v("max_rows", o.max_rows);
}

// Tripwires (64-bit libstdc++ / libc++ layouts). When one fires: add the new field's line to
// the table above, set it to a non-default value in tests/provenance/test_provenance.cpp
// ("every option survives the round trip"), then update the size here.
static_assert(sizeof(void*) != 8 || sizeof(FitOptions) == 312,
              "FitOptions changed: add its new field to fit_fields() in src/provenance/provenance.cpp and to the "
              "non-default options of tests/provenance/test_provenance.cpp, then update this size");
static_assert(sizeof(void*) != 8 || sizeof(CsvOptions) == 72,
              "CsvOptions changed: add its new field to csv_fields() in src/provenance/provenance.cpp and to the "
              "non-default options of tests/provenance/test_provenance.cpp, then update this size");

// ---- Values to JSON. Doubles: nlohmann writes the shortest text that reads back to the same
// bits; JSON has no NaN or infinity, so those are the strings "nan", "inf", "-inf". ----
json to_value(double x) {
  if (std::isnan(x)) return "nan";
  if (std::isinf(x)) return x > 0 ? "inf" : "-inf";
  return x;
}
json to_value(bool x) { return x; }
json to_value(int x) { return x; }
json to_value(std::size_t x) { return x; }
json to_value(const Interval& x) { return json::array({to_value(x.first), to_value(x.second)}); }
json to_value(const ParameterBound& b) {
  return json{{"parameter", to_string(b.parameter)}, {"lower", to_value(b.lower)}, {"upper", to_value(b.upper)}};
}
template <class E, std::enable_if_t<std::is_enum_v<E>, int> = 0>
json to_value(E e) {
  return to_string(e);
}
template <class T>
json to_value(const std::optional<T>& x) {
  return x ? to_value(*x) : json(nullptr);
}
template <class T>
json to_value(const std::vector<T>& xs) {
  json a = json::array();
  for (const T& x : xs) a.push_back(to_value(x));
  return a;
}

// ---- JSON to values: the type must be the field's; errors name `where` (source: key). ----
[[noreturn]] void bad(const std::string& where, const json& v, const std::string& expected) {
  std::string shown = v.dump();
  if (shown.size() > 60) shown = shown.substr(0, 57) + "...";
  throw InputError(where + " = " + shown + " is invalid; expected " + expected);
}

void from_value(const json& v, double& x, const std::string& where) {
  if (v.is_number()) {
    x = v.get<double>();
  } else if (v == "nan") {
    x = std::numeric_limits<double>::quiet_NaN();
  } else if (v == "inf" || v == "-inf") {
    x = (v == "inf" ? 1.0 : -1.0) * std::numeric_limits<double>::infinity();
  } else {
    bad(where, v, "a number");
  }
}
void from_value(const json& v, bool& x, const std::string& where) {
  if (!v.is_boolean()) bad(where, v, "true or false");
  x = v.get<bool>();
}
void from_value(const json& v, int& x, const std::string& where) {
  if (!v.is_number_integer() || v.get<std::int64_t>() < std::numeric_limits<int>::min() ||
      v.get<std::int64_t>() > std::numeric_limits<int>::max())
    bad(where, v, "an integer");
  x = v.get<int>();
}
void from_value(const json& v, std::size_t& x, const std::string& where) {
  if (!v.is_number_unsigned()) bad(where, v, "an integer >= 0");
  x = v.get<std::size_t>();
}
void from_value(const json& v, Interval& x, const std::string& where) {
  if (!v.is_array() || v.size() != 2) bad(where, v, "[min, max]");
  from_value(v[0], x.first, where + "[0]");
  from_value(v[1], x.second, where + "[1]");
}
void from_value(const json& v, ParameterBound& b, const std::string& where) {
  if (!v.is_object() || v.size() != 3 || !v.contains("parameter") || !v.contains("lower") || !v.contains("upper"))
    bad(where, v, "{\"parameter\", \"lower\", \"upper\"}");
  if (!v.at("parameter").is_string()) bad(where + ".parameter", v.at("parameter"), "a parameter name");
  b.parameter = parse_enum<FitParameter>(v.at("parameter").get<std::string>(), where + ".parameter");
  from_value(v.at("lower"), b.lower, where + ".lower");
  from_value(v.at("upper"), b.upper, where + ".upper");
}
template <class E, std::enable_if_t<std::is_enum_v<E>, int> = 0>
void from_value(const json& v, E& e, const std::string& where) {
  if (!v.is_string()) bad(where, v, "one of: " + known_names<E>());
  e = parse_enum<E>(v.get<std::string>(), where);
}
template <class T>
void from_value(const json& v, std::optional<T>& x, const std::string& where) {
  if (v.is_null()) {
    x.reset();
    return;
  }
  T t{};
  from_value(v, t, where);
  x = t;
}
template <class T>
void from_value(const json& v, std::vector<T>& xs, const std::string& where) {
  if (!v.is_array()) bad(where, v, "an array");
  xs.clear();
  for (std::size_t i = 0; i < v.size(); ++i) {
    T t{};
    from_value(v[i], t, where + "[" + std::to_string(i) + "]");
    xs.push_back(t);
  }
}

template <class Options, class Fields>
json write_fields(const Options& o, Fields fields) {
  json j = json::object();
  fields(o, [&](const char* key, const auto& field) { j[key] = to_value(field); });
  return j;
}

// Every key must be a field; a missing one keeps its default (see provenance.hpp).
template <class Options, class Fields>
Options read_fields(const json& j, const std::string& source, Fields fields) {
  if (!j.is_object()) bad(source, j, "a JSON object of options");
  Options o;
  std::set<std::string> known;
  fields(o, [&](const char* key, auto& field) {
    known.insert(key);
    if (j.contains(key)) from_value(j.at(key), field, source + ": " + key);
  });
  for (const auto& item : j.items())
    if (!known.count(item.key()))
      throw InputError(source + ": unknown option '" + item.key() +
                       "' (written by a newer layerjkr? this one, " + std::string(version()) +
                       ", cannot reproduce it)");
  return o;
}

json parse_json(const std::string& text, const std::string& source) {
  try {
    return json::parse(text);
  } catch (const json::parse_error& e) {
    throw InputError(source + ": not valid JSON (" + e.what() + ")");
  }
}

// The scene's own fields, written out: what a scene built in code is recorded as, and what a
// parsed scene must still hold for its JSON to describe it.
json describe(const Scene& s) {
  json m = json::object();
  m["type"] = to_string(s.medium.type);
  for (const auto& [key, value] : {std::pair<const char*, double>{"K", s.medium.K}, {"G", s.medium.G},
                                   {"T", s.medium.T}, {"E", s.medium.E}, {"nu", s.medium.nu}, {"h", s.medium.h}})
    m[key] = to_value(value);
  m["base"] = to_string(s.medium.base);
  if (s.medium.relaxation.kind != RelaxationLaw::Kind::elastic) m["viscoelastic"] = s.medium.relaxation.describe();
  if (s.medium.type == MediumType::layers) {  // every layer and the substrate: a changed stack is stale
    json layers = json::array();
    for (const StackLayer& l : s.medium.stack.layers)
      layers.push_back({{"E", to_value(l.E)}, {"nu", to_value(l.nu)}, {"h", to_value(l.h)}});
    m["layers"] = layers;
    m["stack_base"] = to_string(s.medium.stack.base);
    if (const auto& sub = s.medium.stack.substrate) m["substrate"] = {{"E", to_value(sub->E)}, {"nu", to_value(sub->nu)}};
  }
  json d = json::object();
  d["profile"] = s.profile ? s.profile->describe() : std::string("none");
  d["medium"] = m;
  d["model"] = to_string(s.model);
  d["solver"] = to_string(s.solver);
  d["w"] = to_value(s.w);
  d["tolerance"] = to_value(s.tolerance);
  d["adhesion"] = {{"model", to_string(s.adhesion.model)},
                   {"sigma0", s.adhesion.sigma0 ? to_value(*s.adhesion.sigma0) : json(nullptr)},
                   {"z0", s.adhesion.z0 ? to_value(*s.adhesion.z0) : json(nullptr)}};
  if (s.adhesion.kinetics) d["adhesion"]["kinetics"] = s.adhesion.kinetics->describe();
  return d;
}

json scene_record(const Scene& s) {
  json r = json::object();
  const json description = describe(s);
  json parsed = nullptr;
  std::string note;
  if (s.origin.json.empty()) {
    note = "built in code, not parsed from JSON: recorded by its description only, not reproducible";
  } else {
    // Tables are described by their size and range only; their points are in the JSON.
    const std::string parsed_as = s.origin.description.empty()
                                      ? describe(parse_scene(s.origin.json, "the scene's recorded JSON")).dump()
                                      : s.origin.description;
    if (parsed_as == description.dump())
      parsed = parse_json(s.origin.json, "the scene's recorded JSON");
    else
      note = "changed in code after it was parsed: its JSON no longer describes it; recorded by its description "
             "only, not reproducible";
  }
  r["json"] = parsed;
  r["file"] = s.origin.file.empty() ? json(nullptr) : json(escape_bytes(s.origin.file));
  r["sha256"] = s.origin.file_sha256.empty() ? json(nullptr) : json(s.origin.file_sha256);
  if (!note.empty()) r["note"] = note;
  r["description"] = description;
  return r;
}

json input_record(const InputRecord& in) {
  json r = json::object();
  r["path"] = escape_bytes(in.path);
  r["size"] = in.size;
  r["sha256"] = in.sha256.empty() ? json(nullptr) : json(in.sha256);
  if (!in.error.empty()) r["error"] = in.error;
  return r;
}

const json& member(const json& j, const char* key, const std::string& source) {
  if (!j.is_object() || !j.contains(key)) throw InputError(source + ": has no '" + key + "'");
  return j.at(key);
}

std::string string_member(const json& j, const char* key, const std::string& source) {
  const json& v = member(j, key, source);
  if (!v.is_string()) bad(source + ": " + key, v, "a string");
  return v.get<std::string>();
}

}  // namespace

std::string detail::describe_scene(const Scene& scene) { return describe(scene).dump(); }

const char* version() { return LAYERJKR_VERSION; }

std::string to_json(const FitOptions& options) {
  return write_fields(options, [](auto& o, auto&& v) { fit_fields(o, v); }).dump();
}

std::string to_json(const CsvOptions& options) {
  return write_fields(options, [](auto& o, auto&& v) { csv_fields(o, v); }).dump();
}

FitOptions fit_options_from_json(const std::string& json_text, const std::string& source) {
  FitOptions o = read_fields<FitOptions>(parse_json(json_text, source), source,
                                         [](auto& opts, auto&& v) { fit_fields(opts, v); });
  o.validate();
  return o;
}

CsvOptions csv_options_from_json(const std::string& json_text, const std::string& source) {
  CsvOptions o = read_fields<CsvOptions>(parse_json(json_text, source), source,
                                         [](auto& opts, auto&& v) { csv_fields(opts, v); });
  o.validate();
  return o;
}

std::string scene_json(const Scene& scene) { return scene_record(scene).dump(); }

std::string provenance_json(const Scene& scene, const FitOptions& options, const CsvOptions* csv,
                            const std::vector<InputRecord>& inputs) {
  json p = json::object();
  p["layerjkr_version"] = version();
  p["scene"] = scene_record(scene);
  p["options"] = json::parse(to_json(options));
  if (csv) p["csv"] = json::parse(to_json(*csv));
  json in = json::array();
  for (const InputRecord& r : inputs) in.push_back(input_record(r));
  p["inputs"] = in;
  return p.dump();
}

ProvenanceRecord parse_provenance(const std::string& json_text, const std::string& source) {
  const json p = parse_json(json_text, source);
  if (!p.is_object()) bad(source, p, "a provenance object");
  ProvenanceRecord r;
  r.version = string_member(p, "layerjkr_version", source);
  const json& scene = member(p, "scene", source);
  const json& scene_text = member(scene, "json", source + ": scene");
  if (scene_text.is_object()) {
    r.scene = parse_scene(scene_text.dump(), source + ": scene.json");
    // The rerun records the same scene file and hash as the original (its JSON is the file's).
    if (scene.contains("file") && scene.at("file").is_string()) r.scene->origin.file = unescape_bytes(scene.at("file").get<std::string>());
    if (scene.contains("sha256") && scene.at("sha256").is_string())
      r.scene->origin.file_sha256 = scene.at("sha256").get<std::string>();
  } else if (!scene_text.is_null()) {
    bad(source + ": scene.json", scene_text, "a scene object or null");
  } else {
    r.scene_note = scene.contains("note") && scene.at("note").is_string() ? scene.at("note").get<std::string>()
                                                                          : "no scene JSON recorded";
  }
  r.options = fit_options_from_json(member(p, "options", source).dump(), source + ": options");
  if (p.contains("csv")) r.csv = csv_options_from_json(p.at("csv").dump(), source + ": csv");
  const json& inputs = member(p, "inputs", source);
  if (!inputs.is_array()) bad(source + ": inputs", inputs, "an array");
  for (std::size_t i = 0; i < inputs.size(); ++i) {
    const std::string where = source + ": inputs[" + std::to_string(i) + "]";
    InputRecord in;
    in.path = unescape_bytes(string_member(inputs[i], "path", where));
    from_value(member(inputs[i], "size", where), in.size, where + ": size");
    const json& hash = member(inputs[i], "sha256", where);
    if (hash.is_string()) in.sha256 = hash.get<std::string>();
    if (inputs[i].contains("error") && inputs[i].at("error").is_string()) in.error = inputs[i].at("error").get<std::string>();
    if (in.sha256.size() != 64 && in.error.empty()) bad(where + ": sha256", hash, "64 hex digits");
    r.inputs.push_back(in);
  }
  return r;
}

}  // namespace layerjkr
