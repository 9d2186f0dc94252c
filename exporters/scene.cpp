#include "exporters/scene.h"

#include <cmath>
#include <numbers>

namespace wangscape {

std::array<double, 3> Sun::direction() const {
  const double az = azimuth_degrees * std::numbers::pi / 180.0;
  const double el = elevation_degrees * std::numbers::pi / 180.0;
  // Compass azimuth: 0 = north (+y), 90 = east (+x).
  return {std::sin(az) * std::cos(el), std::cos(az) * std::cos(el), std::sin(el)};
}

}  // namespace wangscape
