// Dart throwing (Shade 2002), the first stage of a Poisson fill (poisson_content.h): round-robin
// over the tiles, shared regions before interiors, each species in turn, with quotas that keep the
// shared strips and corner squares from jamming.
#include <cmath>
#include <limits>

#include "generator/poisson_content.h"

namespace wangscape::poisson_detail {

namespace {

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

}  // namespace

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

}  // namespace wangscape::poisson_detail
