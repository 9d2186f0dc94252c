#include "terrain/terrain_mesh.h"

#include <cmath>
#include <string>

namespace wangscape {

namespace {

// Sample indices 0, s, 2s, ... and always the last one.
std::vector<int> strided(int count, int stride) {
  std::vector<int> out;
  for (int k = 0; k < count; k += stride) out.push_back(k);
  if (out.back() != count - 1) out.push_back(count - 1);
  return out;
}

struct Grid {
  std::vector<int> cols, rows;
  std::vector<std::uint32_t> vertex;  // per grid node, kNone where no vertex
};
constexpr std::uint32_t kNone = ~0u;

}  // namespace

TerrainMesh make_terrain_mesh(const Terrain& terrain, const TerrainMeshOptions& options) {
  const DemRaster& dem = terrain.dem();
  if (options.max_vertices != 0 && options.max_vertices < 3)
    throw Error("terrain mesh vertex budget " + std::to_string(options.max_vertices) + " is too small (at least 3)");
  const std::size_t valid = dem.cell_count() - dem.nodata_count;
  double fraction = 1.0;  // of the samples inside the crop, a first guess
  if (options.crop) {
    const Extent e = terrain.extent(), c = *options.crop;
    const double w = std::min(e.max_x, c.max_x) - std::max(e.min_x, c.min_x);
    const double h = std::min(e.max_y, c.max_y) - std::max(e.min_y, c.min_y);
    fraction = (w > 0 && h > 0) ? w * h / (e.width() * e.height()) : 0.0;
  }
  int stride = 1;
  if (options.max_vertices != 0)
    stride = std::max(1, int(std::floor(std::sqrt(valid * fraction / double(options.max_vertices)))));

  for (;; ++stride) {
    Grid grid{strided(dem.width, stride), strided(dem.height, stride), {}};
    const std::size_t nx = grid.cols.size(), ny = grid.rows.size();
    std::vector<double> xs, ys;
    std::vector<std::size_t> node_of;
    for (std::size_t j = 0; j < ny; ++j)
      for (std::size_t i = 0; i < nx; ++i)
        if (dem.at(grid.cols[i], grid.rows[j])) {
          xs.push_back(grid.cols[i]);
          ys.push_back(grid.rows[j]);
          node_of.push_back(j * nx + i);
        }
    terrain.samples_to_enu(xs, ys);

    TerrainMesh mesh;
    mesh.stride = stride;
    grid.vertex.assign(nx * ny, kNone);
    for (std::size_t k = 0; k < xs.size(); ++k) {
      if (options.crop && !options.crop->contains(xs[k], ys[k])) continue;
      const std::size_t node = node_of[k];
      grid.vertex[node] = std::uint32_t(mesh.positions.size());
      const double h = *dem.at(grid.cols[node % nx], grid.rows[node / nx]);
      mesh.positions.push_back({float(xs[k]), float(ys[k]), float(h)});
    }
    if (options.max_vertices != 0 && mesh.positions.size() > options.max_vertices && stride < dem.width + dem.height)
      continue;

    auto vertex = [&](std::size_t i, std::size_t j) { return grid.vertex[j * nx + i]; };
    auto position = [&](std::uint32_t v) {
      const auto& p = mesh.positions[v];
      return std::array<double, 3>{p[0], p[1], p[2]};
    };
    auto emit = [&](std::uint32_t a, std::uint32_t b, std::uint32_t c) {
      const auto pa = position(a), pb = position(b), pc = position(c);
      const double z = (pb[0] - pa[0]) * (pc[1] - pa[1]) - (pb[1] - pa[1]) * (pc[0] - pa[0]);
      if (z >= 0)
        mesh.triangles.push_back({a, b, c});
      else
        mesh.triangles.push_back({a, c, b});
    };
    for (std::size_t j = 0; j + 1 < ny; ++j)
      for (std::size_t i = 0; i + 1 < nx; ++i) {
        // a b (row j, north side in a north-up DEM)
        // c d (row j + 1)
        const std::uint32_t a = vertex(i, j), b = vertex(i + 1, j), c = vertex(i, j + 1), d = vertex(i + 1, j + 1);
        const int present = (a != kNone) + (b != kNone) + (c != kNone) + (d != kNone);
        if (present == 4) {
          emit(c, d, b);
          emit(c, b, a);
        } else if (present == 3) {
          if (a == kNone) emit(c, d, b);
          if (b == kNone) emit(c, d, a);
          if (c == kNone) emit(d, b, a);
          if (d == kNone) emit(c, b, a);
        }
      }
    if (mesh.triangles.empty())
      throw Error("terrain mesh of DEM '" + dem.path.string() + "' has no triangle" +
                  (options.crop ? std::string(" inside the crop rectangle") : std::string()));

    // Normals: central differences over the neighbouring vertices (one-sided at borders).
    mesh.normals.assign(mesh.positions.size(), {0, 0, 1});
    for (std::size_t j = 0; j < ny; ++j)
      for (std::size_t i = 0; i < nx; ++i) {
        const std::uint32_t v = vertex(i, j);
        if (v == kNone) continue;
        auto neighbour = [&](std::size_t ii, std::size_t jj) { return ii < nx && jj < ny ? vertex(ii, jj) : kNone; };
        const std::uint32_t east = neighbour(i + 1, j), west = i > 0 ? neighbour(i - 1, j) : kNone;
        const std::uint32_t south = neighbour(i, j + 1), north = j > 0 ? neighbour(i, j - 1) : kNone;
        const auto from = position(west != kNone ? west : v), to = position(east != kNone ? east : v);
        const auto below = position(south != kNone ? south : v), above = position(north != kNone ? north : v);
        const std::array<double, 3> t{to[0] - from[0], to[1] - from[1], to[2] - from[2]};
        const std::array<double, 3> u{above[0] - below[0], above[1] - below[1], above[2] - below[2]};
        std::array<double, 3> n{t[1] * u[2] - t[2] * u[1], t[2] * u[0] - t[0] * u[2], t[0] * u[1] - t[1] * u[0]};
        const double length = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
        if (!(length > 0)) continue;  // isolated vertex: keep straight up
        const double sign = n[2] < 0 ? -1.0 : 1.0;
        mesh.normals[v] = {float(sign * n[0] / length), float(sign * n[1] / length), float(sign * n[2] / length)};
      }
    return mesh;
  }
}

}  // namespace wangscape
