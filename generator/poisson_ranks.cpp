// The progressive order of a Poisson fill (poisson_content.h; issue 26 item 2): per point, a rank
// such that the points of rank < d are Poisson at d x the density in every tiling, as dense near
// the tile edges as inside, so a species thinned by its density stays Poisson.
#include <cmath>
#include <limits>

#include "generator/poisson_content.h"

namespace wangscape::poisson_detail {

namespace {

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

}  // namespace

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

}  // namespace wangscape::poisson_detail
