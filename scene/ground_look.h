// The ground's look ([ground] of the scene file): the one shading model of the ground, so
// every output shows the same ground. POV-Ray, Blender and glTF get it baked into an image
// over the terrain (bake_ground, once per build, in make_scene); the Embree reference and the
// LDI view are meant to call color_at per sample.
//
// Materials by height and slope (meadow soil, pumice, rock, snow), each a color ramp over the
// turbulence of one unbounded hashed noise tiling (generator/noise_tiles.h); band borders are
// bent by the same noise so they never run along a contour line. A quilted texture tiling
// (generator/texture_tiles.h, hashed corner-2 tiles of one or two exemplars) either replaces
// the materials ("texture") or adds its detail over them ("both"). With exemplar2_above, the
// tiles are corner-4 and each vertex's color is 2 * (a hashed bit) + (its mark: 1 where the
// terrain at the vertex is above that height): the texture changes from one exemplar to the
// other along the contour (Cohen 2003, section 3.5) and stays stochastic on either side.
#pragma once

#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <vector>

#include "core/extent.h"
#include "generator/image.h"
#include "generator/noise_tiles.h"
#include "generator/texture_tiles.h"
#include "generator/tiling.h"
#include "scene/scene_file.h"

namespace wangscape {

class SceneGround;

// sRGB-encoded color, each channel in [0, 1] (what an 8-bit image stores).
struct GroundColor {
  float r = 0, g = 0, b = 0;
};

class GroundLook {
 public:
  // The terrain height at ENU (x, y) meters, empty off the terrain; thread-safe.
  using HeightAt = std::function<std::optional<double>(double x, double y)>;

  // exemplars: the images the config's exemplar (and exemplar2) name, already read; unused
  // for look = "materials". height_at: where exemplar2_above reads the terrain (required with
  // it). Throws Error (from the tile generators) when they are too small.
  GroundLook(const GroundConfig& config, const std::vector<ImageRgb8>& exemplars, HeightAt height_at = {});

  const GroundConfig& config() const { return config_; }
  // The texture tiles, or nullptr for look = "materials".
  const TextureTileSet* texture_tiles() const { return texture_ ? &*texture_ : nullptr; }

  // The ground's color at ENU (x, y) meters where the ground is `height` meters high and
  // `slope_degrees` steep. O(1), const, thread-safe, allocation-free.
  GroundColor color_at(double x, double y, double height, double slope_degrees) const;

 private:
  GroundColor materials_at(double x, double y, double height, double slope_degrees) const;
  GroundColor texture_at(double x, double y) const;
  std::uint32_t texture_tile(std::int64_t i, std::int64_t j) const;

  GroundConfig config_;
  NoiseField noise_;
  std::optional<TextureTileSet> texture_;
  std::optional<HashedTiling> texture_tiling_;
  HeightAt height_at_;
  float texture_mean_luminance_ = 1;
};

// templates/exemplars/NAME.png for a shipped exemplar's name (no '/' or '.': "meadow",
// "pumice"), or an empty path when `name` looks like a file. Throws Error for an unknown name.
std::filesystem::path shipped_exemplar(const std::string& name);

// The exemplar images a [ground] section names: a shipped name ("meadow", "pumice":
// templates/exemplars/NAME.png) or an image file. Throws the config's Error at the key.
std::vector<ImageRgb8> load_ground_exemplars(const SceneConfig& config);

// The look baked over the ground: pixel centres, north at the top.
struct GroundBake {
  ImageRgb8 image;
  Extent extent;  // ENU meters the image covers
};

// Bakes `look` over ground.extent() with `pixels` along the longer side (the other side in
// proportion, >= 1). Rows in parallel (TBB); the same bytes on any thread count.
GroundBake bake_ground(const GroundLook& look, const SceneGround& ground, int pixels);

}  // namespace wangscape
