// Numbers read from command-line text ("64x48", "-10,5", "0,6300[,1131.5]"), independent of the
// locale: whole strings only, no trailing characters, finite values.
#pragma once

#include <charconv>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace wangscape {

// "<a><separator><b>", both whole numbers of T; false when malformed or out of T's range.
template <typename T>
bool parse_number_pair(const std::string& text, char separator, T& a, T& b) {
  const auto split = text.find(separator);
  if (split == std::string::npos) return false;
  const char* begin = text.data();
  const char* middle = begin + split;
  const char* end = begin + text.size();
  const auto first = std::from_chars(begin, middle, a);
  const auto second = std::from_chars(middle + 1, end, b);
  return first.ec == std::errc() && first.ptr == middle && second.ec == std::errc() && second.ptr == end;
}

// `separator`-separated finite decimal numbers, between min_count and max_count of them; empty
// when the text is not that.
std::optional<std::vector<double>> parse_number_list(const std::string& text, char separator, std::size_t min_count,
                                                     std::size_t max_count);

}  // namespace wangscape
