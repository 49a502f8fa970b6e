// The strict JSON parser and the snippets of scene values in error messages (json_reader.hpp).
#include "json_reader.hpp"

#include <set>
#include <string>
#include <vector>

namespace layerjkr::detail {
namespace {

// Deeper nesting than any scene needs is refused while parsing, before anything recursive
// (dump, destruction) walks the document: 100 000 '[' used to overflow the stack.
constexpr int kMaxDepth = 32;

// Appends v's JSON text until `out` holds more than `budget` characters: a snippet for an
// error message costs O(budget), not O(document), and recursion is bounded by kMaxDepth.
void put(const json& v, std::string& out, std::size_t budget) {
  if (out.size() > budget) return;
  if (!v.is_structured()) {
    out += v.dump();
    return;
  }
  const bool obj = v.is_object();
  out += obj ? '{' : '[';
  bool first = true;
  for (auto it = v.begin(); it != v.end() && out.size() <= budget; ++it, first = false) {
    if (!first) out += ',';
    if (obj) out += json(it.key()).dump() + ':';
    put(*it, out, budget);
  }
  out += obj ? '}' : ']';
}

}  // namespace

std::string show(const json& v) {
  std::string s;
  put(v, s, 80);
  return s.size() > 80 ? s.substr(0, 77) + "..." : s;
}

namespace {

// The keys seen so far in each open object or array, for the parser callback: a key given
// twice in one object is an error (nlohmann keeps the last silently).
struct OpenValue {
  std::string path;
  bool object;
  std::set<std::string> keys;
  std::string last_key;
};

}  // namespace

json parse_strict(const std::string& text, const std::string& source) {
  std::vector<OpenValue> open;
  auto child_path = [&open]() -> std::string {
    if (open.empty()) return "";
    const OpenValue& p = open.back();
    const std::string sep = p.path.empty() ? "" : ".";
    return p.object ? p.path + sep + p.last_key : p.path + "[]";
  };
  const json::parser_callback_t check = [&](int, json::parse_event_t event, json& parsed) {
    using E = json::parse_event_t;
    if (event == E::object_start || event == E::array_start) {
      if (open.size() >= static_cast<std::size_t>(kMaxDepth))
        throw InputError(source + ": the JSON nests objects and arrays deeper than " +
                         std::to_string(kMaxDepth) + " levels, the limit for scene files");
      open.push_back({child_path(), event == E::object_start, {}, {}});
    } else if (event == E::object_end || event == E::array_end) {
      open.pop_back();
    } else if (event == E::key) {
      OpenValue& o = open.back();
      o.last_key = parsed.get<std::string>();
      if (!o.keys.insert(o.last_key).second) {
        const std::string sep = o.path.empty() ? "" : ".";
        throw InputError(source + ": " + o.path + sep + o.last_key +
                         " is given twice in the same object; give each key once");
      }
    }
    return true;
  };
  try {
    return json::parse(text, check);
  } catch (const json::exception& e) {  // syntax errors and number overflow (1e999)
    throw InputError(source + ": not valid JSON (" + e.what() + ")");
  }
}

}  // namespace layerjkr::detail
