// The one rectangle type for areas of the ground: an axis-aligned rectangle in local
// east-north-up meters (x east, y north). Placement, terrain, masks and the scene share it.
#pragma once

namespace wangscape {

struct Extent {
  double min_x = 0, min_y = 0, max_x = 0, max_y = 0;  // meters
  double width() const { return max_x - min_x; }
  double height() const { return max_y - min_y; }
  bool contains(double x, double y) const { return x >= min_x && x <= max_x && y >= min_y && y <= max_y; }
  bool empty() const { return !(width() > 0 && height() > 0); }
  bool operator==(const Extent&) const = default;
  // The overlap of two rectangles (empty() when they do not overlap).
  Extent intersected(const Extent& o) const {
    return {min_x > o.min_x ? min_x : o.min_x, min_y > o.min_y ? min_y : o.min_y, max_x < o.max_x ? max_x : o.max_x,
            max_y < o.max_y ? max_y : o.max_y};
  }
};

}  // namespace wangscape
