#include "scene/far_field.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "core/color.h"
#include "scene/camera_view.h"
#include "scene/scene.h"
#include "scene/shading.h"

namespace wangscape {

namespace {

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

constexpr int kYawBins = 16;
constexpr double kTopShare = 0.25;

// The mean color the camera sees of `mesh` turned by each of kYawBins yaws, seen along `view`
// (unit ENU), each triangle lit by the one shading model (scene/shading.h: its face towards the
// camera, the sun with its translucency, the open sky, no shadows) and divided, per channel, by
// the light of flat ground in the open, so the bake, lit as ground, shows the flower's brightness.
std::array<FieldSplat, kYawBins> side_colors(const Mesh& mesh, const std::array<double, 3>& view, const Sun& sun) {
  constexpr int kCells = 32;
  const ShadingSettings light = with_sun(ShadingSettings{}, sun);
  const auto& to_sun = light.sun_direction;
  // The ground under a low sun keeps a twentieth of it, so that the ratio stays finite.
  const Vec3f ground_light = lit(light, {1, 1, 1}, std::max(0.05f, to_sun[2]), 1);
  // A basis across the view: e1 horizontal, e2 up the picture.
  const std::array<double, 3> e1{-view[1], view[0], 0};
  const double n1 = std::max(std::hypot(e1[0], e1[1]), 1e-9);
  const std::array<double, 3> a{e1[0] / n1, e1[1] / n1, 0};
  const std::array<double, 3> b{view[1] * a[2] - view[2] * a[1], view[2] * a[0] - view[0] * a[2],
                                view[0] * a[1] - view[1] * a[0]};  // view x across: up
  std::array<FieldSplat, kYawBins> out{};
  for (int k = 0; k < kYawBins; ++k) {
    const double yaw = 2 * std::numbers::pi * k / kYawBins, cs = std::cos(yaw), sn = std::sin(yaw);
    std::vector<std::array<double, 3>> p(mesh.positions.size());  // (across, up, depth)
    double lo0 = 1e30, hi0 = -1e30, lo1 = 1e30, hi1 = -1e30;
    for (std::size_t i = 0; i < p.size(); ++i) {
      const auto& q = mesh.positions[i];
      const double x = cs * q[0] - sn * q[1], y = sn * q[0] + cs * q[1], z = q[2];
      p[i] = {x * a[0] + y * a[1], x * b[0] + y * b[1] + z * b[2], x * view[0] + y * view[1] + z * view[2]};
      lo0 = std::min(lo0, p[i][0]), hi0 = std::max(hi0, p[i][0]);
      lo1 = std::min(lo1, p[i][1]), hi1 = std::max(hi1, p[i][1]);
    }
    const double step = std::max({hi0 - lo0, hi1 - lo1, 1e-6}) / kCells;
    std::vector<double> depth(kCells * kCells, 1e30);
    std::vector<FieldSplat> cell(kCells * kCells);
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
      const auto& tri = mesh.triangles[t];
      const auto &A = p[tri[0]], &B = p[tri[1]], &C = p[tri[2]];
      const double area = (B[0] - A[0]) * (C[1] - A[1]) - (C[0] - A[0]) * (B[1] - A[1]);
      if (std::abs(area) < 1e-14) continue;
      // The triangle's normal in ENU (turned by the yaw), for its light.
      const auto& qa = mesh.positions[tri[0]];
      const auto& qb = mesh.positions[tri[1]];
      const auto& qc = mesh.positions[tri[2]];
      const double u[3] = {qb[0] - qa[0], qb[1] - qa[1], qb[2] - qa[2]},
                   w[3] = {qc[0] - qa[0], qc[1] - qa[1], qc[2] - qa[2]};
      const double nx0 = u[1] * w[2] - u[2] * w[1], ny0 = u[2] * w[0] - u[0] * w[2], nz = u[0] * w[1] - u[1] * w[0];
      const double nx = cs * nx0 - sn * ny0, ny = sn * nx0 + cs * ny0, nn = std::sqrt(nx * nx + ny * ny + nz * nz);
      // Two-sided: the face the camera sees, whose normal points against the view.
      const double facing = nx * view[0] + ny * view[1] + nz * view[2] > 0 ? -1 : 1;
      const float cos_sun =
          nn > 0 ? static_cast<float>(facing * (nx * to_sun[0] + ny * to_sun[1] + nz * to_sun[2]) / nn) : 0.0f;
      const std::size_t m = t < mesh.triangle_material.size() ? mesh.triangle_material[t] : 0;
      const bool has_material = m < mesh.materials.size();
      const Vec3f base = has_material ? mesh.materials[m].base_color : Vec3f{0.5f, 0.5f, 0.5f};
      const Vec3f seen = lit(light, base, sun_share(cos_sun, has_material ? mesh.materials[m].translucency : 0), 1);
      const auto index = [&](double v, double lo) {
        return std::clamp(static_cast<int>((v - lo) / step), 0, kCells - 1);
      };
      for (int cy = index(std::min({A[1], B[1], C[1]}), lo1); cy <= index(std::max({A[1], B[1], C[1]}), lo1); ++cy)
        for (int cx = index(std::min({A[0], B[0], C[0]}), lo0); cx <= index(std::max({A[0], B[0], C[0]}), lo0); ++cx) {
          const double px = lo0 + (cx + 0.5) * step, py = lo1 + (cy + 0.5) * step;
          const double w1 = ((C[0] - px) * (A[1] - py) - (A[0] - px) * (C[1] - py)) / area;
          const double w2 = ((A[0] - px) * (B[1] - py) - (B[0] - px) * (A[1] - py)) / area;
          if (w1 < 0 || w2 < 0 || w1 + w2 > 1) continue;
          const double d = (1 - w1 - w2) * A[2] + w1 * B[2] + w2 * C[2];
          const std::size_t c = static_cast<std::size_t>(cy * kCells + cx);
          if (d >= depth[c]) continue;
          depth[c] = d;
          cell[c] = {seen[0] / ground_light[0], seen[1] / ground_light[1], seen[2] / ground_light[2], 1};
        }
    }
    // From afar the camera looks across the field at a grazing angle: the flowers in front hide
    // all but the top of each flower, so only the top quarter of the silhouette counts.
    FieldSplat sum;
    int top_row = -1;
    for (int cy = kCells - 1; cy >= 0 && top_row < 0; --cy)
      for (int cx = 0; cx < kCells; ++cx)
        if (cell[static_cast<std::size_t>(cy * kCells + cx)].coverage > 0) top_row = cy;
    const int band = static_cast<int>(std::ceil((hi1 - lo1) / step * kTopShare));
    for (int cy = std::max(0, top_row - band); cy <= top_row; ++cy)
      for (int cx = 0; cx < kCells; ++cx) {
        const FieldSplat& c = cell[static_cast<std::size_t>(cy * kCells + cx)];
        sum.r += c.r, sum.g += c.g, sum.b += c.b, sum.coverage += c.coverage;
      }
    if (sum.coverage > 0)
      out[static_cast<std::size_t>(k)] = {sum.r / sum.coverage, sum.g / sum.coverage, sum.b / sum.coverage, 1};
  }
  return out;
}

float smoothstep(double lo, double hi, double v) {
  const double t = std::clamp((v - lo) / std::max(hi - lo, 1e-9), 0.0, 1.0);
  return static_cast<float>(t * t * (3 - 2 * t));
}

}  // namespace

FieldTexture::FieldTexture(const SceneField& field, const std::vector<Mesh>& models,
                           const std::array<double, 3>& view_direction, const Sun& sun, int texels)
    : texels_(texels) {
  constexpr int kTopCells = 32;
  std::vector<TopView> views;
  std::vector<std::array<FieldSplat, kYawBins>> seen;
  views.reserve(models.size());
  for (const auto& model : models) {
    views.push_back(top_view(model, kTopCells));
    seen.push_back(side_colors(model, view_direction, sun));
  }
  const double tile = field.placement.tile_size;
  const double texel_area = (tile / texels) * (tile / texels);
  const std::size_t tiles = field.filled.tiles.size();
  auto& base = levels_.emplace_back(tiles, std::vector<FieldSplat>(static_cast<std::size_t>(texels * texels)));
  for (std::size_t t = 0; t < tiles; ++t) {
    auto& image = base[t];
    for (const TilePoint& p : field.filled.tiles[t]) {
      if (views.empty()) break;
      const std::size_t variant = std::min<std::size_t>(p.variant, views.size() - 1);
      const TopView& view = views[variant];
      const double yaw = field.yaw_of(p.yaw), cs = std::cos(yaw) * p.scale, sn = std::sin(yaw) * p.scale;
      const int bin = static_cast<int>(std::lround(yaw / (2 * std::numbers::pi) * kYawBins)) % kYawBins;
      const FieldSplat& color = seen[variant][static_cast<std::size_t>(bin < 0 ? bin + kYawBins : bin)];
      const double step = 2 * view.half / view.cells, cell_area = step * step * p.scale * p.scale;
      for (int cy = 0; cy < view.cells; ++cy)
        for (int cx = 0; cx < view.cells; ++cx) {
          if (!view.cell[static_cast<std::size_t>(cy * view.cells + cx)]) continue;
          const double mx = -view.half + (cx + 0.5) * step, my = -view.half + (cy + 0.5) * step;
          // Wrapped around the tile: what spills over an edge stands for what the neighbours spill in.
          const double u = p.x + (cs * mx - sn * my) / tile, v = p.y + (sn * mx + cs * my) / tile;
          const auto wrap = [&](double w) {
            const int k = static_cast<int>(std::floor(w * texels)) % texels;
            return k < 0 ? k + texels : k;
          };
          FieldSplat& out = image[static_cast<std::size_t>(wrap(v) * texels + wrap(u))];
          const auto a = static_cast<float>(cell_area / texel_area);
          out.r += color.r * a;
          out.g += color.g * a;
          out.b += color.b * a;
          out.coverage += a;
        }
    }
    for (auto& s : image) {
      if (s.coverage > 0) {
        s.r /= s.coverage;
        s.g /= s.coverage;
        s.b /= s.coverage;
      }
      s.coverage = std::min(s.coverage, 1.f);
    }
  }
  // Mip chain: coverage-weighted colors, down to one texel per tile.
  for (int size = texels / 2; size >= 1; size /= 2) {
    const auto& finer = levels_.back();
    std::vector<std::vector<FieldSplat>> level(tiles, std::vector<FieldSplat>(static_cast<std::size_t>(size * size)));
    for (std::size_t t = 0; t < tiles; ++t)
      for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) {
          FieldSplat sum;
          for (int k = 0; k < 4; ++k) {
            const FieldSplat& f = finer[t][static_cast<std::size_t>((2 * y + k / 2) * 2 * size + 2 * x + k % 2)];
            sum.r += f.r * f.coverage;
            sum.g += f.g * f.coverage;
            sum.b += f.b * f.coverage;
            sum.coverage += f.coverage;
          }
          if (sum.coverage > 0) {
            sum.r /= sum.coverage;
            sum.g /= sum.coverage;
            sum.b /= sum.coverage;
          }
          sum.coverage /= 4;
          level[t][static_cast<std::size_t>(y * size + x)] = sum;
        }
    levels_.push_back(std::move(level));
  }
}

FieldSplat FieldTexture::sample(std::uint32_t tile, double u, double v, double footprint) const {
  std::size_t level = 0;
  int size = texels_;
  while (size > 1 && footprint * size > 1.0) {
    size /= 2;
    ++level;
  }
  const int x = std::clamp(static_cast<int>(u * size), 0, size - 1),
            y = std::clamp(static_cast<int>(v * size), 0, size - 1);
  return levels_[level][tile][static_cast<std::size_t>(y * size + x)];
}

FieldSplat FieldTexture::mean() const {
  FieldSplat sum;
  const auto& top = levels_.back();
  for (const auto& tile : top) {
    sum.r += tile[0].r * tile[0].coverage;
    sum.g += tile[0].g * tile[0].coverage;
    sum.b += tile[0].b * tile[0].coverage;
    sum.coverage += tile[0].coverage;
  }
  if (sum.coverage > 0) {
    sum.r /= sum.coverage;
    sum.g /= sum.coverage;
    sum.b /= sum.coverage;
  }
  sum.coverage /= static_cast<float>(std::max<std::size_t>(1, top.size()));
  return sum;
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
  tbb::parallel_for(0, h, [&](int row) {
    const double y = e.max_y - (row + 0.5) * dy;
    for (int col = 0; col < w; ++col) {
      const double x = e.min_x + (col + 0.5) * dx;
      const auto z = field.ground.height(x, y);
      if (!z) continue;
      const float fade = smoothstep(0.9 * far, far, view.distance(x, y, *z));
      if (fade == 0) continue;
      FieldSplat sum;
      for (int k = 0; k < kSub * kSub; ++k) {
        const double sx = x + ((k % kSub + 0.5) / kSub - 0.5) * dx, sy = y + ((k / kSub + 0.5) / kSub - 0.5) * dy;
        const double fi = std::floor(sx / s), fj = std::floor(sy / s);
        const auto i = static_cast<std::int64_t>(fi), j = static_cast<std::int64_t>(fj);
        if (i < whole.i0 || i >= whole.i1 || j < whole.j0 || j >= whole.j1) continue;
        const auto sz = field.ground.height(sx, sy);
        if (!sz || !field.ground.flowers_grow_at(sx, sy, *sz, {fi * s, fj * s, (fi + 1) * s, (fj + 1) * s})) continue;
        std::uint16_t t = 0;
        rows.row(static_cast<int>(j - whole.j0), {&t, 1}, static_cast<int>(i - whole.i0));
        const FieldSplat f = texture.sample(t, sx / s - fi, sy / s - fj, footprint);
        sum.r += f.r * f.coverage;
        sum.g += f.g * f.coverage;
        sum.b += f.b * f.coverage;
        sum.coverage += f.coverage;
      }
      if (sum.coverage == 0) continue;
      const float cover = sum.coverage / (kSub * kSub);
      // Seen at a grazing angle the canopy is thicker: coverage^(1 / sin) along the view ray.
      const double gx =
          (field.ground.height(x + dx, y).value_or(*z) - field.ground.height(x - dx, y).value_or(*z)) / (2 * dx);
      const double gy =
          (field.ground.height(x, y + dy).value_or(*z) - field.ground.height(x, y - dy).value_or(*z)) / (2 * dy);
      const double to_x = cam[0] - x, to_y = cam[1] - y, to_z = cam[2] - *z;
      const double sine = (-gx * to_x - gy * to_y + to_z) /
                          (std::sqrt(gx * gx + gy * gy + 1) * std::sqrt(to_x * to_x + to_y * to_y + to_z * to_z));
      const float seen = 1 - std::pow(1 - std::min(cover, 0.999f), static_cast<float>(1 / std::clamp(sine, 0.05, 1.0)));
      const float a = fade * seen;
      const std::size_t o = bake.image.offset(col, row);
      auto& px = bake.image.pixels;
      const float r = sum.r / sum.coverage, g = sum.g / sum.coverage, b = sum.b / sum.coverage;
      px[o] = linear_to_srgb8(srgb8_to_linear(px[o]) * (1 - a) + r * a);
      px[o + 1] = linear_to_srgb8(srgb8_to_linear(px[o + 1]) * (1 - a) + g * a);
      px[o + 2] = linear_to_srgb8(srgb8_to_linear(px[o + 2]) * (1 - a) + b * a);
    }
  });
}

}  // namespace wangscape
