// Poisson-disk tile contents (Shade 2002, section 3; Cohen 2003, sections 3.3-3.4): points in every
// tile of a set such that, in EVERY valid tiling, the union of the tiles' points keeps one
// minimum distance across every tile edge and corner.
//
// How a tile's content is organised (all lengths are fractions of the tile side):
//  - the interior [w, 1-w)^2 belongs to the tile alone;
//  - the strip of width w on each side of an edge belongs to the edge: its key is the edge
//    color (plus the colors of the edge's two end corners in corner-coded sets), and every tile
//    with that key on that side holds the same points there, the tile across holds the other half
//    (Shade 2002's replication across same-colored edges, written as one two-sided strip);
//  - the w x w corner squares: in sets with corner colors the square around a vertex belongs to
//    the corner color and is shared by the four tiles that meet there (consistent by
//    construction); in plain edge sets each corner square belongs to the pair of edge colors
//    that meet at it, and the tight radius of a flower may never cross the tile corner (Shade 2002).
// Every candidate position is checked against every tile that can sit across each edge AND
// across each corner in some valid tiling, so the distance bound holds in all of them.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <utility>
#include <vector>

#include "generator/image.h"
#include "generator/tileset.h"

namespace wangscape {

// One class (species) of a multi-class fill (Shade 2002, section 3, generalised to classes).
// Two points of classes a and b keep at least packing_a + packing_b apart (plus the larger of
// exclusion[a][b] and exclusion[b][a]), two points of one class its own spacing (0.85 x dart_rho
// x the hexagonal spacing of its own density, or twice its packing radius if larger), in every
// valid tiling, across every edge and corner (docs/filled-tileset-format.md). Classes are thrown
// one after the other, the widest-spaced first; relaxation raises every distance by one factor.
struct PoissonClass {
  double share = 1;               // relative density: this class's share of points_per_tile (shares are normalised)
  double packing_radius = 0;      // tile sides; 0 = half the dart distance of points_per_tile (one class's)
  double tight_radius = 0;        // tile sides; 0 = tight_fraction x packing radius. Never crosses a tile corner
  int variants = 1;               // model variants; TilePoint::variant counts across classes (c's follow c-1's)
  bool edge_objects = false;      // the class's points sit across edges (in the shared strips), never across a corner
  std::vector<double> exclusion;  // optional, per other class k: extra minimum centre distance to k (tile sides)
};

struct PoissonFillOptions {
  // Target number of points whose centre lies in each tile.
  int points_per_tile = 20;
  std::uint64_t seed = 1;
  // Round-robin dart throwing (Shade 2002): up to this many darts per visit of a tile.
  int darts_per_visit = 10000;
  // Packing diameter of the dart phase as a fraction of the hexagonal spacing
  // sqrt(2 A / (sqrt(3) N)) for N = points_per_tile in A = 1 tile (the figure rho measures).
  double dart_rho = 0.75;
  // Tight radius (the flower's extent) as a fraction of the dart-phase packing radius.
  double tight_fraction = 0.8;
  // Relaxation rounds in context (Cohen 2003, section 3.3): Lloyd step, then the distance bound
  // enforced against every neighbour configuration, then a raised bound. 0 = darts only.
  int relax_rounds = 0;
  // Relaxation never raises the packing diameter beyond this rho (also sets the shared width).
  double max_rho = 0.92;
  // Relaxation stops before the spread (std / mean) of nearest-neighbour distances in a sample
  // tiling falls below this: lower means lattice-like.
  double min_nn_spread = 0.03;
  // Per-point attributes: variant in 0..variants-1, yaw uniform in [0, 2 pi), scale uniform.
  int variants = 11;
  double min_scale = 0.85, max_scale = 1.15;
  // Several classes sharing the tiles; empty = one class, the single-class fill (variants above).
  std::vector<PoissonClass> classes;
};

struct TilePoint {
  float x = 0, y = 0;  // tile-local position, fractions of the tile side, in [0, 1)
  float yaw = 0;       // radians, counter-clockwise from east
  float scale = 1;
  std::uint16_t variant = 0;
  // The point's identity: the same id in several tiles is one replicated point, and its
  // attributes are a function of (seed, id) only.
  std::uint32_t id = 0;
  std::uint8_t species = 0;  // the point's class (index into PoissonFillOptions::classes)
  // Progressive order in [0, 1): the points with rank < d are Poisson at d x the density.
  float rank = 0;
  bool operator==(const TilePoint&) const = default;
};

struct FilledTileSet {
  TileSet set;
  std::uint64_t seed = 0;
  double radius_packing = 0;  // half the minimum distance between points of any valid tiling (tile sides)
  double radius_tight = 0;    // flower extent; never crosses a tile corner in plain edge sets (tile sides)
  double shared_width = 0;    // width w of the shared edge strips and corner squares (tile sides)
  int variants = 1;           // total over the classes
  std::vector<std::vector<TilePoint>> tiles;  // per tile of set.tiles, sorted by id
  // Per class: its packing and tight radius (tile sides); one entry for a single-class fill.
  struct ClassRadii {
    double packing = 0, tight = 0;
    bool edge_objects = false;  // the class sits across edges (PoissonClass::edge_objects)
    double spacing = 0;         // the least distance between two points of the class (tile sides)
  };
  std::vector<ClassRadii> classes;
  // Per class: its first variant and its variant count (variants follow class by class).
  std::vector<std::pair<int, int>> class_variants;
};

// Class `species`'s first variant and its number of variants (a single-class set: 0, variants).
std::pair<int, int> class_variant_range(const FilledTileSet& filled, int species);
// The class whose variant range holds `variant` (none past the last class's).
std::optional<int> class_of_variant(const FilledTileSet& filled, int variant);

// What the fill did, for benchmarks and the CLI.
struct PoissonFillReport {
  std::size_t class_points = 0;   // distinct points (replicas counted once)
  double dart_min_distance = 0;   // minimum distance after darts, over all configurations
  double final_min_distance = 0;  // after relaxation
  // The same per pair of classes, class_min_distances of the result.
  std::vector<double> class_min_distance;
  int relax_rounds_run = 0;             // rounds that moved points and kept the bound
  int relax_rounds_rejected = 0;        // rounds undone because the bound could not be kept
  double nn_spread = 0;                 // std/mean of NN distances in the sample tiling at the end
  bool stopped_before_lattice = false;  // relaxation stopped by min_nn_spread
  // Per kept round: the guaranteed minimum distance (tile sides) and the NN spread after it.
  std::vector<double> round_min_distance, round_nn_spread;
};

// The most points per tile a fill takes (cohen8: about 56 s of one core at 10000; docs/limits.md).
inline constexpr int kMaxPointsPerTile = 10000;
// The longest fill accepted, by estimate_poisson_fill: about a minute.
inline constexpr double kMaxFillSeconds = 60.0;

// What a fill will cost, told before it starts (and refused above kMaxFillSeconds).
struct PoissonFillEstimate {
  double points = 0;   // tiles x points per tile
  double seconds = 0;  // of one core, fitted to measured fills (docs/limits.md): within 2x
};
PoissonFillEstimate estimate_poisson_fill(const TileSet& set, const PoissonFillOptions& options);

// Fills every tile of `set`. Deterministic from options.seed, same result on any thread count.
// Throws Error when the options are out of range or the estimate exceeds kMaxFillSeconds.
FilledTileSet fill_poisson_tiles(const TileSet& set, const PoissonFillOptions& options,
                                 PoissonFillReport* report = nullptr);

// For each tile and each of the 8 directions, the tiles that can sit there in a valid tiling:
// edge neighbours share the edge color and the colors of its end corners; diagonal neighbours
// complete a locally valid 2 x 2 block.
class TileAdjacency {
 public:
  explicit TileAdjacency(const TileSet& set);
  // dx, dy in {-1, 0, 1}, not both 0.
  std::span<const std::uint16_t> neighbours(std::size_t tile, int dx, int dy) const {
    return lists_[tile * 9 + static_cast<std::size_t>((dy + 1) * 3 + (dx + 1))];
  }

 private:
  std::vector<std::vector<std::uint16_t>> lists_;
};

// The smallest distance (tile sides) between two point instances of `filled` over every pair of
// tiles that can be neighbours (across an edge or a corner) in a valid tiling, and within tiles.
double min_distance_over_configurations(const FilledTileSet& filled);
// The same per pair of classes: [a * classes + b] (symmetric; classes = the largest species + 1);
// infinity where no two such points meet within a tile side.
std::vector<double> class_min_distances(const FilledTileSet& filled);

// The fill's limits (tile sides): packing and tight radii below kMaxClassRadius; exclusions, and
// the least distance between any two classes, below kMaxClassDistance (a point and its own copy in
// the tile beside, which can sit next to it, are a tile side apart).
inline constexpr double kMaxClassRadius = 0.5;
inline constexpr double kMaxClassDistance = 1.0;
// The least distance (tile sides) the fill keeps between a point of class a and one of class b,
// [a * classes + b]: the two packing radii plus the larger exclusion between them, or a class's
// own spacing at its share of options.points_per_tile (one class: the dart distance). The fill
// refuses options where one reaches kMaxClassDistance.
std::vector<double> class_fill_distances(const PoissonFillOptions& options);
// A pair of classes the fill would keep kMaxClassDistance or more apart.
struct ClassesTooFar {
  std::size_t a = 0, b = 0;  // a <= b; a == b: a class's own spacing at its share
  double distance = 0;       // tile sides (class_fill_distances)
};
// The first such pair (by a, then b), or nothing: the fill refuses options with one.
std::optional<ClassesTooFar> classes_too_far(const PoissonFillOptions& options);

// The attributes of point `id` (a function of the identity only).
struct PointAttributes {
  std::uint16_t variant = 0;
  float yaw = 0, scale = 1;
};
PointAttributes point_attributes(std::uint64_t seed, std::uint32_t id, int variants, double min_scale,
                                 double max_scale);
// Interior variation: the attributes of the k-th point of the tile at world tile (i, j), a
// function of (seed, i, j, k) only, so two copies of one tile carry different flowers.
PointAttributes world_point_attributes(std::uint64_t seed, std::int64_t i, std::int64_t j, std::uint32_t k,
                                       int variants, double min_scale, double max_scale);

// The tile-set sheet (draw_tileset_sheet's layout and colors, paled) with every tile's points:
// packing discs as dark rings, tight discs filled (replicas show in every tile that holds them,
// cut at the tile's border).
ImageRgb8 draw_filled_tileset_sheet(const FilledTileSet& filled, int tile_pixels = 192);

// sqrt(2 A / (sqrt(3) N)): the spacing of N points on a hexagonal lattice over area A; rho is
// the minimum distance over this.
double hexagonal_spacing(double area, double count);

}  // namespace wangscape
