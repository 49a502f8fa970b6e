#include "io/java_properties.hpp"

#include <algorithm>
#include <cstdint>

#include "layerjkr/error.hpp"

namespace layerjkr::detail {
namespace {

void append_utf8(std::string& out, std::uint32_t c) {
  if (c < 0x80) {
    out += static_cast<char>(c);
  } else if (c < 0x800) {
    out += static_cast<char>(0xC0 | (c >> 6));
    out += static_cast<char>(0x80 | (c & 0x3F));
  } else {
    out += static_cast<char>(0xE0 | (c >> 12));
    out += static_cast<char>(0x80 | ((c >> 6) & 0x3F));
    out += static_cast<char>(0x80 | (c & 0x3F));
  }
}

int hex_digit(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return -1;
}

// Joins continuation lines: a line ending in an odd number of backslashes continues, and the
// next line's leading whitespace is dropped.
std::string logical_line(const std::string& text, std::size_t& pos) {
  std::string line;
  bool first = true;
  while (pos < text.size()) {
    std::size_t end = pos;  // a plain loop: find_first_of calls memchr per position
    while (end < text.size() && text[end] != '\n' && text[end] != '\r') ++end;
    std::size_t start = pos;
    if (!first)
      while (start < end && (text[start] == ' ' || text[start] == '\t' || text[start] == '\f')) ++start;
    line.append(text, start, end - start);
    pos = end;
    if (pos < text.size() && text[pos] == '\r') ++pos;
    if (pos < text.size() && text[pos] == '\n') ++pos;
    std::size_t slashes = 0;
    while (slashes < line.size() && line[line.size() - 1 - slashes] == '\\') ++slashes;
    if (slashes % 2 == 0) break;
    line.pop_back();
    first = false;
  }
  return line;
}

// Unescapes s[from, to).
std::string unescape(const std::string& s, std::size_t from, std::size_t to) {
  bool plain = true;  // the common case: ASCII without escapes, copied as is
  for (std::size_t i = from; i < to && plain; ++i) plain = s[i] != '\\' && static_cast<unsigned char>(s[i]) < 0x80;
  if (plain) return s.substr(from, to - from);
  std::string out;
  for (std::size_t i = from; i < to; ++i) {
    const auto byte = static_cast<unsigned char>(s[i]);
    if (byte != '\\' || i + 1 >= to) {
      append_utf8(out, byte);  // Latin-1 byte -> code point
      continue;
    }
    const char c = s[++i];
    if (c == 't') out += '\t';
    else if (c == 'n') out += '\n';
    else if (c == 'r') out += '\r';
    else if (c == 'f') out += '\f';
    else if (c == 'u' && i + 4 < to) {
      std::uint32_t code = 0;
      bool ok = true;
      for (int k = 1; k <= 4; ++k) {
        const int d = hex_digit(s[i + static_cast<std::size_t>(k)]);
        ok = ok && d >= 0;
        code = code * 16 + static_cast<std::uint32_t>(d < 0 ? 0 : d);
      }
      if (ok) {
        append_utf8(out, code);
        i += 4;
      } else {
        out += 'u';
      }
    } else {
      append_utf8(out, static_cast<unsigned char>(c));
    }
  }
  return out;
}

bool is_space(char c) { return c == ' ' || c == '\t' || c == '\f'; }

}  // namespace

Properties parse_properties(const std::string& text, const std::string& where) {
  Properties out;
  std::size_t pos = 0;
  while (pos < text.size()) {
    const std::string line = logical_line(text, pos);
    std::size_t i = 0;
    while (i < line.size() && is_space(line[i])) ++i;
    if (i == line.size() || line[i] == '#' || line[i] == '!') continue;
    std::size_t key_end = i;
    while (key_end < line.size() && line[key_end] != '=' && line[key_end] != ':' && !is_space(line[key_end])) {
      if (line[key_end] == '\\') ++key_end;  // an escaped separator belongs to the key
      ++key_end;
    }
    key_end = std::min(key_end, line.size());
    std::size_t value = key_end;
    while (value < line.size() && is_space(line[value])) ++value;
    if (value < line.size() && (line[value] == '=' || line[value] == ':')) ++value;
    while (value < line.size() && is_space(line[value])) ++value;
    std::string key = unescape(line, i, key_end);
    auto [it, fresh] = out.emplace(std::move(key), unescape(line, value, line.size()));
    if (!fresh)
      throw InputError(where + ": the key '" + it->first + "' is given twice ('" + it->second + "' and '" +
                       unescape(line, value, line.size()) + "')");
  }
  return out;
}

}  // namespace layerjkr::detail
