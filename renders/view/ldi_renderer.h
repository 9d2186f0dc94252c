// The real-time view of a scene folder (seed 003 section 5): the folder's Scene (terrain, sun,
// the field's tiling and masks) and its mmap'ed LDI pack, drawn in software per frame:
//  - the tiles `wangscape build` placed (same tiling, same masks, same tile indices), each
//    frustum-culled by its box and sorted back to front;
//  - per tile a level by its projected size (distance scaled by the view's pixels per radian
//    against the pack's) and a direction by the dot product of the view ray with each
//    direction; across a level's last half and near the bisector of two directions the two
//    LDIs are screen-door dithered (an ordered 4 x 4 threshold), so nothing pops;
//  - each LDI warped (renders/view/ldi_warp.h), sheared onto the tile's two terrain triangles,
//    each depth pixel splatted as a square as large as its projected footprint;
//  - the terrain mesh rasterized (perspective-correct), shaded with the sun and sky of
//    renders/trace/traced_shading.h and colored by Scene::ground_texture;
//  - beyond the last level, one-layer LDIs made once from the coarsest level at 1/2, 1/4, ...
//    of its resolution, warped like the others over doubling distances, so the heads stand out
//    to the horizon; beyond those, each tile's directional average color over the ground;
//  - a software z-buffer: depth and color packed in 64 bits, the smallest kept (tiles warped
//    into one buffer per thread, merged; terrain triangles with an atomic minimum), so tiles and
//    triangles run in parallel (TBB) and the frame is the same on any thread count;
//  - the sky where nothing was drawn.
// Buffers are sized once per renderer: a frame allocates nothing.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <vector>

#include "generator/image.h"
#include "renders/view/view_world.h"

namespace wangscape {

inline constexpr double kMinViewDetail = 0.1, kMaxViewDetail = 10;
// The near field (LdiRenderer::set_near_field): at most this far (meters), and the distance
// `wangscape view` uses unless told (docs/viewer-design.md says how it was chosen).
inline constexpr double kMaxNearField = 100;
inline constexpr double kDefaultNearField = 8;
// The terrain's level of detail (LdiRenderer::set_terrain_error): the most its chunks' levels may
// stray from the fine mesh, in pixels, by default.
inline constexpr double kDefaultTerrainError = 0.5;

// What one frame drew.
struct ViewFrameStats {
  double frame_ms = 0;
  // Of it: choosing and culling tiles, warping LDIs, rasterizing the terrain, ray tracing the
  // near field, resolving (sky).
  std::array<double, 5> phase_ms{};
  std::uint64_t depth_pixels = 0;       // depth pixels warped
  std::uint64_t tiles_drawn = 0;        // in the frustum: drawn as LDIs or as far-field color
  std::uint64_t tiles_culled = 0;       // outside the frustum
  std::uint64_t steep_tiles = 0;        // of those drawn, from the world's steep sets (seen from above)
  std::uint64_t near_tiles = 0;         // in the frustum or not, within the near field: ray traced
  std::uint64_t near_rays = 0;          // rays the near field cast (primary and shadow)
  std::uint64_t tiles_occluded = 0;     // LDI tiles not warped: wholly behind the near field
  bool ray_cast = false;                // the frame beyond the near field was ray cast (ViewEngine)
  std::uint64_t terrain_triangles = 0;  // terrain triangles of the chunks drawn, at their levels of detail
  std::uint64_t terrain_pixels = 0;     // pixels the terrain's triangles tested (inside or not)
  // Tiles drawn per level (each at its nearer level when two are dithered); the last entry
  // counts those beyond the last level, drawn as the far-field color.
  std::vector<std::uint64_t> levels;

  // Adds another sample's time and work (times, depth pixels, rays, terrain triangles and pixels);
  // the tile counts stay this sample's.
  void add_work(const ViewFrameStats& sample);
};

class SceneTracer;

enum class ViewEngine {
  ldi,        // LDIs beyond the near field, the terrain rasterized
  embree,     // the whole frame ray cast (the near field's rays and shading over every pixel, against
              // every flower of the scene): the anchor the LDI frame is measured against
  automatic,  // per frame: the whole frame ray cast when the near field's flowers and ground stop at
              // least kRayCastShare of a coarse grid of its rays (the eye inside the field, where
              // rays end soon and LDIs are slower than rays: docs/viewer-design.md), else as ldi
};
inline constexpr int kMaxViewSamples = 1024;

// How frames are drawn, as `view`'s flags give it: the offline frames and the window apply the
// same settings (LdiRenderer::apply).
struct ViewSettings {
  double detail = 1;                          // set_detail
  double near_field = kDefaultNearField;      // set_near_field
  ViewEngine engine = ViewEngine::automatic;  // set_engine
  int samples = 1;                            // set_samples
};
// The share of the near field's rays that must stop for ViewEngine::automatic to ray cast.
inline constexpr double kRayCastShare = 0.5;

class LdiRenderer {
 public:
  // Throws Error when the size is not 1 .. 16384 per side.
  LdiRenderer(std::shared_ptr<const ViewWorld> world, int width, int height);
  ~LdiRenderer();
  LdiRenderer(const LdiRenderer&) = delete;
  LdiRenderer& operator=(const LdiRenderer&) = delete;

  // Draws one frame into image(). Throws Error for a camera with no direction or a field of
  // view outside (0, 179] degrees (core/vecmath.h check_field_of_view).
  const ViewFrameStats& render(const Camera& camera);
  const ImageRgb8& image() const { return image_; }
  // Per pixel of the last frame: true where the sky shows (nothing was drawn), and the camera
  // depth (meters along the view axis; infinity for the sky).
  bool sky_at(int x, int y) const;
  float depth_at(int x, int y) const;
  // Level-of-detail scale: each level is used up to `detail` times its own distance (1: as the
  // pack was built for; 0.5: coarser levels at half the distance, fewer depth pixels, a faster
  // and blockier frame; 2: finer). Throws Error outside kMinViewDetail .. kMaxViewDetail.
  void set_detail(double detail);
  // The near field: the tiles within `meters` of the eye are not drawn from their LDIs but ray
  // traced from their real flowers (Embree, one ray through each pixel's centre, shaded by the one
  // shading model with the pack's sun and its shadow ray, under the open sky: no sky rays),
  // over the LDIs and the terrain beyond. 0: LDIs everywhere. Throws Error outside
  // 0 .. kMaxNearField.
  void set_near_field(double meters);
  // The terrain's level of detail: each chunk drawn at the coarsest level whose error (how far it
  // strays from the fine mesh, meters) projects to at most `pixels` at the chunk's nearest
  // point; 0: the fine mesh everywhere (large errors are for looking at the levels). Throws
  // Error outside 0 .. 64.
  void set_terrain_error(double pixels);
  // How frames are drawn (ViewEngine); the first frame that ray casts beyond the near field
  // builds the whole scene's Embree BVH.
  void set_engine(ViewEngine engine) { engine_ = engine; }
  // Samples per pixel: render() draws this many frames, each moved by a sub-pixel offset (a
  // low-discrepancy sequence whose first is the pixel centres), and averages them in linear light
  // (anti-aliased offline frames); the statistics sum the samples' time and work (add_work) and
  // count the first sample's tiles. Throws Error outside
  // 1 .. kMaxViewSamples.
  void set_samples(int samples);
  int samples() const { return samples_; }
  // All four of the above.
  void apply(const ViewSettings& settings);
  // Frames of another size from now on (a resized window); the Embree scenes are kept. Throws
  // Error when the size is not 1 .. 16384 per side.
  void resize(int width, int height);
  // Draws only the placed tiles whose entry is nonzero (the terrain and sky as always); empty:
  // every tile. For tests and for looking at single tiles.
  void set_tile_mask(std::vector<std::uint8_t> mask) { mask_ = std::move(mask); }
  // The placed-tile indices warped as LDIs in the last frame, back to front.
  const std::vector<std::uint32_t>& draw_order() const { return order_; }
  // Distance (meters) from the last frame's eye to placed tile `t`'s nearest ground point.
  double tile_distance(std::uint32_t t) const;
  // What the last frame drew placed tile `t` from: its level (the nearer when two are dithered;
  // from the pack's levels on, the far steps) and its LDIs' elevation set (0: the pack's; k: the
  // world's steep set k - 1, ViewWorld::steep_elevations).
  struct TileChoice {
    std::uint32_t level = 0, steep_set = 0;
  };
  TileChoice tile_choice(std::uint32_t t) const;
  int width() const { return image_.width; }
  // The whole scene in Embree (the terrain and every flower, the models' sky share baked), as
  // ViewEngine::embree ray casts it; built on the first call (or the first ray-cast frame), kept.
  const SceneTracer& whole_scene();
  const std::shared_ptr<const ViewWorld>& world() const { return world_; }
  int height() const { return image_.height; }

 private:
  struct Impl;
  std::shared_ptr<const ViewWorld> world_;
  std::unique_ptr<Impl> impl_;
  ImageRgb8 image_;
  std::vector<std::uint32_t> order_;
  std::vector<std::uint8_t> mask_;
  ViewFrameStats stats_;
  double detail_ = 1;
  double near_field_ = 0;
  double terrain_error_ = kDefaultTerrainError;
  ViewEngine engine_ = ViewEngine::ldi;
  int samples_ = 1;
  std::array<float, 2> subpixel_{0, 0};  // the sample's offset, pixels
  const ViewFrameStats& render_sample(const Camera& camera);
  // The frame's named steps (docs/viewer-design.md, "What a frame does"), in the order render() runs them.
  void begin_frame(const Camera& camera);
  void choose_tiles();
  void warp_tiles();
  void choose_chunks();
  void draw_terrain();
  void resolve();
  std::uint64_t trace_near_field();
  std::uint64_t ray_cast_frame();
  double place_near_field();
  double near_share();
  std::uint64_t cast_rays(const SceneTracer& tracer, double reach);
  std::uint64_t cull_occluded_tiles();
};

}  // namespace wangscape
