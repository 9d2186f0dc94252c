#include "renders/view/terrain_chunks.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace wangscape {

namespace {

// Relative: a level whose light strays further from the fine mesh's (at its vertices and grid
// points) counts its cell's size as its error, since a shadow's edge then moves by up to a cell.
constexpr float kLightTolerance = 0.02f;

// The square grid of chunks over the mesh's extent (ENU meters).
struct ChunkGrid {
  double low_x = 0, low_y = 0, cell_w = 1, cell_h = 1;
  int side = 1;
  int cell(double v, double low, double size) const {
    return std::clamp(int(std::floor((v - low) / size)), 0, side - 1);
  }
  // The point at fraction (u, v) of chunk (ci, cj)'s square: computed from the grid, not from the
  // chunk's corner, so two chunks get the same bits for a point on their shared side.
  double x(int ci, double u) const { return low_x + (double(ci) + u) * cell_w; }
  double y(int cj, double v) const { return low_y + (double(cj) + v) * cell_h; }
};

// One chunk's vertices, levels and borrowed triangles, built on its own (the chunks in
// parallel), its indices local; appended in chunk order afterwards.
struct ChunkPart {
  std::vector<float> x, y, z, r, g, b;
  std::vector<std::array<std::uint32_t, 3>> triangles;
  std::vector<TerrainChunks::Level> levels;
  std::vector<TerrainChunks::Borrowed> borrowed;
  std::array<float, 3> low{std::numeric_limits<float>::max(), std::numeric_limits<float>::max(),
                           std::numeric_limits<float>::max()};
  std::array<float, 3> high{-std::numeric_limits<float>::max(), -std::numeric_limits<float>::max(),
                            -std::numeric_limits<float>::max()};

  std::uint32_t add(float px, float py, float pz, const std::array<float, 3>& light, bool skirt = false) {
    x.push_back(px);
    y.push_back(py);
    z.push_back(pz);
    r.push_back(light[0]);
    g.push_back(light[1]);
    b.push_back(light[2]);
    if (!skirt) {
      const float p[3] = {px, py, pz};
      for (std::size_t c = 0; c < 3; ++c) {
        low[c] = std::min(low[c], p[c]);
        high[c] = std::max(high[c], p[c]);
      }
    }
    return std::uint32_t(x.size() - 1);
  }
  // Drops what was added after the first `vertices` vertices and `triangles_kept` triangles (a level
  // not kept). The box keeps them: it only grows, and a level's points lie on the fine surface.
  void truncate(std::size_t vertices, std::size_t triangles_kept) {
    for (auto* v : {&x, &y, &z, &r, &g, &b}) v->resize(vertices);
    triangles.resize(triangles_kept);
  }
};

// A regular lattice of (n + 1) x (n + 1) points over a chunk's square with the fine mesh's
// surface and light sampled at each (invalid where no triangle of the mesh holds the point).
struct Lattice {
  int n = 0;
  std::vector<std::uint8_t> valid;
  std::vector<float> z;
  std::vector<std::array<float, 3>> light;
  std::size_t at(int i, int j) const { return std::size_t(j) * std::size_t(n + 1) + std::size_t(i); }
};

// The surface and light of one of a level's cells, split along its south-west to north-east
// diagonal, at fraction (u, v) of the cell (corners SW, SE, NW, NE of the lattice).
template <class T>
T on_cell(const T& sw, const T& se, const T& nw, const T& ne, float u, float v) {
  return u >= v ? sw + (se - sw) * u + (ne - se) * v : sw + (nw - sw) * v + (ne - nw) * u;
}

class ChunkBuilder {
 public:
  ChunkBuilder(const Mesh& mesh, const std::vector<std::array<float, 3>>& light, const ChunkGrid& grid,
               const std::vector<std::int32_t>& owner)
      : mesh_(mesh), light_(light), grid_(grid), owner_(owner) {}

  // Chunk `self` over grid cell (ci, cj); `overlapping`: the mesh's triangles whose box meets its
  // square, ascending; `neighbour`: whether a chunk lies west, east, south, north.
  ChunkPart build(std::uint32_t self, int ci, int cj, const std::vector<std::uint32_t>& overlapping,
                  const std::array<bool, 4>& neighbour) const {
    ChunkPart part;
    // Level 0: the triangles it owns; those of its neighbours that reach into it, borrowed.
    std::vector<std::uint32_t> ids;
    for (const std::uint32_t t : overlapping)
      ids.insert(ids.end(), mesh_.triangles[t].begin(), mesh_.triangles[t].end());
    std::sort(ids.begin(), ids.end());
    ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
    for (const std::uint32_t i : ids)
      part.add(mesh_.positions[i][0], mesh_.positions[i][1], mesh_.positions[i][2], light_[i]);
    const auto local = [&](std::uint32_t i) {
      return std::uint32_t(std::lower_bound(ids.begin(), ids.end(), i) - ids.begin());
    };
    TerrainChunks::Level fine;
    fine.vertex_count = std::uint32_t(ids.size());
    for (const std::uint32_t t : overlapping) {
      const auto& tri = mesh_.triangles[t];
      const std::array<std::uint32_t, 3> remapped{local(tri[0]), local(tri[1]), local(tri[2])};
      if (std::uint32_t(owner_[t]) == self)
        part.triangles.push_back(remapped);
      else
        part.borrowed.push_back({remapped, std::uint32_t(owner_[t])});
    }
    fine.triangle_count = std::uint32_t(part.triangles.size());
    part.levels.push_back(fine);

    // The finest grid: fewer triangles than it stands in for.
    int n = 1;
    if (fine.triangle_count <= 2) return part;
    while (std::size_t(2) * std::size_t(2 * n) * std::size_t(2 * n) < fine.triangle_count) n *= 2;
    const Lattice lattice = sample(ci, cj, n, overlapping);

    // Where the levels are measured: the fine vertices in the square and the lattice's points.
    struct Reference {
      float u, v, z;  // (u, v): lattice units
      std::array<float, 3> light;
    };
    std::vector<Reference> references;
    const double x0 = grid_.x(ci, 0), y0 = grid_.y(cj, 0);
    const double to_u = n / grid_.cell_w, to_v = n / grid_.cell_h;
    for (const std::uint32_t i : ids) {
      const auto& p = mesh_.positions[i];
      const double u = (p[0] - x0) * to_u, v = (p[1] - y0) * to_v;
      if (u >= 0 && v >= 0 && u <= n && v <= n) references.push_back({float(u), float(v), p[2], light_[i]});
    }
    for (int j = 0; j <= n; ++j)
      for (int i = 0; i <= n; ++i)
        if (lattice.valid[lattice.at(i, j)])
          references.push_back({float(i), float(j), lattice.z[lattice.at(i, j)], lattice.light[lattice.at(i, j)]});

    std::uint32_t previous = fine.triangle_count;
    for (int cells = n; cells >= 1; cells /= 2) {
      const std::size_t before_vertices = part.x.size(), before_triangles = part.triangles.size();
      const TerrainChunks::Level level = grid_level(part, ci, cj, lattice, cells, overlapping, neighbour, references);
      if (level.triangle_count - level.skirt_triangles >= previous) {  // not cheaper: dropped
        part.truncate(before_vertices, before_triangles);
        continue;
      }
      previous = level.triangle_count - level.skirt_triangles;
      part.levels.push_back(level);
    }
    return part;
  }

 private:
  const Mesh& mesh_;
  const std::vector<std::array<float, 3>>& light_;
  const ChunkGrid& grid_;
  const std::vector<std::int32_t>& owner_;

  Lattice sample(int ci, int cj, int n, const std::vector<std::uint32_t>& overlapping) const {
    Lattice lattice;
    lattice.n = n;
    const std::size_t points = std::size_t(n + 1) * std::size_t(n + 1);
    lattice.valid.assign(points, 0);
    lattice.z.assign(points, 0);
    lattice.light.assign(points, {0, 0, 0});
    const double x0 = grid_.x(ci, 0), y0 = grid_.y(cj, 0), dx = grid_.cell_w / n, dy = grid_.cell_h / n;
    constexpr double kInside = -1e-7;            // barycentric tolerance: points on an edge belong to it
    for (const std::uint32_t t : overlapping) {  // ascending: the first triangle holding a point wins
      const auto& tri = mesh_.triangles[t];
      const auto &a = mesh_.positions[tri[0]], &b = mesh_.positions[tri[1]], &c = mesh_.positions[tri[2]];
      const double det = (double(b[0]) - a[0]) * (double(c[1]) - a[1]) - (double(b[1]) - a[1]) * (double(c[0]) - a[0]);
      if (!(std::abs(det) > 0)) continue;
      const int i0 = std::max(0, int(std::ceil((std::min({a[0], b[0], c[0]}) - x0) / dx - 1e-6)));
      const int i1 = std::min(n, int(std::floor((std::max({a[0], b[0], c[0]}) - x0) / dx + 1e-6)));
      const int j0 = std::max(0, int(std::ceil((std::min({a[1], b[1], c[1]}) - y0) / dy - 1e-6)));
      const int j1 = std::min(n, int(std::floor((std::max({a[1], b[1], c[1]}) - y0) / dy + 1e-6)));
      for (int j = j0; j <= j1; ++j)
        for (int i = i0; i <= i1; ++i) {
          const std::size_t k = lattice.at(i, j);
          if (lattice.valid[k]) continue;
          const double px = grid_.x(ci, double(i) / n), py = grid_.y(cj, double(j) / n);
          const double wb = ((px - a[0]) * (double(c[1]) - a[1]) - (py - a[1]) * (double(c[0]) - a[0])) / det;
          const double wc = ((double(b[0]) - a[0]) * (py - a[1]) - (double(b[1]) - a[1]) * (px - a[0])) / det;
          const double wa = 1 - wb - wc;
          if (wa < kInside || wb < kInside || wc < kInside) continue;
          lattice.valid[k] = 1;
          lattice.z[k] = float(wa * a[2] + wb * b[2] + wc * c[2]);
          for (std::size_t q = 0; q < 3; ++q)
            lattice.light[k][q] = float(wa * light_[tri[0]][q] + wb * light_[tri[1]][q] + wc * light_[tri[2]][q]);
        }
    }
    return lattice;
  }

  // The level of `cells` x `cells` grid cells (every (lattice.n / cells)-th lattice point),
  // appended to `part`: its grid triangles, the fine triangles of cells that leave the mesh, its
  // skirts (its last triangles, Level::skirt_triangles), and its errors measured at `references`.
  template <class References>
  TerrainChunks::Level grid_level(ChunkPart& part, int ci, int cj, const Lattice& lattice, int cells,
                                  const std::vector<std::uint32_t>& overlapping, const std::array<bool, 4>& neighbour,
                                  const References& references) const {
    const int step = lattice.n / cells;
    const auto point = [&](int a, int b) { return lattice.at(a * step, b * step); };
    std::vector<std::uint8_t> cell_valid(std::size_t(cells) * std::size_t(cells));
    for (int b = 0; b < cells; ++b)
      for (int a = 0; a < cells; ++a)
        cell_valid[std::size_t(b * cells + a)] = lattice.valid[point(a, b)] && lattice.valid[point(a + 1, b)] &&
                                                 lattice.valid[point(a, b + 1)] && lattice.valid[point(a + 1, b + 1)];
    const auto valid_cell = [&](int a, int b) { return cell_valid[std::size_t(b * cells + a)] != 0; };

    TerrainChunks::Level level;
    level.first_vertex = std::uint32_t(part.x.size());
    level.first_triangle = std::uint32_t(part.triangles.size());
    // The grid's vertices.
    std::vector<std::uint32_t> vertex(std::size_t(cells + 1) * std::size_t(cells + 1), ~0u);
    const auto grid_vertex = [&](int a, int b) {
      std::uint32_t& v = vertex[std::size_t(b * (cells + 1) + a)];
      if (v == ~0u) {
        const std::size_t k = point(a, b);
        v = part.add(float(grid_.x(ci, double(a) / cells)), float(grid_.y(cj, double(b) / cells)), lattice.z[k],
                     lattice.light[k]);
      }
      return v;
    };
    for (int b = 0; b < cells; ++b)
      for (int a = 0; a < cells; ++a) {
        if (!valid_cell(a, b)) continue;
        const std::uint32_t sw = grid_vertex(a, b), se = grid_vertex(a + 1, b), nw = grid_vertex(a, b + 1),
                            ne = grid_vertex(a + 1, b + 1);
        part.triangles.push_back({sw, se, ne});
        part.triangles.push_back({sw, ne, nw});
      }
    // Cells that leave the mesh keep the fine triangles that meet them.
    std::vector<std::uint32_t> kept_vertices;
    std::vector<std::uint32_t> kept;
    const double x0 = grid_.x(ci, 0), y0 = grid_.y(cj, 0);
    const double cell_w = grid_.cell_w / cells, cell_h = grid_.cell_h / cells;
    for (const std::uint32_t t : overlapping) {
      const auto& tri = mesh_.triangles[t];
      const auto &p = mesh_.positions[tri[0]], &q = mesh_.positions[tri[1]], &s = mesh_.positions[tri[2]];
      const int a0 = std::clamp(int(std::floor((std::min({p[0], q[0], s[0]}) - x0) / cell_w)), 0, cells - 1);
      const int a1 = std::clamp(int(std::floor((std::max({p[0], q[0], s[0]}) - x0) / cell_w)), 0, cells - 1);
      const int b0 = std::clamp(int(std::floor((std::min({p[1], q[1], s[1]}) - y0) / cell_h)), 0, cells - 1);
      const int b1 = std::clamp(int(std::floor((std::max({p[1], q[1], s[1]}) - y0) / cell_h)), 0, cells - 1);
      bool meets_invalid = false;
      for (int b = b0; b <= b1 && !meets_invalid; ++b)
        for (int a = a0; a <= a1 && !meets_invalid; ++a) meets_invalid = !valid_cell(a, b);
      if (!meets_invalid) continue;
      kept.push_back(t);
      kept_vertices.insert(kept_vertices.end(), tri.begin(), tri.end());
    }
    std::sort(kept_vertices.begin(), kept_vertices.end());
    kept_vertices.erase(std::unique(kept_vertices.begin(), kept_vertices.end()), kept_vertices.end());
    const std::uint32_t kept_base = std::uint32_t(part.x.size());
    for (const std::uint32_t i : kept_vertices)
      part.add(mesh_.positions[i][0], mesh_.positions[i][1], mesh_.positions[i][2], light_[i]);
    for (const std::uint32_t t : kept) {
      std::array<std::uint32_t, 3> remapped{};
      for (std::size_t k = 0; k < 3; ++k)
        remapped[k] = kept_base + std::uint32_t(std::lower_bound(kept_vertices.begin(), kept_vertices.end(),
                                                                 mesh_.triangles[t][k]) -
                                                kept_vertices.begin());
      part.triangles.push_back(remapped);
    }
    // Skirts: along each side of a grid cell that borders another chunk or a cell of fine
    // triangles, a wall down from the side (its bottom vertices last, lowered per frame).
    struct Side {
      int a0, b0, a1, b1;
    };
    std::vector<Side> sides;
    for (int b = 0; b < cells; ++b)
      for (int a = 0; a < cells; ++a) {
        if (!valid_cell(a, b)) continue;
        const bool west = a == 0 ? neighbour[0] : !valid_cell(a - 1, b);
        const bool east = a == cells - 1 ? neighbour[1] : !valid_cell(a + 1, b);
        const bool south = b == 0 ? neighbour[2] : !valid_cell(a, b - 1);
        const bool north = b == cells - 1 ? neighbour[3] : !valid_cell(a, b + 1);
        if (west) sides.push_back({a, b, a, b + 1});
        if (east) sides.push_back({a + 1, b, a + 1, b + 1});
        if (south) sides.push_back({a, b, a + 1, b});
        if (north) sides.push_back({a, b + 1, a + 1, b + 1});
      }
    const std::uint32_t skirt_base = std::uint32_t(part.x.size());
    std::vector<std::uint32_t> bottom(vertex.size(), ~0u);
    const auto bottom_vertex = [&](int a, int b) {
      std::uint32_t& v = bottom[std::size_t(b * (cells + 1) + a)];
      if (v == ~0u) {
        const std::uint32_t top = vertex[std::size_t(b * (cells + 1) + a)];
        v = part.add(part.x[top], part.y[top], part.z[top], {part.r[top], part.g[top], part.b[top]}, true);
      }
      return v;
    };
    for (const Side& s : sides) {
      const std::uint32_t p = vertex[std::size_t(s.b0 * (cells + 1) + s.a0)];
      const std::uint32_t q = vertex[std::size_t(s.b1 * (cells + 1) + s.a1)];
      const std::uint32_t pb = bottom_vertex(s.a0, s.b0), qb = bottom_vertex(s.a1, s.b1);
      part.triangles.push_back({p, q, qb});
      part.triangles.push_back({p, qb, pb});
    }
    level.skirt_triangles = std::uint32_t(2 * sides.size());
    level.vertex_count = std::uint32_t(part.x.size()) - level.first_vertex;
    level.skirt_vertices = std::uint32_t(part.x.size()) - skirt_base;
    level.triangle_count = std::uint32_t(part.triangles.size()) - level.first_triangle;

    // Its errors against the fine mesh.
    const float scale = float(step);
    float height_error = 0, light_error = 0;
    for (const auto& ref : references) {
      const int a = std::clamp(int(std::floor(ref.u / scale)), 0, cells - 1);
      const int b = std::clamp(int(std::floor(ref.v / scale)), 0, cells - 1);
      if (!valid_cell(a, b)) continue;
      const float u = std::clamp(ref.u / scale - float(a), 0.0f, 1.0f),
                  v = std::clamp(ref.v / scale - float(b), 0.0f, 1.0f);
      const std::size_t sw = point(a, b), se = point(a + 1, b), nw = point(a, b + 1), ne = point(a + 1, b + 1);
      height_error = std::max(
          height_error, std::abs(ref.z - on_cell(lattice.z[sw], lattice.z[se], lattice.z[nw], lattice.z[ne], u, v)));
      for (std::size_t c = 0; c < 3; ++c) {
        const float coarse =
            on_cell(lattice.light[sw][c], lattice.light[se][c], lattice.light[nw][c], lattice.light[ne][c], u, v);
        light_error = std::max(light_error, std::abs(ref.light[c] - coarse) / std::max({ref.light[c], coarse, 1e-4f}));
      }
    }
    level.height_error = height_error;
    level.error =
        light_error > kLightTolerance ? std::max(height_error, float(std::hypot(cell_w, cell_h))) : height_error;
    return level;
  }
};

}  // namespace

TerrainChunks make_terrain_chunks(const Mesh& mesh, const std::vector<std::array<float, 3>>& light) {
  TerrainChunks out;
  if (mesh.triangles.empty()) return out;
  const MeshExtent extent = measure_extent(mesh);
  const std::array<float, 3>&low = extent.min, &high = extent.max;
  ChunkGrid grid;
  grid.side = std::max(1, int(std::lround(std::sqrt(double(mesh.triangles.size()) / double(kTerrainChunkTriangles)))));
  grid.low_x = low[0];
  grid.low_y = low[1];
  grid.cell_w = std::max(double(high[0]) - low[0], 1e-6) / grid.side;
  grid.cell_h = std::max(double(high[1]) - low[1], 1e-6) / grid.side;
  const std::size_t cells = std::size_t(grid.side) * std::size_t(grid.side);

  // Each triangle's owner cell (by centroid), and per cell the triangles whose box meets it.
  std::vector<std::int32_t> owner_cell(mesh.triangles.size());
  std::vector<std::vector<std::uint32_t>> overlapping(cells);
  for (std::uint32_t t = 0; t < mesh.triangles.size(); ++t) {
    const auto& ids = mesh.triangles[t];
    float cx = 0, cy = 0, x0 = std::numeric_limits<float>::max(), y0 = x0, x1 = -x0, y1 = -x0;
    for (const std::uint32_t i : ids) {
      const auto& p = mesh.positions[i];
      cx += p[0] / 3;
      cy += p[1] / 3;
      x0 = std::min(x0, p[0]);
      x1 = std::max(x1, p[0]);
      y0 = std::min(y0, p[1]);
      y1 = std::max(y1, p[1]);
    }
    owner_cell[t] = grid.cell(cy, grid.low_y, grid.cell_h) * grid.side + grid.cell(cx, grid.low_x, grid.cell_w);
    for (int j = grid.cell(y0, grid.low_y, grid.cell_h); j <= grid.cell(y1, grid.low_y, grid.cell_h); ++j)
      for (int i = grid.cell(x0, grid.low_x, grid.cell_w); i <= grid.cell(x1, grid.low_x, grid.cell_w); ++i)
        overlapping[std::size_t(j * grid.side + i)].push_back(t);
  }
  // A chunk per cell that any triangle meets.
  std::vector<std::int32_t> chunk_of(cells, -1);
  std::vector<std::uint32_t> chunk_cell;
  for (std::size_t c = 0; c < cells; ++c)
    if (!overlapping[c].empty()) {
      chunk_of[c] = std::int32_t(chunk_cell.size());
      chunk_cell.push_back(std::uint32_t(c));
    }
  std::vector<std::int32_t> owner(mesh.triangles.size());
  for (std::size_t t = 0; t < owner.size(); ++t) owner[t] = chunk_of[std::size_t(owner_cell[t])];

  const ChunkBuilder builder(mesh, light, grid, owner);
  std::vector<ChunkPart> parts(chunk_cell.size());
  std::vector<std::array<std::int32_t, 4>> neighbours(chunk_cell.size());
  tbb::parallel_for(std::size_t(0), parts.size(), [&](std::size_t k) {
    const int ci = int(chunk_cell[k]) % grid.side, cj = int(chunk_cell[k]) / grid.side;
    const auto at = [&](int i, int j) {
      return i < 0 || j < 0 || i >= grid.side || j >= grid.side ? -1 : chunk_of[std::size_t(j * grid.side + i)];
    };
    neighbours[k] = {at(ci - 1, cj), at(ci + 1, cj), at(ci, cj - 1), at(ci, cj + 1)};
    const std::array<bool, 4> has{neighbours[k][0] >= 0, neighbours[k][1] >= 0, neighbours[k][2] >= 0,
                                  neighbours[k][3] >= 0};
    parts[k] = builder.build(std::uint32_t(k), ci, cj, overlapping[chunk_cell[k]], has);
  });

  for (std::size_t k = 0; k < parts.size(); ++k) {
    ChunkPart& part = parts[k];
    const std::uint32_t vertex_base = std::uint32_t(out.x.size()), triangle_base = std::uint32_t(out.triangles.size());
    TerrainChunks::Chunk chunk;
    chunk.first_level = std::uint32_t(out.levels.size());
    chunk.level_count = std::uint32_t(part.levels.size());
    chunk.first_borrowed = std::uint32_t(out.borrowed.size());
    chunk.borrowed_count = std::uint32_t(part.borrowed.size());
    chunk.neighbours = neighbours[k];
    chunk.low = part.low;
    chunk.high = part.high;
    for (TerrainChunks::Level level : part.levels) {
      level.first_vertex += vertex_base;
      level.first_triangle += triangle_base;
      out.levels.push_back(level);
    }
    for (TerrainChunks::Borrowed b : part.borrowed) {
      for (std::uint32_t& i : b.ids) i += vertex_base;
      out.borrowed.push_back(b);
    }
    // Each level's triangles index its own vertices: offset by the chunk's base.
    for (auto t : part.triangles) {
      for (std::uint32_t& i : t) i += vertex_base;
      out.triangles.push_back(t);
    }
    out.x.insert(out.x.end(), part.x.begin(), part.x.end());
    out.y.insert(out.y.end(), part.y.begin(), part.y.end());
    out.z.insert(out.z.end(), part.z.begin(), part.z.end());
    out.light_r.insert(out.light_r.end(), part.r.begin(), part.r.end());
    out.light_g.insert(out.light_g.end(), part.g.begin(), part.g.end());
    out.light_b.insert(out.light_b.end(), part.b.begin(), part.b.end());
    out.chunks.push_back(chunk);
    part = ChunkPart{};
  }
  return out;
}

}  // namespace wangscape
