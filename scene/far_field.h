// The field beyond the camera-aware far distance: no instances, but the ground bake carries what
// the flowers show from the camera. What they show is rendered once per build: a square of the
// real field (the set's tiles, every flower turned and scaled as placement does, the proxies
// when there are some) is rasterized from the sun, for its shadows, and along the view at
// grazing angles (sines 0.05 to 0.8), where the flowers in front hide the stems and the ground;
// each look is the share of rays the canopy stops, and the colors of its yellow (petals) and of
// the rest, lit by the one shading model relative to the flat ground's light (the bake is lit
// again as ground). Painting mixes the look for each bake pixel's sine over the terrain's look,
// each pixel showing the yellow or the rest as often as the canopy does (the bake is far coarser
// than a head): the band keeps the field's mean color and its specks of yellow. Each tile's
// flowers splatted from above (their top-down footprints, with a mip chain) say where the field
// is denser or sparser, and the masks where it grows.
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

// Linear RGB (relative to the light of flat ground in the open) and the fraction of the ground
// it covers.
struct FieldSplat {
  float r = 0, g = 0, b = 0, coverage = 0;
};

// The canopy seen from afar along one grazing ray: the colors of the yellow it shows (petals)
// and of the rest (leaves, stems, disks, shadows), each with its share of what the rays meet
// (coverage: yellow's + rest's = 1), and the share of rays stopped before the ground.
struct CanopyLook {
  FieldSplat yellow, rest;
  float coverage = 0;
  FieldSplat mean() const;  // the two mixed by their shares; coverage: the rays stopped
};

class FieldTexture {
 public:
  // `models`: what stands beyond `far` in the tile points' variant order (the proxies when the
  // scene has them: what a render with proxies to the horizon shows); `view_direction`: unit ENU
  // vector from the camera towards the far field; `texels`: per tile side (power of two).
  FieldTexture(const SceneField& field, const std::vector<Mesh>& models, const std::array<double, 3>& view_direction,
               const Sun& sun, int texels = 16);
  // The top-down coverage of tile `tile` at tile-local (u, v) in [0, 1), averaged over about
  // `footprint` tile sides.
  float coverage(std::uint32_t tile, double u, double v, double footprint) const;
  // The same for the points of species `species` only ([[species]]: SceneField::species).
  float species_coverage(std::size_t species, std::uint32_t tile, double u, double v, double footprint) const;
  // The mean top-down coverage over every tile.
  float mean_coverage() const { return mean_coverage_; }
  // What the field shows along a view ray `sine` above the ground (0.05 .. 0.8; clamped): the
  // flowers the rays meet, lit and shadowed by the sun, rendered from a square of the field.
  CanopyLook look(double sine) const;

  // The sines at which the canopy is rendered (look() interpolates between them).
  static constexpr std::array<double, 5> kLookSines{0.05, 0.1, 0.2, 0.4, 0.8};

 private:
  int texels_ = 16;
  // levels_[l][tile] holds (texels >> l)^2 coverages, row-major, v = 0 first.
  std::vector<std::vector<std::vector<float>>> levels_;
  std::vector<std::vector<std::vector<std::vector<float>>>> species_levels_;  // per species, as levels_
  float coverage_in(const std::vector<std::vector<std::vector<float>>>& levels, std::uint32_t tile, double u, double v,
                    double footprint) const;
  float mean_coverage_ = 0;
  std::array<CanopyLook, kLookSines.size()> looks_{};
};

// Mixes the field texture into `bake` where the ground is farther than the view's far distance
// (fading in over its last tenth) and the masks let flowers grow. Rows in parallel; the same
// bytes on any thread count.
void paint_far_field(GroundBake& bake, const SceneField& field, const FieldTexture& texture, const CameraView& view);

}  // namespace wangscape
