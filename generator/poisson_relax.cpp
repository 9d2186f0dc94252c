// Relaxation in context (Cohen 2003, section 3.3), the second stage of a Poisson fill
// (poisson_content.h): Lloyd steps over random valid neighbourhoods, the distance bound enforced
// over every configuration, and the guard that stops before the points line up like a lattice.
#include <tbb/parallel_reduce.h>

#include <cmath>
#include <limits>

#include "generator/point_metrics.h"
#include "generator/poisson_content.h"

namespace wangscape::poisson_detail {

namespace {

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

}  // namespace

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

void relax_in_context(const RelaxContext& ctx, const SampleTiling& sample, double d_start, double cap_d,
                      PointSet& points, Content& content, PoissonFillReport& report) {
  const ContentModel& model = ctx.model;
  const SpeciesTable& species = ctx.species;
  const PoissonFillOptions& options = ctx.options;
  double d_current = d_start;
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
      ++report.relax_rounds_rejected;
      continue;
    }
    const double spread = nn_spread(sample, content);
    if (spread < options.min_nn_spread) {
      // Lattice-like: undo this round and stop.
      points = before;
      build_content(model, points, content);
      report.stopped_before_lattice = true;
      break;
    }
    d_current = std::max(reached, std::min(cap_d, min_meeting_distance(model, content, species, cap_d)));
    ++report.relax_rounds_run;
    report.round_min_distance.push_back(d_current);
    report.round_nn_spread.push_back(spread);
  }
}

}  // namespace wangscape::poisson_detail
