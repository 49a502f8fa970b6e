// layerjkr: text that reaches a terminal or a file - names and messages made printable.
//
// A file name on Linux is any bytes but '/' and NUL: it may hold line breaks, escape sequences
// (ESC, BEL) that a terminal obeys, and bytes that are not UTF-8 (Latin-1 names on old shares),
// which JSON cannot hold. layerjkr writes such names reversibly and prints messages safely:
//
//   escape_bytes("M\xfcller.jpk-force") == "M\\xfcller.jpk-force"   // reversible, valid UTF-8
//   unescape_bytes(escape_bytes(s)) == s                              // for every s
//   printable("bad \x1b]0;owned\x07 value") == "bad \\x1b]0;owned\\x07 value"
#pragma once

#include <cstddef>
#include <string>
#include <string_view>

namespace layerjkr {

/// True if `s` is well-formed UTF-8 (no overlong forms, no surrogates, nothing beyond U+10FFFF).
bool is_utf8(const std::string& s);

/// `s` as valid UTF-8 with nothing a terminal obeys, reversibly: a backslash becomes `\\`; every
/// byte that is not part of a well-formed UTF-8 character, and every control character but the
/// line feed (C0, DEL, and C1 as the UTF-8 bytes that encode it), becomes `\xNN` (two lowercase
/// hex digits per byte). Line feeds stay (a CSV cell quotes them, JSON escapes them). Used for
/// every file name layerjkr writes into a table, a record or a report.
std::string escape_bytes(const std::string& s);

/// The inverse of escape_bytes: `\\` and `\xNN` become the bytes they stand for. Any other
/// backslash is kept as it is (text written before names were escaped reads back unchanged).
std::string unescape_bytes(const std::string& s);

/// `s` for a person to read on a terminal or a page: as escape_bytes, but a backslash stays a
/// backslash (not reversible). Every message layerjkr prints goes through it, so a value echoed
/// from a file (a scene string, a CSV header cell, an instrument header, a file name) cannot set
/// the terminal's title, clear the screen or colour the text.
std::string printable(const std::string& s);

/// printable() of the first `max_bytes` bytes of `s`, with "..." if it was longer: a value that
/// may come from a binary file, shown in a message.
std::string printable(std::string_view s, std::size_t max_bytes);

}  // namespace layerjkr
