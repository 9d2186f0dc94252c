// Helpers the exporters share: float32 bounds, one material list for the whole scene,
// BlenderGIS georeference keys, the ground's PNG.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <limits>
#include <memory>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "scene/scene.h"

namespace wangscape {

// Axis-aligned bounds of float32 points, exactly as stored (no widening).
struct Bounds3f {
  std::array<float, 3> min{std::numeric_limits<float>::infinity(), std::numeric_limits<float>::infinity(),
                           std::numeric_limits<float>::infinity()};
  std::array<float, 3> max{-std::numeric_limits<float>::infinity(), -std::numeric_limits<float>::infinity(),
                           -std::numeric_limits<float>::infinity()};
  bool empty() const { return min[0] > max[0]; }
  void extend(const std::array<float, 3>& p) {
    for (int i = 0; i < 3; ++i) {
      if (p[i] < min[i]) min[i] = p[i];
      if (p[i] > max[i]) max[i] = p[i];
    }
  }
};

Bounds3f bounds_of(std::span<const std::array<float, 3>> points);

// The material used for terrain that carries none: dry loam.
Material default_ground_material();

// Every distinct material of the scene once (terrain first, then each model's), and for
// each mesh the scene-wide index of each of its material slots.
struct MaterialTable {
  std::vector<Material> materials;
  std::vector<std::uint32_t> terrain_slots;             // empty if the scene has no terrain
  std::vector<std::vector<std::uint32_t>> model_slots;  // one list per model
};
MaterialTable build_material_table(const Scene& scene);

// Throws Error naming `what` when the mesh's arrays disagree in size or its vertex or
// material indices point outside. (Absent triangle_material means material 0 everywhere.)
void check_mesh(const Mesh& mesh, const std::string& what);

// BlenderGIS scene properties ("SRID", "crs x", "crs y", "latitude", "longitude") found in
// the georeference under the names docs/blender-format.md lists; absent keys are left out.
// Values: SRID a string ("EPSG:32632"), the others numbers.
std::vector<std::pair<std::string, std::string>> blendergis_properties(const Georeference& georeference);

// The PNG of a baked ground, encoded once however many writers of a build ask for it
// (POV-Ray and Blender write it, glTF embeds it). Thread-safe.
std::shared_ptr<const std::string> ground_png(const std::shared_ptr<const GroundBake>& bake);

}  // namespace wangscape
