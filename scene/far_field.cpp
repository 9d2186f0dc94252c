#include "scene/far_field.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <numbers>

#include "core/color.h"
#include "core/hash.h"
#include "core/vecmath.h"
#include "generator/tiling.h"
#include "scene/camera_view.h"
#include "scene/scene.h"
#include "scene/shading_light.h"

namespace wangscape {

namespace {

// For an image seen from afar: the mean linear RGB of the texels whose alpha is at least
// `cutoff` (0: all), and the share of texels that are.
std::array<float, 4> covered_mean(const TextureImage& image, float cutoff) {
  double sum[3] = {0, 0, 0};
  std::size_t covered = 0;
  const std::size_t texels = image.rgba.size() / 4;
  for (std::size_t i = 0; i < texels; ++i) {
    if (float(image.rgba[i * 4 + 3]) / 255.0f < cutoff) continue;
    for (std::size_t c = 0; c < 3; ++c) sum[c] += srgb8_to_linear(image.rgba[i * 4 + c]);
    ++covered;
  }
  if (covered == 0) return {0, 0, 0, 0};
  return {float(sum[0] / double(covered)), float(sum[1] / double(covered)), float(sum[2] / double(covered)),
          float(double(covered) / double(texels))};
}

// A model seen from straight above: per cell of a square grid over its reach, whether it
// covers the ground there.
struct TopView {
  double half = 0;  // the grid spans [-half, half]^2 meters, model space
  int cells = 0;
  std::vector<std::uint8_t> cell;  // 1 where covered
};

TopView top_view(const Mesh& mesh, int cells) {
  TopView view;
  view.cells = cells;
  for (const auto& p : mesh.positions)
    view.half = std::max({view.half, double(std::abs(p[0])), double(std::abs(p[1]))});
  view.half = std::max(view.half, 1e-3);
  view.cell.assign(static_cast<std::size_t>(cells * cells), 0);
  const double step = 2 * view.half / cells;
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    const auto& tri = mesh.triangles[t];
    const auto& a = mesh.positions[tri[0]];
    const auto& b = mesh.positions[tri[1]];
    const auto& c = mesh.positions[tri[2]];
    const double area = (b[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (b[1] - a[1]);
    if (std::abs(area) < 1e-12) continue;
    const auto cell_of = [&](double v) { return std::clamp(static_cast<int>((v + view.half) / step), 0, cells - 1); };
    const int cx0 = cell_of(std::min({a[0], b[0], c[0]})), cx1 = cell_of(std::max({a[0], b[0], c[0]}));
    const int cy0 = cell_of(std::min({a[1], b[1], c[1]})), cy1 = cell_of(std::max({a[1], b[1], c[1]}));
    for (int cy = cy0; cy <= cy1; ++cy)
      for (int cx = cx0; cx <= cx1; ++cx) {
        const double px = -view.half + (cx + 0.5) * step, py = -view.half + (cy + 0.5) * step;
        const double w1 = ((c[0] - px) * (a[1] - py) - (a[0] - px) * (c[1] - py)) / area;
        const double w2 = ((a[0] - px) * (b[1] - py) - (b[0] - px) * (a[1] - py)) / area;
        if (w1 < 0 || w2 < 0 || w1 + w2 > 1) continue;
        view.cell[static_cast<std::size_t>(cy * cells + cx)] = 1;
      }
  }
  return view;
}

// ---------------------------------------------------------------------------------------------
// The canopy seen from afar. A square of the real field (the set's tiles under a tiling, every
// flower turned and scaled as placement does) is rasterized twice: from the sun, for its
// shadows, and along the view at a grazing angle, for what the camera sees. Only rays whose whole
// path through the canopy layer lies inside the square count, so the square's sides (flowers seen
// whole from the side) never do.

// A flower of the square: its model and its placement (ENU meters from the square's centre).
struct PlacedFlower {
  const Mesh* mesh = nullptr;
  double x = 0, y = 0, cos_yaw = 1, sin_yaw = 0, scale = 1;
  Vector3d world(const std::array<float, 3>& q) const {
    return {x + scale * (cos_yaw * q[0] - sin_yaw * q[1]), y + scale * (sin_yaw * q[0] + cos_yaw * q[1]), scale * q[2]};
  }
};

// The square's side (meters) at most, the triangles it holds at most (a dense field of detailed
// flowers gets a smaller square: its lowest grazing looks are then left out), and the side of one
// raster cell (meters across the picture).
constexpr double kMaxSquare = 80;
constexpr double kMaxSquareTriangles = 4e6;
constexpr double kCell = 0.02;

// The side (meters, whole tiles) of the square to render of `field`.
double square_side(const SceneField& field, const std::vector<Mesh>& models) {
  const double tile = field.placement.tile_size;
  double triangles = 0;  // per tile, over the filled set
  for (const auto& points_of_tile : field.filled.tiles)
    for (const TilePoint& p : points_of_tile)
      triangles += double(models[std::min<std::size_t>(p.variant, models.size() - 1)].triangles.size());
  const double per_tile = triangles / double(std::max<std::size_t>(1, field.filled.tiles.size()));
  const double tiles = std::sqrt(kMaxSquareTriangles / std::max(per_tile, 1.0));
  return tile * std::max(1.0, std::min(std::floor(tiles), std::floor(kMaxSquare / tile)));
}

std::vector<PlacedFlower> square_of_field(const SceneField& field, const std::vector<Mesh>& models, double side) {
  const double tile = field.placement.tile_size;
  const int tiles = static_cast<int>(std::lround(side / tile));
  TilingOptions options;
  options.algorithm =
      field.placement.algorithm == TilingAlgorithm::hash ? TilingAlgorithm::scanline : field.placement.algorithm;
  options.seed = field.placement.seed;
  const Tiling tiling = make_tiling(field.filled.set, tiles, tiles, options);
  const auto& world = field.placement.world_attributes;
  std::vector<PlacedFlower> flowers;
  for (int j = 0; j < tiles; ++j)
    for (int i = 0; i < tiles; ++i) {
      const auto& points = field.filled.tiles[tiling.at(i, j)];
      for (std::uint32_t k = 0; k < points.size(); ++k) {
        const TilePoint& p = points[k];
        PointAttributes a{p.variant, p.yaw, p.scale};
        if (world)
          a = world_point_attributes(world->seed, i, j, k, world->variants, world->min_scale, world->max_scale);
        const double yaw = field.yaw_of(a.yaw);
        flowers.push_back({&models[std::min<std::size_t>(a.variant, models.size() - 1)], (i + p.x) * tile - side / 2,
                           (j + p.y) * tile - side / 2, std::cos(yaw), std::sin(yaw), a.scale});
      }
    }
  return flowers;
}

// A depth raster: per cell the nearest triangle (depth, flower, triangle). Cells are (column,
// row) of `columns` x `rows`; `project` maps a world point to (column, row, depth) in cells.
struct DepthRaster {
  int columns = 0, rows = 0;
  std::vector<float> depth;
  std::vector<std::uint32_t> flower, triangle;

  DepthRaster(int c, int r)
      : columns(c),
        rows(r),
        depth(std::size_t(c) * std::size_t(r), std::numeric_limits<float>::infinity()),
        flower(depth.size(), ~0u),
        triangle(depth.size(), 0) {}

  template <class Project>
  void draw(const std::vector<PlacedFlower>& flowers, const Project& project) {
    std::vector<Vector3d> p;
    for (std::size_t f = 0; f < flowers.size(); ++f) {
      const Mesh& mesh = *flowers[f].mesh;
      p.resize(mesh.positions.size());
      double lo_x = 1e300, hi_x = -1e300, lo_y = 1e300, hi_y = -1e300;
      for (std::size_t v = 0; v < p.size(); ++v) {
        p[v] = project(flowers[f].world(mesh.positions[v]));
        lo_x = std::min(lo_x, p[v][0]), hi_x = std::max(hi_x, p[v][0]);
        lo_y = std::min(lo_y, p[v][1]), hi_y = std::max(hi_y, p[v][1]);
      }
      if (hi_x < 0 || hi_y < 0 || lo_x >= columns || lo_y >= rows) continue;  // off the raster
      for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
        const auto& tri = mesh.triangles[t];
        const Vector3d &A = p[tri[0]], &B = p[tri[1]], &C = p[tri[2]];
        const double area = (B[0] - A[0]) * (C[1] - A[1]) - (C[0] - A[0]) * (B[1] - A[1]);
        if (std::abs(area) < 1e-12) continue;
        const int x0 = std::max(0, static_cast<int>(std::floor(std::min({A[0], B[0], C[0]}))));
        const int x1 = std::min(columns - 1, static_cast<int>(std::floor(std::max({A[0], B[0], C[0]}))));
        const int y0 = std::max(0, static_cast<int>(std::floor(std::min({A[1], B[1], C[1]}))));
        const int y1 = std::min(rows - 1, static_cast<int>(std::floor(std::max({A[1], B[1], C[1]}))));
        for (int y = y0; y <= y1; ++y)
          for (int x = x0; x <= x1; ++x) {
            const double px = x + 0.5, py = y + 0.5;
            const double w1 = ((C[0] - px) * (A[1] - py) - (A[0] - px) * (C[1] - py)) / area;
            const double w2 = ((A[0] - px) * (B[1] - py) - (B[0] - px) * (A[1] - py)) / area;
            if (w1 < 0 || w2 < 0 || w1 + w2 > 1) continue;
            const auto d = static_cast<float>((1 - w1 - w2) * A[2] + w1 * B[2] + w2 * C[2]);
            const std::size_t c = std::size_t(y) * std::size_t(columns) + std::size_t(x);
            if (d >= depth[c]) continue;
            depth[c] = d;
            flower[c] = static_cast<std::uint32_t>(f);
            triangle[c] = static_cast<std::uint32_t>(t);
          }
      }
    }
  }
};

// An orthographic frame: `across` and `up` span the picture, `along` points away from the eye
// (towards the light for the sun's frame, where depth is measured backwards).
struct Frame {
  Vector3d across, up, along;
};

Frame frame_along(const Vector3d& direction) {
  Vector3d across{-direction[1], direction[0], 0};
  const double n = std::hypot(across[0], across[1]);
  across = n > 1e-9 ? Vector3d{across[0] / n, across[1] / n, 0} : Vector3d{1, 0, 0};
  return {across, cross(direction, across), direction};
}

// What the sun sees of the square: the depth (towards the sun) of the first surface per cell.
class SunMap {
 public:
  // `side`: the square's; `top`: its tallest flower (meters).
  SunMap(const std::vector<PlacedFlower>& flowers, double side, double top, const Vector3d& to_sun)
      : frame_(frame_along({-to_sun[0], -to_sun[1], -to_sun[2]})) {
    for (const double x : {-side / 2, side / 2})
      for (const double y : {-side / 2, side / 2})
        for (const double z : {0.0, top}) {
          lo_[0] = std::min(lo_[0], dot({x, y, z}, frame_.across));
          lo_[1] = std::min(lo_[1], dot({x, y, z}, frame_.up));
          hi_[1] = std::max(hi_[1], dot({x, y, z}, frame_.up));
          hi_[0] = std::max(hi_[0], dot({x, y, z}, frame_.across));
        }
    raster_ = std::make_unique<DepthRaster>(static_cast<int>((hi_[0] - lo_[0]) / kSunCell) + 1,
                                            static_cast<int>((hi_[1] - lo_[1]) / kSunCell) + 1);
    raster_->draw(flowers, [&](const Vector3d& p) { return project(p); });
  }
  // Whether the sun reaches the world point `p` (not behind another surface).
  bool lit(const Vector3d& p) const {
    const Vector3d q = project(p);
    const int x = static_cast<int>(q[0]), y = static_cast<int>(q[1]);
    if (x < 0 || y < 0 || x >= raster_->columns || y >= raster_->rows) return true;
    return q[2] <= raster_->depth[std::size_t(y) * std::size_t(raster_->columns) + std::size_t(x)] + kBias;
  }

 private:
  static constexpr double kSunCell = 0.03;  // meters
  static constexpr double kBias = 0.04;     // meters: a surface never shadows itself
  Vector3d project(const Vector3d& p) const {
    return {(dot(p, frame_.across) - lo_[0]) / kSunCell, (dot(p, frame_.up) - lo_[1]) / kSunCell, dot(p, frame_.along)};
  }
  Frame frame_;
  std::array<double, 2> lo_{1e30, 1e30}, hi_{-1e30, -1e30};
  std::unique_ptr<DepthRaster> raster_;
};

// Sunflower yellow (a petal's base color), the part of the canopy that shows as specks from afar.
bool is_yellow(const Vec3f& base) { return base[0] > 0.3f && base[1] > 0.4f * base[0] && base[2] < 0.3f * base[1]; }

// The canopy along one grazing view: the rays that enter the canopy layer (below the tallest
// flower) and leave it through the ground inside the square, from a point of view `sine` above
// the ground plane, heading `heading` (unit, horizontal).
CanopyLook look_at_canopy(const std::vector<PlacedFlower>& flowers, double side, double top, const SunMap& sun_map,
                          const ShadingSettings& light, const Vec3f& ground_light, const Vector3d& heading,
                          double sine) {
  const double cosine = std::sqrt(1 - sine * sine), cotangent = cosine / sine;
  const Vector3d view{heading[0] * cosine, heading[1] * cosine, -sine};
  const Vector3d across{-heading[1], heading[0], 0};
  // Rays by (across, where they pass the canopy's top along the heading); each row of cells is
  // kCell / sine long along the ground.
  const double path = top * cotangent;  // along the ground, from the top of the canopy to the ground
  const double reach = side / 2 - std::min(2.0, side / 8);  // inside the square whatever the heading
  const double half_width = reach / 2, first = -reach * 0.9, last = reach * 0.9 - path;
  if (last <= first) return {};
  // Rows of cells kCell of the picture high; at most kMaxRows of them (plenty for a mean).
  constexpr int kMaxRows = 512;
  const double row_step = kCell / sine;
  DepthRaster raster(static_cast<int>(2 * half_width / kCell),
                     std::clamp(static_cast<int>((last - first) / row_step), 1, kMaxRows));
  raster.draw(flowers, [&](const Vector3d& p) {
    const double along = dot(p, heading) - (top - p[2]) * cotangent;
    return Vector3d{(dot(p, across) + half_width) / kCell, (along - first) / row_step, (top - p[2]) / sine};
  });
  CanopyLook look;
  for (int row = 0; row < raster.rows; ++row)
    for (int column = 0; column < raster.columns; ++column) {
      const std::size_t c = std::size_t(row) * std::size_t(raster.columns) + std::size_t(column);
      if (raster.flower[c] == ~0u) continue;
      const PlacedFlower& f = flowers[raster.flower[c]];
      const Mesh& mesh = *f.mesh;
      const auto& tri = mesh.triangles[raster.triangle[c]];
      const Vector3d a = f.world(mesh.positions[tri[0]]), b = f.world(mesh.positions[tri[1]]),
                     d = f.world(mesh.positions[tri[2]]);
      const Vector3d n = cross(b - a, d - a);
      const double area = length(n);
      if (area <= 0) continue;
      // Two-sided: the face the camera sees, whose normal points against the view.
      const double facing = dot(n, view) > 0 ? -1 / area : 1 / area;
      const Vector3d to_sun{light.sun_direction[0], light.sun_direction[1], light.sun_direction[2]};
      const auto cos_sun = static_cast<float>(facing * dot(n, to_sun));
      // The point itself, back from the raster: where the ray meets the triangle.
      const double depth = raster.depth[c];
      const double z = top - depth * sine;
      const double along = first + (row + 0.5) * row_step + (top - z) * cotangent;
      const double offset = (column + 0.5) * kCell - half_width;  // across the view
      const Vector3d point{heading[0] * along + across[0] * offset, heading[1] * along + across[1] * offset, z};
      const std::size_t m =
          raster.triangle[c] < mesh.triangle_material.size() ? mesh.triangle_material[raster.triangle[c]] : 0;
      const bool has_material = m < mesh.materials.size();
      Vec3f base = has_material ? mesh.materials[m].base_color : Vec3f{0.5f, 0.5f, 0.5f};
      // A model's image: its mean colour, and a cutout covers only its share (leaf cards).
      float cover = 1;
      if (has_material && mesh.materials[m].base_color_map) {
        const auto mean = covered_mean(*mesh.materials[m].base_color_map, mesh.materials[m].alpha_cutoff);
        for (std::size_t k = 0; k < 3; ++k) base[k] *= mean[k];
        cover = mean[3];
      }
      const float sun = sun_map.lit(point) ? sun_share(cos_sun, has_material ? mesh.materials[m].translucency : 0) : 0;
      const Vec3f seen = lit(light, base, sun, 1);
      FieldSplat& sum = is_yellow(base) ? look.yellow : look.rest;
      sum.r += cover * seen[0] / ground_light[0];
      sum.g += cover * seen[1] / ground_light[1];
      sum.b += cover * seen[2] / ground_light[2];
      sum.coverage += cover;
    }
  const float all = look.yellow.coverage + look.rest.coverage;
  if (all == 0) return {};
  for (FieldSplat* part : {&look.yellow, &look.rest})
    if (part->coverage > 0) {
      part->r /= part->coverage, part->g /= part->coverage, part->b /= part->coverage;
      part->coverage /= all;
    }
  look.coverage = float(double(all) / (double(raster.columns) * raster.rows));
  return look;
}

}  // namespace

FieldTexture::FieldTexture(const SceneField& field, const std::vector<Mesh>& models,
                           const std::array<double, 3>& view_direction, const Sun& sun, int texels)
    : texels_(texels) {
  constexpr int kTopCells = 32;
  std::vector<TopView> views;
  views.reserve(models.size());
  for (const auto& model : models) views.push_back(top_view(model, kTopCells));
  const double tile = field.placement.tile_size;
  const double texel_area = (tile / texels) * (tile / texels);
  const std::size_t tiles = field.filled.tiles.size();
  // The top-down coverage of each tile's points, texels x texels per tile: of them all and, with
  // [[species]], of each species' own (painting counts a species only where it grows). Each
  // point is splatted once, into both.
  using TileImages = std::vector<std::vector<float>>;
  const std::size_t species_count = field.species ? field.species->size() : 0;
  TileImages all(tiles, std::vector<float>(static_cast<std::size_t>(texels * texels)));
  std::vector<TileImages> of_species(species_count, all);
  const auto wrap = [texels](double w) {
    const int k = static_cast<int>(std::floor(w * texels)) % texels;
    return k < 0 ? k + texels : k;
  };
  for (std::size_t t = 0; t < tiles && !views.empty(); ++t)
    for (const TilePoint& p : field.filled.tiles[t]) {
      std::vector<float>* own = p.species < species_count ? &of_species[p.species][t] : nullptr;
      const TopView& view = views[std::min<std::size_t>(p.variant, views.size() - 1)];
      const double yaw = field.yaw_of(p.yaw), cs = std::cos(yaw) * p.scale, sn = std::sin(yaw) * p.scale;
      const double step = 2 * view.half / view.cells, cell_area = step * step * p.scale * p.scale;
      for (int cy = 0; cy < view.cells; ++cy)
        for (int cx = 0; cx < view.cells; ++cx) {
          if (!view.cell[static_cast<std::size_t>(cy * view.cells + cx)]) continue;
          const double mx = -view.half + (cx + 0.5) * step, my = -view.half + (cy + 0.5) * step;
          // Wrapped around the tile: what spills over an edge stands for what the neighbours spill in.
          const double u = p.x + (cs * mx - sn * my) / tile, v = p.y + (sn * mx + cs * my) / tile;
          const auto texel = static_cast<std::size_t>(wrap(v) * texels + wrap(u));
          const auto cover = static_cast<float>(cell_area / texel_area);
          all[t][texel] += cover;
          if (own) (*own)[texel] += cover;
        }
    }
  // Each image clamped to full cover, with its mip chain down to one texel per tile.
  const auto coverage_levels = [&](TileImages base) {
    std::vector<TileImages> levels;
    for (auto& image : base)
      for (auto& c : image) c = std::min(c, 1.f);
    levels.push_back(std::move(base));
    for (int size = texels / 2; size >= 1; size /= 2) {
      const auto& finer = levels.back();
      TileImages level(tiles, std::vector<float>(static_cast<std::size_t>(size * size)));
      for (std::size_t t = 0; t < tiles; ++t)
        for (int y = 0; y < size; ++y)
          for (int x = 0; x < size; ++x) {
            float sum = 0;
            for (int k = 0; k < 4; ++k)
              sum += finer[t][static_cast<std::size_t>((2 * y + k / 2) * 2 * size + 2 * x + k % 2)];
            level[t][static_cast<std::size_t>(y * size + x)] = sum / 4;
          }
      levels.push_back(std::move(level));
    }
    return levels;
  };
  levels_ = coverage_levels(std::move(all));
  for (TileImages& images : of_species) species_levels_.push_back(coverage_levels(std::move(images)));
  for (const auto& tile_cover : levels_.back()) mean_coverage_ += tile_cover[0];
  mean_coverage_ /= static_cast<float>(std::max<std::size_t>(1, tiles));

  // The canopy from afar, at each grazing sine, in parallel (the square and the sun's map shared).
  if (models.empty()) return;
  const ShadingSettings light = with_sun(ShadingSettings{}, sun);
  const auto& to_sun = light.sun_direction;
  // The ground under a low sun keeps a twentieth of it, so that the ratio stays finite.
  const Vec3f ground_light = lit(light, {1, 1, 1}, std::max(0.05f, to_sun[2]), 1);
  const double side = square_side(field, models);
  const std::vector<PlacedFlower> flowers = square_of_field(field, models, side);
  double top = 0;
  for (const PlacedFlower& f : flowers)
    for (const auto& q : f.mesh->positions) top = std::max(top, f.scale * q[2]);
  const SunMap sun_map(flowers, side, top, {to_sun[0], to_sun[1], to_sun[2]});
  const double heading_norm = std::max(std::hypot(view_direction[0], view_direction[1]), 1e-9);
  const Vector3d heading{view_direction[0] / heading_norm, view_direction[1] / heading_norm, 0};
  tbb::parallel_for(std::size_t{0}, kLookSines.size(), [&](std::size_t k) {
    looks_[k] = look_at_canopy(flowers, side, top, sun_map, light, ground_light, heading, kLookSines[k]);
  });
}

float FieldTexture::coverage(std::uint32_t tile, double u, double v, double footprint) const {
  return coverage_in(levels_, tile, u, v, footprint);
}

float FieldTexture::species_coverage(std::size_t species, std::uint32_t tile, double u, double v,
                                     double footprint) const {
  return coverage_in(species_levels_[species], tile, u, v, footprint);
}

float FieldTexture::coverage_in(const std::vector<std::vector<std::vector<float>>>& levels, std::uint32_t tile,
                                double u, double v, double footprint) const {
  std::size_t level = 0;
  int size = texels_;
  while (size > 1 && footprint * size > 1.0) {
    size /= 2;
    ++level;
  }
  const int x = std::clamp(static_cast<int>(u * size), 0, size - 1),
            y = std::clamp(static_cast<int>(v * size), 0, size - 1);
  return levels[level][tile][static_cast<std::size_t>(y * size + x)];
}

CanopyLook FieldTexture::look(double sine) const {
  // Linear in log(sine) between the sines looked at, the nearest one outside them; a sine too
  // low for the square rendered (no rays through it) takes the lowest one it showed.
  std::size_t low = 0;
  while (low < kLookSines.size() && looks_[low].coverage == 0) ++low;
  if (low == kLookSines.size()) return {};
  if (low + 1 == kLookSines.size() || sine <= kLookSines[low]) return looks_[low];
  const double s = std::min(sine, kLookSines.back());
  std::size_t k = low;
  while (k + 2 < kLookSines.size() && s > kLookSines[k + 1]) ++k;
  const auto t = static_cast<float>(std::log(s / kLookSines[k]) / std::log(kLookSines[k + 1] / kLookSines[k]));
  const auto mix = [t](const FieldSplat& a, const FieldSplat& b) {
    return FieldSplat{a.r + (b.r - a.r) * t, a.g + (b.g - a.g) * t, a.b + (b.b - a.b) * t,
                      a.coverage + (b.coverage - a.coverage) * t};
  };
  const CanopyLook &a = looks_[k], &b = looks_[k + 1];
  return {mix(a.yellow, b.yellow), mix(a.rest, b.rest), a.coverage + (b.coverage - a.coverage) * t};
}

FieldSplat CanopyLook::mean() const {
  const float y = yellow.coverage, o = 1 - y;
  return {yellow.r * y + rest.r * o, yellow.g * y + rest.g * o, yellow.b * y + rest.b * o, coverage};
}

void paint_far_field(GroundBake& bake, const SceneField& field, const FieldTexture& texture, const CameraView& view) {
  const double s = field.placement.tile_size;
  const TileRange whole = tile_range(*field.placement.area, s);
  const RowTiles rows(field.filled.set, whole, field.placement);
  const Extent& e = bake.extent;
  const int w = bake.image.width, h = bake.image.height;
  const double dx = e.width() / w, dy = e.height() / h;
  const double far = view.options().far;
  constexpr int kSub = 2;  // subsamples per pixel side
  const double footprint = std::max(dx, dy) / kSub / s;
  const auto& cam = view.position();
  const float mean_cover = std::max(texture.mean_coverage(), 1e-6f);
  tbb::parallel_for(0, h, [&](int row) {
    const double y = e.max_y - (row + 0.5) * dy;
    std::vector<double> densities(field.species ? field.species->size() : 0);
    for (int col = 0; col < w; ++col) {
      const double x = e.min_x + (col + 0.5) * dx;
      const auto z = field.ground.height(x, y);
      if (!z) continue;
      const float fade = smoothstep(0.9 * far, far, view.distance(x, y, *z));
      if (fade == 0) continue;
      float cover = 0;
      for (int k = 0; k < kSub * kSub; ++k) {
        const double sx = x + ((k % kSub + 0.5) / kSub - 0.5) * dx, sy = y + ((k / kSub + 0.5) / kSub - 0.5) * dy;
        const double fi = std::floor(sx / s), fj = std::floor(sy / s);
        const auto i = static_cast<std::int64_t>(fi), j = static_cast<std::int64_t>(fj);
        if (i < whole.i0 || i >= whole.i1 || j < whole.j0 || j >= whole.j1) continue;
        const auto sz = field.ground.height(sx, sy);
        if (!sz || !field.ground.flowers_grow_at(sx, sy, *sz, {fi * s, fj * s, (fi + 1) * s, (fj + 1) * s})) continue;
        std::uint16_t t = 0;
        rows.row(static_cast<int>(j - whole.j0), {&t, 1}, static_cast<int>(i - whole.i0));
        if (!field.species) {
          cover += texture.coverage(t, sx / s - fi, sy / s - fj, footprint);
          continue;
        }
        // [[species]]: each species where its rules let it grow, thinned by its density there.
        field.species->densities_where_grow(sx, sy, *sz, densities);
        for (std::size_t c = 0; c < densities.size(); ++c)
          if (densities[c] > 0)
            cover +=
                static_cast<float>(densities[c]) * texture.species_coverage(c, t, sx / s - fi, sy / s - fj, footprint);
      }
      if (cover == 0) continue;
      // The ray's sine against the ground picks the canopy's look: at a grazing angle the
      // flowers hide more of the ground, and show their heads more than their stems.
      const double gx =
          (field.ground.height(x + dx, y).value_or(*z) - field.ground.height(x - dx, y).value_or(*z)) / (2 * dx);
      const double gy =
          (field.ground.height(x, y + dy).value_or(*z) - field.ground.height(x, y - dy).value_or(*z)) / (2 * dy);
      const double to_x = cam[0] - x, to_y = cam[1] - y, to_z = cam[2] - *z;
      const double sine = (-gx * to_x - gy * to_y + to_z) /
                          (std::sqrt(gx * gx + gy * gy + 1) * std::sqrt(to_x * to_x + to_y * to_y + to_z * to_z));
      const CanopyLook look = texture.look(sine);
      // The bake is far coarser than a head: each pixel shows the yellow of the petals or the rest
      // of the canopy, as often as the canopy shows them (a hash of the pixel: the same bytes on
      // any thread count), so the field keeps its mean color and its specks of yellow.
      const auto speck = unit_float(mix64((std::uint64_t(row) << 32) ^ std::uint64_t(col)));
      const FieldSplat& canopy = speck < look.yellow.coverage ? look.yellow : look.rest;
      // Where the masks or a sparse tile leave less of the field, less of it shows.
      const float a = fade * std::min(1.f, look.coverage * cover / (kSub * kSub) / mean_cover);
      const std::size_t o = bake.image.offset(col, row);
      auto& px = bake.image.pixels;
      px[o] = linear_to_srgb8(srgb8_to_linear(px[o]) * (1 - a) + canopy.r * a);
      px[o + 1] = linear_to_srgb8(srgb8_to_linear(px[o + 1]) * (1 - a) + canopy.g * a);
      px[o + 2] = linear_to_srgb8(srgb8_to_linear(px[o + 2]) * (1 - a) + canopy.b * a);
    }
  });
}

}  // namespace wangscape
