// What the Poisson fill (generator/poisson_tiles.h) shares between its files: the content model
// (who owns which part of a tile: interiors, edge strips, corner squares), the points of a fill
// under construction, the classes' distances, the pairs of points that can meet in some tiling,
// and the fill's stages: dart throwing (poisson_darts.cpp), relaxation in context
// (poisson_relax.cpp) and the progressive order (poisson_ranks.cpp). Internal to generator/.
#pragma once

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "generator/poisson_tiles.h"
#include "generator/tiling.h"

namespace wangscape::poisson_detail {

// ---- hashing and random numbers (portable: the same bytes with every standard library) ----

// SplitMix64's finalizer alone (core/hash.h's mix64 without its golden-ratio step first): every
// draw of a fill is keyed through it, so it stays as it is.
inline std::uint64_t finalize64(std::uint64_t z) {
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

inline std::uint64_t hash_combine(std::uint64_t a, std::uint64_t b) {
  return finalize64(a * 0x9e3779b97f4a7c15ULL + b + 1);
}

struct Rng {
  std::uint64_t state;
  std::uint64_t next() { return finalize64(state += 0x9e3779b97f4a7c15ULL); }
  double uniform() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }  // [0, 1)
  std::size_t below(std::size_t n) { return static_cast<std::size_t>(next() % n); }
};

struct Vec2 {
  double x = 0, y = 0;
};
inline Vec2 operator+(Vec2 a, Vec2 b) { return {a.x + b.x, a.y + b.y}; }
inline Vec2 operator-(Vec2 a, Vec2 b) { return {a.x - b.x, a.y - b.y}; }
inline Vec2 operator*(double s, Vec2 a) { return {s * a.x, s * a.y}; }
inline double dot(Vec2 a, Vec2 b) { return a.x * b.x + a.y * b.y; }
inline double norm2(Vec2 a) { return dot(a, a); }

struct Rect {
  double x0 = 0, y0 = 0, x1 = 0, y1 = 0;  // [x0, x1) x [y0, y1)
  bool contains(Vec2 p) const { return p.x >= x0 && p.x < x1 && p.y >= y0 && p.y < y1; }
};

// The 8 neighbour directions, and their index 0..8 in a 3 x 3 block (4 = the tile itself).
inline constexpr std::array<std::array<int, 2>, 8> kDirections = {
    {{-1, -1}, {0, -1}, {1, -1}, {-1, 0}, {1, 0}, {-1, 1}, {0, 1}, {1, 1}}};
inline int block_index(int dx, int dy) { return (dy + 1) * 3 + (dx + 1); }

// Whether tile-local q lies within `reach` of the side or corner of direction (dx, dy), so that a
// point of the tile there can be closer than `reach`.
inline bool near_side(Vec2 q, int dx, int dy, double reach) {
  const bool x_ok = dx == 0 || (dx < 0 ? q.x < reach : q.x > 1.0 - reach);
  const bool y_ok = dy == 0 || (dy < 0 ? q.y < reach : q.y > 1.0 - reach);
  return x_ok && y_ok;
}

// Keys of an edge as seen from the two tiles that share it: edge color and end-corner colors.
using EdgeKey = std::array<int, 3>;
inline EdgeKey south_key(const Tile& t) { return {t.s(), t.sw(), t.se()}; }
inline EdgeKey north_key(const Tile& t) { return {t.n(), t.nw(), t.ne()}; }
inline EdgeKey west_key(const Tile& t) { return {t.w(), t.sw(), t.nw()}; }
inline EdgeKey east_key(const Tile& t) { return {t.e(), t.se(), t.ne()}; }

// ---- content classes: who owns which part of a tile ----

inline constexpr double kEdgeEpsilon = 1e-7;  // keeps points strictly inside their half-open regions

enum class ClassKind : std::uint8_t { interior, horizontal_strip, vertical_strip, vertex, corner_square };

struct ContentClass {
  ClassKind kind = ClassKind::interior;
  Rect region;              // class-local: where relaxation may move its points
  std::vector<Vec2> avoid;  // tile corners the tight radius may not cross (plain edge sets), class-local
  std::vector<int> groups;  // the (class, region) groups the class appears in
};

// One part (3 x 3 region) of the tiles that share a class there: where it sits in the tile,
// which tiles hold it, and which tiles can sit next to those in each direction.
struct Group {
  int cls = -1;
  int region = 0;
  Vec2 offset;     // tile-local = class-local + offset
  Rect tile_rect;  // tile-local part of the class region these tiles hold
  std::vector<std::uint16_t> holders;
  std::array<std::vector<std::uint16_t>, 9> around;  // by block_index; [4] unused
};

// A point as one tile holds it.
struct Held {
  std::uint32_t point = 0;
  Vec2 q;  // tile-local
  std::int8_t ox = 0, oy = 0;
  std::uint8_t species = 0;
};
struct Content {
  std::vector<std::vector<Held>> tiles;   // what each tile holds
  std::vector<std::vector<Held>> groups;  // the points of each group (as its holders hold them)
};

class ContentModel {
 public:
  // corner_width: half-side of the vertex squares of sets with corner colors (else = shared_width).
  ContentModel(const TileSet& set, const TileAdjacency& adjacency, double shared_width, double corner_width);

  double shared_width() const { return w_; }
  // Area (tile sides^2) of region 0..8 as region_of cuts a tile.
  double region_area(int region) const {
    if (region == 4) return (1.0 - 2.0 * w_) * (1.0 - 2.0 * w_) - 4.0 * (wc_ - w_) * (wc_ - w_);
    if (region % 2 == 1) return w_ * (1.0 - 2.0 * wc_);  // a strip
    return wc_ * wc_;                                    // a corner square
  }
  // Area of all the parts of class `cls` (both sides of a strip, the four quarters of a vertex).
  double class_area(int cls) const {
    double area = 0;
    for (int g : classes_[static_cast<std::size_t>(cls)].groups) area += region_area(group(g).region);
    return area;
  }
  std::size_t tile_count() const { return tile_count_; }
  const std::vector<ContentClass>& classes() const { return classes_; }
  const Group& group(int g) const { return groups_[static_cast<std::size_t>(g)]; }
  std::size_t group_count() const { return groups_.size(); }

  // Corner squares (half-side wc) first, then strips (width w), then the interior.
  int region_of(Vec2 q) const {
    const int cx = q.x < wc_ ? 0 : (q.x < 1.0 - wc_ ? 1 : 2);
    const int cy = q.y < wc_ ? 0 : (q.y < 1.0 - wc_ ? 1 : 2);
    if (cx != 1 && cy != 1) return cy * 3 + cx;
    const int rx = q.x < w_ ? 0 : (q.x < 1.0 - w_ ? 1 : 2);
    const int ry = q.y < w_ ? 0 : (q.y < 1.0 - w_ ? 1 : 2);
    return ry * 3 + rx;
  }
  int group_at(std::size_t tile, Vec2 q) const { return group_of_[tile * 9 + static_cast<std::size_t>(region_of(q))]; }

  // The group of class `cls` that holds class-local position p, or -1.
  int group_holding(int cls, Vec2 p) const {
    for (int g : classes_[static_cast<std::size_t>(cls)].groups)
      if (group(g).tile_rect.contains(p + group(g).offset)) return g;
    return -1;
  }

  // Where a tight radius lets a point of class `cls` be (plain edge sets: outside the quarter
  // discs of radius tight around the tile corners).
  bool tight_allows(int cls, Vec2 p, double tight) const {
    for (const Vec2& v : classes_[static_cast<std::size_t>(cls)].avoid)
      if (norm2(p - v) < tight * tight) return false;
    return true;
  }

  // Nearest allowed class-local position to p.
  Vec2 clamp(int cls, Vec2 p, double tight) const {
    const ContentClass& c = classes_[static_cast<std::size_t>(cls)];
    p.x = std::clamp(p.x, c.region.x0 + kEdgeEpsilon, c.region.x1 - kEdgeEpsilon);
    p.y = std::clamp(p.y, c.region.y0 + kEdgeEpsilon, c.region.y1 - kEdgeEpsilon);
    for (const Vec2& v : c.avoid) {
      const Vec2 r = p - v;
      const double len = std::sqrt(norm2(r));
      if (len < tight) {
        // Out of the quarter disc, along the ray from the corner (or the diagonal if at it).
        const Vec2 dir = len > 1e-12 ? (1.0 / len) * r
                                     : (1.0 / std::sqrt(2.0)) * Vec2{v.x < 0.5 ? 1.0 : -1.0, v.y < 0.5 ? 1.0 : -1.0};
        p = v + (tight * (1.0 + 1e-9) + kEdgeEpsilon) * dir;
      }
    }
    return p;
  }

 private:
  double w_, wc_;
  std::size_t tile_count_;
  std::vector<ContentClass> classes_;
  std::vector<Group> groups_;
  std::vector<int> group_of_;  // [tile * 9 + region]
};

// The class points of a set under construction.
struct PointSet {
  std::vector<Vec2> local;  // class-local positions
  std::vector<int> cls;
  std::vector<std::uint8_t> species;
};

// Adds point p at tile-local q to group g and every tile that holds it.
void add_to_content(const ContentModel& model, int g, std::uint32_t p, Vec2 q, std::uint8_t species, Content& content);
// The content of every tile and group from the class points.
void build_content(const ContentModel& model, const PointSet& points, Content& content);

// ---- the classes (species) of a fill ----

// Per species: its target count, radii and the minimum centre distance to every species. One
// species (no PoissonFillOptions::classes) is the single-class fill: every distance the dart d.
struct SpeciesTable {
  std::size_t count = 1;
  std::vector<double> distance2;  // [a * count + b]: squared minimum centre distance (tile sides)
  std::vector<double> reach;      // per species: its largest distance to any species
  std::vector<double> per_tile;   // target points per tile
  std::vector<double> packing, tight;
  std::vector<char> edge_objects;
  std::vector<int> variants;
  std::vector<std::size_t> order;  // the order they are thrown in: the widest own spacing first
  double widest_spacing = 0;       // the widest own spacing of a class that is not edge objects
  // [a * count + b]: the distance over the dart distance of the whole density (1 for one class):
  // relaxation raises every distance by one factor.
  std::vector<double> weight;
  std::vector<double> row_weight;  // per species: its largest weight
  double distance(std::size_t a, std::size_t b) const { return std::sqrt(distance2[a * count + b]); }
};

// ---- points that meet across edges and corners ----

// A pair of points that can meet in some tiling: relative position local[i] - local[j] + k.
struct Pair {
  std::uint32_t i = 0, j = 0;
  std::int8_t kx = 0, ky = 0;
  auto operator<=>(const Pair&) const = default;
};

// Visits every (point a in group holders, point b of a tile that can be there) meeting within
// reach_of(a), once per group: f(a, b, shift) with b's tile-local position + shift relative to a's.
template <class Reach, class F>
void for_each_meeting(const ContentModel& model, const Content& content, std::size_t g, Reach reach_of, F&& f) {
  const Group& group = model.group(static_cast<int>(g));
  for (const Held& a : content.groups[g]) {
    const double reach = reach_of(a), r2 = reach * reach;
    for (std::uint16_t t : group.holders)
      for (const Held& b : content.tiles[t])
        if (b.point != a.point && norm2(b.q - a.q) < r2) f(a, b, Vec2{});
    for (const auto& [dx, dy] : kDirections) {
      if (!near_side(a.q, dx, dy, reach)) continue;
      const Vec2 shift{static_cast<double>(dx), static_cast<double>(dy)};
      for (std::uint16_t u : group.around[static_cast<std::size_t>(block_index(dx, dy))])
        for (const Held& b : content.tiles[u])
          if (norm2(b.q + shift - a.q) < r2) f(a, b, shift);
    }
  }
}

// The smallest distance between two points meeting in any tiling, over their classes' weight
// (the distance itself for one class), or `limit` if none is smaller.
double min_meeting_distance(const ContentModel& model, const Content& content, const SpeciesTable& species,
                            double limit);

// Every pair that can meet within reach_of(one of them), both orders, sorted, without duplicates.
template <class Reach>
std::vector<Pair> meeting_pairs(const ContentModel& model, const Content& content, Reach reach_of) {
  std::vector<std::vector<Pair>> per_group(model.group_count());
  tbb::parallel_for(std::size_t{0}, model.group_count(), [&](std::size_t g) {
    for_each_meeting(model, content, g, reach_of, [&](const Held& a, const Held& b, Vec2 shift) {
      if (a.point == b.point) return;  // a point and its own replica are a tile side apart
      // a.q - (b.q + shift) = local_a - local_b + (o_a - o_b - shift)
      per_group[g].push_back({a.point, b.point, static_cast<std::int8_t>(a.ox - b.ox - static_cast<int>(shift.x)),
                              static_cast<std::int8_t>(a.oy - b.oy - static_cast<int>(shift.y))});
    });
  });
  std::vector<Pair> pairs;
  for (auto& v : per_group) pairs.insert(pairs.end(), v.begin(), v.end());
  for (std::size_t n = pairs.size(), k = 0; k < n; ++k)
    pairs.push_back(
        {pairs[k].j, pairs[k].i, static_cast<std::int8_t>(-pairs[k].kx), static_cast<std::int8_t>(-pairs[k].ky)});
  std::sort(pairs.begin(), pairs.end());
  pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
  return pairs;
}

// ---- the fill's stages ----

// Dart throwing (poisson_darts.cpp).

// One pass of dart throwing: the regions it throws into (bit r = region r of region_of) and
// whether the class quotas hold.
struct DartPass {
  unsigned regions = 0;
  bool capped = true;
};
// Per (content class, species), the most points the capped passes may put in it.
std::vector<double> class_quotas(const ContentModel& model, const PoissonFillOptions& options,
                                 const SpeciesTable& species);
// Round-robin dart throwing (Shade 2002) over `passes`, species by species, into points and content.
void throw_darts(const ContentModel& model, const PoissonFillOptions& options, const SpeciesTable& species,
                 std::span<const DartPass> passes, std::span<const double> quota, PointSet& points, Content& content);

// Relaxation in context (poisson_relax.cpp).

// What relaxation reads: the fill's model, neighbours, options and classes.
struct RelaxContext {
  const ContentModel& model;
  const TileAdjacency& adjacency;
  const PoissonFillOptions& options;
  const SpeciesTable& species;
  // Whether relaxation leaves point p where it is: edge objects stay (their place across the edge
  // is chosen).
  bool stays(const PointSet& points, std::size_t p) const { return species.edge_objects[points.species[p]]; }
  // Where relaxation may move point p.
  Vec2 moved(const PointSet& points, std::size_t p, Vec2 to) const {
    return stays(points, p) ? points.local[p] : model.clamp(points.cls[p], to, species.tight[points.species[p]]);
  }
};

// A fixed sample tiling for the nearest-neighbour spread (the lattice guard).
struct SampleTiling {
  Tiling tiling;
  bool usable = false;
};
SampleTiling sample_tiling(const TileSet& set, std::uint64_t seed);
// The spread (std / mean) of nearest-neighbour distances over the sample tiling (NaN without one).
double nn_spread(const SampleTiling& sample, const Content& content);
// Up to options.relax_rounds rounds from the distance d_start (raised towards cap_d while rounds
// keep it), each undone when it cannot keep its bound or lines the sample up like a lattice;
// counts the rounds and their figures in `report`.
void relax_in_context(const RelaxContext& ctx, const SampleTiling& sample, double d_start, double cap_d,
                      PointSet& points, Content& content, PoissonFillReport& report);

// The progressive order (poisson_ranks.cpp): per point, its rank in [0, 1) within its species;
// the points of rank < d are Poisson at d x the density.
std::vector<float> progressive_ranks(const ContentModel& model, const Content& content, const PointSet& points,
                                     const SpeciesTable& species, const PoissonFillOptions& options);

}  // namespace wangscape::poisson_detail
