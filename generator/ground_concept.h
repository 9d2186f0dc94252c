// The ground that placement stands instances on, as a concept, so generator/ never
// needs to know about DEMs: terrain/ provides a DEM-backed ground, FlatGround is a plane.
// Coordinates are local east-north-up meters (x east, y north, z up).
#pragma once

#include <array>
#include <concepts>
#include <optional>

#include "core/extent.h"

namespace wangscape {

// What placement asks of a ground. All calls must be thread-safe (const, no caches).
//  extent():          the area that has ground, ENU meters
//  height(x, y):      ground height in meters, nullopt outside or where there is no data
//  slope_degrees(x,y): angle between the ground normal and up, degrees; nullopt where no data
template <class G>
concept Ground = requires(const G& g, double x, double y) {
  { g.extent() } -> std::convertible_to<Extent>;
  { g.height(x, y) } -> std::convertible_to<std::optional<double>>;
  { g.slope_degrees(x, y) } -> std::convertible_to<std::optional<double>>;
};

// A flat plane at height z over an extent.
struct FlatGround {
  Extent area;
  double z = 0.0;
  Extent extent() const { return area; }
  std::optional<double> height(double x, double y) const {
    return area.contains(x, y) ? std::optional<double>(z) : std::nullopt;
  }
  std::optional<double> slope_degrees(double x, double y) const {
    return area.contains(x, y) ? std::optional<double>(0.0) : std::nullopt;
  }
};
static_assert(Ground<FlatGround>);

}  // namespace wangscape
