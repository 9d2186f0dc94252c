#include "renders/view/view_world.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"
#include "core/hash.h"
#include "folder/scene_folder.h"
#include "generator/placement.h"
#include "renders/ldi/ldi_scene.h"
#include "renders/trace/field_sky.h"
#include "renders/trace/terrain_shadows.h"
#include "renders/trace/traced_shading.h"
#include "renders/view/view_samples.h"

namespace wangscape {

namespace fs = std::filesystem;
using namespace view_detail;

namespace {

constexpr float kCanopyShare = 0.55f;  // of the prism top: the far field's color comes from samples above it
// Far-field steps after the pack's levels: one-layer LDIs of 1/2, 1/4, ... of the coarsest
// level's resolution, each over twice the distance of the one before.
constexpr std::uint32_t kFarSteps = 5;

// itself), kept where the block's hashed threshold is below their share of the block, so
// that the tile's cover is kept on average. Each sample sits at its block's centre.
// A block's keep threshold in (0, 1): white noise hashed from the block and the LDI (an ordered
// dither is the same in every tile, so its pattern and its seams at the tile's sides repeat with
// the tiles: rows along the tile grid).
float block_threshold(std::uint32_t x, std::uint32_t y, std::uint32_t salt) {
  return unit_float(mix64(mix64(salt) ^ (std::uint64_t(x) << 32 | y))) + 0.5f / 16777216.0f;  // in (0, 1)
}

LdiImage one_layer_ldi(const LdiView& v, int factor) {
  const LdiFrame& f = *v.frame;
  const std::uint32_t salt = (f.tile * 64 + f.direction) * 64 + std::uint32_t(factor);
  LdiImage out;
  out.frame = f;
  out.frame.width = (f.width + std::uint32_t(factor) - 1) / std::uint32_t(factor);
  out.frame.height = (f.height + std::uint32_t(factor) - 1) / std::uint32_t(factor);
  out.frame.pixel_size = f.pixel_size * float(factor);
  const std::uint32_t w = out.frame.width, h = out.frame.height;
  // A block shows one species, the one most of its front samples show (all of them in a field
  // of one species), so that a view can still leave it out where that species does not grow.
  struct Block {
    double r = 0, g = 0, b = 0, depth = 0;
    std::uint32_t flowers = 0, shown = 0;
    std::uint16_t normal = 0;
    std::uint8_t plant = kAnyPlant;
    std::array<std::uint32_t, kPlantSpecies + 1> per_species{};  // the last: kAnyPlant
    int most = 0;                                                // the species most samples show
  };
  std::vector<Block> blocks(std::size_t(w) * h);
  const auto species_of = [](std::uint8_t plant) { return plant == kAnyPlant ? kPlantSpecies : plant >> 5; };
  for_each_front_sample(v, [&](int x, int y, const DepthPixel& front, bool is_ground) {
    if (is_ground) return;
    Block& b = blocks[std::size_t(y / factor) * w + std::uint32_t(x / factor)];
    ++b.flowers;
    ++b.per_species[std::size_t(species_of(front.plant))];
  });
  for (Block& b : blocks)
    b.most = int(std::max_element(b.per_species.begin(), b.per_species.end()) - b.per_species.begin());
  const Luts& lut = luts();
  for_each_front_sample(v, [&](int x, int y, const DepthPixel& front, bool is_ground) {
    if (is_ground) return;
    Block& b = blocks[std::size_t(y / factor) * w + std::uint32_t(x / factor)];
    if (species_of(front.plant) != b.most) return;
    if (b.shown++ == 0) b.plant = front.plant;
    b.r += lut.to_linear[front.r];
    b.g += lut.to_linear[front.g];
    b.b += lut.to_linear[front.b];
    b.depth += front.depth();
    if (b.shown == 1) b.normal = front.normal();
  });
  const double area = double(factor) * double(factor);
  out.row_spans.push_back(0);
  for (std::uint32_t y = 0; y < h; ++y) {
    std::uint32_t first = w, last = 0;
    for (std::uint32_t x = 0; x < w; ++x) {
      const Block& b = blocks[std::size_t(y) * w + x];
      if (b.flowers == 0 || double(b.flowers) / area <= block_threshold(x, y, salt)) continue;
      first = std::min(first, x);
      last = x;
    }
    if (first < w) {
      out.spans.push_back({std::uint16_t(first), std::uint16_t(last - first + 1), std::uint32_t(out.counts.size()),
                           std::uint32_t(out.depth_pixels.size())});
      for (std::uint32_t x = first; x <= last; ++x) {
        const Block& b = blocks[std::size_t(y) * w + x];
        const bool kept = b.flowers > 0 && double(b.flowers) / area > block_threshold(x, y, salt);
        out.counts.push_back(kept ? 1 : 0);
        if (!kept) continue;
        const double n = double(b.shown);
        out.depth_pixels.push_back(DepthPixel::make(lut.encode(float(b.r / n)), lut.encode(float(b.g / n)),
                                                    lut.encode(float(b.b / n)), std::uint16_t(std::lround(b.depth / n)),
                                                    b.normal, b.plant));
      }
    }
    out.row_spans.push_back(std::uint32_t(out.spans.size()));
  }
  out.frame.span_count = std::uint32_t(out.spans.size());
  out.frame.pixel_count = std::uint32_t(out.counts.size());
  out.frame.depth_pixel_count = std::uint32_t(out.depth_pixels.size());
  return out;
}

// How many rank steps of each species' plants grow at (x, y, z): none where its rules forbid it,
// else its density there in steps (the stream keeps a plant where its rank < the density).
// densities: the caller's buffer of rules.size(), filled with every species' at once (the ground
// is read once).
std::array<std::uint8_t, kPlantSpecies> plant_steps(const SpeciesRules& rules, double x, double y, double z,
                                                    std::vector<double>& densities) {
  const std::size_t species = rules.size();
  rules.densities_where_grow(x, y, z, densities);
  std::array<std::uint8_t, kPlantSpecies> steps{};
  for (std::size_t s = 0; s < std::min<std::size_t>(species, kPlantSpecies); ++s)
    steps[s] = std::uint8_t(std::clamp(std::lround(densities[s] * kPlantRankSteps), 0L, long(kPlantRankSteps)));
  return steps;
}

}  // namespace

std::int32_t ViewWorld::placed_tile_at(double x, double y, float& u, float& v) const {
  const double fx = x / tile_size_, fy = y / tile_size_;
  const double cell_x = std::floor(fx), cell_y = std::floor(fy);
  const std::int64_t ci = std::int64_t(cell_x) - grid_i0_, cj = std::int64_t(cell_y) - grid_j0_;
  if (ci < 0 || cj < 0 || ci >= grid_width_ || cj >= grid_height_) return -1;
  u = float(fx - cell_x);
  v = float(fy - cell_y);
  return grid_[std::size_t(cj * grid_width_ + ci)];
}

std::shared_ptr<const ViewWorld> ViewWorld::load(const fs::path& dir, const StageObserver& stage) {
  const SceneFolder folder = SceneFolder::open(dir, SceneFolder::Parts::pack);
  return std::make_shared<const ViewWorld>(
      folder.make_scene(stage), Packs{folder.pack(), folder.steep_pack(), folder.sky_shares(), folder.ground_light()},
      folder.light(), &folder.placed());
}

namespace {
std::shared_ptr<const LdiPack> opened(const fs::path& pack) {
  return pack.empty() ? nullptr : std::make_shared<const LdiPack>(pack);
}
}  // namespace

ViewWorld::ViewWorld(Scene scene, const fs::path& pack_path, const ShadingSettings& shading,
                     const PlacedTiles* placed_tiles, const Prepared& prepared)
    : ViewWorld(std::move(scene),
                Packs{opened(pack_path), opened(prepared.steep_pack), prepared.sky_shares, prepared.ground_light},
                shading, placed_tiles) {}

ViewWorld::ViewWorld(Scene scene, Packs packs, const ShadingSettings& shading_settings, const PlacedTiles* placed_tiles)
    : scene_(std::move(scene)),
      pack_(std::move(packs.pack)),
      steep_pack_(std::move(packs.steep_pack)),
      shading_(shading_settings),
      sun_shading_(with_sun(shading_settings, scene_.sun)),
      ground_colors_(scene_.ground_texture.get(), shading_.ground_color),
      stems_(scene_.models) {
  // The view leaves the wind out: an LDI is a tile's, shared by every place the tile lies, so it
  // cannot lean per plant; the near field and the truth it is compared with stand still with it.
  scene_.wind.reset();
  if (!scene_.field) throw Error("scene '" + scene_.name + "': no field of flowers to view");
  const SceneField& field = *scene_.field;
  const LdiPackInfo& info = pack_->info();
  tile_size_ = field.placement.tile_size;
  if (info.tiles != field.filled.tiles.size() || std::abs(info.tile_size - tile_size_) > 1e-4)
    throw Error(pack_->path(), "",
                "was built for another tile set (" + std::to_string(info.tiles) + " tiles of " +
                    std::to_string(info.tile_size) + " m; the scene has " + std::to_string(field.filled.tiles.size()) +
                    " of " + std::to_string(tile_size_) + " m)");
  if (steep_pack_ && !(steep_pack_->info() == steep_pack_info(info)))
    throw Error(steep_pack_->path(), "",
                "does not hold the steep sets of " + pack_->path().string() + ": rebuild the folder");
  if (!packs.sky_shares.empty()) {
    sky_ = read_sky_shares(packs.sky_shares, scene_);
    std::call_once(sky_once_, [] {});
  }
  // Read before the work below, so that a damaged file is refused at once.
  if (!packs.ground_light.empty())
    ground_light_ = read_ground_light(packs.ground_light, field.filled.tiles.size(), kGroundLightResolution);

  // The tiles placement keeps: the tiling's cells over the area that received a flower, as the
  // build found them (or by a placement pass of our own), with the set's tile at each as the build
  // kept it (or, from a version 1 folder or a placement pass, by running the tiling again).
  const PlacedTiles found = placed_tiles ? PlacedTiles{} : place_tiles(field);
  const PlacedTiles& placed = placed_tiles ? *placed_tiles : found;
  const std::vector<std::uint16_t> tiled =
      placed.set_tiles.empty() ? placed_set_tiles(field, placed) : placed.set_tiles;
  const TileRange range = tile_range(*field.placement.area, tile_size_);
  if (placed.i0 != range.i0 || placed.j0 != range.j0 || placed.width != std::max(0, range.width()) ||
      placed.height != std::max(0, range.height()) || tiled.size() != placed.cells.size())
    throw Error("scene '" + scene_.name + "': the placed tiles' grid is not the field's");
  grid_i0_ = range.i0;
  grid_j0_ = range.j0;
  grid_width_ = placed.width;
  grid_height_ = placed.height;
  grid_.assign(std::size_t(grid_width_) * std::size_t(grid_height_), -1);
  for (std::size_t p = 0; p < placed.cells.size(); ++p) {  // ascending: rows south to north
    const std::uint32_t cell = placed.cells[p];
    const std::int64_t r = cell / std::uint32_t(grid_width_), c = cell % std::uint32_t(grid_width_);
    const double x0 = double(grid_i0_ + c) * tile_size_, y0 = double(grid_j0_ + r) * tile_size_;
    grid_[cell] = std::int32_t(tiles_.size());
    tiles_.x0.push_back(x0);
    tiles_.y0.push_back(y0);
    tiles_.tile.push_back(tiled[p]);
    tiles_.cell.push_back(std::int32_t(cell));
    const double corners[4][2] = {
        {x0, y0}, {x0 + tile_size_, y0}, {x0, y0 + tile_size_}, {x0 + tile_size_, y0 + tile_size_}};
    const double centre = field.ground.height(x0 + tile_size_ / 2, y0 + tile_size_ / 2).value_or(0.0);
    float lo = 1e30f, hi = -1e30f;
    for (int k = 0; k < 4; ++k) {
      const float h = float(field.ground.height(corners[k][0], corners[k][1]).value_or(centre));
      tiles_.h[std::size_t(k)].push_back(h);
      lo = std::min(lo, h);
      hi = std::max(hi, h);
    }
    tiles_.z_min.push_back(lo);
    tiles_.z_max.push_back(hi);
    if (field.species) {
      constexpr int n = Tiles::kPlantCells;
      auto& steps = tiles_.plant_steps.emplace_back();
      std::vector<double> densities(field.species->size());
      for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
          const double x = x0 + (i + 0.5) * tile_size_ / n, y = y0 + (j + 0.5) * tile_size_ / n;
          const auto cell_steps = plant_steps(*field.species, x, y, ground_height(x, y, centre), densities);
          std::copy(cell_steps.begin(), cell_steps.end(), steps.begin() + (j * n + i) * kPlantSpecies);
        }
    }
  }

  // Light as the LDI build's: the scene's sun (scaled by its strength, where the terrain does not
  // shadow it) and the open sky.
  const auto sun = scene_.sun.direction();
  sun_ = {float(sun[0]), float(sun[1]), float(sun[2])};
  const Mesh& mesh = scene_.terrain;
  const std::vector<float> sunlit = terrain_sun_visibility(mesh, sun_);
  std::vector<std::array<float, 3>> light(mesh.positions.size());
  for (std::size_t v = 0; v < mesh.positions.size(); ++v) {
    const std::array<float, 3> n = v < mesh.normals.size() ? mesh.normals[v] : std::array<float, 3>{0, 0, 1};
    const float cos_sun = sunlit[v] * std::max(0.0f, n[0] * sun_[0] + n[1] * sun_[1] + n[2] * sun_[2]);
    light[v] = lit(sun_shading_, {1, 1, 1}, cos_sun, 1);  // the irradiance: a white ground's color
  }
  terrain_ = make_terrain_chunks(mesh, light);
  // A folder built before the ground light was kept: baked as the build bakes it (the same bytes).
  if (packs.ground_light.empty()) ground_light_ = bake_scene_ground_light(scene_, shading_, kGroundLightResolution);

  // The far field: per tile and direction, the coarsest LDI's front flower samples averaged —
  // those in the canopy's upper part: seen from afar at a grazing angle, the tiles in front hide
  // the rest (stems and leaves low down); without any there, all of them.
  const std::uint32_t level = info.levels - 1;
  const float canopy = kCanopyShare * info.prism_top;
  far_.assign(std::size_t(info.tiles) * info.directions, {0, 0, 0, 0});
  const Luts& lut = luts();
  for (std::uint32_t t = 0; t < info.tiles; ++t)
    for (std::uint32_t d = 0; d < info.directions; ++d) {
      const LdiView v = pack_->ldi(t, level, d);
      double sum[3] = {0, 0, 0}, top_sum[3] = {0, 0, 0};
      std::uint64_t flowers = 0, ground = 0, top = 0;
      for_each_front_sample(v, [&](int x, int y, const DepthPixel& front, bool is_ground) {
        if (is_ground) {
          ++ground;
          return;
        }
        ++flowers;
        const double rgb[3] = {lut.to_linear[front.r], lut.to_linear[front.g], lut.to_linear[front.b]};
        for (int c = 0; c < 3; ++c) sum[c] += rgb[c];
        if (v.position(x, y, front)[2] >= canopy) {
          ++top;
          for (int c = 0; c < 3; ++c) top_sum[c] += rgb[c];
        }
      });
      if (flowers == 0) continue;
      auto& out = far_[std::size_t(t) * info.directions + d];
      for (int c = 0; c < 3; ++c)
        out[std::size_t(c)] = float(top ? top_sum[c] / double(top) : sum[c] / double(flowers));
      out[3] = float(double(flowers) / double(flowers + ground));
    }

  // The one-layer far LDIs, while the coarsest level's resolution allows a step.
  while (far_steps_ < kFarSteps && (pack_->ldi(0, level, 0).frame->width >> (far_steps_ + 1)) >= 1) ++far_steps_;
  far_ldis_.reserve(std::size_t(info.tiles) * info.directions * far_steps_);
  for (std::uint32_t t = 0; t < info.tiles; ++t)
    for (std::uint32_t d = 0; d < info.directions; ++d)
      for (std::uint32_t k = 0; k < far_steps_; ++k)
        far_ldis_.push_back(one_layer_ldi(pack_->ldi(t, level, d), 2 << k));
}

LdiView ViewWorld::far_ldi(std::uint32_t tile, std::uint32_t direction, std::uint32_t step) const {
  return far_ldis_[(std::size_t(tile) * pack_->info().directions + direction) * far_steps_ + step].view();
}

void ViewWorld::prepare_steep() const {
  std::call_once(steep_once_, [this] {
    const LdiPackInfo& info = pack_->info();
    const std::size_t sets = steep_elevations().size(), per_set = std::size_t(info.tiles) * info.directions;
    if (!steep_pack_) {
      std::vector<LdiImage> sampled(sets * per_set);
      for (std::uint32_t t = 0; t < info.tiles; ++t)
        for (LdiImage& ldi : build_scene_steep_ldis(scene_, info, shading_, t)) {
          const std::uint32_t set = steep_pack_level(ldi.frame.level);  // (its own inverse)
          sampled[(std::size_t(set) * info.tiles + t) * info.directions + ldi.frame.direction] = std::move(ldi);
        }
      steep_sampled_ = std::move(sampled);
    }
    std::vector<LdiImage> far(sets * per_set * far_steps_);
    for (std::uint32_t set = 0; set < sets; ++set)
      for (std::uint32_t t = 0; t < info.tiles; ++t)
        for (std::uint32_t d = 0; d < info.directions; ++d) {
          const std::size_t at = (std::size_t(set) * info.tiles + t) * info.directions + d;
          for (std::uint32_t k = 0; k < far_steps_; ++k)
            far[at * far_steps_ + k] = one_layer_ldi(steep_ldi(set, t, d, 0), 2 << k);
        }
    steep_far_ = std::move(far);
  });
}

// From above, where a pixel holds the tops of a few flowers, the coarsest level's resolution
// stood in for finer levels and broke the heads into blocks (25 m up, SSIM against the truth at
// 1280 x 720: 0.498 at the coarsest level's 64 pixels per tile, 0.519 at the finest stood-in
// level's 89, where the exact one-sample image scores 0.585; finer still, 0.531 at 111 and 0.550
// at 148; at 640 x 360 0.444 and 0.470, exact 0.454): steep_resolution() (renders/ldi/ldi_scene.h).
LdiView ViewWorld::steep_ldi(std::uint32_t set, std::uint32_t tile, std::uint32_t direction, std::uint32_t step) const {
  const LdiPackInfo& info = pack_->info();
  const std::size_t at = (std::size_t(set) * info.tiles + tile) * info.directions + direction;
  if (step > 0) return steep_far_[at * far_steps_ + step - 1].view();
  return steep_pack_ ? steep_pack_->ldi(tile, steep_pack_level(set), direction) : steep_sampled_[at].view();
}

const SceneTracer::SkyShares& ViewWorld::sky_shares() const {
  std::call_once(sky_once_, [this] { sky_ = bake_field_sky(scene_, sun_shading_); });
  return sky_;
}

double ViewWorld::ground_height(double x, double y, double fallback) const {
  return scene_.field->ground.height(x, y).value_or(fallback);
}

}  // namespace wangscape
