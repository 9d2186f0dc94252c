// Reading the text files a user names (scene files, tile-set JSON) defensively: a folder, a
// FIFO or a device is refused before it is opened (a FIFO would block, /dev/zero never ends), a
// file over the limit is refused before it is read, and nesting that would overflow a parser's
// stack is refused before parsing. Limits: docs/limits.md.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>

namespace wangscape {

// The whole file, if it is a regular file of at most max_bytes. Throws Error naming the file
// and, for a size, the size and the limit; `what` says what kind of file ("scene file").
std::string read_text_file(const std::filesystem::path& file, std::uintmax_t max_bytes, std::string_view what);

// Throws Error naming the file and line when brackets ([ and {, outside strings) nest deeper
// than max_depth, or a key holds more than max_depth dots (a TOML key of that many dotted parts
// is a table that deep). Keys are TOML's before '=' and JSON's before ':'; the dots of numbers
// and strings are not counted, so JSON written on one line passes as it does on many.
void check_nesting(std::string_view text, const std::filesystem::path& file, int max_depth);

// The nesting limit of every document Wangscape reads.
inline constexpr int kMaxNesting = 64;

}  // namespace wangscape
