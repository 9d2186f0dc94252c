// The content model of a Poisson fill (poisson_content.h): the parts of a tile and the tiles that
// share each, the points meeting across edges and corners, and which tiles can be neighbours
// (TileAdjacency) with the least distances a filled set keeps over them.
#include <tbb/parallel_reduce.h>

#include <cmath>
#include <limits>
#include <map>

#include "generator/poisson_content.h"

namespace wangscape {

namespace poisson_detail {

ContentModel::ContentModel(const TileSet& set, const TileAdjacency& adjacency, double shared_width, double corner_width)
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

}  // namespace poisson_detail

using poisson_detail::block_index;
using poisson_detail::east_key;
using poisson_detail::EdgeKey;
using poisson_detail::kDirections;
using poisson_detail::near_side;
using poisson_detail::north_key;
using poisson_detail::south_key;
using poisson_detail::Vec2;
using poisson_detail::west_key;

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

}  // namespace wangscape
