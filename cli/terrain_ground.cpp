#include "cli/terrain_ground.h"

#include <charconv>
#include <cmath>
#include <stdexcept>

namespace wangscape::cli {

namespace {
std::optional<double> parse_number(std::string_view text) {
  while (!text.empty() && text.front() == ' ') text.remove_prefix(1);
  while (!text.empty() && text.back() == ' ') text.remove_suffix(1);
  double value = 0;
  const auto result = std::from_chars(text.data(), text.data() + text.size(), value);
  if (result.ec != std::errc() || result.ptr != text.data() + text.size() || !std::isfinite(value)) return std::nullopt;
  return value;
}
}  // namespace

LatLon parse_lat_lon(const std::string& text) {
  const auto comma = text.find(',');
  const auto lat = comma == std::string::npos ? std::nullopt : parse_number(std::string_view(text).substr(0, comma));
  const auto lon = comma == std::string::npos ? std::nullopt : parse_number(std::string_view(text).substr(comma + 1));
  if (!lat || !lon || std::abs(*lat) > 90 || std::abs(*lon) > 180)
    throw std::invalid_argument("origin '" + text +
                                "' is not LAT,LON in WGS 84 degrees (latitude -90..90, longitude -180..180)");
  return {*lat, *lon};
}

}  // namespace wangscape::cli
