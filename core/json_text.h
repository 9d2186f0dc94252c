// JSON text of what Wangscape writes or says, through nlohmann-json's dump, without letting a
// user's bytes fail it: text that is not UTF-8 (a DEM's CRS, a folder name with a 0xFF byte) is
// written with U+FFFD in its place instead of throwing json.exception.type_error.316. A template
// over the JSON type, so core/ stays on the standard library (its users bring nlohmann-json).
#pragma once

#include <string>

namespace wangscape {

// j.dump(indent) (-1: one line; N: N spaces a level) with invalid UTF-8 replaced.
template <class JsonT>
std::string json_text(const JsonT& j, int indent = -1) {
  return j.dump(indent, ' ', false, JsonT::error_handler_t::replace);
}

}  // namespace wangscape
