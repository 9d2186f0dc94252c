#include "core/text_file.h"

#include <fstream>
#include <iterator>

#include "core/error.h"

namespace wangscape {

std::string read_text_file(const std::filesystem::path& file, std::uintmax_t max_bytes, std::string_view what) {
  std::error_code ec;
  const auto status = std::filesystem::status(file, ec);
  if (ec || !std::filesystem::exists(status))
    throw Error(file, "", "cannot read the " + std::string(what) + ": no such file");
  if (!std::filesystem::is_regular_file(status))
    throw Error(file, "", "the " + std::string(what) + " is not a regular file (a folder, a pipe or a device)");
  const auto size = std::filesystem::file_size(file, ec);
  if (!ec && size > max_bytes)
    throw Error(file, "",
                "the " + std::string(what) + " holds " + std::to_string(size) + " bytes; at most " +
                    std::to_string(max_bytes) + " are read");
  std::ifstream in(file, std::ios::binary);
  if (!in) throw Error(file, "", "cannot read the " + std::string(what));
  std::string text;
  text.reserve(static_cast<std::size_t>(ec ? 0 : size));
  char buffer[65536];
  while (in.read(buffer, sizeof buffer) || in.gcount() > 0) {
    text.append(buffer, static_cast<std::size_t>(in.gcount()));
    if (text.size() > max_bytes)  // grew while being read
      throw Error(file, "", "the " + std::string(what) + " holds more than " + std::to_string(max_bytes) + " bytes");
  }
  return text;
}

void check_nesting(std::string_view text, const std::filesystem::path& file, int max_depth) {
  // Dots count only inside a key: a TOML key before its '=' (a line at the top level, a table
  // header, an inline table's entries), a JSON key before its ':'. A value's decimal points and a
  // JSON array's numbers are never keys, so a document written on one line reads as one on many.
  std::string open;  // the brackets open at this point, innermost last
  int dots = 0, line = 1;
  bool key = true;  // in a key: at the start of a top-level line, after '{' or a '{' entry's ','
  char quote = 0;   // the quote of the string we are in, or 0
  const auto start_key = [&](bool is_key) {
    key = is_key;
    dots = 0;
  };
  for (std::size_t k = 0; k < text.size(); ++k) {
    const char c = text[k];
    if (c == '\n') {
      ++line;
      if (open.empty()) start_key(true);
    }
    if (quote) {
      if (c == '\\' && quote == '"') {
        ++k;  // an escaped character
      } else if (c == quote || c == '\n') {
        quote = 0;
      }
      continue;
    }
    switch (c) {
      case '"':
      case '\'':
        quote = c;
        break;
      case '#':  // a TOML comment runs to the end of the line
        while (k + 1 < text.size() && text[k + 1] != '\n') ++k;
        break;
      case '[':
      case '{':
        if (static_cast<int>(open.size()) >= max_depth)
          throw Error(
              file, std::to_string(line),
              "brackets nest deeper than " + std::to_string(max_depth) + " levels; that is not a scene or tile set");
        open += c;
        if (c == '{')
          start_key(true);
        else if (!key)
          start_key(false);  // an array; a '[' in a key is a TOML table header
        break;
      case ']':
      case '}':
        if (!open.empty()) open.pop_back();
        start_key(false);
        break;
      case ',':
        start_key(!open.empty() && open.back() == '{');
        break;
      case '=':
      case ':':
        start_key(false);
        break;
      case '.':
        if (key && ++dots > max_depth)
          throw Error(
              file, std::to_string(line),
              "a key of more than " + std::to_string(max_depth) + " dotted parts; tables nest at most that deep");
        break;
      default:
        break;
    }
  }
}

}  // namespace wangscape
