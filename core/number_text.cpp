#include "core/number_text.h"

#include <cmath>

namespace wangscape {

std::string fixed_text(double value, int decimals) {
  char text[512];  // 1e308 in full and 30 decimals
  return std::string(text, std::to_chars(text, text + sizeof text, value, std::chars_format::fixed, decimals).ptr);
}

std::string significant_text(double value, int digits) {
  char text[64];
  return std::string(text, std::to_chars(text, text + sizeof text, value, std::chars_format::general, digits).ptr);
}

std::string byte_text(double bytes) {
  static const char* const units[] = {"B", "kB", "MB", "GB", "TB", "PB"};
  int unit = 0;
  while (unit < 5 && std::abs(bytes) >= 999.5) {
    bytes /= 1000;
    ++unit;
  }
  // Past 999 PB: whole petabytes, never an exponent.
  return (unit == 0 || bytes >= 999.5 ? fixed_text(bytes, 0) : significant_text(bytes, 3)) + " " + units[unit];
}

std::optional<std::vector<double>> parse_number_list(const std::string& text, char separator, std::size_t min_count,
                                                     std::size_t max_count) {
  std::vector<double> values;
  const char* p = text.data();
  const char* const end = p + text.size();
  while (true) {
    const char* stop = p;
    while (stop != end && *stop != separator) ++stop;
    double v = 0;
    const auto parsed = std::from_chars(p, stop, v);  // the "C" locale's format, always
    if (parsed.ec != std::errc() || parsed.ptr != stop || !std::isfinite(v)) return std::nullopt;
    values.push_back(v);
    if (values.size() > max_count) return std::nullopt;
    if (stop == end) break;
    p = stop + 1;
  }
  if (values.size() < min_count) return std::nullopt;
  return values;
}

}  // namespace wangscape
