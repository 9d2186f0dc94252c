// The terrain as a triangle mesh in the scene's ENU frame, for exporters: one vertex per
// DEM sample (or per every k-th sample, to meet a vertex budget), no-data skipped.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

#include "terrain/terrain.h"

namespace wangscape {

struct TerrainMesh {
  std::vector<std::array<float, 3>> positions;          // ENU meters, z = orthometric height
  std::vector<std::array<float, 3>> normals;            // unit, z > 0
  std::vector<std::array<std::uint32_t, 3>> triangles;  // counter-clockwise seen from +z
  int stride = 1;                                       // DEM samples per mesh vertex step
};

struct TerrainMeshOptions {
  std::size_t max_vertices = 0;  // 0 = no limit (every DEM sample)
  std::optional<Extent> crop;    // keep only samples inside, ENU meters
};

// Vertices stand on DEM samples (every `stride`-th column and row, plus the last ones),
// at their exact ENU positions; normals come from the neighbouring vertices. A grid quad
// becomes two triangles when its four corners have data, one when three do. Throws
// Error if the crop leaves no triangle or the budget is below 3 vertices.
TerrainMesh make_terrain_mesh(const Terrain& terrain, const TerrainMeshOptions& options = {});

}  // namespace wangscape
