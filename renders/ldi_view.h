// The real-time view of a scene folder (seed 003 section 5): the folder's Scene (terrain, sun,
// the field's tiling and masks) and its mmap'ed LDI pack, drawn in software per frame:
//  - the tiles `wangscape build` placed (same tiling, same masks, same tile indices), each
//    frustum-culled by its box and sorted back to front;
//  - per tile a level by its projected size (distance scaled by the view's pixels per radian
//    against the pack's) and a direction by the dot product of the view ray with each
//    direction; across a level's last half and near the bisector of two directions the two
//    LDIs are screen-door dithered (an ordered 4 x 4 threshold), so nothing pops;
//  - each LDI warped in McMillan's occlusion-compatible order (pixels far from the eye's
//    epipole first, layers back to front), sheared onto the tile's two terrain triangles,
//    each depth pixel splatted as a square as large as its projected footprint;
//  - the terrain mesh rasterized (perspective-correct), shaded with the sun and sky of
//    renders/shading.h and colored by Scene::ground_texture;
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
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "generator/image.h"
#include "renders/embree_reference.h"
#include "renders/ground_colors.h"
#include "renders/image_compare.h"
#include "renders/ldi_pack.h"
#include "renders/shading.h"
#include "scene/scene.h"

namespace wangscape {

// Where the eye is and where it looks (ENU meters), and its horizontal field of view.
struct ViewCamera {
  std::array<double, 3> position{0, 0, 2};
  std::array<double, 3> target{10, 0, 2};
  double fov_degrees = 50;
};

// The scene folder as the view needs it: the Scene, the pack, the placed tiles with their
// terrain corners, the terrain mesh with its lighting and the far-field colors. Immutable.
class ViewWorld {
 public:
  // Reads DIR/scene.toml (load_scene_folder_config; where its files are not found, relative
  // paths resolve against the data folder, data_root(), as for the default scene) and
  // DIR/tiles.ldi. Throws Error naming the file
  // at fault: a missing folder, scene or pack, a corrupt pack, a pack of another tile set.
  static std::shared_ptr<const ViewWorld> load(const std::filesystem::path& dir, const StageObserver& stage = {});
  // The same from a Scene already made and a pack file (tests).
  ViewWorld(Scene scene, const std::filesystem::path& pack_path, const ShadingSettings& shading = {});

  struct Tiles {                          // structure of arrays, one entry per placed tile, rows south to north
    std::vector<double> x0, y0;           // the tile's south-west corner, meters
    std::vector<std::uint32_t> tile;      // index into the set (and the pack)
    std::vector<std::int32_t> cell;       // index into the tile grid
    std::array<std::vector<float>, 4> h;  // ground height at the corners: SW, SE, NW, NE
    std::vector<float> z_min, z_max;      // of the corners
    std::size_t size() const { return tile.size(); }
  };
  // The terrain mesh in square chunks of about kTerrainChunkTriangles triangles, each with its
  // own copy of its vertices (contiguous), so a frame culls whole chunks by their box and
  // transforms only the vertices of those it draws, with no two tasks writing one vertex.
  struct Terrain {                                        // structure of arrays
    std::vector<float> x, y, z;                           // ENU meters
    std::vector<float> light_r, light_g, light_b;         // sun + sky irradiance (linear) at the vertex
    std::vector<std::array<std::uint32_t, 3>> triangles;  // chunk by chunk
    struct Chunk {
      std::uint32_t first_vertex = 0, vertex_count = 0, first_triangle = 0, triangle_count = 0;
      std::array<float, 3> low{}, high{};  // the box of its vertices, ENU meters
    };
    std::vector<Chunk> chunks;
  };

  const Scene& scene() const { return scene_; }
  const LdiPack& pack() const { return *pack_; }
  const Tiles& tiles() const { return tiles_; }
  const Terrain& terrain() const { return terrain_; }
  double tile_size() const { return tile_size_; }
  // The grid of tile cells over the field's area (-1 where no tile was placed).
  std::int64_t grid_i0() const { return grid_i0_; }
  std::int64_t grid_j0() const { return grid_j0_; }
  int grid_width() const { return grid_width_; }
  int grid_height() const { return grid_height_; }
  const std::vector<std::int32_t>& grid() const { return grid_; }
  // Per (set tile, direction): the linear average color of the coarsest LDI's front flower
  // samples and the share of its front samples that are flowers (not ground).
  const std::vector<std::array<float, 4>>& far_colors() const { return far_; }
  // Beyond the pack's levels, the field goes on as one-layer LDIs (seed 003's future work), per
  // (set tile, direction) and step: step k has 1 / 2^(k+1) of the coarsest level's resolution
  // and is drawn over twice the distance of step k - 1; beyond the last step, the far colors.
  std::uint32_t far_steps() const { return far_steps_; }
  LdiView far_ldi(std::uint32_t tile, std::uint32_t direction, std::uint32_t step) const;
  // The ground's height (meters) at (x, y), or `fallback` off the ground.
  double ground_height(double x, double y, double fallback) const;
  // Linear base color of the ground at (x, y): the baked ground texture (bilinear), or the
  // shading model's ground color without [ground]; the Embree reference's (GroundColors).
  std::array<float, 3> ground_color(double x, double y) const { return ground_colors_.at(x, y); }
  const std::array<float, 3>& sun_direction() const { return sun_; }
  // The light the pack was shaded with (the scene's [ldi] sky rays; the Embree reference of
  // --compare uses it too).
  const ShadingSettings& shading() const { return shading_; }

 private:
  Scene scene_;
  std::unique_ptr<LdiPack> pack_;
  Tiles tiles_;
  Terrain terrain_;
  double tile_size_ = 4;
  std::int64_t grid_i0_ = 0, grid_j0_ = 0;
  int grid_width_ = 0, grid_height_ = 0;
  std::vector<std::int32_t> grid_;
  std::vector<std::array<float, 4>> far_;
  std::uint32_t far_steps_ = 0;
  std::vector<LdiImage> far_ldis_;  // (tile * directions + direction) * far_steps_ + step
  std::array<float, 3> sun_{0, 0, 1};
  ShadingSettings shading_;
  GroundColors ground_colors_;  // of scene_'s bake, shading_'s plain ground
};

inline constexpr double kMinViewDetail = 0.1, kMaxViewDetail = 10;

// What one frame drew.
struct ViewFrameStats {
  double frame_ms = 0;
  // Of it: choosing and culling tiles, warping LDIs, rasterizing the terrain, resolving (sky).
  std::array<double, 4> phase_ms{};
  std::uint64_t depth_pixels = 0;  // depth pixels warped
  std::uint64_t tiles_drawn = 0;   // in the frustum: drawn as LDIs or as far-field color
  std::uint64_t tiles_culled = 0;  // outside the frustum
  // Tiles drawn per level (each at its nearer level when two are dithered); the last entry
  // counts those beyond the last level, drawn as the far-field color.
  std::vector<std::uint64_t> levels;
};

class LdiRenderer {
 public:
  // Throws Error when the size is not 1 .. 16384 per side.
  LdiRenderer(std::shared_ptr<const ViewWorld> world, int width, int height);
  ~LdiRenderer();
  LdiRenderer(const LdiRenderer&) = delete;
  LdiRenderer& operator=(const LdiRenderer&) = delete;

  // Draws one frame into image(). Throws Error for a camera with no direction or a field of
  // view outside (0, 179) degrees.
  const ViewFrameStats& render(const ViewCamera& camera);
  const ImageRgb8& image() const { return image_; }
  // Per pixel of the last frame: true where the sky shows (nothing was drawn), and the camera
  // depth (meters along the view axis; infinity for the sky).
  bool sky_at(int x, int y) const;
  float depth_at(int x, int y) const;
  // Level-of-detail scale: each level is used up to `detail` times its own distance (1: as the
  // pack was built for; 0.5: coarser levels at half the distance, fewer depth pixels, a faster
  // and blockier frame; 2: finer). Throws Error outside kMinViewDetail .. kMaxViewDetail.
  void set_detail(double detail);
  // Draws only the placed tiles whose entry is nonzero (the terrain and sky as always); empty:
  // every tile. For tests and for looking at single tiles.
  void set_tile_mask(std::vector<std::uint8_t> mask) { mask_ = std::move(mask); }
  // The placed-tile indices warped as LDIs in the last frame, back to front.
  const std::vector<std::uint32_t>& draw_order() const { return order_; }
  // Distance (meters) from the last frame's eye to placed tile `t`'s nearest ground point.
  double tile_distance(std::uint32_t t) const;
  int width() const { return image_.width; }
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
};

// ---- what `wangscape view` runs -------------------------------------------------------------

struct ViewRequest {
  std::filesystem::path dir;
  std::optional<std::array<double, 3>> camera;   // E, N, H; H absent (NaN) = head height above the ground
  std::optional<std::array<double, 3>> look_at;  // E, N, H
  std::optional<double> fov_degrees;
  int width = 0, height = 0;  // 0 = the scene's image size
  std::filesystem::path out;  // one offline frame
  bool stats = false, json = false;
  int repeat = 0;                    // frames timed for --stats (0: 200)
  std::filesystem::path path;        // keyframes JSON
  std::filesystem::path frames_dir;  // where the path's frames go
  double path_fps = 24;
  std::string script;          // window: scripted input (docs/viewer.md)
  bool compare = false;        // also ray trace the frame with Embree and compare
  std::filesystem::path diff;  // with compare: the difference image
  int reference_samples = 0;   // with compare: samples per pixel (0: the scene's)
  int threads = 0;             // 0 = all cores
  double detail = 1;           // LdiRenderer::set_detail
  bool quiet = false;
};

// The camera of the request: its flags, or the scene's own camera. Throws Error naming the
// flag at fault (--fov outside (0, 179), a camera off the ground without a height, ...).
ViewCamera view_camera(const ViewWorld& world, const ViewRequest& request);

// Offline frame(s), path playback or the window, as the request says; prints stats to stdout.
// Returns the exit code (0). Throws Error for bad input.
int run_view(const ViewRequest& request);

// The renderer's last frame (drawn from `camera`) against the Embree reference of the same
// camera and size, ray traced with the light the pack was shaded with at `samples_per_pixel`
// (0: the scene's): PSNR, SSIM, holes (sky in the frame where the reference has geometry) and
// the difference image; `reference` holds the reference's own figures (its time).
struct ViewComparison {
  ImageComparison comparison;
  ReferenceStats reference;
};
ViewComparison compare_with_reference(const ViewWorld& world, const LdiRenderer& renderer, const ViewCamera& camera,
                                      int samples_per_pixel);

// Median frame statistics over `frames` renders of one camera.
ViewFrameStats measure_view(LdiRenderer& renderer, const ViewCamera& camera, int frames);
// {"frame_ms": ..., "fps": ..., "depth_pixels": ..., "tiles": {...}, "levels": [...]}
std::string view_stats_json(const ViewFrameStats& stats);

}  // namespace wangscape
