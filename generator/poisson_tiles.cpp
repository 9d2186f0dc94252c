// The Poisson fill of a tile set (generator/poisson_tiles.h): its options and classes checked, the
// strips' widths chosen, the stages run (poisson_content.h: darts, relaxation, progressive order)
// and the points exported with their attributes; the fill's cost estimate and its sheet.
#include "generator/poisson_tiles.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <numbers>
#include <optional>
#include <string>

#include "core/number_text.h"
#include "generator/poisson_content.h"
#include "generator/tiling_preview.h"

namespace wangscape {

using poisson_detail::build_content;
using poisson_detail::class_quotas;
using poisson_detail::Content;
using poisson_detail::ContentModel;
using poisson_detail::DartPass;
using poisson_detail::east_key;
using poisson_detail::EdgeKey;
using poisson_detail::hash_combine;
using poisson_detail::Held;
using poisson_detail::kDirections;
using poisson_detail::min_meeting_distance;
using poisson_detail::nn_spread;
using poisson_detail::PointSet;
using poisson_detail::relax_in_context;
using poisson_detail::RelaxContext;
using poisson_detail::Rng;
using poisson_detail::sample_tiling;
using poisson_detail::SampleTiling;
using poisson_detail::SpeciesTable;
using poisson_detail::throw_darts;
using poisson_detail::west_key;

namespace {

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

// Each class's radii as the fill kept them, from the least distances between classes over every
// configuration (FilledTileSet::classes; class_min_distances).
std::vector<FilledTileSet::ClassRadii> class_radii(const FilledTileSet& filled, const SpeciesTable& species,
                                                   const std::vector<double>& least) {
  if (species.count == 1) return {{filled.radius_packing, filled.radius_tight, false, 2.0 * filled.radius_packing}};
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
  std::vector<FilledTileSet::ClassRadii> radii;
  for (std::size_t c = 0; c < species.count; ++c)
    radii.push_back(
        {factor * species.packing[c], species.tight[c], species.edge_objects[c] != 0, factor * species.distance(c, c)});
  return radii;
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
  relax_in_context(ctx, sample, std::min(dart_d, rep.dart_min_distance), cap_d, points, content, rep);

  FilledTileSet filled =
      export_points(set, options, species, progressive_ranks(model, content, points, species, options), content);
  rep.class_min_distance = class_min_distances(filled);
  const std::vector<double>& least = rep.class_min_distance;
  rep.final_min_distance = *std::min_element(least.begin(), least.end());
  rep.nn_spread = nn_spread(sample, content);
  filled.radius_packing = 0.5 * rep.final_min_distance * (1.0 - 1e-6);
  filled.radius_tight = tight;
  filled.shared_width = w;
  filled.classes = class_radii(filled, species, least);
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
