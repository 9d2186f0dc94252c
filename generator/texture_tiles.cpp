#include "generator/texture_tiles.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <limits>
#include <map>
#include <string>

namespace wangscape {

namespace {

constexpr std::uint64_t kInfinite = std::numeric_limits<std::uint64_t>::max() / 4;

std::uint64_t mix(std::uint64_t z) {
  z += 0x9E3779B97F4A7C15ull;
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

// Deterministic draws from one (seed, stream) pair, so parallel work never shares a generator.
class Draws {
 public:
  Draws(std::uint64_t seed, std::uint64_t stream) : state_(mix(seed ^ mix(stream))) {}
  int uniform(int lo, int hi) {  // inclusive
    return lo + static_cast<int>(mix(state_++) % static_cast<std::uint64_t>(hi - lo + 1));
  }

 private:
  std::uint64_t state_;
};

int square_difference(const std::uint8_t* a, const std::uint8_t* b) {
  const int r = a[0] - b[0], g = a[1] - b[1], bl = a[2] - b[2];
  return r * r + g * g + bl * bl;
}

// Quadrants of a tile around its centre, each split between a horizontal-edge diamond (first)
// and a vertical-edge diamond (second) by one cut along its diagonal.
enum Quadrant : int { kNEq = 0, kSEq, kSWq, kNWq };
constexpr std::array<int, 4> kFirstSlot = {kN, kS, kS, kN};
constexpr std::array<int, 4> kSecondSlot = {kE, kE, kW, kW};

struct Diamond {
  int orientation = 0;                // 0: N/S edge, halves west/east; 1: E/W edge, halves north/south
  std::size_t first = 0, second = 0;  // windows of the west (north) and east (south) halves
  bool mixed() const { return first != second; }
};

// What does not change during the search.
struct Problem {
  int size = 0, half = 0, band = 0, separation = 0;
  std::span<const ImageRgb8> exemplars;
  std::vector<Diamond> diamonds;
  std::vector<std::array<std::size_t, 4>> tile_diamonds;   // per tile, per slot
  std::vector<std::vector<std::size_t>> window_diamonds;   // diamonds reading each window
  std::vector<std::vector<std::size_t>> window_tiles;      // tiles reading each window
  std::vector<std::vector<std::size_t>> window_quadrants;  // tile * 4 + quadrant of the quadrants reading each window
};

struct Layout {
  std::vector<TextureWindow> windows;
  std::vector<std::vector<int>> cuts;  // per mixed diamond: one threshold per row across the edge
};

// The slot's window-relative offset of tile pixel (x, y): the inverse of texture_source_pixel.
std::array<int, 2> slot_offset(int size, int slot, int x, int y) {
  const TextureWindow origin{0, 0, 0};
  return texture_source_pixel(size, origin, slot, x, y);
}

const std::uint8_t* window_pixel(const Problem& p, const TextureWindow& w, int dx, int dy) {
  const ImageRgb8& image = p.exemplars[static_cast<std::size_t>(w.exemplar)];
  return &image.pixels[image.offset(w.x + dx, w.y + dy)];
}

// The window a diamond shows at window-relative (dx, dy): its mixed diamonds' cut across the edge.
std::size_t diamond_window(const Problem& p, const Layout& layout, std::size_t diamond, int dx, int dy) {
  const Diamond& d = p.diamonds[diamond];
  if (!d.mixed()) return d.first;
  const int along = d.orientation == 0 ? dx : dy, across = d.orientation == 0 ? dy : dx;
  return along < layout.cuts[diamond][static_cast<std::size_t>(across + p.half)] ? d.first : d.second;
}

struct Source {
  std::size_t window = 0;
  int slot = 0;
};

Source pixel_source(const Problem& p, const Layout& layout, std::size_t tile, int slot, int x, int y) {
  const auto [dx, dy] = slot_offset(p.size, slot, x, y);
  return {diamond_window(p, layout, p.tile_diamonds[tile][static_cast<std::size_t>(slot)], dx, dy), slot};
}

const std::uint8_t* source_color(const Problem& p, const Layout& layout, const Source& s, int x, int y) {
  const auto [ex, ey] = texture_source_pixel(p.size, layout.windows[s.window], s.slot, x, y);
  const ImageRgb8& image = p.exemplars[static_cast<std::size_t>(layout.windows[s.window].exemplar)];
  return &image.pixels[image.offset(ex, ey)];
}

// The cut joining a mixed diamond's halves: per row across the edge a threshold c in
// [-band, band] along it (first half where along < c), rows moving by at most one pixel. Returns
// the cost of the seam pairs it leaves (over the whole diamond); writes the thresholds to `cut`.
std::uint64_t bisector_cut(const Problem& p, const Layout& layout, std::size_t diamond, std::vector<int>* cut) {
  const Diamond& d = p.diamonds[diamond];
  const TextureWindow& a = layout.windows[d.first];
  const TextureWindow& b = layout.windows[d.second];
  const int band = p.band, states = 2 * band + 1, rows = p.size;
  // Row costs for along in [-band - 1, band].
  const auto row_errors = [&](int row, std::vector<std::uint64_t>& e) {
    const int across = row - p.half;
    for (int along = -band - 1; along <= band; ++along) {
      const int dx = d.orientation == 0 ? along : across, dy = d.orientation == 0 ? across : along;
      e[static_cast<std::size_t>(along + band + 1)] =
          static_cast<std::uint64_t>(square_difference(window_pixel(p, a, dx, dy), window_pixel(p, b, dx, dy)));
    }
  };
  std::vector<std::uint64_t> e(static_cast<std::size_t>(states + 1)), e_next(e.size());
  const auto at = [&](const std::vector<std::uint64_t>& errors, int along) {
    return errors[static_cast<std::size_t>(along + band + 1)];
  };
  std::vector<std::uint64_t> cost(static_cast<std::size_t>(states)), next(cost.size());
  std::vector<std::int8_t> back(static_cast<std::size_t>(rows * states), 0);
  row_errors(0, e);
  for (int c = -band; c <= band; ++c) cost[static_cast<std::size_t>(c + band)] = at(e, c - 1) + at(e, c);
  for (int row = 1; row < rows; ++row) {
    row_errors(row, e_next);
    for (int c = -band; c <= band; ++c) {
      std::uint64_t best = kInfinite;
      std::int8_t from = 0;
      // The cut crosses the edge itself straight (rows half - 1 and half, one in each tile), so
      // the pixels facing each other across the edge read the same window.
      const int steps = row == p.half ? 0 : 1;
      for (int step = -steps; step <= steps; ++step) {
        const int previous = c + step;
        if (previous < -band || previous > band) continue;
        // A step leaves one vertical seam pair, in the column between the two thresholds.
        const int column = std::min(c, previous);
        const std::uint64_t move = step == 0 ? 0 : at(e, column) + at(e_next, column);
        const std::uint64_t total = cost[static_cast<std::size_t>(previous + band)] + move;
        if (total < best) best = total, from = static_cast<std::int8_t>(step);
      }
      next[static_cast<std::size_t>(c + band)] = best + at(e_next, c - 1) + at(e_next, c);
      back[static_cast<std::size_t>(row * states + c + band)] = from;
    }
    std::swap(cost, next);
    std::swap(e, e_next);
  }
  const auto end = std::min_element(cost.begin(), cost.end());
  if (cut) {
    cut->assign(static_cast<std::size_t>(rows), 0);
    int c = static_cast<int>(end - cost.begin()) - band;
    for (int row = rows - 1; row >= 0; --row) {
      (*cut)[static_cast<std::size_t>(row)] = c;
      c += back[static_cast<std::size_t>(row * states + c + band)];
    }
  }
  return *end;
}

// Tile pixel of quadrant-local (a, b): a pixels from the centre towards the vertical edge, b
// towards the horizontal edge.
std::array<int, 2> quadrant_pixel(int half, int quadrant, int a, int b) {
  const bool east = quadrant == kNEq || quadrant == kSEq, north = quadrant == kNEq || quadrant == kNWq;
  return {east ? half + a : half - 1 - a, north ? half - 1 - b : half + b};
}

// The cut of one quadrant. Pixels lie on anti-diagonals k = a + b (0 at the centre, 2 half - 2
// at the tile corner) at q = a - b; pixel (k, q) takes the first (horizontal-edge) diamond when
// q < c_k. c_k steps by one between anti-diagonals, stays within the band, keeps both ends of
// every anti-diagonal on their own side (so border pixels keep their edge's diamond and no seam
// crosses into the next quadrant) and is pinned at the centre and corner pixels (first diamond).
// Returns the cost of the seam pairs inside the quadrant; writes c_k to `cut`.
std::uint64_t quadrant_cut(const Problem& p, const Layout& layout, std::size_t tile, int quadrant,
                           std::vector<int>* cut) {
  const int size = p.size, last = size - 2, band = p.band;
  const int first_slot = kFirstSlot[static_cast<std::size_t>(quadrant)];
  const int second_slot = kSecondSlot[static_cast<std::size_t>(quadrant)];
  const auto length = [&](int k) { return std::min(k, last - k) + 1; };
  const auto limit = [&](int k) { return std::min(band, length(k) - 2); };
  // Per anti-diagonal, pixel errors for q in [-(band + 2), band + 2].
  const int reach = band + 2, span = 2 * reach + 1;
  // A slot whose diamond is one window maps tile pixels to exemplar bytes by a fixed offset:
  // the fast path. Mixed diamonds go through their cut.
  struct Fetch {
    const std::uint8_t* pixels = nullptr;
    std::ptrdiff_t origin = 0, width = 0;  // byte offset of tile pixel (0, 0); exemplar width
  };
  const auto fetch = [&](int slot) {
    Fetch f;
    const Diamond& d = p.diamonds[p.tile_diamonds[tile][static_cast<std::size_t>(slot)]];
    if (d.mixed()) return f;
    const TextureWindow& w = layout.windows[d.first];
    const ImageRgb8& image = p.exemplars[static_cast<std::size_t>(w.exemplar)];
    const auto [x0, y0] = texture_source_pixel(p.size, w, slot, 0, 0);
    f.pixels = image.pixels.data();
    f.width = image.width;
    f.origin = (static_cast<std::ptrdiff_t>(y0) * f.width + x0) * 3;
    return f;
  };
  const Fetch first_fetch = fetch(first_slot), second_fetch = fetch(second_slot);
  const auto color = [&](const Fetch& f, int slot, int x, int y) {
    if (f.pixels) return f.pixels + f.origin + (static_cast<std::ptrdiff_t>(y) * f.width + x) * 3;
    return source_color(p, layout, pixel_source(p, layout, tile, slot, x, y), x, y);
  };
  const auto corner = quadrant_pixel(p.half, quadrant, 0, 0);  // no structured binding: clang 14 cannot capture one
  const int x0 = corner[0], y0 = corner[1];
  const int step_x = quadrant == kNEq || quadrant == kSEq ? 1 : -1,
            step_y = quadrant == kSEq || quadrant == kSWq ? 1 : -1;
  const auto errors = [&](int k, std::vector<std::uint64_t>& e) {
    std::fill(e.begin(), e.end(), kInfinite);
    const int extent = std::min(length(k) - 1, reach);
    for (int q = ((extent - k) & 1) ? 1 - extent : -extent; q <= extent; q += 2) {
      const int x = x0 + step_x * ((k + q) / 2), y = y0 + step_y * ((k - q) / 2);
      e[static_cast<std::size_t>(q + reach)] = static_cast<std::uint64_t>(
          square_difference(color(first_fetch, first_slot, x, y), color(second_fetch, second_slot, x, y)));
    }
  };
  const int states = 2 * band + 3, offset = band + 1;  // c in [-band - 1, band + 1]
  std::vector<std::uint64_t> e(static_cast<std::size_t>(span)), e_next(e.size());
  std::vector<std::uint64_t> cost(static_cast<std::size_t>(states), kInfinite), next(cost.size());
  std::vector<std::int8_t> back(static_cast<std::size_t>((last + 1) * states), 0);
  cost[static_cast<std::size_t>(1 + offset)] = 0;
  errors(0, e);
  for (int k = 0; k < last; ++k) {
    errors(k + 1, e_next);
    std::fill(next.begin(), next.end(), kInfinite);
    // Allowed thresholds on k + 1: parity opposite to its pixels', within the limit.
    const int lim = k + 1 == last ? 1 : limit(k + 1);
    const int lo = k + 1 == last ? 1 : (((lim + k) & 1) ? 1 - lim : -lim);
    for (int c2 = lo; c2 <= lim; c2 += 2) {
      for (const int step : {-1, 1}) {
        const int c = c2 + step;
        if (c < -band - 1 || c > band + 1 || cost[static_cast<std::size_t>(c + offset)] >= kInfinite) continue;
        // Moving the threshold by one between anti-diagonals leaves exactly one seam pair: pixel
        // q = c2 on k against pixel c on k+1 (when both exist).
        const std::uint64_t eq = e[static_cast<std::size_t>(c2 + reach)],
                            er = e_next[static_cast<std::size_t>(c + reach)];
        const std::uint64_t pairs = eq < kInfinite && er < kInfinite ? eq + er : 0;
        const std::uint64_t total = cost[static_cast<std::size_t>(c + offset)] + pairs;
        if (total < next[static_cast<std::size_t>(c2 + offset)]) {
          next[static_cast<std::size_t>(c2 + offset)] = total;
          back[static_cast<std::size_t>((k + 1) * states + c2 + offset)] = static_cast<std::int8_t>(step);
        }
      }
    }
    std::swap(cost, next);
    std::swap(e, e_next);
  }
  if (cut) {
    cut->assign(static_cast<std::size_t>(last + 1), 0);
    int c = 1;
    for (int k = last; k >= 0; --k) {
      (*cut)[static_cast<std::size_t>(k)] = c;
      c += back[static_cast<std::size_t>(k * states + c + offset)];
    }
  }
  return cost[static_cast<std::size_t>(1 + offset)];
}

// The two pairs across the centre lines that every layout has: the N and S diamonds meet
// between the NE and SE centre pixels and between the NW and SW ones.
std::uint64_t centre_pairs(const Problem& p, const Layout& layout, std::size_t tile) {
  std::uint64_t total = 0;
  for (const int x : {p.half - 1, p.half}) {
    const int y_north = p.half - 1, y_south = p.half;
    const Source n = pixel_source(p, layout, tile, kN, x, y_north);
    const Source s = pixel_source(p, layout, tile, kS, x, y_south);
    total += static_cast<std::uint64_t>(
        square_difference(source_color(p, layout, n, x, y_north), source_color(p, layout, s, x, y_north)) +
        square_difference(source_color(p, layout, n, x, y_south), source_color(p, layout, s, x, y_south)));
  }
  return total;
}

// The quadrants a slot's diamond reaches into.
constexpr std::array<std::array<int, 2>, 4> kSlotQuadrants = {{{kNEq, kNWq}, {kNEq, kSEq}, {kSEq, kSWq}, {kSWq, kNWq}}};

// Far enough from every other window of its exemplar, also at the offsets where diamonds meet.
bool well_separated(const Problem& p, const Layout& layout, std::size_t window, const TextureWindow& at) {
  const int h = p.half;
  static constexpr std::array<std::array<int, 2>, 9> kMeet = {
      {{0, 0}, {0, 2}, {0, -2}, {2, 0}, {-2, 0}, {1, 1}, {1, -1}, {-1, 1}, {-1, -1}}};
  for (std::size_t other = 0; other < layout.windows.size(); ++other) {
    const TextureWindow& o = layout.windows[other];
    if (other == window || o.exemplar != at.exemplar) continue;
    for (const auto& [mx, my] : kMeet) {
      const int dx = at.x - o.x - mx * h, dy = at.y - o.y - my * h;
      if (std::max(std::abs(dx), std::abs(dy)) < p.separation) return false;
    }
  }
  return true;
}

// A random window position, one pixel inside the exemplar (seam costs read one pixel beyond a
// source's own region).
TextureWindow random_window(const Problem& p, int exemplar, Draws& draws) {
  const ImageRgb8& image = p.exemplars[static_cast<std::size_t>(exemplar)];
  return {exemplar, draws.uniform(p.half + 1, image.width - p.half - 1),
          draws.uniform(p.half + 1, image.height - p.half - 1)};
}

}  // namespace

std::size_t TextureTileSet::window_index(int orientation, int color, int mark) const {
  const int horizontal = set.has_edges ? set.horizontal_colors : 1;
  return static_cast<std::size_t>(((orientation == 0 ? 0 : horizontal) + color) * marks + mark);
}

std::uint64_t TextureTileSet::total_error() const {
  std::uint64_t total = 0;
  for (const TextureTile& t : tiles) total += t.error;
  return total;
}

TextureTileSet make_texture_tiles(const TileSet& set, std::span<const ImageRgb8> exemplars,
                                  const TextureTileOptions& options, TextureTileReport* report) {
  const std::string where = "texture tiles of " + set.describe();
  const int size = options.tile_size;
  if (size < 16 || size > 4096 || size % 2 != 0)
    throw Error(where + ": tile size " + std::to_string(size) + "; expected an even number in 16..4096");
  if (exemplars.empty() || exemplars.size() > 2)
    throw Error(where + ": " + std::to_string(exemplars.size()) + " exemplars; expected 1 or 2");
  for (std::size_t e = 0; e < exemplars.size(); ++e)
    if (exemplars[e].width < size + 2 || exemplars[e].height < size + 2)
      throw Error(where + ": exemplar " + std::to_string(e + 1) + " is " + std::to_string(exemplars[e].width) + " x " +
                  std::to_string(exemplars[e].height) + " pixels; tiles of " + std::to_string(size) +
                  " need at least " + std::to_string(size + 2) + " x " + std::to_string(size + 2));
  if (options.band < 0 || options.band > size / 8)
    throw Error(where + ": band " + std::to_string(options.band) + "; expected 0..tile size / 8");
  if (options.rounds < 0 || options.candidates < 1 || options.min_separation < 0)
    throw Error(where + ": expected rounds >= 0, candidates >= 1, min separation >= 0");

  TextureTileSet result;
  result.set = set;
  result.tile_size = size;
  result.marks = set.has_corners ? std::max(1, set.corner_colors) : 1;
  const int horizontal = set.has_edges ? set.horizontal_colors : 1, vertical = set.has_edges ? set.vertical_colors : 1;
  const std::size_t window_count = static_cast<std::size_t>((horizontal + vertical) * result.marks);

  Problem p;
  p.size = size;
  p.half = size / 2;
  p.band = options.band > 0 ? options.band : std::max(2, size / 16);
  p.separation = options.min_separation > 0 ? options.min_separation : size / 8;
  p.exemplars = exemplars;
  p.window_diamonds.resize(window_count);
  p.window_tiles.resize(window_count);
  p.window_quadrants.resize(window_count);
  std::map<std::array<int, 4>, std::size_t> diamond_ids;
  const auto color = [](int c) { return c < 0 ? 0 : c; };
  for (std::size_t t = 0; t < set.size(); ++t) {
    const Tile& tile = set.tiles[t];
    // Per slot: the marks at the west/north end and at the east/south end of the edge.
    const std::array<std::array<int, 2>, 4> ends = {
        {{tile.nw(), tile.ne()}, {tile.ne(), tile.se()}, {tile.sw(), tile.se()}, {tile.nw(), tile.sw()}}};
    std::array<std::size_t, 4> slots{};
    for (int slot = 0; slot < 4; ++slot) {
      const int orientation = slot == kN || slot == kS ? 0 : 1;
      const int edge = color(tile.colors[static_cast<std::size_t>(slot)]);
      const int m1 = color(ends[static_cast<std::size_t>(slot)][0]),
                m2 = color(ends[static_cast<std::size_t>(slot)][1]);
      const auto [it, added] = diamond_ids.try_emplace({orientation, edge, m1, m2}, p.diamonds.size());
      if (added) {
        const Diamond d{orientation, result.window_index(orientation, edge, m1),
                        result.window_index(orientation, edge, m2)};
        p.diamonds.push_back(d);
        p.window_diamonds[d.first].push_back(it->second);
        if (d.mixed()) p.window_diamonds[d.second].push_back(it->second);
      }
      slots[static_cast<std::size_t>(slot)] = it->second;
      const Diamond& d = p.diamonds[it->second];
      for (const std::size_t w : {d.first, d.second}) {
        if (p.window_tiles[w].empty() || p.window_tiles[w].back() != t) p.window_tiles[w].push_back(t);
        for (const int q : kSlotQuadrants[static_cast<std::size_t>(slot)])
          p.window_quadrants[w].push_back(t * 4 + static_cast<std::size_t>(q));
      }
    }
    p.tile_diamonds.push_back(slots);
  }
  for (std::vector<std::size_t>& quadrants : p.window_quadrants) {
    std::sort(quadrants.begin(), quadrants.end());
    quadrants.erase(std::unique(quadrants.begin(), quadrants.end()), quadrants.end());
  }

  // Initial windows: random, well separated; window w reads exemplar (its mark) mod exemplars.
  Layout layout;
  layout.windows.resize(window_count);
  layout.cuts.resize(p.diamonds.size());
  for (std::size_t w = 0; w < window_count; ++w) {
    const int exemplar =
        static_cast<int>(static_cast<std::size_t>(w % static_cast<std::size_t>(result.marks)) % exemplars.size());
    Draws draws(options.seed, 0x1000000 + w);
    bool placed = false;
    for (int attempt = 0; attempt < 10000 && !placed; ++attempt) {
      const TextureWindow at = random_window(p, exemplar, draws);
      layout.windows[w] = at;
      // Windows after w are not placed yet: check against the placed ones only.
      Layout placed_only;
      placed_only.windows.assign(layout.windows.begin(), layout.windows.begin() + static_cast<std::ptrdiff_t>(w + 1));
      placed = well_separated(p, placed_only, w, at);
    }
    if (!placed)
      throw Error(where + ": exemplar " + std::to_string(exemplar + 1) + " has no room for " +
                  std::to_string(window_count) + " windows of " + std::to_string(size) + " pixels kept " +
                  std::to_string(p.separation) +
                  " pixels apart; use a larger exemplar, smaller tiles or a smaller separation");
  }
  std::vector<std::uint64_t> diamond_cost(p.diamonds.size(), 0), centre_costs(set.size(), 0);
  std::vector<std::uint64_t> quadrant_costs(set.size() * 4, 0);
  for (std::size_t d = 0; d < p.diamonds.size(); ++d)
    if (p.diamonds[d].mixed()) diamond_cost[d] = bisector_cut(p, layout, d, &layout.cuts[d]);
  tbb::parallel_for(std::size_t{0}, set.size(), [&](std::size_t t) {
    centre_costs[t] = centre_pairs(p, layout, t);
    for (int q = 0; q < 4; ++q)
      quadrant_costs[t * 4 + static_cast<std::size_t>(q)] = quadrant_cut(p, layout, t, q, nullptr);
  });
  const auto objective = [&] {
    std::uint64_t total = 0;
    for (const auto* costs : {&diamond_cost, &centre_costs, &quadrant_costs})
      for (const std::uint64_t c : *costs) total += c;
    return total;
  };
  TextureTileReport stats;
  stats.initial_cost = objective();

  // The search: per window, candidates in parallel; the cheapest (first on ties) replaces the
  // window when it lowers the cost of the tiles and diamonds that read it.
  struct Trial {
    TextureWindow at;
    std::uint64_t cost = kInfinite;
    std::vector<std::vector<int>> cuts;  // of the window's mixed diamonds
    std::vector<std::uint64_t> diamond_costs, centre_costs, quadrant_costs;
  };
  for (int round = 0; round < options.rounds; ++round)
    for (std::size_t w = 0; w < window_count; ++w) {
      const std::vector<std::size_t>& diamonds = p.window_diamonds[w];
      const std::vector<std::size_t>& tiles = p.window_tiles[w];
      const std::vector<std::size_t>& quadrants = p.window_quadrants[w];
      if (tiles.empty()) continue;
      std::uint64_t current = 0;
      for (const std::size_t d : diamonds) current += diamond_cost[d];
      for (const std::size_t t : tiles) current += centre_costs[t];
      for (const std::size_t q : quadrants) current += quadrant_costs[q];
      std::vector<Trial> trials(static_cast<std::size_t>(options.candidates));
      Draws draws(options.seed, (static_cast<std::uint64_t>(round) << 32) + w);
      for (Trial& trial : trials) {
        trial.at = layout.windows[w];
        for (int attempt = 0; attempt < 64; ++attempt) {
          const TextureWindow at = random_window(p, layout.windows[w].exemplar, draws);
          if (well_separated(p, layout, w, at)) {
            trial.at = at;
            trial.cost = 0;
            break;
          }
        }
      }
      tbb::parallel_for(std::size_t{0}, trials.size(), [&](std::size_t k) {
        Trial& trial = trials[k];
        if (trial.cost >= kInfinite) return;
        Layout local = layout;
        local.windows[w] = trial.at;
        for (const std::size_t d : diamonds) {
          const std::uint64_t c = p.diamonds[d].mixed() ? bisector_cut(p, local, d, &local.cuts[d]) : 0;
          trial.diamond_costs.push_back(c);
          trial.cuts.push_back(local.cuts[d]);
          trial.cost += c;
        }
        for (const std::size_t t : tiles) {
          trial.centre_costs.push_back(centre_pairs(p, local, t));
          trial.cost += trial.centre_costs.back();
        }
        for (const std::size_t q : quadrants) {
          trial.quadrant_costs.push_back(quadrant_cut(p, local, q / 4, static_cast<int>(q % 4), nullptr));
          trial.cost += trial.quadrant_costs.back();
        }
      });
      stats.candidates_tried += options.candidates;
      std::size_t best = 0;
      for (std::size_t k = 1; k < trials.size(); ++k)
        if (trials[k].cost < trials[best].cost) best = k;
      if (trials[best].cost >= current) continue;
      ++stats.moves_accepted;
      Trial& chosen = trials[best];
      layout.windows[w] = chosen.at;
      for (std::size_t k = 0; k < diamonds.size(); ++k) {
        layout.cuts[diamonds[k]] = std::move(chosen.cuts[k]);
        diamond_cost[diamonds[k]] = chosen.diamond_costs[k];
      }
      for (std::size_t k = 0; k < tiles.size(); ++k) centre_costs[tiles[k]] = chosen.centre_costs[k];
      for (std::size_t k = 0; k < quadrants.size(); ++k) quadrant_costs[quadrants[k]] = chosen.quadrant_costs[k];
    }
  stats.final_cost = objective();
  if (report) *report = stats;

  // The tiles: labels from the cuts, pixels from the sources, and the seam cost they leave.
  result.windows = layout.windows;
  result.tiles.resize(set.size());
  tbb::parallel_for(std::size_t{0}, set.size(), [&](std::size_t t) {
    TextureTile& out = result.tiles[t];
    out.image = ImageRgb8(size, size);
    out.source.assign(static_cast<std::size_t>(size) * static_cast<std::size_t>(size), 0);
    std::vector<Source> sources(out.source.size());
    std::vector<int> cut;
    for (int quadrant = 0; quadrant < 4; ++quadrant) {
      quadrant_cut(p, layout, t, quadrant, &cut);
      for (int b = 0; b < p.half; ++b)
        for (int a = 0; a < p.half; ++a) {
          const auto [x, y] = quadrant_pixel(p.half, quadrant, a, b);
          const bool first = a - b < cut[static_cast<std::size_t>(a + b)];
          const int slot =
              first ? kFirstSlot[static_cast<std::size_t>(quadrant)] : kSecondSlot[static_cast<std::size_t>(quadrant)];
          const Source s = pixel_source(p, layout, t, slot, x, y);
          const std::size_t o =
              static_cast<std::size_t>(y) * static_cast<std::size_t>(size) + static_cast<std::size_t>(x);
          sources[o] = s;
          out.source[o] = static_cast<std::uint16_t>(s.window * 4 + static_cast<std::size_t>(s.slot));
          const std::uint8_t* c = source_color(p, layout, s, x, y);
          out.image.set(x, y, {c[0], c[1], c[2]});
        }
    }
    for (int y = 0; y < size; ++y)
      for (int x = 0; x < size; ++x) {
        const std::size_t o =
            static_cast<std::size_t>(y) * static_cast<std::size_t>(size) + static_cast<std::size_t>(x);
        for (const auto& [nx, ny] : {std::array<int, 2>{x + 1, y}, std::array<int, 2>{x, y + 1}}) {
          if (nx >= size || ny >= size) continue;
          const std::size_t n =
              static_cast<std::size_t>(ny) * static_cast<std::size_t>(size) + static_cast<std::size_t>(nx);
          if (out.source[o] == out.source[n]) continue;
          const Source& a = sources[o];
          const Source& b = sources[n];
          out.error += static_cast<std::uint64_t>(
              square_difference(source_color(p, layout, a, x, y), source_color(p, layout, b, x, y)) +
              square_difference(source_color(p, layout, a, nx, ny), source_color(p, layout, b, nx, ny)));
        }
      }
  });
  return result;
}

ImageRgb8 draw_texture_tiling(const TextureTileSet& tiles, const Tiling& tiling) {
  const std::int64_t t = tiles.tile_size;
  if (tiling.width < 1 || tiling.height < 1 || tiling.width * t * tiling.height * t > (std::int64_t{1} << 28))
    throw Error("texture tiling preview: " + std::to_string(tiling.width) + " x " + std::to_string(tiling.height) +
                " tiles of " + std::to_string(t) + " pixels; expected a positive size of at most 2^28 pixels");
  for (const std::uint16_t index : tiling.tiles)
    if (index >= tiles.tiles.size())
      throw Error("texture tiling preview: tile " + std::to_string(index) + " of a set of " +
                  std::to_string(tiles.tiles.size()));
  const int size = tiles.tile_size;
  ImageRgb8 image(tiling.width * size, tiling.height * size);
  tbb::parallel_for(0, tiling.height, [&](int lj) {
    const int top = (tiling.height - 1 - lj) * size;
    for (int li = 0; li < tiling.width; ++li) {
      const ImageRgb8& tile = tiles.tiles[tiling.at(li, lj)].image;
      for (int y = 0; y < size; ++y)
        std::copy_n(&tile.pixels[tile.offset(0, y)], static_cast<std::size_t>(size) * 3,
                    &image.pixels[image.offset(li * size, top + y)]);
    }
  });
  return image;
}

}  // namespace wangscape
