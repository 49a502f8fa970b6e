// The NanoScope text header (nanoscope_header.hpp). Facts from
// ../shared/data/instrument/bruker/FORMAT_NOTES.md sections 1-2.
#include "io/nanoscope_header.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>

#include "io/csv_rows.hpp"
#include "layerjkr/error.hpp"

namespace layerjkr::detail {
namespace {

// Blanks, tabs and CR around keys and values: real headers write `\Capture mode : x` and
// `\PF PGain<TAB>: 99.8`.
std::string_view strip(std::string_view s) {
  const auto b = s.find_first_not_of(" \t\r");
  if (b == std::string_view::npos) return {};
  return s.substr(b, s.find_last_not_of(" \t\r") - b + 1);
}

// A leading finite number of `s` (from_chars takes no '+'), its length in `used`.
std::optional<double> leading_number(std::string_view s, std::size_t& used) {
  const std::size_t skip = !s.empty() && s[0] == '+' ? 1 : 0;
  double v = 0.0;
  const auto [end, ec] = std::from_chars(s.data() + skip, s.data() + s.size(), v);
  if (ec != std::errc() || !std::isfinite(v)) return std::nullopt;
  used = static_cast<std::size_t>(end - s.data());
  return v;
}

// A number that is the first word of `s`: "0.000375 V/LSB" yes, "\Data length V/LSB" no.
std::optional<double> first_word_number(std::string_view s) {
  s = strip(s);
  std::size_t used = 0;
  const std::optional<double> v = leading_number(s, used);
  if (!v || (used < s.size() && s[used] != ' ' && s[used] != '\t')) return std::nullopt;
  return v;
}

}  // namespace

const std::string* NanoscopeSection::find(std::string_view key) const {
  for (const auto& [k, v] : entries)
    if (k == key) return &v;
  return nullptr;
}

const std::string* NanoscopeSection::find_any_case(std::string_view key) const {
  const auto lower = [](char c) { return static_cast<char>(std::tolower(static_cast<unsigned char>(c))); };
  for (const auto& [k, v] : entries)
    if (k.size() == key.size() && std::equal(k.begin(), k.end(), key.begin(), [&](char a, char b) { return lower(a) == lower(b); }))
      return &v;
  return nullptr;
}

NanoscopeParameter parse_nanoscope_parameter(std::string_view value) {
  NanoscopeParameter p;
  std::string_view rest = strip(value);
  if (rest.empty()) return p;
  p.type = rest[0];
  rest = strip(rest.substr(1));
  if (!rest.empty() && rest[0] == '[') {
    const std::size_t close = rest.find(']');
    if (close == std::string_view::npos) return p;
    p.soft_scale = std::string(strip(rest.substr(1, close - 1)));
    rest = strip(rest.substr(close + 1));
  }
  if (p.type == 'S') {
    const std::size_t open = rest.find('"');
    const std::size_t close = open == std::string_view::npos ? open : rest.find('"', open + 1);
    if (close != std::string_view::npos) p.quoted = std::string(rest.substr(open + 1, close - open - 1));
    return p;
  }
  if (!rest.empty() && rest[0] == '(') {
    const std::size_t close = rest.find(')');
    if (close == std::string_view::npos) return p;
    p.hard_scale = first_word_number(rest.substr(1, close - 1));
    rest = strip(rest.substr(close + 1));
  }
  p.hard_value = first_word_number(rest);
  return p;
}

NanoscopeHeader::NanoscopeHeader(std::string_view text, std::string path) : path_(std::move(path)) {
  sections_.push_back({});  // lines before the first `\*` (none in a valid file)
  std::size_t pos = 0;
  while (pos < text.size()) {
    std::size_t end = text.find('\n', pos);
    if (end == std::string_view::npos) end = text.size();
    const std::string_view line = strip(text.substr(pos, end - pos));
    pos = end + 1;
    if (line.size() < 2 || line[0] != '\\') continue;  // blank lines, padding
    if (line[1] == '*') {
      sections_.push_back({std::string(strip(line.substr(2))), {}});
      continue;
    }
    // The key ends at the first ':' after an `@<group>:` prefix (`\@4:Z scale: V ...`).
    std::size_t from = 1;
    if (line[1] == '@') {
      std::size_t d = 2;
      while (d < line.size() && line[d] >= '0' && line[d] <= '9') ++d;
      if (d > 2 && d < line.size() && line[d] == ':') from = d + 1;
    }
    const std::size_t colon = line.find(':', from);
    const std::string_view key = strip(line.substr(1, colon == std::string_view::npos ? colon : colon - 1));
    const std::string_view value = colon == std::string_view::npos ? std::string_view{} : strip(line.substr(colon + 1));
    sections_.back().entries.emplace_back(std::string(key), std::string(value));
  }
}

const NanoscopeSection* NanoscopeHeader::section(std::string_view name) const {
  for (const NanoscopeSection& s : sections_)
    if (s.name == name) return &s;
  return nullptr;
}

const NanoscopeSection& NanoscopeHeader::need_section(std::string_view name) const {
  const NanoscopeSection* s = section(name);
  if (!s) throw InputError(path_ + ": the header has no section \\*" + std::string(name));
  return *s;
}

void NanoscopeHeader::fail(const NanoscopeSection& section, const std::string& what) const {
  throw InputError(path_ + ": \\*" + section.name + ": " + what);
}

const std::string& NanoscopeHeader::text(const NanoscopeSection& section, std::string_view key) const {
  const std::string* v = section.find(key);
  if (!v) fail(section, "no \\" + std::string(key));
  return *v;
}

double NanoscopeHeader::number(const NanoscopeSection& section, std::string_view key, std::string* unit) const {
  const std::string& v = text(section, key);
  std::size_t used = 0;
  const std::optional<double> x = leading_number(v, used);
  const std::string_view rest = strip(std::string_view(v).substr(x ? used : 0));
  // A unit is text after a blank; a second number ("1024 1024") is not one.
  const bool unit_ok = rest.empty() || (used < v.size() && (v[used] == ' ' || v[used] == '\t') &&
                                        rest.find_first_of("0123456789+-.") != 0);
  if (!x || !unit_ok || (!unit && !rest.empty()))
    fail(section, "\\" + std::string(key) + " = '" + v + "': expected one finite number" +
                      (unit ? " and an optional unit" : ""));
  if (unit) *unit = std::string(rest);
  return *x;
}

std::int64_t NanoscopeHeader::whole(const NanoscopeSection& section, std::string_view key, std::int64_t lo,
                                    std::int64_t hi) const {
  const std::vector<std::int64_t> v = wholes(section, key, lo, hi);
  if (v.size() != 1)
    fail(section, "\\" + std::string(key) + " = '" + text(section, key) + "': expected one whole number in [" +
                      std::to_string(lo) + ", " + std::to_string(hi) + "]");
  return v[0];
}

std::vector<std::int64_t> NanoscopeHeader::wholes(const NanoscopeSection& section, std::string_view key,
                                                  std::int64_t lo, std::int64_t hi) const {
  const std::string& v = text(section, key);
  std::vector<std::int64_t> out;
  std::string_view rest = strip(v);
  while (!rest.empty()) {
    std::int64_t x = 0;
    const auto [end, ec] = std::from_chars(rest.data(), rest.data() + rest.size(), x);
    const std::size_t used = static_cast<std::size_t>(end - rest.data());
    if (ec != std::errc() || x < lo || x > hi || (used < rest.size() && rest[used] != ' ' && rest[used] != '\t'))
      fail(section, "\\" + std::string(key) + " = '" + v + "': expected whole numbers in [" + std::to_string(lo) +
                        ", " + std::to_string(hi) + "]");
    out.push_back(x);
    rest = strip(rest.substr(used));
  }
  if (out.empty()) fail(section, "\\" + std::string(key) + " is empty; expected whole numbers");
  return out;
}

NanoscopeParameter NanoscopeHeader::parameter(const NanoscopeSection& section, std::string_view key) const {
  return parse_nanoscope_parameter(text(section, key));
}

double NanoscopeHeader::sensitivity(const std::string& soft_scale, const std::string& user) const {
  if (soft_scale.empty()) throw InputError(path_ + ": " + user + " names no sensitivity ([Sens. ...])");
  const std::string key = "@" + soft_scale;
  for (const NanoscopeSection& s : sections_) {
    const std::string* v = s.find(key);
    if (!v) continue;
    const std::optional<double> x = parse_nanoscope_parameter(*v).hard_value;
    if (!x || !(*x > 0.0)) fail(s, "\\" + key + " = '" + *v + "': expected a finite sensitivity > 0 (" + user + ")");
    return *x;
  }
  throw InputError(path_ + ": the header has no \\" + key + " (the sensitivity " + user + " refers to)");
}

}  // namespace layerjkr::detail
