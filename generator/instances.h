// Instances: flowers (or any model) placed in the world, as structure-of-arrays batches.
// Placement produces them batch by batch in a spatially coherent order; nothing holds the
// instances of a whole terrain at once.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace wangscape {

struct InstanceBatch {
  std::vector<float> x, y, z;          // ENU meters; z is the ground height at (x, y)
  std::vector<float> yaw;              // radians, counter-clockwise about +z (up) from +x (east)
  std::vector<float> scale;            // uniform scale factor, 1 = the model as built
  std::vector<std::uint16_t> variant;  // model variant 0..V-1
  std::vector<std::uint32_t> tile;     // index into the tile set's tiles
  std::vector<float> rank;             // the point's progressive order in [0, 1) (TilePoint::rank); 0 if hand-made

  std::size_t size() const { return x.size(); }
  bool empty() const { return x.empty(); }
  void clear();
  void reserve(std::size_t n);
  void push_back(float px, float py, float pz, float pyaw, float pscale, std::uint16_t pvariant, std::uint32_t ptile,
                 float prank = 0.0f);
};

}  // namespace wangscape
