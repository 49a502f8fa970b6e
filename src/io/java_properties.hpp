// Internal: Java .properties text (ISO-8859-1, as JPK writes it) to a key -> value map.
#pragma once

#include <map>
#include <string>

namespace layerjkr::detail {

using Properties = std::map<std::string, std::string>;

/// Parses `text`: '#' and '!' comments, key/value separated by '=', ':' or whitespace,
/// backslash escapes (\t \n \r \f, \uXXXX as UTF-8, any other escaped character as itself)
/// and line continuations. Latin-1 bytes are converted to UTF-8. A key given twice throws
/// InputError "<where>: the key '<key>' is given twice (...)": Java's Properties.store never
/// writes one twice, so a repeat is damage, and which value holds would be a guess.
Properties parse_properties(const std::string& text, const std::string& where);

}  // namespace layerjkr::detail
