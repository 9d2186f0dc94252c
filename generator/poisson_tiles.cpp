#include "generator/poisson_tiles.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <numbers>
#include <optional>
#include <string>

#include "core/number_text.h"
#include "generator/point_metrics.h"
#include "generator/tiling.h"
#include "generator/tiling_preview.h"

namespace wangscape {

namespace {

// ---- hashing and random numbers (portable: the same bytes with every standard library) ----

std::uint64_t mix64(std::uint64_t z) {
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

std::uint64_t hash_combine(std::uint64_t a, std::uint64_t b) { return mix64(a * 0x9e3779b97f4a7c15ULL + b + 1); }

struct Rng {
  std::uint64_t state;
  std::uint64_t next() { return mix64(state += 0x9e3779b97f4a7c15ULL); }
  double uniform() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }  // [0, 1)
  std::size_t below(std::size_t n) { return static_cast<std::size_t>(next() % n); }
};

struct Vec2 {
  double x = 0, y = 0;
};
Vec2 operator+(Vec2 a, Vec2 b) { return {a.x + b.x, a.y + b.y}; }
Vec2 operator-(Vec2 a, Vec2 b) { return {a.x - b.x, a.y - b.y}; }
Vec2 operator*(double s, Vec2 a) { return {s * a.x, s * a.y}; }
double dot(Vec2 a, Vec2 b) { return a.x * b.x + a.y * b.y; }
double norm2(Vec2 a) { return dot(a, a); }

struct Rect {
  double x0 = 0, y0 = 0, x1 = 0, y1 = 0;  // [x0, x1) x [y0, y1)
  bool contains(Vec2 p) const { return p.x >= x0 && p.x < x1 && p.y >= y0 && p.y < y1; }
};

// The 8 neighbour directions, and their index 0..8 in a 3 x 3 block (4 = the tile itself).
constexpr std::array<std::array<int, 2>, 8> kDirections = {
    {{-1, -1}, {0, -1}, {1, -1}, {-1, 0}, {1, 0}, {-1, 1}, {0, 1}, {1, 1}}};
int block_index(int dx, int dy) { return (dy + 1) * 3 + (dx + 1); }

// Whether tile-local q lies within `reach` of the side or corner of direction (dx, dy), so that a
// point of the tile there can be closer than `reach`.
bool near_side(Vec2 q, int dx, int dy, double reach) {
  const bool x_ok = dx == 0 || (dx < 0 ? q.x < reach : q.x > 1.0 - reach);
  const bool y_ok = dy == 0 || (dy < 0 ? q.y < reach : q.y > 1.0 - reach);
  return x_ok && y_ok;
}

// Keys of an edge as seen from the two tiles that share it: edge color and end-corner colors.
using EdgeKey = std::array<int, 3>;
EdgeKey south_key(const Tile& t) { return {t.s(), t.sw(), t.se()}; }
EdgeKey north_key(const Tile& t) { return {t.n(), t.nw(), t.ne()}; }
EdgeKey west_key(const Tile& t) { return {t.w(), t.sw(), t.nw()}; }
EdgeKey east_key(const Tile& t) { return {t.e(), t.se(), t.ne()}; }

// ---- content classes: who owns which part of a tile ----

constexpr double kEdgeEpsilon = 1e-7;  // keeps points strictly inside their half-open regions

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
  ContentModel(const TileSet& set, const TileAdjacency& adjacency, double shared_width, double corner_width)
      : w_(shared_width), wc_(set.has_corners ? corner_width : shared_width), tile_count_(set.tiles.size()) {
    std::map<std::array<int, 4>, int> class_by_key;
    auto class_for = [&](std::array<int, 4> key, ClassKind kind, Rect region, std::vector<Vec2> avoid) {
      auto [it, inserted] = class_by_key.emplace(key, static_cast<int>(classes_.size()));
      if (inserted) classes_.push_back({kind, region, set.has_corners ? std::vector<Vec2>{} : std::move(avoid), {}});
      return it->second;
    };
    const double w = w_, wc = wc_;
    // New darts go to the class of the region they land in (cuts at w), but relaxation may move a
    // point a margin m past that line: hard walls between classes would line points up along them.
    const double m = 0.5 * w;
    const Rect whole{0.0, 0.0, 1.0, 1.0};
    const std::vector<Vec2> tile_corners = {{0, 0}, {1, 0}, {0, 1}, {1, 1}};
    group_of_.assign(tile_count_ * 9, -1);
    std::map<std::pair<int, int>, int> group_by_key;
    for (std::size_t t = 0; t < tile_count_; ++t) {
      const Tile& tile = set.tiles[t];
      for (int ry = 0; ry < 3; ++ry)
        for (int rx = 0; rx < 3; ++rx) {
          int cls = -1;
          Vec2 offset;
          if (rx == 1 && ry == 1) {
            cls = class_for({0, static_cast<int>(t), 0, 0}, ClassKind::interior, whole, tile_corners);
          } else if (rx == 1) {
            const EdgeKey key = ry == 0 ? south_key(tile) : north_key(tile);
            cls = class_for({1, key[0], key[1], key[2]}, ClassKind::horizontal_strip,
                            Rect{wc - m, -w - m, 1.0 - wc + m, w + m}, {{0, 0}, {1, 0}});
            offset = {0.0, ry == 0 ? 0.0 : 1.0};
          } else if (ry == 1) {
            const EdgeKey key = rx == 0 ? west_key(tile) : east_key(tile);
            cls = class_for({2, key[0], key[1], key[2]}, ClassKind::vertical_strip,
                            Rect{-w - m, wc - m, w + m, 1.0 - wc + m}, {{0, 0}, {0, 1}});
            offset = {rx == 0 ? 0.0 : 1.0, 0.0};
          } else {
            const int corner_slot = ry == 0 ? (rx == 0 ? kSW : kSE) : (rx == 0 ? kNW : kNE);
            const Vec2 vertex{rx == 0 ? 0.0 : 1.0, ry == 0 ? 0.0 : 1.0};
            if (set.has_corners) {
              // The square around a vertex belongs to the vertex's color: the four tiles that
              // meet there hold its four quarters.
              cls = class_for({3, tile.colors[static_cast<std::size_t>(corner_slot)], 0, 0}, ClassKind::vertex,
                              Rect{-wc - m, -wc - m, wc + m, wc + m}, {});
              offset = vertex;
            } else {
              const int horizontal = ry == 0 ? tile.s() : tile.n();
              const int vertical = rx == 0 ? tile.w() : tile.e();
              const Rect square{rx == 0 ? 0.0 : 1.0 - w - m, ry == 0 ? 0.0 : 1.0 - w - m, rx == 0 ? w + m : 1.0,
                                ry == 0 ? w + m : 1.0};
              cls = class_for({4 + corner_slot, horizontal, vertical, 0}, ClassKind::corner_square, square, {vertex});
            }
          }
          // The part of the class region this tile holds: its region shifted into the tile, cut
          // to the tile (two-sided strips and vertex squares are shared with the tiles across).
          const Rect& cr = classes_[static_cast<std::size_t>(cls)].region;
          const Rect tile_rect{std::max(0.0, cr.x0 + offset.x), std::max(0.0, cr.y0 + offset.y),
                               std::min(1.0, cr.x1 + offset.x), std::min(1.0, cr.y1 + offset.y)};
          const int region = ry * 3 + rx;
          auto [it, inserted] = group_by_key.emplace(std::pair{cls, region}, static_cast<int>(groups_.size()));
          if (inserted) {
            Group g;
            g.cls = cls;
            g.region = region;
            g.offset = offset;
            g.tile_rect = tile_rect;
            groups_.push_back(std::move(g));
            classes_[static_cast<std::size_t>(cls)].groups.push_back(it->second);
          }
          groups_[static_cast<std::size_t>(it->second)].holders.push_back(static_cast<std::uint16_t>(t));
          group_of_[t * 9 + static_cast<std::size_t>(region)] = it->second;
        }
    }
    // Holders share most neighbours (complete-edge-8: 512 holders of 512 each): each is
    // collected once, then sorted, instead of sorting every repeat.
    std::vector<char> seen(tile_count_, 0);
    for (Group& g : groups_)
      for (const auto& [dx, dy] : kDirections) {
        std::vector<std::uint16_t>& around = g.around[static_cast<std::size_t>(block_index(dx, dy))];
        for (std::uint16_t t : g.holders)
          for (std::uint16_t u : adjacency.neighbours(t, dx, dy))
            if (!seen[u]) seen[u] = 1, around.push_back(u);
        for (std::uint16_t u : around) seen[u] = 0;
        std::sort(around.begin(), around.end());
      }
  }

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

void add_to_content(const ContentModel& model, int g, std::uint32_t p, Vec2 q, std::uint8_t species, Content& content) {
  const Group& group = model.group(g);
  const Held h{p, q, static_cast<std::int8_t>(group.offset.x), static_cast<std::int8_t>(group.offset.y), species};
  content.groups[static_cast<std::size_t>(g)].push_back(h);
  for (std::uint16_t t : group.holders) content.tiles[t].push_back(h);
}

void build_content(const ContentModel& model, const PointSet& points, Content& content) {
  content.tiles.assign(model.tile_count(), {});
  content.groups.assign(model.group_count(), {});
  for (std::size_t p = 0; p < points.local.size(); ++p) {
    const int g = model.group_holding(points.cls[p], points.local[p]);
    if (g < 0) continue;  // cannot happen: positions are clamped into their class region
    add_to_content(model, g, static_cast<std::uint32_t>(p), points.local[p] + model.group(g).offset, points.species[p],
                   content);
  }
}

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

constexpr double kOwnSpacingShare = 0.85;

SpeciesTable make_species_table(const PoissonFillOptions& options, double dart_d, double tight) {
  SpeciesTable table;
  if (options.classes.empty()) {
    table.distance2 = {dart_d * dart_d};
    table.weight = {dart_d / dart_d};
    table.row_weight = table.weight;
    table.reach = {dart_d};
    table.per_tile = {static_cast<double>(options.points_per_tile)};
    table.packing = {0.5 * dart_d};
    table.tight = {tight};
    table.edge_objects = {0};
    table.variants = {options.variants};
    table.order = {0};
    return table;
  }
  const std::vector<PoissonClass>& classes = options.classes;
  const std::size_t n = classes.size();
  table.count = n;
  double total_share = 0;
  for (const PoissonClass& c : classes) total_share += c.share;
  std::vector<double> own(n);
  for (std::size_t s = 0; s < n; ++s) {
    const PoissonClass& c = classes[s];
    table.per_tile.push_back(options.points_per_tile * c.share / total_share);
    // Default packing: the union is Poisson at the total density, as one class is.
    table.packing.push_back(c.packing_radius > 0 ? c.packing_radius : 0.5 * dart_d);
    table.tight.push_back(c.tight_radius > 0 ? c.tight_radius : options.tight_fraction * table.packing[s]);
    table.edge_objects.push_back(c.edge_objects ? 1 : 0);
    table.variants.push_back(c.variants);
    // Each class is Poisson on its own at its own density (Wei 2010's multi-class rule), a little
    // below dart_rho: the union's bound jams the classes first. Measured (cohen8, 40 points per
    // tile, shares 0.7 / 0.25 / 0.05 with a 0.08 packing radius, seeds 1-3): 82 / 84 / 80 % of the
    // targets at 1.0 x dart_rho, 95 / 96 / 96 % at 0.85.
    own[s] = std::max(kOwnSpacingShare * options.dart_rho * hexagonal_spacing(1.0, table.per_tile[s]),
                      2.0 * table.packing[s]);
  }
  auto exclusion = [&](std::size_t a, std::size_t b) {
    return b < classes[a].exclusion.size() ? classes[a].exclusion[b] : 0.0;
  };
  table.distance2.resize(n * n);
  table.reach.assign(n, 0.0);
  for (std::size_t a = 0; a < n; ++a)
    for (std::size_t b = 0; b < n; ++b) {
      const double d = std::max(a == b ? own[a] : table.packing[a] + table.packing[b],
                                table.packing[a] + table.packing[b] + std::max(exclusion(a, b), exclusion(b, a)));
      table.distance2[a * n + b] = d * d;
      table.weight.push_back(d / dart_d);
      if (b == 0) table.row_weight.push_back(0.0);
      table.row_weight[a] = std::max(table.row_weight[a], d / dart_d);
      table.reach[a] = std::max(table.reach[a], d);
    }
  for (std::size_t s = 0; s < n; ++s)
    if (!table.edge_objects[s]) table.widest_spacing = std::max(table.widest_spacing, table.distance(s, s));
  table.order.resize(n);
  for (std::size_t s = 0; s < n; ++s) table.order[s] = s;
  std::stable_sort(table.order.begin(), table.order.end(),
                   [&](std::size_t a, std::size_t b) { return own[a] > own[b]; });
  return table;
}

// Whether tile-local q of group g, a point of species s, keeps its distance to every point of
// every tile that holds g and of every tile that can sit next to those.
bool keeps_distance(const ContentModel& model, const Content& content, int g, Vec2 q, const SpeciesTable& species,
                    std::size_t s) {
  const Group& group = model.group(g);
  const double* d2 = &species.distance2[s * species.count];
  for (std::uint16_t t : group.holders)
    for (const Held& h : content.tiles[t])
      if (norm2(h.q - q) < d2[h.species]) return false;
  for (const auto& [dx, dy] : kDirections) {
    if (!near_side(q, dx, dy, species.reach[s])) continue;
    const Vec2 shift{static_cast<double>(dx), static_cast<double>(dy)};
    for (std::uint16_t u : group.around[static_cast<std::size_t>(block_index(dx, dy))])
      for (const Held& h : content.tiles[u])
        if (norm2(h.q + shift - q) < d2[h.species]) return false;
  }
  return true;
}

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
                            double limit) {
  return tbb::parallel_reduce(
      tbb::blocked_range<std::size_t>(0, model.group_count()), limit,
      [&](const tbb::blocked_range<std::size_t>& range, double best) {
        for (std::size_t g = range.begin(); g != range.end(); ++g)
          for_each_meeting(
              model, content, g, [&](const Held& a) { return limit * species.row_weight[a.species]; },
              [&](const Held& a, const Held& b, Vec2 shift) {
                if (a.point == b.point && shift.x == 0 && shift.y == 0) return;
                best = std::min(
                    best, std::sqrt(norm2(b.q + shift - a.q)) / species.weight[a.species * species.count + b.species]);
              });
        return best;
      },
      [](double a, double b) { return std::min(a, b); });
}

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

// ---- dart throwing (Shade 2002) ----

// Per class, the most points the capped dart passes may put in it: no cap for interiors; for
// shared classes their area's share of the target count, rounded at random. Every holder's darts
// land in a shared class, so without a cap the strips and corner squares jam long before the
// interiors fill and the interiors next to them starve. Strips take 0.9 of their share, as the
// interiors do not quite reach the target density (measured over 64 seeds, cohen8: edge density
// 1.02 after darts and 1.01 after relaxation, against 1.09 / 1.04 with 0.95 of it).
// With species, quotas are per (content class, species): [c * species.count + s]; edge objects
// live in the strips only, uncapped.
std::vector<double> class_quotas(const ContentModel& model, const PoissonFillOptions& options,
                                 const SpeciesTable& species) {
  constexpr double kStripShare = 0.9, kCornerShare = 1.0;
  std::vector<double> quota(model.classes().size() * species.count, std::numeric_limits<double>::infinity());
  Rng rng{hash_combine(options.seed, 0x9a07a)};
  for (std::size_t c = 0; c < model.classes().size(); ++c) {
    const ClassKind kind = model.classes()[c].kind;
    if (kind == ClassKind::interior) continue;
    const double share = kind == ClassKind::corner_square ? kCornerShare : kStripShare;
    for (std::size_t s = 0; s < species.count; ++s)
      if (!species.edge_objects[s])
        quota[c * species.count + s] =
            std::floor(share * model.class_area(static_cast<int>(c)) * species.per_tile[s] + rng.uniform());
  }
  return quota;
}

// The regions (bits of region_of) a species' darts may land in: edge objects only the strips.
constexpr unsigned kStripRegions = 0b010101010u, kAllRegions = 0b111111111u;
unsigned species_regions(const SpeciesTable& species, std::size_t s) {
  return species.edge_objects[s] ? kStripRegions : kAllRegions;
}

// Edge objects: the tight disc crosses the edge of the strip the point is in and no tile corner.
bool edge_object_allows(int region, Vec2 q, double tight) {
  const double to_edge = region == 1 ? q.y : region == 7 ? 1.0 - q.y : region == 3 ? q.x : 1.0 - q.x;
  if (to_edge >= tight) return false;
  for (const Vec2 corner : {Vec2{0, 0}, Vec2{1, 0}, Vec2{0, 1}, Vec2{1, 1}})
    if (norm2(q - corner) < tight * tight) return false;
  return true;
}

// One pass of dart throwing: the regions it throws into (bit r = region r of region_of) and
// whether the class quotas hold.
struct DartPass {
  unsigned regions = 0;
  bool capped = true;
};

// Round-robin dart throwing (Shade 2002): tiles are visited in turn, each visit throws up to
// darts_per_visit darts until one lands (keeps distance d in every configuration); a tile is
// done with a pass when it holds its share of the target count in the pass's regions (by area)
// or a visit lands nothing. The passes go from the most shared regions to everywhere: shared
// points must avoid the interiors of every tile that holds them, so thrown together with the
// interiors they would starve (Cohen 2003, Fig. 9); thrown first, they do not.
// Several species (classes): one after the other, the widest-spaced first, each with every pass (the
// sparse ones starve at the tile borders otherwise: cohen8 with grass, flowers and boulders, 40
// points per tile, the flowers' edge / corner density was 0.80 / 0.48 of the interior's with the
// species taken in turn at each visit of a tile, 0.99 / 0.84 one after the other).
void throw_darts(const ContentModel& model, const PoissonFillOptions& options, const SpeciesTable& species,
                 std::span<const DartPass> passes, std::span<const double> quota, PointSet& points, Content& content) {
  Rng rng{hash_combine(options.seed, 0xda27)};
  const std::size_t tile_count = model.tile_count(), n = species.count;
  std::vector<int> class_count(model.classes().size() * n, 0);
  for (const std::size_t s : species.order) {
    const auto id_species = static_cast<std::uint8_t>(s);
    std::vector<std::array<std::size_t, 9>> region_count(tile_count, std::array<std::size_t, 9>{});
    double species_area = 0;  // the whole tile, or the strips for edge objects
    for (int r = 0; r < 9; ++r)
      if ((species_regions(species, s) >> r) & 1u) species_area += model.region_area(r);
    for (const DartPass& pass : passes) {
      const unsigned regions = pass.regions & species_regions(species, s);
      if (regions == 0) continue;
      auto in_pass = [regions](int region) { return ((regions >> region) & 1u) != 0; };
      double area = 0;
      for (int r = 0; r < 9; ++r)
        if (in_pass(r)) area += model.region_area(r);
      const auto target = static_cast<std::size_t>(
          std::lround(species.per_tile[s] * (species.edge_objects[s] ? area / species_area : area)));
      std::vector<bool> saturated(tile_count, false);
      for (bool any_needy = true; any_needy;) {
        any_needy = false;
        for (std::size_t t = 0; t < tile_count; ++t) {
          std::size_t have = 0;
          for (int r = 0; r < 9; ++r)
            if (in_pass(r)) have += region_count[t][static_cast<std::size_t>(r)];
          if (saturated[t] || have >= target) continue;
          any_needy = true;
          bool landed = false;
          for (int dart = 0; dart < options.darts_per_visit && !landed; ++dart) {
            Vec2 q{rng.uniform(), rng.uniform()};
            while (!in_pass(model.region_of(q))) q = {rng.uniform(), rng.uniform()};
            const int g = model.group_at(t, q);
            const Group& group = model.group(g);
            const auto cls = static_cast<std::size_t>(group.cls) * n + s;
            if (pass.capped && class_count[cls] >= quota[cls]) continue;
            if (!model.tight_allows(group.cls, q - group.offset, species.tight[s])) continue;
            if (species.edge_objects[s] && !edge_object_allows(group.region, q, species.tight[s])) continue;
            if (!keeps_distance(model, content, g, q, species, s)) continue;
            const auto id = static_cast<std::uint32_t>(points.local.size());
            points.local.push_back(q - group.offset);
            points.cls.push_back(group.cls);
            points.species.push_back(id_species);
            ++class_count[cls];
            add_to_content(model, g, id, q, id_species, content);
            for (std::uint16_t holder : group.holders) ++region_count[holder][static_cast<std::size_t>(group.region)];
            landed = true;
          }
          if (!landed) saturated[t] = true;
        }
      }
    }
  }
}

// ---- relaxation in context (Cohen 2003, section 3.3) ----

// A random valid 3 x 3 neighbourhood around `center`: tiles by block_index, -1 where no tile fits.
std::array<int, 9> random_context(const TileAdjacency& adjacency, std::size_t center, Rng& rng) {
  std::array<int, 9> block{};
  for (int attempt = 0; attempt < 16; ++attempt) {
    block.fill(-1);
    block[4] = static_cast<int>(center);
    bool sides_ok = true;
    for (const auto& [dx, dy] : kDirections) {
      if (dx != 0 && dy != 0) continue;
      const auto list = adjacency.neighbours(center, dx, dy);
      if (list.empty()) {
        sides_ok = false;
        continue;
      }
      block[static_cast<std::size_t>(block_index(dx, dy))] = list[rng.below(list.size())];
    }
    bool corners_ok = true;
    for (const auto& [dx, dy] : kDirections) {
      if (dx == 0 || dy == 0) continue;
      const int vertical = block[static_cast<std::size_t>(block_index(0, dy))];
      const int horizontal = block[static_cast<std::size_t>(block_index(dx, 0))];
      if (vertical < 0 || horizontal < 0) {
        corners_ok = false;
        continue;
      }
      const auto a = adjacency.neighbours(static_cast<std::size_t>(vertical), dx, 0);
      const auto b = adjacency.neighbours(static_cast<std::size_t>(horizontal), 0, dy);
      std::vector<std::uint16_t> common;
      std::set_intersection(a.begin(), a.end(), b.begin(), b.end(), std::back_inserter(common));
      if (common.empty()) {
        corners_ok = false;
        continue;
      }
      block[static_cast<std::size_t>(block_index(dx, dy))] = common[rng.below(common.size())];
    }
    if (sides_ok && corners_ok) break;
  }
  return block;
}

// Centroid of the Voronoi cell of `site` among `others`, clipped to a square of half-side `box`.
Vec2 voronoi_centroid(Vec2 site, std::vector<Vec2>& others, double box) {
  std::sort(others.begin(), others.end(), [&](Vec2 a, Vec2 b) { return norm2(a - site) < norm2(b - site); });
  std::vector<Vec2> poly = {site + Vec2{-box, -box}, site + Vec2{box, -box}, site + Vec2{box, box},
                            site + Vec2{-box, box}};
  std::vector<Vec2> next;
  for (const Vec2& o : others) {
    double reach2 = 0;
    for (const Vec2& v : poly) reach2 = std::max(reach2, norm2(v - site));
    if (norm2(o - site) > 4.0 * reach2) break;  // farther than twice the cell: cannot cut it
    const Vec2 normal = o - site;
    const Vec2 mid = 0.5 * (o + site);
    next.clear();
    for (std::size_t k = 0; k < poly.size(); ++k) {
      const Vec2 a = poly[k], b = poly[(k + 1) % poly.size()];
      const double da = dot(a - mid, normal), db = dot(b - mid, normal);
      if (da <= 0) next.push_back(a);
      if ((da <= 0) != (db <= 0)) next.push_back(a + (da / (da - db)) * (b - a));
    }
    poly.swap(next);
    if (poly.size() < 3) return site;
  }
  double area = 0;
  Vec2 c;
  for (std::size_t k = 0; k < poly.size(); ++k) {
    const Vec2 a = poly[k], b = poly[(k + 1) % poly.size()];
    const double cross = a.x * b.y - b.x * a.y;
    area += cross;
    c = c + cross * (a + b);
  }
  if (std::abs(area) < 1e-18) return site;
  return (1.0 / (3.0 * area)) * c;
}

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

// One Lloyd step: each point moves to the mean of its Voronoi centroids over a few random valid
// neighbourhoods of the tiles that hold it (replicas move together: they are one point).
void lloyd_step(const RelaxContext& ctx, const Content& content, int round, double d, PointSet& points) {
  constexpr int kContexts = 4;
  std::vector<Vec2> moved(points.local.size());
  tbb::parallel_for(std::size_t{0}, points.local.size(), [&](std::size_t p) {
    if (ctx.stays(points, p)) {  // no centroids to gather
      moved[p] = points.local[p];
      return;
    }
    const int g = ctx.model.group_holding(points.cls[p], points.local[p]);
    const Group& group = ctx.model.group(g);
    const Vec2 q = points.local[p] + group.offset;
    Rng rng{hash_combine(hash_combine(ctx.options.seed, static_cast<std::uint64_t>(round)), p)};
    std::vector<Vec2> others;
    Vec2 sum;
    for (int k = 0; k < kContexts; ++k) {
      const std::size_t center = group.holders[rng.below(group.holders.size())];
      const std::array<int, 9> block = random_context(ctx.adjacency, center, rng);
      others.clear();
      const double gather2 = 9.0 * d * d;
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const int tile = block[static_cast<std::size_t>(block_index(dx, dy))];
          if (tile < 0) continue;
          const Vec2 shift{static_cast<double>(dx), static_cast<double>(dy)};
          for (const Held& h : content.tiles[static_cast<std::size_t>(tile)]) {
            if (dx == 0 && dy == 0 && h.point == p) continue;
            const Vec2 o = h.q + shift;
            if (norm2(o - q) < gather2) others.push_back(o);
          }
        }
      sum = sum + (voronoi_centroid(q, others, 1.5 * d) - q);
    }
    moved[p] = ctx.moved(points, p, points.local[p] + (1.0 / kContexts) * sum);
  });
  points.local.swap(moved);
}

// Pushes apart every pair that can meet closer than d x their classes' weight (Jacobi steps over
// all neighbour configurations), keeping each point in its class region. True when no pair is
// left closer.
bool enforce_distance(const RelaxContext& ctx, double d, PointSet& points, Content& content) {
  constexpr int kPasses = 3, kSteps = 60;
  const SpeciesTable& species = ctx.species;
  for (int pass = 0; pass < kPasses; ++pass) {
    build_content(ctx.model, points, content);
    if (min_meeting_distance(ctx.model, content, species, d) >= d) return true;
    const std::vector<Pair> pairs =
        meeting_pairs(ctx.model, content, [&](const Held& a) { return 1.5 * d * species.row_weight[a.species]; });
    std::vector<std::size_t> first(points.local.size() + 1, 0);
    for (const Pair& pr : pairs) ++first[pr.i + 1];
    for (std::size_t k = 1; k < first.size(); ++k) first[k] += first[k - 1];
    std::vector<Vec2> next(points.local.size());
    for (int step = 0; step < kSteps; ++step) {
      const bool any = tbb::parallel_reduce(
          tbb::blocked_range<std::size_t>(0, points.local.size()), false,
          [&](const tbb::blocked_range<std::size_t>& range, bool found) {
            for (std::size_t i = range.begin(); i != range.end(); ++i) {
              Vec2 push;
              for (std::size_t k = first[i]; k < first[i + 1]; ++k) {
                const Pair& pr = pairs[k];
                const Vec2 r = points.local[i] - points.local[pr.j] + Vec2{double(pr.kx), double(pr.ky)};
                const double len2 = norm2(r);
                const double need = d * species.weight[points.species[i] * species.count + points.species[pr.j]];
                if (len2 >= need * need) continue;
                found = true;
                const double len = std::sqrt(len2);
                const Vec2 dir = len > 1e-12 ? (1.0 / len) * r : Vec2{i < pr.j ? 1.0 : -1.0, 0.0};
                push = push + (0.5 * (need * 1.002 - len)) * dir;
              }
              next[i] = ctx.moved(points, i, points.local[i] + push);
            }
            return found;
          },
          [](bool a, bool b) { return a || b; });
      points.local.swap(next);
      if (!any) break;
    }
  }
  build_content(ctx.model, points, content);
  return min_meeting_distance(ctx.model, content, species, d) >= d;
}

// A fixed sample tiling for the nearest-neighbour spread (the lattice guard).
struct SampleTiling {
  Tiling tiling;
  bool usable = false;
};

SampleTiling sample_tiling(const TileSet& set, std::uint64_t seed) {
  SampleTiling sample;
  for (const TilingAlgorithm algorithm : kTilingAlgorithms) {  // the first that can lay the set
    try {
      TilingOptions options;
      options.algorithm = algorithm;
      options.seed = hash_combine(seed, 0x5a3);
      sample.tiling = make_tiling(set, 16, 16, options);
      sample.usable = true;
      return sample;
    } catch (const Error&) {
    }
  }
  return sample;
}

double nn_spread(const SampleTiling& sample, const Content& content) {
  if (!sample.usable) return std::numeric_limits<double>::quiet_NaN();
  std::vector<float> x, y;
  const Tiling& tiling = sample.tiling;
  for (int j = 0; j < tiling.height; ++j)
    for (int i = 0; i < tiling.width; ++i)
      for (const Held& h : content.tiles[tiling.at(i, j)]) {
        x.push_back(static_cast<float>(i + h.q.x));
        y.push_back(static_cast<float>(j + h.q.y));
      }
  const Extent area{0, 0, static_cast<double>(tiling.width), static_cast<double>(tiling.height)};
  return nearest_neighbour_stats(x, y, area).spread;
}

// ---- progressive order (issue 26 item 2): thinning that stays Poisson ----

// Per point, its rank in [0, 1) within its species: the points of rank < d are a Poisson subset
// in every tiling, as dense near the tile edges as inside. A geometric ladder of densities d
// (rungs, kLowestDensity to 1), from the largest distance down: a rung takes points not yet taken
// up to d of them, each keeping rank_rho x the hexagonal spacing of d x the species' density from
// every point taken, over every configuration (meeting_pairs); ranks follow the rungs, in a
// random order (of seed and id) within one, each point counted by the tiles that hold it, so
// rank < d keeps about d of the points of a tiling. Replicas are one point: one rank.
// Near the edges a plain ladder leaves a tile grid: a shared point (strip, corner square) must
// keep its distance from the interiors of every tile holding it and every tile across, so once
// the interiors next to it are taken it rarely fits, and taken first in each rung it crowds the
// interior just inside the strip (cohen8, 60 per tile, d = 0.125: 0.48-0.52 of the mean density
// 0.10-0.15 tile sides from an edge, 1.29-1.40 beside it). So:
//  - the shared points climb the ladder kSharedLead rungs ahead of the interiors: they take their
//    places before the interiors around them, and an interior point keeps from a shared point of
//    a later rung that rung's distance (every pair keeps the distance of the later of its rungs);
//  - every rung fills rings of kRankRing by distance to the nearest edge (out to kRankRingsReach,
//    then the rest of the tile as one) evenly: the ring least
//    filled for its area offers the next point, and no ring takes more than d of its area's
//    share (the fill itself is thinner at the edges and corners);
//  - rings short of d take points at 0.95 and 0.9 of the rung's distance.
// Measured (points of rank < d, density across a tile in bands of 0.05 tile sides over the mean
// band, 60-300 fills; rho over 64 x 64 tilings, seeds 1-4), d = 0.5 / 0.25 / 0.125, before ->
// now: cohen8 60 per tile: least band 0.73 / 0.58 / 0.51 -> 0.80 / 0.73 / 0.72, most 1.14 /
// 1.20 / 1.42 -> 1.11 / 1.15 / 1.17, rho 0.57-0.60 / 0.58-0.59 / 0.64-0.67 -> 0.56-0.58 /
// 0.56-0.58 / 0.57-0.61; relaxed (30 rounds) least 0.76 / 0.73 / 0.36 -> 0.85 / 0.74 / 0.78;
// corner-2 and complete-edge-2 alike (least 0.46-0.79 -> 0.60-0.79). A random subset: rho 0.61 /
// 0.43 / 0.34. At 20 per tile the least band rises (0.35-0.73 -> 0.47-0.81) but bands of
// 1.2-1.5 stay (the fill itself is layered there: 0.62-1.33 at d = 1), and rho at d = 0.125
// falls by up to 0.05-0.1 (0.50-0.63 against 0.54-0.67). The outermost band stays lowest, and
// the corners: the fill itself holds 0.8 of the mean density within 0.05 of an edge, 0.6 in the
// corners.
// Edge objects (only in the strips) fill their rings by their own counts, not by area.
constexpr double kLowestDensity = 1.0 / 16;
constexpr int kDensityRungs = 32;
constexpr int kSharedLead = 3;
constexpr double kRankRing = 0.025, kRankRingsReach = 0.25;
constexpr std::array<double, 2> kCatchUpScales = {0.95, 0.9};

std::vector<float> progressive_ranks(const ContentModel& model, const Content& content, const PointSet& points,
                                     const SpeciesTable& species, const PoissonFillOptions& options) {
  const std::size_t n = points.local.size();
  std::vector<float> rank(n, 0.0f);
  constexpr double rank_rho = 0.7;
  // Rings of kRankRing out to kRankRingsReach from the edges, then one ring for the rest (rings
  // of a few points a tile would starve: each point counts whole against its ring's share).
  constexpr int rings = static_cast<int>(kRankRingsReach / kRankRing) + 1;
  auto rung_density = [](int k) { return std::pow(kLowestDensity, 1.0 - double(k) / (kDensityRungs - 1)); };
  auto rung_radius = [&](std::size_t s, int k) {
    return std::min(rank_rho * hexagonal_spacing(1.0, rung_density(k) * species.per_tile[s]), 0.45);
  };
  double reach = 0;
  for (std::size_t s = 0; s < species.count; ++s) reach = std::max(reach, rung_radius(s, 0));
  // Same-species neighbours within the largest rung, with their least distance over configurations.
  std::vector<std::vector<std::pair<std::uint32_t, double>>> near(n);
  for (const Pair& p : meeting_pairs(model, content, [reach](const Held&) { return reach; })) {
    if (points.species[p.i] != points.species[p.j]) continue;
    const double d = std::sqrt(norm2(points.local[p.i] - points.local[p.j] + Vec2{double(p.kx), double(p.ky)}));
    near[p.i].push_back({p.j, d});
  }
  // The phase a point takes its rung in: 0 shared (climbing ahead), 1 interior.
  std::vector<std::uint8_t> phase_of(n);
  for (std::uint32_t p = 0; p < n; ++p)
    phase_of[p] = model.classes()[static_cast<std::size_t>(points.cls[p])].kind != ClassKind::interior ? 0 : 1;
  auto shuffle_key = [&](std::uint32_t p) { return hash_combine(hash_combine(options.seed, 0x7a4c), p); };
  std::vector<double> holders(n);
  std::vector<int> ring(n);
  for (std::uint32_t p = 0; p < n; ++p) {
    const int g = model.group_holding(points.cls[p], points.local[p]);
    holders[p] = double(model.group(g).holders.size());
    const Vec2 q = points.local[p] + model.group(g).offset;
    const double to_edge = std::min(std::min(q.x, 1.0 - q.x), std::min(q.y, 1.0 - q.y));
    ring[p] = std::min(static_cast<int>(to_edge / kRankRing), rings - 1);
  }
  for (std::size_t s = 0; s < species.count; ++s) {
    std::vector<std::uint32_t> members;
    for (std::uint32_t p = 0; p < n; ++p)
      if (points.species[p] == s) members.push_back(p);
    std::sort(members.begin(), members.end(),
              [&](std::uint32_t a, std::uint32_t b) { return shuffle_key(a) < shuffle_key(b); });
    double total = 0;
    std::array<double, 2> phase_total{}, phase_taken{};  // [shared, interior]
    std::vector<double> ring_share(rings, 0.0), ring_taken(rings, 0.0);
    for (const std::uint32_t p : members) {
      total += holders[p];
      phase_total[phase_of[p]] += holders[p];
      if (species.edge_objects[s]) ring_share[static_cast<std::size_t>(ring[p])] += holders[p];
    }
    if (!species.edge_objects[s])
      for (int b = 0; b < rings; ++b) {
        const double outer = 1.0 - 2.0 * b * kRankRing, inner = b + 1 < rings ? 1.0 - 2.0 * (b + 1) * kRankRing : 0.0;
        ring_share[static_cast<std::size_t>(b)] = total * (outer * outer - inner * inner);
      }
    std::vector<double> radius(kDensityRungs);
    for (int k = 0; k < kDensityRungs; ++k) radius[static_cast<std::size_t>(k)] = rung_radius(s, k);
    std::vector<int> rung(n, kDensityRungs);  // the rung that took the point; kDensityRungs = the rest
    // Whether p may join rung k at scale x the distances: every pair keeps its later rung's.
    auto fits = [&](std::uint32_t p, int k, double scale) {
      return std::none_of(near[p].begin(), near[p].end(), [&](const auto& neighbour) {
        const int other = rung[neighbour.first];
        return other < kDensityRungs && neighbour.second < scale * radius[static_cast<std::size_t>(std::max(k, other))];
      });
    };
    auto ring_room = [&](std::uint32_t p, double d) {
      const auto b = static_cast<std::size_t>(ring[p]);
      return ring_taken[b] + 0.5 * holders[p] <= d * ring_share[b];
    };
    auto take = [&](std::uint32_t p, int k, int phase) {
      rung[p] = k;
      phase_taken[static_cast<std::size_t>(phase)] += holders[p];
      ring_taken[static_cast<std::size_t>(ring[p])] += holders[p];
    };
    auto fill_rung = [&](int k, int phase) {
      const double d = rung_density(k);
      auto candidate = [&](std::uint32_t p) { return rung[p] == kDensityRungs && phase_of[p] == phase; };
      std::vector<std::vector<std::uint32_t>> queue(rings);
      for (const std::uint32_t p : members)
        if (candidate(p)) queue[static_cast<std::size_t>(ring[p])].push_back(p);
      std::vector<std::size_t> next(rings, 0);
      while (true) {
        int best = -1;
        double best_fill = std::numeric_limits<double>::infinity();
        for (int b = 0; b < rings; ++b) {
          const auto i = static_cast<std::size_t>(b);
          if (next[i] == queue[i].size()) continue;
          const double fill = ring_taken[i] / ring_share[i];
          if (fill < d && fill < best_fill) best_fill = fill, best = b;
        }
        if (best < 0) break;
        const std::uint32_t p = queue[static_cast<std::size_t>(best)][next[static_cast<std::size_t>(best)]++];
        const auto ph = static_cast<std::size_t>(phase);
        if (phase_taken[ph] + holders[p] > d * phase_total[ph] + 1e-9) break;
        if (ring_room(p, d) && fits(p, k, 1.0)) take(p, k, phase);
      }
      for (const double scale : kCatchUpScales)
        for (const std::uint32_t p : members)
          if (candidate(p) && ring_room(p, d) && fits(p, k, scale)) take(p, k, phase);
    };
    for (int step = 0; step < kDensityRungs + kSharedLead; ++step) {
      if (step < kDensityRungs) fill_rung(step, 0);
      if (step >= kSharedLead) fill_rung(step - kSharedLead, 1);
    }
    std::sort(members.begin(), members.end(), [&](std::uint32_t a, std::uint32_t b) {
      return std::pair{rung[a], shuffle_key(a)} < std::pair{rung[b], shuffle_key(b)};
    });
    double before = 0;
    for (const std::uint32_t p : members) {
      rank[p] = static_cast<float>(std::min((before + 0.5 * holders[p]) / total, 1.0 - 1e-7));
      before += holders[p];
    }
  }
  return rank;
}

FilledTileSet export_points(const TileSet& set, const PoissonFillOptions& options, const SpeciesTable& species,
                            std::span<const float> rank, const Content& content) {
  FilledTileSet filled;
  filled.set = set;
  filled.seed = options.seed;
  filled.variants = 0;
  for (const int v : species.variants) {
    filled.class_variants.push_back({filled.variants, v});
    filled.variants += v;
  }
  filled.tiles.resize(set.tiles.size());
  const float below_one = std::nextafter(1.0f, 0.0f);
  for (std::size_t t = 0; t < set.tiles.size(); ++t) {
    for (const Held& h : content.tiles[t]) {
      TilePoint tp;
      tp.x = std::clamp(static_cast<float>(h.q.x), 0.0f, below_one);
      tp.y = std::clamp(static_cast<float>(h.q.y), 0.0f, below_one);
      tp.id = h.point;
      tp.species = h.species;
      tp.rank = rank[h.point];
      const auto [first_variant, variant_count] = filled.class_variants[h.species];
      const PointAttributes a =
          point_attributes(options.seed, h.point, variant_count, options.min_scale, options.max_scale);
      tp.variant = static_cast<std::uint16_t>(first_variant + a.variant);
      tp.yaw = a.yaw;
      tp.scale = a.scale;
      filled.tiles[t].push_back(tp);
    }
  }
  return filled;
}

// The packing diameter (tile sides) of the dart phase, and the tight radius of a class that sets none.
double dart_distance(const PoissonFillOptions& options) {
  return options.dart_rho * hexagonal_spacing(1.0, options.points_per_tile);
}
double default_tight_radius(const PoissonFillOptions& options) {
  return options.tight_fraction * 0.5 * dart_distance(options);
}

void check_options(const PoissonFillOptions& o) {
  auto fail = [](const std::string& what) { throw Error("Poisson fill: " + what); };
  if (o.classes.size() > 255) fail(std::to_string(o.classes.size()) + " classes; expected at most 255");
  long total_variants = 0;
  for (std::size_t c = 0; c < o.classes.size(); ++c) {
    const PoissonClass& k = o.classes[c];
    const std::string name = "class " + std::to_string(c) + ": ";
    if (!(k.share > 0 && std::isfinite(k.share))) fail(name + "share " + std::to_string(k.share) + "; expected > 0");
    if (!(k.packing_radius >= 0 && k.packing_radius < kMaxClassRadius))
      fail(name + "packing radius " + std::to_string(k.packing_radius) + "; expected 0.." +
           number_text(kMaxClassRadius) + " tile sides");
    if (!(k.tight_radius >= 0 && k.tight_radius < kMaxClassRadius))
      fail(name + "tight radius " + std::to_string(k.tight_radius) + "; expected 0.." + number_text(kMaxClassRadius) +
           " tile sides");
    if (k.variants < 1) fail(name + "variants " + std::to_string(k.variants) + "; expected >= 1");
    total_variants += k.variants;
    if (k.exclusion.size() > o.classes.size())
      fail(name + std::to_string(k.exclusion.size()) + " exclusion distances; expected at most one per class");
    for (const double e : k.exclusion)
      if (!(e >= 0 && e < kMaxClassDistance))
        fail(name + "exclusion " + std::to_string(e) + "; expected 0.." + number_text(kMaxClassDistance) +
             " tile sides");
  }
  if (total_variants > 65535) fail(std::to_string(total_variants) + " variants over the classes; expected <= 65535");
  if (o.points_per_tile < 1 || o.points_per_tile > kMaxPointsPerTile)
    fail("points per tile " + std::to_string(o.points_per_tile) + "; expected 1.." + std::to_string(kMaxPointsPerTile));
  if (o.darts_per_visit < 1) fail("darts per visit " + std::to_string(o.darts_per_visit) + "; expected >= 1");
  if (!(o.dart_rho > 0.1 && o.dart_rho < 0.9)) fail("dart rho " + std::to_string(o.dart_rho) + "; expected 0.1..0.9");
  if (!(o.max_rho >= o.dart_rho && o.max_rho < 1.0))
    fail("max rho " + std::to_string(o.max_rho) + "; expected dart rho..1");
  if (!(o.tight_fraction > 0 && o.tight_fraction <= 1.0))
    fail("tight fraction " + std::to_string(o.tight_fraction) + "; expected (0, 1]");
  if (o.relax_rounds < 0) fail("relax rounds " + std::to_string(o.relax_rounds) + "; expected >= 0");
  if (o.variants < 1 || o.variants > 65535) fail("variants " + std::to_string(o.variants) + "; expected 1..65535");
  if (!(o.min_scale > 0 && o.max_scale >= o.min_scale))
    fail("scale range " + std::to_string(o.min_scale) + ".." + std::to_string(o.max_scale) +
         "; expected 0 < min <= max");
}

// A point and its own copy in the tile beside (a tile can sit next to itself) are a tile side
// apart: no distance may reach it. The distances are symmetric: a <= b is enough.
std::optional<ClassesTooFar> first_too_far(const SpeciesTable& species) {
  for (std::size_t a = 0; a < species.count; ++a)
    for (std::size_t b = a; b < species.count; ++b)
      if (species.distance(a, b) >= kMaxClassDistance) return ClassesTooFar{a, b, species.distance(a, b)};
  return std::nullopt;
}

void check_species(const SpeciesTable& species) {
  if (const std::optional<ClassesTooFar> far = first_too_far(species))
    throw Error("Poisson fill: classes " + std::to_string(far->a) + " and " + std::to_string(far->b) + " keep " +
                std::to_string(far->distance) +
                " tile sides apart (packing radii plus exclusion, or the class's own spacing); expected < " +
                number_text(kMaxClassDistance) + ": raise the points per tile or shrink the radii");
}

}  // namespace

PoissonFillEstimate estimate_poisson_fill(const TileSet& set, const PoissonFillOptions& options) {
  // Each dart is checked against the tiles that may sit beside its tile: the mean number of
  // east neighbours (4 in cohen8, K^3 in complete-edge-K) drives the cost of large sets.
  std::map<EdgeKey, double> west_keys;
  for (const Tile& t : set.tiles) west_keys[west_key(t)] += 1;
  double neighbours = 0;
  for (const Tile& t : set.tiles) neighbours += west_keys[east_key(t)];
  neighbours /= std::max<double>(1, double(set.tiles.size()));
  // Fitted (user CPU seconds, docs/limits.md): cohen8 at 500 / 2000 / 4000 points per tile
  // 0.57 / 2.98 / 9.88 s, complete-edge-4 at 20: 0.94 s, -6 at 10: 5.5 s, -8 at 20: 72.9 s; each
  // relaxation round about 0.45 of the darts.
  const double p = options.points_per_tile;
  PoissonFillEstimate estimate;
  estimate.points = double(set.tiles.size()) * p;
  const double darts = estimate.points * 3.43e-5 * (1 + p / 517) * std::pow(std::max(1.0, neighbours / 4), 0.66);
  // Several classes: each thrown on its own against all (cohen8 with 3 classes, darts only: 5.9x
  // one class's time at 500 points per tile, 3.6x at 2000).
  const double classes = 1.0 + 1.2 * std::max<double>(0, double(options.classes.size()) - 1);
  estimate.seconds = 0.3 + classes * darts * (1 + 0.45 * std::max(0, options.relax_rounds));
  return estimate;
}

std::pair<int, int> class_variant_range(const FilledTileSet& filled, int species) {
  if (species >= 0 && static_cast<std::size_t>(species) < filled.class_variants.size())
    return filled.class_variants[static_cast<std::size_t>(species)];
  return {0, filled.variants};
}

std::vector<double> class_fill_distances(const PoissonFillOptions& options) {
  const SpeciesTable table = make_species_table(options, dart_distance(options), default_tight_radius(options));
  std::vector<double> distances(table.distance2.size());
  for (std::size_t k = 0; k < distances.size(); ++k) distances[k] = std::sqrt(table.distance2[k]);
  return distances;
}

std::optional<ClassesTooFar> classes_too_far(const PoissonFillOptions& options) {
  return first_too_far(make_species_table(options, dart_distance(options), default_tight_radius(options)));
}

std::optional<int> class_of_variant(const FilledTileSet& filled, int variant) {
  const int classes = std::max<int>(1, static_cast<int>(filled.class_variants.size()));
  for (int c = 0; c < classes; ++c) {
    const auto [first, count] = class_variant_range(filled, c);
    if (variant >= first && variant < first + count) return c;
  }
  return std::nullopt;
}

double hexagonal_spacing(double area, double count) { return std::sqrt(2.0 * area / (std::sqrt(3.0) * count)); }

PointAttributes point_attributes(std::uint64_t seed, std::uint32_t id, int variants, double min_scale,
                                 double max_scale) {
  Rng rng{hash_combine(hash_combine(seed, 0xa77), id)};
  PointAttributes a;
  a.variant = static_cast<std::uint16_t>(rng.below(static_cast<std::size_t>(std::max(variants, 1))));
  a.yaw = static_cast<float>(rng.uniform() * 2.0 * std::numbers::pi);
  a.scale = static_cast<float>(min_scale + (max_scale - min_scale) * rng.uniform());
  return a;
}

PointAttributes world_point_attributes(std::uint64_t seed, std::int64_t i, std::int64_t j, std::uint32_t k,
                                       int variants, double min_scale, double max_scale) {
  const std::uint64_t where = hash_combine(
      hash_combine(hash_combine(seed ^ 0x3c1d, static_cast<std::uint64_t>(i)), static_cast<std::uint64_t>(j)), k);
  return point_attributes(seed, static_cast<std::uint32_t>(where >> 32) ^ static_cast<std::uint32_t>(where), variants,
                          min_scale, max_scale);
}

TileAdjacency::TileAdjacency(const TileSet& set) {
  const std::size_t n = set.tiles.size();
  lists_.assign(n * 9, {});
  auto list = [&](std::size_t t, int dx, int dy) -> std::vector<std::uint16_t>& {
    return lists_[t * 9 + static_cast<std::size_t>(block_index(dx, dy))];
  };
  for (std::size_t t = 0; t < n; ++t)
    for (std::size_t u = 0; u < n; ++u) {
      const Tile &a = set.tiles[t], &b = set.tiles[u];
      if (east_key(a) == west_key(b)) list(t, 1, 0).push_back(static_cast<std::uint16_t>(u));
      if (west_key(a) == east_key(b)) list(t, -1, 0).push_back(static_cast<std::uint16_t>(u));
      if (north_key(a) == south_key(b)) list(t, 0, 1).push_back(static_cast<std::uint16_t>(u));
      if (south_key(a) == north_key(b)) list(t, 0, -1).push_back(static_cast<std::uint16_t>(u));
    }
  // Diagonal (dx, dy): u completes a 2 x 2 block with t, some v at (0, dy) and some h at (dx, 0):
  // u's side towards v matches one of the v's, and u's side towards h matches one of the h's.
  for (std::size_t t = 0; t < n; ++t)
    for (int dy : {-1, 1})
      for (int dx : {-1, 1}) {
        std::vector<EdgeKey> from_vertical, from_horizontal;
        for (std::uint16_t v : list(t, 0, dy))
          from_vertical.push_back(dx > 0 ? east_key(set.tiles[v]) : west_key(set.tiles[v]));
        for (std::uint16_t h : list(t, dx, 0))
          from_horizontal.push_back(dy > 0 ? north_key(set.tiles[h]) : south_key(set.tiles[h]));
        // Few distinct keys among many neighbours (complete-edge-8: 512 tiles, 8 keys): keeping
        // each once makes this O(n^2) instead of O(n^2 K^3), seconds instead of minutes.
        for (auto* keys : {&from_vertical, &from_horizontal}) {
          std::sort(keys->begin(), keys->end());
          keys->erase(std::unique(keys->begin(), keys->end()), keys->end());
        }
        for (std::size_t u = 0; u < n; ++u) {
          const Tile& b = set.tiles[u];
          const EdgeKey towards_v = dx > 0 ? west_key(b) : east_key(b);
          const EdgeKey towards_h = dy > 0 ? south_key(b) : north_key(b);
          if (std::binary_search(from_vertical.begin(), from_vertical.end(), towards_v) &&
              std::binary_search(from_horizontal.begin(), from_horizontal.end(), towards_h))
            list(t, dx, dy).push_back(static_cast<std::uint16_t>(u));
        }
      }
}

double min_distance_over_configurations(const FilledTileSet& filled) {
  const std::vector<double> by_class = class_min_distances(filled);
  return *std::min_element(by_class.begin(), by_class.end());
}

std::vector<double> class_min_distances(const FilledTileSet& filled) {
  const TileAdjacency adjacency(filled.set);
  const std::size_t n = filled.tiles.size();
  std::size_t classes = 1;
  for (const auto& tile : filled.tiles)
    for (const TilePoint& p : tile) classes = std::max<std::size_t>(classes, p.species + 1u);
  using Matrix = std::vector<double>;
  return tbb::parallel_reduce(
      tbb::blocked_range<std::size_t>(0, n), Matrix(classes * classes, std::numeric_limits<double>::infinity()),
      [&](const tbb::blocked_range<std::size_t>& range, Matrix best) {
        auto note = [&](const TilePoint& a, const TilePoint& b, double d) {
          double& ab = best[a.species * classes + b.species];
          double& ba = best[b.species * classes + a.species];
          ab = ba = std::min(ab, d);
        };
        for (std::size_t t = range.begin(); t != range.end(); ++t) {
          const auto& own = filled.tiles[t];
          for (std::size_t a = 0; a < own.size(); ++a)
            for (std::size_t b = a + 1; b < own.size(); ++b)
              note(own[a], own[b], std::hypot(double(own[a].x) - own[b].x, double(own[a].y) - own[b].y));
          for (const auto& [dx, dy] : kDirections)
            for (std::uint16_t u : adjacency.neighbours(t, dx, dy))
              for (const TilePoint& a : own) {
                // No pair farther than every class pair's best so far can lower any of them.
                const double reach = std::min(*std::max_element(best.begin(), best.end()), 1.0);
                if (!near_side(Vec2{a.x, a.y}, dx, dy, reach)) continue;
                for (const TilePoint& b : filled.tiles[u])
                  note(a, b, std::hypot(double(b.x) + dx - a.x, double(b.y) + dy - a.y));
              }
        }
        return best;
      },
      [](Matrix a, const Matrix& b) {
        for (std::size_t k = 0; k < a.size(); ++k) a[k] = std::min(a[k], b[k]);
        return a;
      });
}

FilledTileSet fill_poisson_tiles(const TileSet& set, const PoissonFillOptions& options, PoissonFillReport* report) {
  check_options(options);
  if (const auto estimate = estimate_poisson_fill(set, options); estimate.seconds > kMaxFillSeconds)
    throw Error(set.describe() + ": filling " + std::to_string(set.tiles.size()) + " tiles with " +
                std::to_string(options.points_per_tile) + " points each (" + std::to_string(options.relax_rounds) +
                " relaxation rounds) would take about " + std::to_string(std::lround(estimate.seconds)) +
                " s; at most " + std::to_string(std::lround(kMaxFillSeconds)) +
                " s are accepted: use fewer points per tile, fewer relaxation rounds or a smaller tile set");
  if (set.tiles.empty()) throw Error(set.describe() + ": no tiles to fill");
  if (set.tiles.size() > std::numeric_limits<std::uint16_t>::max())
    throw Error(set.describe() + ": " + std::to_string(set.tiles.size()) + " tiles; expected at most 65535");
  const double spacing = hexagonal_spacing(1.0, options.points_per_tile);
  const double dart_d = dart_distance(options);
  const double cap_d = options.max_rho * spacing;
  // The shared strips are at least as wide as the largest packing radius relaxation may reach,
  // so two tile-owned interior points never meet across an edge closer than the bound. Plain
  // edge sets take wider strips: a point just inside a strip must keep its distance from the
  // interiors of every tile holding the strip, and the seam where that thins the points out,
  // together with the layer the interior points form against it (hard discs against a wall),
  // then lies past the zone within one packing diameter of the edge rather than inside it.
  // Measured (cohen8, 20 points per tile, 64 x 64 tilings, mean of 64 seeds; edge / corner
  // density over the interior's, after darts ; after relaxation 100): 1.02 / 1.04 ; 1.01 / 0.99
  // at 0.82 cap_d, 0.99 / 0.99 ; 1.04 / 1.01 at 0.84, 0.97 / 0.93 ; 1.08 / 1.02 at 0.86 (0.95
  // of the strip share there), and at 0.5 without the quotas 1.01 / 0.92 ; 0.95 / 0.93.
  const double tight = default_tight_radius(options);
  const SpeciesTable species = make_species_table(options, dart_d, tight);
  check_species(species);
  // Sets with corner colors and several classes: the strips are as wide for the widest-spaced
  // class (up to 0.3 tile sides: a few boulders a tile do not widen them) as for one class.
  // Measured (corner-2, 40 points per tile, shares 0.7 / 0.25 / 0.05, 6 seeds, edge / corner
  // density over the interior's): flowers 0.73 / 0.77 with the union's strips, 1.11 / 1.13 with
  // these (grass 0.95 / 0.83 and 0.89 / 1.26). Plain edge sets' strips already hold the flowers.
  const double strip_d = set.has_corners ? std::max(cap_d, std::min(species.widest_spacing, 0.3)) : cap_d;
  const double w = std::min((set.has_corners ? 0.5 : 0.82) * strip_d, 0.45);
  if (cap_d >= 1.0)
    throw Error("Poisson fill: " + std::to_string(options.points_per_tile) +
                " points per tile are too few for a packing diameter below the tile side");

  const TileAdjacency adjacency(set);
  // Sets with corner colors: the vertex squares (consistent by construction) reach past the
  // strips far enough that the ends of two perpendicular strips, whose other ends vary, rarely
  // meet (0.75 of the distance that rules it out entirely; more repeats the vertex content over
  // more of the tile). Measured (bench/poisson_bench): corner-2 corner density within 2 % of the
  // interior after darts and after relaxation; 0.80 -> 0.99 after darts for cohen8-corners.
  const double corner_w = std::min(w + 0.75 * cap_d / std::sqrt(2.0), 0.45);
  const ContentModel model(set, adjacency, w, corner_w);
  PointSet points;
  Content content;
  build_content(model, points, content);
  // Sets with corner colors: shared regions first, then everywhere, uncapped (measured best for
  // them). Plain edge sets: corner squares first (the most constrained: they meet every diagonal
  // tile), then strips, then everywhere, with the class quotas; then the strips and interiors
  // once more without them, for the tiles whose interiors jammed short of the target (cohen8:
  // 19.2 points per tile with this pass, 18.6 without).
  constexpr unsigned kCorners = 0b101000101u, kShared = 0b111101111u, kEverywhere = 0b111111111u;
  constexpr unsigned kStripsAndInterior = kEverywhere & ~kCorners;
  const std::vector<DartPass> passes =
      set.has_corners
          ? std::vector<DartPass>{{kShared, false}, {kEverywhere, false}}
          : std::vector<DartPass>{{kCorners, true}, {kShared, true}, {kEverywhere, true}, {kStripsAndInterior, false}};
  const std::vector<double> quota = class_quotas(model, options, species);
  throw_darts(model, options, species, passes, quota, points, content);

  PoissonFillReport rep;
  rep.class_points = points.local.size();
  build_content(model, points, content);
  rep.dart_min_distance = min_meeting_distance(model, content, species, 2.0 * cap_d);

  const RelaxContext ctx{model, adjacency, options, species};
  const SampleTiling sample = sample_tiling(set, options.seed);
  double d_current = std::min(dart_d, rep.dart_min_distance);
  // The raised bound: +1 % per round, growing to +2 % while rounds succeed, halved on failure.
  double growth = 0.01;
  // Several classes: every distance is raised by one factor (d_current over the dart distance).
  for (int round = 0; round < options.relax_rounds && d_current < cap_d; ++round) {
    const PointSet before = points;
    lloyd_step(ctx, content, round, d_current, points);
    const double target = std::min(cap_d, d_current * (1.0 + growth));
    bool kept = enforce_distance(ctx, target, points, content);
    double reached = target;
    if (!kept) {
      growth = std::max(growth * 0.5, 0.001);
      kept = enforce_distance(ctx, d_current, points, content);
      reached = d_current;
    } else {
      growth = std::min(growth * 1.5, 0.02);
    }
    if (!kept) {
      points = before;
      build_content(model, points, content);
      ++rep.relax_rounds_rejected;
      continue;
    }
    const double spread = nn_spread(sample, content);
    if (spread < options.min_nn_spread) {
      // Lattice-like: undo this round and stop.
      points = before;
      build_content(model, points, content);
      rep.stopped_before_lattice = true;
      break;
    }
    d_current = std::max(reached, std::min(cap_d, min_meeting_distance(model, content, species, cap_d)));
    ++rep.relax_rounds_run;
    rep.round_min_distance.push_back(d_current);
    rep.round_nn_spread.push_back(spread);
  }

  FilledTileSet filled =
      export_points(set, options, species, progressive_ranks(model, content, points, species, options), content);
  rep.class_min_distance = class_min_distances(filled);
  const std::vector<double>& least = rep.class_min_distance;
  rep.final_min_distance = *std::min_element(least.begin(), least.end());
  rep.nn_spread = nn_spread(sample, content);
  filled.radius_packing = 0.5 * rep.final_min_distance * (1.0 - 1e-6);
  filled.radius_tight = tight;
  filled.shared_width = w;
  if (species.count == 1) {
    filled.classes = {{filled.radius_packing, filled.radius_tight, false, 2.0 * filled.radius_packing}};
  } else {
    // Relaxation raised every distance by one factor: the radii say what the points keep (below 1
    // only by the rounding of positions to floats).
    double factor = std::numeric_limits<double>::infinity();
    const auto present = static_cast<std::size_t>(std::lround(std::sqrt(double(least.size()))));  // classes with points
    for (std::size_t a = 0; a < present; ++a)
      for (std::size_t b = 0; b < present; ++b)
        if (std::isfinite(least[a * present + b]))
          factor = std::min(factor, least[a * present + b] / species.distance(a, b));
    if (!std::isfinite(factor)) factor = 1.0;
    factor *= 1.0 - 1e-6;
    for (std::size_t c = 0; c < species.count; ++c)
      filled.classes.push_back({factor * species.packing[c], species.tight[c], species.edge_objects[c] != 0,
                                factor * species.distance(c, c)});
  }
  if (report) *report = rep;
  return filled;
}

namespace {

// The points a tile shows: its own, and the edge objects of the tiles across its edges whose
// discs reach into it (the same for every tile that can sit there), shifted into its frame.
std::vector<TilePoint> points_shown(const FilledTileSet& filled, const TileAdjacency& adjacency, std::size_t t) {
  std::vector<TilePoint> shown = filled.tiles[t];
  for (const auto& [dx, dy] : kDirections) {
    if (dx != 0 && dy != 0) continue;
    const auto across = adjacency.neighbours(t, dx, dy);
    if (across.empty()) continue;
    for (TilePoint p : filled.tiles[across.front()]) {
      if (p.species >= filled.classes.size() || !filled.classes[p.species].edge_objects) continue;
      p.x += static_cast<float>(dx);
      p.y += static_cast<float>(dy);
      const double to_edge = dx != 0 ? std::abs(p.x - (dx > 0 ? 1.0 : 0.0)) : std::abs(p.y - (dy > 0 ? 1.0 : 0.0));
      if (to_edge < filled.classes[p.species].tight) shown.push_back(p);
    }
  }
  return shown;
}

}  // namespace

ImageRgb8 draw_filled_tileset_sheet(const FilledTileSet& filled, int tile_pixels) {
  ImageRgb8 image = draw_tileset_sheet(filled.set, tile_pixels);
  const TileAdjacency adjacency(filled.set);
  // Class 0 green (the single-class sheet), then yellow flowers, grey-brown boulders, ...
  constexpr std::array<Rgb8, 4> kClassColors = {{{40, 130, 40}, {215, 175, 20}, {120, 100, 85}, {60, 90, 190}}};
  auto radii = [&](std::uint8_t species) {
    if (species < filled.classes.size()) return filled.classes[species];
    return FilledTileSet::ClassRadii{filled.radius_packing, filled.radius_tight, false, 2 * filled.radius_packing};
  };
  // The same grid as draw_tileset_sheet (tiling_preview.cpp): columns ~ sqrt(n), gap, pitch.
  const int count = static_cast<int>(filled.set.size());
  const int columns = std::clamp(static_cast<int>(std::ceil(std::sqrt(static_cast<double>(count)))), 1, 16);
  const int gap = std::max(2, tile_pixels / 8);
  const int pitch = tile_pixels + gap;
  for (int t = 0; t < count; ++t) {
    const std::vector<TilePoint> shown = points_shown(filled, adjacency, static_cast<std::size_t>(t));
    const int x0 = gap + (t % columns) * pitch, y0 = gap + (t / columns) * pitch;
    for (int y = 0; y < tile_pixels; ++y)
      for (int x = 0; x < tile_pixels; ++x) {
        Rgb8 c = image.at(x0 + x, y0 + y);
        c = {static_cast<std::uint8_t>(255 - (255 - c.r) * 2 / 5), static_cast<std::uint8_t>(255 - (255 - c.g) * 2 / 5),
             static_cast<std::uint8_t>(255 - (255 - c.b) * 2 / 5)};
        const double u = (x + 0.5) / tile_pixels, v = 1.0 - (y + 0.5) / tile_pixels;  // tile-local, y north
        for (const TilePoint& p : shown) {
          const double r = std::hypot(u - p.x, v - p.y);
          const FilledTileSet::ClassRadii radius = radii(p.species);
          if (r < radius.tight)
            c = kClassColors[p.species % kClassColors.size()];
          else if (std::abs(r - radius.packing) < 0.6 / tile_pixels)
            c = {30, 30, 30};
        }
        image.set(x0 + x, y0 + y, c);
      }
  }
  return image;
}

}  // namespace wangscape
