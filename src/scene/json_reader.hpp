// Internal: reading a scene's JSON (scene_reader.cpp, medium_reader.cpp) - a strict parser (a
// depth limit, duplicate keys refused) and a JsonReader whose every failure names the file, the key,
// the value given and the valid range.
#pragma once

#include <cmath>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "layerjkr/error.hpp"
#include "layerjkr/types.hpp"

namespace layerjkr::detail {

using json = nlohmann::json;

/// Parses `text` with a depth limit and duplicate-key detection, both while parsing; InputError
/// naming `source` otherwise.
json parse_strict(const std::string& text, const std::string& source);

/// v's JSON text cut to 80 characters, for error messages: O(80), not O(document).
std::string show(const json& v);

class JsonReader {
 public:
  explicit JsonReader(std::string source) : source_(std::move(source)) {}

  [[noreturn]] void fail(const std::string& key, const std::string& what) const {
    throw InputError(source_ + ": " + key + " " + what);
  }

  const json& object(const json& parent, const std::string& key, const std::string& path) const {
    if (!parent.contains(key)) fail(path, "is missing");
    const json& v = parent.at(key);
    if (!v.is_object()) fail(path, "must be a JSON object, got " + show(v));
    return v;
  }

  void only_keys(const json& obj, const std::string& path, const std::set<std::string>& allowed) const {
    for (const auto& item : obj.items())
      if (!allowed.count(item.key())) {
        std::string list;
        for (const auto& k : allowed) list += (list.empty() ? "" : ", ") + k;
        fail(path + "." + item.key(), "is not a known key here (known: " + list + ")");
      }
  }

  double number(const json& obj, const std::string& key, const std::string& path) const {
    if (!obj.contains(key)) fail(path + "." + key, "is missing");
    return as_number(obj.at(key), path + "." + key);
  }

  double as_number(const json& v, const std::string& path) const {
    if (!v.is_number()) fail(path, "must be a number, got " + show(v));
    const double d = v.get<double>();
    if (!std::isfinite(d)) fail(path, "must be finite, got " + show(v));
    return d;
  }

  std::string string(const json& obj, const std::string& key, const std::string& path) const {
    if (!obj.contains(key)) fail(path + "." + key, "is missing");
    const json& v = obj.at(key);
    if (!v.is_string()) fail(path + "." + key, "must be a string, got " + show(v));
    return v.get<std::string>();
  }

  std::vector<double> numbers(const json& obj, const std::string& key,
                              const std::string& path) const {
    if (!obj.contains(key)) fail(path + "." + key, "is missing");
    const json& v = obj.at(key);
    if (!v.is_array()) fail(path + "." + key, "must be an array of numbers, got " + show(v));
    std::vector<double> out;
    for (std::size_t i = 0; i < v.size(); ++i)
      out.push_back(as_number(v[i], path + "." + key + "[" + std::to_string(i) + "]"));
    return out;
  }

  // Runs a library factory; its DomainError is re-thrown naming the scene key.
  template <class F>
  auto checked(const std::string& path, F make) const {
    try {
      return make();
    } catch (const DomainError& e) {
      throw InputError(source_ + ": " + path + ": " + e.what());
    }
  }

 private:
  std::string source_;
};

// An enum spelled by the registry (types.hpp), or a failure naming the key and the known values.
template <class E>
E read_enum(const JsonReader& in, const std::string& text, const std::string& key) {
  if (const std::optional<E> e = from_string<E>(text)) return *e;
  in.fail(key, "= \"" + text + "\" is unknown (known: " + known_names<E>() + ")");
}

}  // namespace layerjkr::detail
