// The field beyond the camera-aware far distance: no instances, but the ground bake carries the
// flowers' color and coverage. Each tile of the filled set has its flowers splatted from above
// (each model's top-down footprint, turned and scaled as placement turns and scales it) into a
// small image with a mip chain. A flower's color is the mean of what the camera sees of it:
// the model rasterized along the view direction at its yaw, lit by the sun, relative to the
// flat ground's light (the bake is lit again as ground). The bake samples the splats through
// the field's own tiling where the masks let flowers grow, and mixes them over the terrain's
// look by the coverage seen along the view ray (a canopy seen at a grazing angle hides more of
// the ground than from above).
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "scene/ground_look.h"
#include "templates/mesh.h"

namespace wangscape {

struct SceneField;
struct Sun;
class CameraView;

// Linear RGB and the fraction of ground covered.
struct FieldSplat {
  float r = 0, g = 0, b = 0, coverage = 0;
};

class FieldTexture {
 public:
  // `models`: the full variants the tile points index; `view_direction`: unit ENU vector from
  // the camera towards the far field; `texels`: per tile side (power of two).
  FieldTexture(const SceneField& field, const std::vector<Mesh>& models, const std::array<double, 3>& view_direction,
               const Sun& sun, int texels = 16);
  // Tile `tile` at tile-local (u, v) in [0, 1), averaged over about `footprint` tile sides.
  FieldSplat sample(std::uint32_t tile, double u, double v, double footprint) const;
  // The mean over every tile (what the field looks like from very far).
  FieldSplat mean() const;

 private:
  int texels_ = 16;
  // levels_[l][tile] holds (texels >> l)^2 splats, row-major, v = 0 first.
  std::vector<std::vector<std::vector<FieldSplat>>> levels_;
};

// Mixes the field texture into `bake` where the ground is farther than the view's far distance
// (fading in over its last tenth) and the masks let flowers grow. Rows in parallel; the same
// bytes on any thread count.
void paint_far_field(GroundBake& bake, const SceneField& field, const FieldTexture& texture, const CameraView& view);

}  // namespace wangscape
