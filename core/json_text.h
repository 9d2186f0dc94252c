// JSON text of what Wangscape writes or says, through nlohmann-json's dump, without letting a
// user's bytes fail it: text that is not UTF-8 (a DEM's CRS, a folder name with a 0xFF byte) is
// written with U+FFFD in its place instead of throwing json.exception.type_error.316. A template
// over the JSON type, so core/ stays on the standard library (its users bring nlohmann-json).
#pragma once

#include <exception>
#include <string>

namespace wangscape {

// j.dump(indent) (-1: one line; N: N spaces a level) with invalid UTF-8 replaced.
template <class JsonT>
std::string json_text(const JsonT& j, int indent = -1) {
  return j.dump(indent, ' ', false, JsonT::error_handler_t::replace);
}

// What a nlohmann-json exception says without its id: "[json.exception.parse_error.101] parse
// error at line 1, column 2: ..." becomes "parse error at line 1, column 2: ...".
inline std::string json_error_text(const std::exception& e) {
  std::string reason = e.what();
  if (const auto close = reason.find("] "); reason.starts_with("[json.exception") && close != std::string::npos)
    reason.erase(0, close + 2);
  return reason;
}

}  // namespace wangscape
