// User text (a tile-set name, a path, a value from a file) made safe to echo on a terminal:
// control characters would move the cursor, recolor or retitle it, or forge extra lines.
#pragma once

#include <string>
#include <string_view>

namespace wangscape {

// `text` with each C0 control character, DEL and each UTF-8 encoded C1 control written as an
// escape (`\n`, `\t`, `\r`, `\x1b`, `\u009b`); other bytes, UTF-8 included, unchanged. With
// `keep_newlines`, '\n' stays (for messages that quote several lines of a tool's log).
std::string printable(std::string_view text, bool keep_newlines = false);

// `text` as valid UTF-8: each byte that does not begin or continue a well-formed sequence (an
// overlong form, a surrogate, beyond U+10FFFF, a lone 0xFF from a Latin-1 file) becomes U+FFFD,
// as JSON output does, so text files we write (scene.pov's comments) stay UTF-8.
std::string valid_utf8(std::string_view text);

}  // namespace wangscape
