#include "generator/texture_tiles.h"

#include "core/hash.h"
#include "generator/image_spectrum.h"
#include "generator/noise_tiles.h"
#include "generator/tiling.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numbers>
#include <optional>
#include <string>

namespace wangscape {

namespace {

constexpr std::uint64_t kInfinite = std::numeric_limits<std::uint64_t>::max() / 4;

// Deterministic draws from one (seed, stream) pair, so parallel work never shares a generator.
class Draws {
 public:
  Draws(std::uint64_t seed, std::uint64_t stream) : state_(mix64(seed ^ mix64(stream))) {}
  int uniform(int lo, int hi) {  // inclusive
    return lo + static_cast<int>(mix64(state_++) % static_cast<std::uint64_t>(hi - lo + 1));
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

// What does not change during one exemplar's search. Every diamond key of the set (orientation,
// edge color, the corner marks at the edge's two ends) owns one window of that exemplar.
struct Problem {
  int size = 0, half = 0, band = 0, separation = 0;
  int exemplar = 0;
  std::span<const ImageRgb8> exemplars;
  std::vector<std::array<std::size_t, 4>> tile_windows;    // per tile, per slot
  std::vector<std::vector<std::size_t>> window_tiles;      // tiles reading each window
  std::vector<std::vector<std::size_t>> window_quadrants;  // tile * 4 + quadrant of the quadrants reading each window
};

struct Layout {
  std::vector<TextureWindow> windows;
};

struct Source {
  std::size_t window = 0;
  int slot = 0;
};

Source pixel_source(const Problem& p, std::size_t tile, int slot) {
  return {p.tile_windows[tile][static_cast<std::size_t>(slot)], slot};
}

const std::uint8_t* source_color(const Problem& p, const Layout& layout, const Source& s, int x, int y) {
  const auto [ex, ey] = texture_source_pixel(p.size, layout.windows[s.window], s.slot, x, y);
  const ImageRgb8& image = p.exemplars[static_cast<std::size_t>(layout.windows[s.window].exemplar)];
  return &image.pixels[image.offset(ex, ey)];
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
  // A slot maps tile pixels to exemplar bytes by a fixed offset.
  struct Fetch {
    const std::uint8_t* pixels = nullptr;
    std::ptrdiff_t origin = 0, width = 0;  // byte offset of tile pixel (0, 0); exemplar width
  };
  const auto fetch = [&](int slot) {
    Fetch f;
    const TextureWindow& w = layout.windows[p.tile_windows[tile][static_cast<std::size_t>(slot)]];
    const ImageRgb8& image = p.exemplars[static_cast<std::size_t>(w.exemplar)];
    const auto [x0, y0] = texture_source_pixel(p.size, w, slot, 0, 0);
    f.pixels = image.pixels.data();
    f.width = image.width;
    f.origin = (static_cast<std::ptrdiff_t>(y0) * f.width + x0) * 3;
    return f;
  };
  const Fetch first_fetch = fetch(first_slot), second_fetch = fetch(second_slot);
  const auto color = [&](const Fetch& f, int x, int y) {
    return f.pixels + f.origin + (static_cast<std::ptrdiff_t>(y) * f.width + x) * 3;
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
      e[static_cast<std::size_t>(q + reach)] =
          static_cast<std::uint64_t>(square_difference(color(first_fetch, x, y), color(second_fetch, x, y)));
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
    const Source n = pixel_source(p, tile, kN);
    const Source s = pixel_source(p, tile, kS);
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

std::uint64_t TextureTileSet::total_error() const {
  std::uint64_t total = 0;
  for (const TextureTile& t : tiles) total += t.error;
  return total;
}

namespace {

// Windows keep p.separation apart when they can: from half a tile, halved while the exemplar has
// no room, down to the floor. Throws Error naming the exemplar when even the floor has no room.
Layout place_windows(Problem& p, std::size_t window_count, int floor, std::uint64_t seed, const std::string& where) {
  Layout layout;
  layout.windows.resize(window_count);
  for (p.separation = std::max(floor, p.size / 2);; p.separation = std::max(floor, p.separation / 2)) {
    bool all = true;
    for (std::size_t w = 0; w < window_count && all; ++w) {
      Draws draws(seed, 0x1000000 + (static_cast<std::uint64_t>(p.exemplar) << 20) + w);
      bool placed = false;
      for (int attempt = 0; attempt < 2000 && !placed; ++attempt) {
        const TextureWindow at = random_window(p, p.exemplar, draws);
        layout.windows[w] = at;
        // Windows after w are not placed yet: check against the placed ones only.
        Layout placed_only;
        placed_only.windows.assign(layout.windows.begin(), layout.windows.begin() + static_cast<std::ptrdiff_t>(w + 1));
        placed = well_separated(p, placed_only, w, at);
      }
      all = placed;
    }
    if (all) return layout;
    if (p.separation == floor)
      throw Error(where + ": exemplar " + std::to_string(p.exemplar + 1) + " has no room for " +
                  std::to_string(window_count) + " windows of " + std::to_string(p.size) + " pixels kept " +
                  std::to_string(floor) +
                  " pixels apart; use a larger exemplar, smaller tiles or a smaller separation");
  }
}

// The sample search (Cohen 2003, section 3.2) over one exemplar's windows: per window,
// candidates in parallel; the cheapest (first on ties) replaces the window when it lowers the cost
// of the quadrants that read it.
void search_windows(const Problem& p, Layout& layout, const TextureTileOptions& options, TextureTileReport& stats) {
  const std::size_t tile_count = p.tile_windows.size();
  std::vector<std::uint64_t> centre_costs(tile_count, 0), quadrant_costs(tile_count * 4, 0);
  tbb::parallel_for(std::size_t{0}, tile_count, [&](std::size_t t) {
    centre_costs[t] = centre_pairs(p, layout, t);
    for (int q = 0; q < 4; ++q)
      quadrant_costs[t * 4 + static_cast<std::size_t>(q)] = quadrant_cut(p, layout, t, q, nullptr);
  });
  const auto objective = [&] {
    std::uint64_t total = 0;
    for (const auto* costs : {&centre_costs, &quadrant_costs})
      for (const std::uint64_t c : *costs) total += c;
    return total;
  };
  stats.initial_cost += objective();
  struct Trial {
    TextureWindow at;
    std::uint64_t cost = kInfinite;
    std::vector<std::uint64_t> centre_costs, quadrant_costs;
  };
  for (int round = 0; round < options.rounds; ++round)
    for (std::size_t w = 0; w < layout.windows.size(); ++w) {
      const std::vector<std::size_t>& tiles = p.window_tiles[w];
      const std::vector<std::size_t>& quadrants = p.window_quadrants[w];
      if (tiles.empty()) continue;
      std::uint64_t current = 0;
      for (const std::size_t t : tiles) current += centre_costs[t];
      for (const std::size_t q : quadrants) current += quadrant_costs[q];
      std::vector<Trial> trials(static_cast<std::size_t>(options.candidates));
      Draws draws(options.seed,
                  (static_cast<std::uint64_t>(round) << 32) + (static_cast<std::uint64_t>(p.exemplar) << 24) + w);
      for (Trial& trial : trials) {
        trial.at = layout.windows[w];
        for (int attempt = 0; attempt < 64; ++attempt) {
          const TextureWindow at = random_window(p, p.exemplar, draws);
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
      const Trial& chosen = trials[best];
      layout.windows[w] = chosen.at;
      for (std::size_t k = 0; k < tiles.size(); ++k) centre_costs[tiles[k]] = chosen.centre_costs[k];
      for (std::size_t k = 0; k < quadrants.size(); ++k) quadrant_costs[quadrants[k]] = chosen.quadrant_costs[k];
    }
  stats.final_cost += objective();
}

// Per pixel of tile t, row-major: the source the quadrant cuts give it.
std::vector<Source> tile_sources(const Problem& p, const Layout& layout, std::size_t t) {
  std::vector<Source> sources(static_cast<std::size_t>(p.size) * static_cast<std::size_t>(p.size));
  std::vector<int> cut;
  for (int quadrant = 0; quadrant < 4; ++quadrant) {
    quadrant_cut(p, layout, t, quadrant, &cut);
    for (int b = 0; b < p.half; ++b)
      for (int a = 0; a < p.half; ++a) {
        const auto [x, y] = quadrant_pixel(p.half, quadrant, a, b);
        const bool first = a - b < cut[static_cast<std::size_t>(a + b)];
        const int slot =
            first ? kFirstSlot[static_cast<std::size_t>(quadrant)] : kSecondSlot[static_cast<std::size_t>(quadrant)];
        sources[static_cast<std::size_t>(y) * static_cast<std::size_t>(p.size) + static_cast<std::size_t>(x)] =
            pixel_source(p, t, slot);
      }
  }
  return sources;
}

// A tile's own interior: a patch of the exemplar (a window read through slot N, so the whole
// tile is one straight copy of it) over all of the tile but a border, inside a closed cut around
// the tile centre. Tiles that share their edges' diamonds then still differ inside: with K colors
// per edge, a neighbour shares each diamond with probability ~1/K, and without interiors a 2-color
// set repeated half of its picture at one tile's shift. Until issue 23's second pass the interior
// was a disc (radius 3/8 to 1/2 of a side less 3 pixels): the tile's corners, a quarter of it,
// stayed the diamonds', and the corners of four tiles around every tiling vertex showed the same
// soil spots as often as their edge colors matched (cohen8: a lattice of spots at the tile period).
struct Interior {
  TextureWindow window;       // read through kN
  std::vector<float> radius;  // per angle step: pixels whose centre is closer to the tile centre are inside
  std::uint64_t cost = kInfinite;
};

constexpr int kInteriorAngles = 256;
// The interior comes no closer than this to the tile's edges (the border row keeps its diamonds,
// so tiles stay seamless across edges); its cut runs up to a sixteenth of a side deeper in. A
// wider band (a sixth of a side, or a 3-pixel border) let the cut wander inwards: interiors
// covered 0.56-0.6 of a tile instead of 0.83, and cohen8 repeated 0.28 instead of 0.21.
constexpr double kInteriorBorder = 1;

int angle_step(double dx, double dy) {
  const double turn = std::atan2(dy, dx) / (2 * std::numbers::pi);
  return static_cast<int>(std::lround((turn < 0 ? turn + 1 : turn) * kInteriorAngles)) % kInteriorAngles;
}

bool inside(const Interior& interior, int size, int x, int y) {
  const double dx = x + 0.5 - size / 2.0, dy = y + 0.5 - size / 2.0;
  return std::hypot(dx, dy) < interior.radius[static_cast<std::size_t>(angle_step(dx, dy))];
}

// The cheapest closed cut around the tile centre between `base` (the tile's sources without an
// interior) and the patch of `window`: per angle step a depth of 0 to size / 16 pixels inside the
// square kInteriorBorder pixels within the tile's edges, neighbouring steps differing by at most
// one pixel of depth, the last step next to the first (dynamic programming per first depth). The
// cost is the seam pairs across the cut, |patch - base|^2 on both pixels of each pair.
Interior interior_cut(const Problem& p, const Layout& layout, const std::vector<Source>& base,
                      const TextureWindow& window) {
  if (p.size < 24) return {window, std::vector<float>(kInteriorAngles, 0.f), 0};  // no room: no interior
  const int states = p.size / 16 + 1;
  const ImageRgb8& image = p.exemplars[static_cast<std::size_t>(window.exemplar)];
  const auto error_at = [&](double radius, double angle) {
    const int x = std::clamp(static_cast<int>(std::floor(p.half + radius * std::cos(angle))), 0, p.size - 1);
    const int y = std::clamp(static_cast<int>(std::floor(p.half + radius * std::sin(angle))), 0, p.size - 1);
    const auto [ex, ey] = texture_source_pixel(p.size, window, kN, x, y);
    const Source& s =
        base[static_cast<std::size_t>(y) * static_cast<std::size_t>(p.size) + static_cast<std::size_t>(x)];
    return static_cast<std::uint64_t>(
        square_difference(&image.pixels[image.offset(ex, ey)], source_color(p, layout, s, x, y)));
  };
  // Per angle step, the radius of the square's boundary (depth 0).
  std::vector<double> reach(kInteriorAngles);
  std::vector<std::uint64_t> errors(static_cast<std::size_t>(kInteriorAngles * states));
  for (int k = 0; k < kInteriorAngles; ++k) {
    const double angle = 2 * std::numbers::pi * k / kInteriorAngles;
    reach[static_cast<std::size_t>(k)] =
        (p.half - kInteriorBorder) / std::max(std::abs(std::cos(angle)), std::abs(std::sin(angle)));
    for (int d = 0; d < states; ++d) {
      const double r = reach[static_cast<std::size_t>(k)] - d;
      errors[static_cast<std::size_t>(k * states + d)] = error_at(r - 0.5, angle) + error_at(r + 0.5, angle);
    }
  }
  Interior best;
  best.window = window;
  std::vector<std::uint64_t> cost(static_cast<std::size_t>(states)), next(cost.size());
  std::vector<std::int8_t> back(static_cast<std::size_t>(kInteriorAngles * states));
  for (int first = 0; first < states; ++first) {
    std::fill(cost.begin(), cost.end(), kInfinite);
    cost[static_cast<std::size_t>(first)] = errors[static_cast<std::size_t>(first)];
    for (int k = 1; k < kInteriorAngles; ++k) {
      for (int r = 0; r < states; ++r) {
        std::uint64_t low = kInfinite;
        std::int8_t from = 0;
        for (int step = -1; step <= 1; ++step) {
          const int q = r + step;
          if (q < 0 || q >= states || cost[static_cast<std::size_t>(q)] >= low) continue;
          low = cost[static_cast<std::size_t>(q)];
          from = static_cast<std::int8_t>(step);
        }
        next[static_cast<std::size_t>(r)] =
            low >= kInfinite ? kInfinite : low + errors[static_cast<std::size_t>(k * states + r)];
        back[static_cast<std::size_t>(k * states + r)] = from;
      }
      std::swap(cost, next);
    }
    for (int last = std::max(0, first - 1); last <= std::min(states - 1, first + 1); ++last) {
      if (cost[static_cast<std::size_t>(last)] >= best.cost) continue;
      best.cost = cost[static_cast<std::size_t>(last)];
      best.radius.assign(kInteriorAngles, 0);
      for (int k = kInteriorAngles - 1, d = last; k >= 0; --k) {
        best.radius[static_cast<std::size_t>(k)] = static_cast<float>(reach[static_cast<std::size_t>(k)] - d);
        d += back[static_cast<std::size_t>(k * states + d)];
      }
    }
  }
  return best;
}

// Which exemplar a pixel of a corner-marked tile shows (Cohen 2003, section 3.5, with a boundary
// that is not the tile grid): the corner marks (exemplar index of each corner) interpolated with
// the quintic fade, plus noise tiles of the same set (4 cells per tile side) scaled by
// kBoundaryNoise and by a factor that is 0 at the corners and 1 at the centre, is >= 1/2 for the
// second exemplar. Both terms agree across every shared edge, so the boundary is seamless; the
// noise bends it away from the tile midlines (fbm of 4 and 8 cells at 0.4 left straight boundaries
// along them; 2.0 scattered islands of one exemplar in the other), and pixels within 1/16 tile of a
// corner keep the corner's exemplar (|noise| <= 1, the factor <= 0.234 there).
constexpr float kBoundaryNoise = 1.2f;

bool second_exemplar(const NoiseTileSet& noise, std::uint32_t tile, const std::array<float, 4>& marks, int size, int x,
                     int y) {
  // Border pixels read the boundary on the edge itself, where both tiles agree, so the two pixels
  // facing each other across an edge show the same exemplar (and, each quilting being seamless,
  // continue each other).
  const auto at = [size](int k) {
    return k == 0 ? 0.f : k == size - 1 ? 1.f : (static_cast<float>(k) + 0.5f) / static_cast<float>(size);
  };
  const float u = at(x), v = 1 - at(y);  // north up
  const auto fade = [](float t) { return t * t * t * (t * (t * 6 - 15) + 10); };
  const float fu = fade(u), fv = fade(v);
  // marks: sw, se, nw, ne
  const float south = marks[0] + fu * (marks[1] - marks[0]), north = marks[2] + fu * (marks[3] - marks[2]);
  const float corners = 2 * (u * (1 - u) + v * (1 - v));
  const float value = south + fv * (north - south) + kBoundaryNoise * corners * noise.sample(tile, 0, u, v).value;
  return value >= 0.5f;
}

}  // namespace

// Refuses options and exemplars the quilting cannot use, naming `where`.
void check_texture_inputs(const std::string& where, std::span<const ImageRgb8> exemplars,
                          const TextureTileOptions& options) {
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
}

// Tile t's pixels from its sources (per layer), the layer at each pixel the marks' boundary picks
// (none: the first), and the seam cost its cuts and the boundary leave.
void compose_tile(TextureTile& out, const Tile& tile, std::uint32_t t, int size, std::size_t block,
                  const std::vector<std::vector<Source>>& sources, const std::vector<Problem>& problems,
                  const std::vector<Layout>& layouts, const std::optional<NoiseTileSet>& boundary) {
  out.image = ImageRgb8(size, size);
  out.source.assign(static_cast<std::size_t>(size) * static_cast<std::size_t>(size), 0);
  const auto mark = [](int c) { return static_cast<float>((c < 0 ? 0 : c) % 2); };
  const std::array<float, 4> marks = {mark(tile.sw()), mark(tile.se()), mark(tile.nw()), mark(tile.ne())};
  std::vector<int> layer_of(out.source.size(), 0);
  const auto color_of = [&](int layer, const Source& s, int x, int y) {
    return source_color(problems[static_cast<std::size_t>(layer)], layouts[static_cast<std::size_t>(layer)], s, x, y);
  };
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) {
      const std::size_t o = static_cast<std::size_t>(y) * static_cast<std::size_t>(size) + static_cast<std::size_t>(x);
      const int layer = boundary && second_exemplar(*boundary, t, marks, size, x, y);
      layer_of[o] = layer;
      const Source& s = sources[static_cast<std::size_t>(layer)][o];
      out.source[o] = static_cast<std::uint16_t>((static_cast<std::size_t>(layer) * block + s.window) * 4 +
                                                 static_cast<std::size_t>(s.slot));
      const std::uint8_t* c = color_of(layer, s, x, y);
      out.image.set(x, y, {c[0], c[1], c[2]});
    }
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) {
      const std::size_t o = static_cast<std::size_t>(y) * static_cast<std::size_t>(size) + static_cast<std::size_t>(x);
      for (const auto& [nx, ny] : {std::array<int, 2>{x + 1, y}, std::array<int, 2>{x, y + 1}}) {
        if (nx >= size || ny >= size) continue;
        const std::size_t n =
            static_cast<std::size_t>(ny) * static_cast<std::size_t>(size) + static_cast<std::size_t>(nx);
        if (out.source[o] == out.source[n]) continue;
        const int la = layer_of[o], lb = layer_of[n];
        const Source& a = sources[static_cast<std::size_t>(la)][o];
        const Source& b = sources[static_cast<std::size_t>(lb)][n];
        out.error += static_cast<std::uint64_t>(square_difference(color_of(la, a, x, y), color_of(lb, b, x, y)) +
                                                square_difference(color_of(la, a, nx, ny), color_of(lb, b, nx, ny)));
      }
    }
}

TextureTileSet make_texture_tiles(const TileSet& set, std::span<const ImageRgb8> exemplars,
                                  const TextureTileOptions& options, TextureTileReport* report) {
  const std::string where = "texture tiles of " + set.describe();
  check_texture_inputs(where, exemplars, options);
  const int size = options.tile_size;

  TextureTileSet result;
  result.set = set;
  result.tile_size = size;
  result.marks = set.has_corners ? std::max(1, set.corner_colors) : 1;
  // Two exemplars in a corner-marked set: one quilting per exemplar, joined per pixel by the
  // marks' boundary. Otherwise one quilting of the first exemplar.
  const int layers = set.has_corners && exemplars.size() == 2 ? 2 : 1;

  // Diamond keys, in order of first use: every key owns one window per layer.
  Problem shape;
  shape.size = size;
  shape.half = size / 2;
  shape.band = options.band > 0 ? options.band : std::max(2, size / 16);
  shape.exemplars = exemplars;
  std::map<std::array<int, 4>, std::size_t> window_ids;
  const auto color = [](int c) { return c < 0 ? 0 : c; };
  for (std::size_t t = 0; t < set.size(); ++t) {
    const Tile& tile = set.tiles[t];
    // Per slot: the marks at the west/north end and at the east/south end of the edge.
    const std::array<std::array<int, 2>, 4> ends = {
        {{tile.nw(), tile.ne()}, {tile.ne(), tile.se()}, {tile.sw(), tile.se()}, {tile.nw(), tile.sw()}}};
    std::array<std::size_t, 4> slots{};
    for (int slot = 0; slot < 4; ++slot) {
      const int orientation = slot == kN || slot == kS ? 0 : 1;
      const std::array<int, 4> key = {orientation, color(tile.colors[static_cast<std::size_t>(slot)]),
                                      color(ends[static_cast<std::size_t>(slot)][0]),
                                      color(ends[static_cast<std::size_t>(slot)][1])};
      const auto [it, added] = window_ids.try_emplace(key, window_ids.size());
      if (added) {
        shape.window_tiles.emplace_back();
        shape.window_quadrants.emplace_back();
      }
      const std::size_t w = it->second;
      slots[static_cast<std::size_t>(slot)] = w;
      if (shape.window_tiles[w].empty() || shape.window_tiles[w].back() != t) shape.window_tiles[w].push_back(t);
      for (const int q : kSlotQuadrants[static_cast<std::size_t>(slot)])
        shape.window_quadrants[w].push_back(t * 4 + static_cast<std::size_t>(q));
    }
    shape.tile_windows.push_back(slots);
  }
  for (std::vector<std::size_t>& quadrants : shape.window_quadrants) {
    std::sort(quadrants.begin(), quadrants.end());
    quadrants.erase(std::unique(quadrants.begin(), quadrants.end()), quadrants.end());
  }
  const std::size_t window_count = window_ids.size();
  // An explicit separation is a floor the windows must keep; by default they come as close as they must.
  const int floor = options.min_separation > 0 ? options.min_separation : 1;

  TextureTileReport stats;
  std::vector<Problem> problems;
  std::vector<Layout> layouts;
  // Per layer, per tile: its sources, the interior over the diamonds.
  std::vector<std::vector<std::vector<Source>>> layer_sources;
  const std::size_t block = window_count + set.size();  // windows per layer: the keys', then the interiors
  if (static_cast<std::size_t>(layers) * block * 4 > 65536)
    throw Error(where + ": " + std::to_string(set.size()) + " tiles; texture tiles hold at most 8000");
  for (int layer = 0; layer < layers; ++layer) {
    Problem p = shape;
    p.exemplar = layer;
    Layout layout = place_windows(p, window_count, floor, options.seed, where);
    search_windows(p, layout, options, stats);
    std::vector<std::vector<Source>> sources(set.size());
    std::vector<Interior> interiors(set.size());
    tbb::parallel_for(std::size_t{0}, set.size(), [&](std::size_t t) {
      sources[t] = tile_sources(p, layout, t);
      // As many random patches as the window search tries per window, the cheapest cut kept (a quarter
      // as many left visible seams along the cuts, now that they run near the edges).
      Draws draws(options.seed, (std::uint64_t{1} << 48) + (static_cast<std::uint64_t>(layer) << 32) + t);
      for (int c = 0; c < std::max(1, options.candidates); ++c) {
        TextureWindow window = random_window(p, layer, draws);
        window.y -= p.half;  // read through kN: rows [y, y + size) are the patch centred on the draw
        Interior candidate = interior_cut(p, layout, sources[t], window);
        if (candidate.cost < interiors[t].cost) interiors[t] = std::move(candidate);
      }
    });
    for (std::size_t t = 0; t < set.size(); ++t) {
      layout.windows.push_back(interiors[t].window);
      for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x)
          if (inside(interiors[t], size, x, y))
            sources[t][static_cast<std::size_t>(y) * static_cast<std::size_t>(size) + static_cast<std::size_t>(x)] = {
                window_count + t, kN};
    }
    result.windows.insert(result.windows.end(), layout.windows.begin(), layout.windows.end());
    problems.push_back(std::move(p));
    layouts.push_back(std::move(layout));
    layer_sources.push_back(std::move(sources));
  }
  if (report) *report = stats;

  // The tiles: per pixel the layer the marks' boundary picks, its source there, and the seam
  // cost the cuts and the boundary leave.
  const std::optional<NoiseTileSet> boundary =
      layers == 2 ? std::optional<NoiseTileSet>(NoiseTileSet(set, {.lattice = 4, .octaves = 1, .seed = options.seed}))
                  : std::nullopt;
  result.tiles.resize(set.size());
  tbb::parallel_for(std::size_t{0}, set.size(), [&](std::size_t t) {
    std::vector<std::vector<Source>> sources;
    for (int layer = 0; layer < layers; ++layer) sources.push_back(layer_sources[static_cast<std::size_t>(layer)][t]);
    compose_tile(result.tiles[t], set.tiles[t], static_cast<std::uint32_t>(t), size, block, sources, problems, layouts,
                 boundary);
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

TexturePreviewFigures texture_preview_figures(const TileSet& set, std::span<const ImageRgb8> exemplars, int seeds) {
  TexturePreviewFigures mean;
  constexpr int kTile = 64;
  for (int seed = 1; seed <= seeds; ++seed) {
    TextureTileOptions options;
    options.tile_size = kTile;
    options.seed = static_cast<std::uint64_t>(seed);
    const TextureTileSet tiles = make_texture_tiles(set, exemplars, options);
    TilingOptions tiling;
    tiling.seed = static_cast<std::uint64_t>(seed);
    const GrayImage preview = to_gray(draw_texture_tiling(tiles, make_tiling(tiles.set, 16, 8, tiling)));
    mean.axis_ratio += axis_energy_ratio(preview) / seeds;
    mean.repetition += tile_repetition(preview, kTile) / seeds;
    mean.peak += tile_period_peak(preview, kTile) / seeds;
  }
  return mean;
}

}  // namespace wangscape
