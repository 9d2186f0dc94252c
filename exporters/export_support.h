// Helpers the exporters share: float32 bounds, one material list for the whole scene,
// BlenderGIS georeference keys, the ground's PNG.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <limits>
#include <memory>
#include <mutex>
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

// The material used for terrain that carries none: the one shading model's plain ground
// (ShadingSettings::ground_color), as the Embree reference and the view show it.
Material default_ground_material();

// Every distinct material of the scene once (terrain first, then each model's), and for
// each mesh the scene-wide index of each of its material slots.
struct MaterialTable {
  std::vector<Material> materials;
  std::vector<std::uint32_t> terrain_slots;             // empty if the scene has no terrain
  std::vector<std::vector<std::uint32_t>> model_slots;  // one list per model
};
MaterialTable build_material_table(const Scene& scene);

// A material's image as the exporters write it (POV-Ray and Blender read the file beside the
// scene, glTF holds the same bytes), so that every engine draws what the Embree reference does:
// the texels times the base colour (sRGB-encoded again), alpha cut to 0 or 255 at the material's
// cutoff (255 everywhere without one). `file`: a name for the folder ("map_leaf_card.png").
struct MaterialTexture {
  std::string file;  // empty: the material maps no image
  std::string png;   // the PNG's bytes
};
// One per material of the table, in its order; names are unique within the table.
std::vector<MaterialTexture> material_textures(const MaterialTable& table);

// Throws Error naming `what` when the mesh's arrays disagree in size or its vertex or
// material indices point outside. (Absent triangle_material means material 0 everywhere.)
void check_mesh(const Mesh& mesh, const std::string& what);

// BlenderGIS scene properties ("SRID", "crs x", "crs y", "latitude", "longitude") found in
// the georeference under the names docs/blender-format.md lists; absent keys are left out.
// Values: SRID a string ("EPSG:32632"), the others numbers.
std::vector<std::pair<std::string, std::string>> blendergis_properties(const Georeference& georeference);

// A baked ground encoded as PNG once for all the writers of one build (POV-Ray and Blender write
// it, glTF embeds it: the same bytes). The build (folder/scene_folder.h, its writers' stage) owns one and hands it to
// each writer in its options; a writer made alone makes its own. Thread-safe.
class EncodedGround {
 public:
  explicit EncodedGround(std::shared_ptr<const GroundBake> bake) : bake_(std::move(bake)) {}
  // The PNG bytes, encoded on the first call; the bake must not be null.
  const std::string& png() const;

 private:
  std::shared_ptr<const GroundBake> bake_;
  mutable std::once_flag encoded_;
  mutable std::string png_;
};

// `given` (the build's), or a new EncodedGround of scene.ground_texture when none was given.
std::shared_ptr<const EncodedGround> encoded_ground(const Scene& scene, std::shared_ptr<const EncodedGround> given);

}  // namespace wangscape
