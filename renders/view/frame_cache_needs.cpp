// The sample cache's choice: what each pixel needs, the fresh samples the budget allows, tracing
// them, and the kept samples they hide.
#include "renders/view/frame_cache_impl.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <optional>

#include "renders/trace/scene_tracer.h"
#include "renders/trace/traced_shading.h"
#include "renders/view/ldi_renderer.h"
#include "renders/view/view_samples.h"

namespace wangscape {

using namespace frame_cache_detail;  // the cache's inner parts (frame_cache_impl.h)

using namespace view_detail;

// ---- what each pixel needs ------------------------------------------------------------------

namespace {

// Of eight neighbours' depths (NaN for one outside the frame, which counts as neither): around a
// hole (depth NaN), how many show the sky; around a sample, how many lie nearer than `depth` by
// more than kGapDepth of it. The other count is 0 (no caller reads it).
inline std::array<int, 2> counts_around(float depth, const std::array<float, 8>& n) {
  int sky = 0, nearer = 0;
  if (is_none(depth)) {
    for (const float d : n) sky += d == kInf;
  } else {
    const float gap = depth * (1 - kGapDepth);
    for (const float d : n) nearer += d < gap;
  }
  return {sky, nearer};
}

// counts_around for pixel (x, y) in samples k of a w x h frame.
inline std::array<int, 2> neighbour_counts(const Sample* k, int w, int h, int x, int y, float depth) {
  std::array<float, 8> n;
  std::size_t i = 0;
  for (int dy = -1; dy <= 1; ++dy)
    for (int dx = -1; dx <= 1; ++dx) {
      if (dx == 0 && dy == 0) continue;
      const bool inside = x + dx >= 0 && y + dy >= 0 && x + dx < w && y + dy < h;
      n[i++] = inside ? k[std::size_t(y + dy) * std::size_t(w) + std::size_t(x + dx)].depth : kNone;
    }
  return counts_around(depth, n);
}

}  // namespace

void FrameCache::Impl::classify(std::uint64_t frame, bool still, const EnteringBand& band) {
  Sample* const k = now().data();
  std::uint8_t* const needs = need.data();
  const int w = width, h = height;
  tbb::parallel_for(tbb::blocked_range<int>(0, h, 4), [&](const tbb::blocked_range<int>& r) {
    const EnteringBand edges = band;
    const bool moving = !still;
    // Pixel p's need, from its sample's depth d and its neighbours': how many show the sky, how
    // many lie nearer by a gap.
    const auto judge = [&](std::size_t p, int x, int y, float d, int sky, int nearer) {
      std::uint8_t judged;
      if (is_none(d))
        judged = sky == 8 ? kSkyFill : kHole;  // a hole among sky is sky: nothing stands in it
      else if (nearer >= kGapNeighbours)
        judged = kHole;
      else if (needs[p] == kStretched)
        judged = kStretched;
      else if (k[p].source == SampleSource::frame || k[p].source == SampleSource::lent)
        judged = kStale;
      else if (k[p].age >= kMaxAge || (pixel_hash(p, 1) + frame) % kRefreshPeriod == 0)
        judged = kRefresh;
      else
        judged = kKeep;
      if (judged != kHole && moving && x % kProbeSpacing == kProbeSpacing / 2 &&
          y % kProbeSpacing == kProbeSpacing / 2 && edges.holds(x, y, w, h))
        judged = kProbe;
      needs[p] = judged;
    };
    const auto at_edge = [&](int x, int y) {
      const std::size_t p = std::size_t(y) * std::size_t(w) + std::size_t(x);
      const float d = k[p].depth;
      const auto [sky, nearer] = neighbour_counts(k, w, h, x, y, d);
      judge(p, x, y, d, sky, nearer);
    };
    for (int y = r.begin(); y != r.end(); ++y) {
      if (!moving) {  // the same view: nothing new shows through a gap, nothing is stale
        for (int x = 0; x < w; ++x) {
          const std::size_t p = std::size_t(y) * std::size_t(w) + std::size_t(x);
          if (is_none(k[p].depth))
            at_edge(x, y);  // (a hole: sky, or still a hole)
          else
            needs[p] = needs[p] == kStretched ? kStretched : kKeep;
        }
        continue;
      }
      if (y == 0 || y + 1 == h || w < 3) {
        for (int x = 0; x < w; ++x) at_edge(x, y);
        continue;
      }
      // Inside the frame, the 3 x 3 depths slide along the row: three loads a pixel, not nine.
      const Sample* above = k + std::size_t(y - 1) * std::size_t(w);
      const Sample* row = above + w;
      const Sample* below = row + w;
      at_edge(0, y);
      float a0 = above[0].depth, a1 = above[1].depth, r0 = row[0].depth, r1 = row[1].depth, b0 = below[0].depth,
            b1 = below[1].depth;
      for (int x = 1; x + 1 < w; ++x) {
        const float a2 = above[x + 1].depth, r2 = row[x + 1].depth, b2 = below[x + 1].depth;
        const float d = r1;
        const auto [sky, nearer] = counts_around(d, {a0, a1, a2, r0, r2, b0, b1, b2});
        judge(std::size_t(y) * std::size_t(w) + std::size_t(x), x, y, d, sky, nearer);
        a0 = a1;
        a1 = a2;
        r0 = r1;
        r1 = r2;
        b0 = b1;
        b1 = b2;
      }
      at_edge(w - 1, y);
    }
  });
  // Applied after every pixel was judged, so a judgement never sees another's outcome.
  tbb::parallel_for(tbb::blocked_range<int>(0, h, 4), [&](const tbb::blocked_range<int>& r) {
    for (int y = r.begin(); y != r.end(); ++y) {
      std::array<std::uint32_t, kNeeds> counts{};
      for (int x = 0; x < w; ++x) {
        const std::size_t p = std::size_t(y) * std::size_t(w) + std::size_t(x);
        const std::uint8_t judged = needs[p];
        if (judged == kSkyFill) {
          k[p].depth = kInf;
          k[p].source = SampleSource::sky;
          k[p].count = 0;
          k[p].age = 0;
          k[p].sub_x = k[p].sub_y = 0;
          needs[p] = kKeep;
          ++counts[kKeep];
          continue;
        }
        if (judged == kHole) k[p].depth = kNone;
        ++counts[judged];
      }
      row_needs[std::size_t(y)] = counts;
    }
  });
}

std::array<std::uint64_t, kNeeds> FrameCache::Impl::count_needs() const {
  std::array<std::uint64_t, kNeeds> total{};
  for (const auto& row : row_needs)
    for (std::size_t c = 0; c < kNeeds; ++c) total[c] += row[c];
  return total;
}

// The pixels `take(p, x, y)` accepts into fresh, block by block (kBlock x kBlock pixels, in rows of
// blocks), so that 16 neighbouring fresh samples make one packet of rays. Parallel: counted per
// row of blocks, then written at each one's offset. Returns how many.
template <class Take>
std::size_t FrameCache::Impl::gather_fresh(const Take& take) {
  const int block_rows = (height + kBlock - 1) / kBlock;
  const auto visit = [&](int by, auto&& on) {
    for (int bx = 0; bx < width; bx += kBlock)
      for (int y = by * kBlock; y < std::min(height, (by + 1) * kBlock); ++y)
        for (int x = bx; x < std::min(width, bx + kBlock); ++x) {
          const std::size_t p = std::size_t(y) * std::size_t(width) + std::size_t(x);
          if (take(p, x, y)) on(p);
        }
  };
  tbb::parallel_for(0, block_rows, [&](int by) {
    std::uint32_t n = 0;
    visit(by, [&](std::size_t) { ++n; });
    row_fresh[std::size_t(by) + 1] = n;
  });
  row_fresh[0] = 0;
  for (int by = 0; by < block_rows; ++by) row_fresh[std::size_t(by) + 1] += row_fresh[std::size_t(by)];
  tbb::parallel_for(0, block_rows, [&](int by) {
    std::uint32_t at = row_fresh[std::size_t(by)];
    visit(by, [&](std::size_t p) { fresh[at++] = std::uint32_t(p); });
  });
  return row_fresh[std::size_t(block_rows)];
}

// In motion: the needs in order (holes, stretched, stale, refresh) while the budget lasts; of the need it
// runs out in, a share spread over the frame by a hash.
std::size_t FrameCache::Impl::select(const std::array<std::uint64_t, kNeeds>& needs, std::uint64_t budget,
                                     std::uint64_t frame) {
  std::uint8_t last = kKeep;  // the first need not taken whole
  std::uint32_t share = 0;    // of it, the pixels whose hash is below this (of 2^32)
  std::uint64_t left = budget;
  for (std::uint8_t c = kProbe; c < kKeep; ++c) {
    if (needs[c] <= left) {
      left -= needs[c];
      continue;
    }
    last = c;
    share = std::uint32_t(double(left) / double(needs[c]) * 4294967295.0);
    break;
  }
  const std::size_t n = gather_fresh([&](std::size_t p, int, int) {
    const std::uint8_t c = need[p];
    return c < last || (c == last && pixel_hash(p, frame * 2 + 7) < share);
  });
  // Where each is traced: its own sample's place, or the mean place of its neighbours' own samples.
  const Sample* const k = now().data();
  const std::uint8_t* const pixel_needs = need.data();
  const std::uint32_t* const fresh_pixels = fresh.data();
  std::array<std::int8_t, 2>* const places = lattice.data();
  const int w = width, h = height;
  const int own = int(kStretchedOffset * kSubScale);
  const auto own_sample = [=](std::size_t q) {  // a sample in its own pixel, not a hole or a copy
    const Sample& s = k[q];
    return !is_none(s.depth) && pixel_needs[q] >= kStale && s.source != SampleSource::lent &&
           std::abs(s.sub_x) <= own && std::abs(s.sub_y) <= own;
  };
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 1024), [=](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t i = r.begin(); i != r.end(); ++i) {
      const std::size_t p = fresh_pixels[i];
      if (own_sample(p)) {
        places[p] = {k[p].sub_x, k[p].sub_y};
        continue;
      }
      const int x = int(p % std::size_t(w)), y = int(p / std::size_t(w));
      int sum_x = 0, sum_y = 0, count = 0;
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          if ((dx == 0 && dy == 0) || x + dx < 0 || y + dy < 0 || x + dx >= w || y + dy >= h) continue;
          const std::size_t q = std::size_t(y + dy) * std::size_t(w) + std::size_t(x + dx);
          if (!own_sample(q)) continue;
          sum_x += k[q].sub_x;
          sum_y += k[q].sub_y;
          ++count;
        }
      places[p] = count ? std::array<std::int8_t, 2>{std::int8_t(sum_x / count), std::int8_t(sum_y / count)}
                        : std::array<std::int8_t, 2>{0, 0};
    }
  });
  return n;
}

// While still: the holes, then the next slots of the schedule, as many as the budget holds
// (at least one).
std::size_t FrameCache::Impl::select_still(std::uint64_t budget) {
  const std::array<std::uint64_t, kNeeds> needs = count_needs();
  const std::uint64_t holes = needs[kHole] + needs[kStretched];
  const double per_slot = double(pixels()) / kStillSlots;
  const std::uint32_t slots = std::uint32_t(
      std::clamp(std::floor(double(budget > holes ? budget - holes : 0) / per_slot), 1.0, double(kStillSlots)));
  const std::uint32_t first = still_slot;
  still_slot = (still_slot + slots) % kStillSlots;
  // Whole 4 x 4 blocks take their turn together: their rays make full, coherent packets
  // (scattered rays cost 550 ns each in motion against 214 ns a pixel for a whole frame's). Each
  // block's turn is found once, not at each of its pixels (BM_StillFrames at 1280 x 720, under load: the choosing phase
  // 10.1 -> 8.7 ms).
  const int wide = blocks_wide();
  tbb::parallel_for(0, (height + kBlock - 1) / kBlock, [&](int by) {
    for (int bx = 0; bx < wide; ++bx) {
      const std::size_t block = std::size_t(by) * std::size_t(width) + std::size_t(bx);
      block_due[std::size_t(by) * std::size_t(wide) + std::size_t(bx)] =
          (pixel_hash(block, 3) % kStillSlots - first + kStillSlots) % kStillSlots < slots;
    }
  });
  return gather_fresh([&](std::size_t p, int x, int y) {
    return need[p] < kStale || block_due[std::size_t(y / kBlock) * std::size_t(wide) + std::size_t(x / kBlock)];
  });
}

// ---- tracing the fresh samples: the whole scene's rays --------------------------------------

void FrameCache::Impl::trace(LdiRenderer& renderer, std::size_t n, bool still) {
  const SceneTracer& tracer = renderer.whole_scene();
  const ViewWorld& world = *renderer.world();
  const ViewProjection& view = projection;
  const Vector3d from{view.eye[0] - tracer.origin()[0], view.eye[1] - tracer.origin()[1],
                      view.eye[2] - tracer.origin()[2]};
  ShadingSettings shading = world.sun_shading();
  // Still: the reference's own sky rays (the pack's light), so a still sample is a reference
  // sample (one ray each is unbiased too and cheaper, but a camera that stopped showed the grain
  // of one-ray samples over its leaves for seconds). Moving: the baked sky share instead.
  if (!still) shading.ao_rays = 0;
  KeptSamples& k = now();
  const std::size_t packets = (n + 15) / 16;
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, packets, 4), [&](const tbb::blocked_range<std::size_t>& r) {
    std::array<Vector3d, 16> d;
    std::array<float, 16> tfar;
    std::array<std::array<float, 2>, 16> offset;
    bool valid[16], hit_valid[16];
    std::optional<SceneTracer::Hit> hit[16];
    SurfaceSample surfaces[16];
    Vec3f colors[16];
    for (std::size_t packet = r.begin(); packet != r.end(); ++packet) {
      for (int l = 0; l < 16; ++l) {
        const std::size_t i = packet * 16 + std::size_t(l);
        valid[l] = i < n;
        if (!valid[l]) continue;
        const std::size_t p = fresh[i];
        const int x = int(p % std::size_t(width)), y = int(p / std::size_t(width));
        // Still: the pixel's next point of the R2 sequence (its first at the centre).
        offset[l] = still ? r2_offset(still_samples(k[p]))
                          : std::array<float, 2>{float(lattice[p][0]) / kSubScale, float(lattice[p][1]) / kSubScale};
        d[l] = view.ray_through(double(x) + 0.5 + offset[l][0], double(y) + 0.5 + offset[l][1]);
        tfar[l] = kInf;
      }
      tracer.intersect16(from, d.data(), tfar.data(), valid, hit);
      for (int l = 0; l < 16; ++l) {
        hit_valid[l] = valid[l] && hit[l].has_value();
        if (hit_valid[l]) surfaces[l] = tracer.surface(*hit[l], from, d[l], world.ground_colors());
      }
      if (still) {
        for (int l = 0; l < 16; ++l)
          if (hit_valid[l]) {
            const std::size_t p = fresh[packet * 16 + std::size_t(l)];
            colors[l] = shade(tracer.scene(), shading, surfaces[l], mix64(p * 65537 + k[p].count));
          }
      } else {
        shade_in_the_open16(tracer.scene(), shading, surfaces, hit_valid, colors);
      }
      for (int l = 0; l < 16; ++l) {
        if (!valid[l]) continue;
        const std::size_t p = fresh[packet * 16 + std::size_t(l)];
        const Vec3f dir{float(d[l][0]), float(d[l][1]), float(d[l][2])};
        const Vec3f c = hit_valid[l] ? colors[l] : sky_radiance(world.shading(), dir);
        const float depth = hit_valid[l] ? float(double(hit[l]->t) * dot(d[l], view.forward)) : kInf;
        const int before = still_samples(k[p]);
        const bool found = !still && depth < k[p].depth * (1 - kGapDepth);  // (false for a hole's NaN)
        if (still && before > 0) {
          const float w = 1.0f / float(before + 1);
          for (std::size_t a = 0; a < 3; ++a) k[p].color[a] += (c[a] - k[p].color[a]) * w;
          k[p].count = std::uint16_t(std::min(65535, before + 1));
          k[p].depth = std::min(k[p].depth, depth);  // the pixel reprojects with its nearest surface
          k[p].source = SampleSource::still;
        } else {
          k[p].color = {c[0], c[1], c[2]};
          k[p].count = still ? 1 : 0;
          k[p].depth = depth;
          k[p].sub_x = sub_code(offset[l][0]);
          k[p].sub_y = sub_code(offset[l][1]);
          k[p].source = still ? SampleSource::still : hit_valid[l] ? SampleSource::ray : SampleSource::sky;
        }
        k[p].age = 0;
        need[p] = found ? kFound : kTraced;
      }
    }
  });
  tracer.check("tracing the frame's fresh samples");
}

// After tracing, of the kept samples near a traced one (only there can the neighbourhood
// classify() judged have changed):
// - one behind a found surface within kLendReach pixels (nearer by kGapDepth) shows that surface
//   until traced (kCovered: a copy of the nearest found sample at its own centre, SampleSource::lent);
// - else one that traced surfaces now surround (five of its neighbours nearer) was seen through
//   what was a gap: it is dropped (a hole, shown as its neighbours, traced first next frame).
// Judged first, then applied, so no judgement sees another's outcome. Marks only rise (kept <
// kHidden < kCovered), so a pixel two traced ones judge at once ends the same on any thread count;
// one of them claims the applying.
void FrameCache::Impl::drop_hidden(std::size_t n) {
  KeptSamples& k = now();
  const auto mark_of = [&](std::size_t q) { return std::atomic_ref<std::uint8_t>(need[q]); };
  const auto kept_sample = [&](std::uint8_t c, std::size_t q) {
    return c != kTraced && c != kFound && !is_none(k[q].depth);
  };
  const auto raise = [&](std::size_t q, std::uint8_t to) {
    std::atomic_ref<std::uint8_t> mark = mark_of(q);
    std::uint8_t seen = mark.load(std::memory_order_relaxed);
    while (seen < to && seen != kTraced && seen != kFound &&
           !mark.compare_exchange_weak(seen, to, std::memory_order_relaxed)) {
    }
  };
  // Calls visit(qx, qy, q) for the pixels within `reach` of pixel p.
  const auto around = [&](std::size_t p, int reach, auto&& visit) {
    const int x = int(p % std::size_t(width)), y = int(p / std::size_t(width));
    for (int qy = std::max(0, y - reach); qy <= std::min(height - 1, y + reach); ++qy)
      for (int qx = std::max(0, x - reach); qx <= std::min(width - 1, x + reach); ++qx)
        visit(qx, qy, std::size_t(qy) * std::size_t(width) + std::size_t(qx));
  };
  // Judging.
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 256), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t i = r.begin(); i != r.end(); ++i) {
      const std::size_t p = fresh[i];
      if (mark_of(p).load(std::memory_order_relaxed) == kFound)
        around(p, kLendReach, [&](int, int, std::size_t q) {
          if (kept_sample(mark_of(q).load(std::memory_order_relaxed), q) && k[p].depth < k[q].depth * (1 - kGapDepth))
            raise(q, kCovered);
        });
      around(p, 1, [&](int qx, int qy, std::size_t q) {
        const std::uint8_t seen = mark_of(q).load(std::memory_order_relaxed);
        if (kept_sample(seen, q) && seen < kHidden &&
            neighbour_counts(k.data(), width, height, qx, qy, k[q].depth)[1] >= kGapNeighbours)
          raise(q, kHidden);
      });
    }
  });
  // Applying. The lender: the nearest found sample within reach that is nearer by kGapDepth (the
  // lower index wins a tie).
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 256), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t i = r.begin(); i != r.end(); ++i)
      around(fresh[i], kLendReach, [&](int, int, std::size_t q) {
        std::atomic_ref<std::uint8_t> mark = mark_of(q);
        std::uint8_t seen = mark.load(std::memory_order_relaxed);
        if (seen == kHidden) {
          std::atomic_ref<float>(k[q].depth).store(kNone, std::memory_order_relaxed);
        } else if (seen == kCovered && mark.compare_exchange_strong(seen, kKeep, std::memory_order_relaxed)) {
          std::size_t lender = pixels();
          around(q, kLendReach, [&](int, int, std::size_t f) {
            if (mark_of(f).load(std::memory_order_relaxed) == kFound && k[f].depth < k[q].depth * (1 - kGapDepth) &&
                (lender == pixels() || k[f].depth < k[lender].depth))
              lender = f;
          });
          k[q] = Sample{k[lender].depth, k[lender].color, 0, 0, 0, 0, SampleSource::lent};
        }
      });
  });
}

}  // namespace wangscape
