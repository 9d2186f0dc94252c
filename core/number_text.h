// Numbers to and from text, independent of the locale (std::to_chars, std::from_chars: the "C"
// locale's format, always). Reading: command-line text ("64x48", "-10,5", "0,6300[,1131.5]"),
// whole strings only, no trailing characters, finite values. Writing: the shortest text that
// reads back as the same value, fixed decimals, or significant digits. Thread safe.
#pragma once

#include <charconv>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace wangscape {

// ---- writing ----------------------------------------------------------------------------------

// Appends the shortest text that reads back as exactly `value` (an integer or a float or double:
// "42", "0.1", "1e+300", "-0", "inf", "nan").
template <typename T>
void append_number(std::string& out, T value) {
  char text[64];
  out.append(text, std::to_chars(text, text + sizeof text, value).ptr);
}

// The shortest text that reads back as exactly `value`, as append_number writes it.
template <typename T>
std::string number_text(T value) {
  std::string out;
  append_number(out, value);
  return out;
}

// `value` with exactly `decimals` digits after the point, correctly rounded ("12.50", "-0.0");
// decimals 0 to 30.
std::string fixed_text(double value, int decimals);

// `value` with at most `digits` significant digits, as printf's %g writes it ("1200", "0.5",
// "1.5e+07"); digits 1 to 30.
std::string significant_text(double value, int digits);

// A size in bytes for people, in decimal units with three significant digits: "812 B",
// "4.5 kB", "61.2 MB", "3.08 GB", "1.2 TB".
std::string byte_text(double bytes);

// ---- reading ----------------------------------------------------------------------------------

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
