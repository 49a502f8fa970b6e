// Internal: Java .properties text (ISO-8859-1, as JPK writes it) to a key -> value map.
#pragma once

#include <map>
#include <string>

namespace layerjkr::detail {

using Properties = std::map<std::string, std::string>;

/// Parses `text`: '#' and '!' comments, key/value separated by '=', ':' or whitespace,
/// backslash escapes (\t \n \r \f, \uXXXX as UTF-8, any other escaped character as itself)
/// and line continuations. Latin-1 bytes are converted to UTF-8.
Properties parse_properties(const std::string& text);

}  // namespace layerjkr::detail
