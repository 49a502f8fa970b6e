#include "io/java_properties.hpp"

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <stdexcept>

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

// Joins continuation lines of text[pos, stop): a line ending in an odd number of backslashes
// continues, and the next line's leading whitespace is dropped.
std::string logical_line(const std::string& text, std::size_t& pos, std::size_t stop) {
  std::string line;
  bool first = true;
  while (pos < stop) {
    std::size_t end = pos;  // a plain loop: find_first_of calls memchr per position
    while (end < stop && text[end] != '\n' && text[end] != '\r') ++end;
    std::size_t start = pos;
    if (!first)
      while (start < end && (text[start] == ' ' || text[start] == '\t' || text[start] == '\f')) ++start;
    line.append(text, start, end - start);
    pos = end;
    if (pos < stop && text[pos] == '\r') ++pos;
    if (pos < stop && text[pos] == '\n') ++pos;
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

// Word-at-a-time scans: a curve's headers are ~10 KB, and a byte-by-byte loop over them
// was a fifth of the reading time.
constexpr std::uint64_t kOnes = 0x0101010101010101ULL, kHighs = 0x8080808080808080ULL;

// Nonzero if a byte of x is c (exact for the word as a whole, not for which byte it is).
constexpr std::uint64_t has_byte(std::uint64_t x, unsigned char c) {
  const std::uint64_t v = x ^ (kOnes * c);
  return (v - kOnes) & ~v & kHighs;
}

std::uint64_t word(const std::string& s, std::size_t i) {
  std::uint64_t x = 0;
  std::memcpy(&x, s.data() + i, sizeof x);
  return x;
}

// The first position in s[i, to) of a line end, a backslash or a non-ASCII byte, or `to`.
std::size_t line_stop(const std::string& s, std::size_t i, std::size_t to) {
  for (; to - i >= 8; i += 8) {
    const std::uint64_t x = word(s, i);
    if ((x & kHighs) | has_byte(x, '\n') | has_byte(x, '\r') | has_byte(x, '\\')) break;
  }
  while (i < to && s[i] != '\n' && s[i] != '\r' && s[i] != '\\' && static_cast<unsigned char>(s[i]) < 0x80) ++i;
  return i;
}

// The first position in s[i, to) of a key separator ('=', ':', whitespace) or a backslash, or `to`.
std::size_t key_stop(const std::string& s, std::size_t i, std::size_t to) {
  for (; to - i >= 8; i += 8) {
    const std::uint64_t x = word(s, i);
    if (has_byte(x, '=') | has_byte(x, ':') | has_byte(x, ' ') | has_byte(x, '\t') | has_byte(x, '\f') |
        has_byte(x, '\\'))
      break;
  }
  while (i < to && s[i] != '=' && s[i] != ':' && !is_space(s[i]) && s[i] != '\\') ++i;
  return i;
}

// Where a line's key ends and its value starts, in s[from, to): the key is s[from, key_end).
void split(const std::string& s, std::size_t from, std::size_t to, std::size_t& key_end, std::size_t& value) {
  key_end = key_stop(s, from, to);
  while (key_end < to && s[key_end] == '\\') key_end = key_stop(s, key_end + 2 > to ? to : key_end + 2, to);  // an escaped separator belongs to the key
  key_end = std::min(key_end, to);
  value = key_end;
  while (value < to && is_space(s[value])) ++value;
  if (value < to && (s[value] == '=' || s[value] == ':')) ++value;
  while (value < to && is_space(s[value])) ++value;
}

}  // namespace

std::size_t Properties::lower(std::string_view key) const {
  std::size_t lo = 0, n = entries_.size();
  while (n > 0) {
    const std::size_t half = n / 2;
    if (key_at(lo + half) < key) {
      lo += half + 1;
      n -= half + 1;
    } else {
      n = half;
    }
  }
  return lo;
}

std::optional<std::string_view> Properties::find(std::string_view key) const {
  const std::size_t i = lower(key);
  if (i == entries_.size() || key_at(i) != key) return std::nullopt;
  return entry(i).second;
}

std::string_view Properties::at(std::string_view key) const {
  if (const std::optional<std::string_view> v = find(key)) return *v;
  throw std::out_of_range("Properties::at: no key '" + std::string(key) + "'");
}

Properties::Range Properties::with_prefix(std::string_view prefix) const {
  const std::size_t first = lower(prefix);
  std::size_t last = first;
  while (last < entries_.size() && key_at(last).substr(0, prefix.size()) == prefix) ++last;
  return {{this, first}, {this, last}};
}

Properties parse_properties(std::string text, const std::string& where) {
  Properties out;
  std::string& t = out.text_;
  t = std::move(text);
  const std::size_t stop = t.size();  // the arena of unescaped lines grows after it
  out.entries_.reserve(stop / 64);  // JPK's lines are ~90 bytes
  std::size_t pos = 0;
  while (pos < stop) {
    const std::size_t end = line_stop(t, pos, stop);
    // No escape, continuation or Latin-1: the line is used where it stands.
    const bool plain = end == stop || t[end] == '\n' || t[end] == '\r';
    Properties::Entry e;
    e.line = out.entries_.size();
    if (plain) {
      std::size_t i = pos;
      pos = end;
      if (pos < stop && t[pos] == '\r') ++pos;
      if (pos < stop && t[pos] == '\n') ++pos;
      while (i < end && is_space(t[i])) ++i;
      if (i == end || t[i] == '#' || t[i] == '!') continue;
      std::size_t key_end = 0, value = 0;
      split(t, i, end, key_end, value);
      e.key = i;
      e.key_length = key_end - i;
      e.value = value;
      e.value_length = end - value;
    } else {
      const std::string line = logical_line(t, pos, stop);
      std::size_t i = 0;
      while (i < line.size() && is_space(line[i])) ++i;
      if (i == line.size() || line[i] == '#' || line[i] == '!') continue;
      std::size_t key_end = 0, value = 0;
      split(line, i, line.size(), key_end, value);
      const std::string key = unescape(line, i, key_end), val = unescape(line, value, line.size());
      e.key = t.size();
      e.key_length = key.size();
      t += key;
      e.value = t.size();
      e.value_length = val.size();
      t += val;
    }
    out.entries_.push_back(e);
  }
  const auto key_of = [&t](const Properties::Entry& e) { return std::string_view(t).substr(e.key, e.key_length); };
  std::sort(out.entries_.begin(), out.entries_.end(), [&](const Properties::Entry& a, const Properties::Entry& b) {
    const int c = key_of(a).compare(key_of(b));
    return c < 0 || (c == 0 && a.line < b.line);
  });
  // A key repeated with the same value is one value (instruments write such repeats); with
  // another value it is a conflict with no evidence of which one the instrument meant. The one
  // reported is the first in the text, with the value the key had before it.
  std::size_t repeat = 0;
  for (std::size_t i = 1; i < out.entries_.size(); ++i)
    if (key_of(out.entries_[i]) == key_of(out.entries_[i - 1]) &&
        out.entry(i).second != out.entry(i - 1).second &&
        (repeat == 0 || out.entries_[i].line < out.entries_[repeat].line))
      repeat = i;
  if (repeat != 0) {
    const auto [key, first] = out.entry(repeat - 1);
    throw InputError(where + ": the key '" + std::string(key) + "' is given twice ('" + std::string(first) + "' and '" +
                     std::string(out.entry(repeat).second) + "')");
  }
  return out;
}

}  // namespace layerjkr::detail
