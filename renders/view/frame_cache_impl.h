// The sample cache's inner parts (renders/view/frame_cache.h), shared by its three sources: the
// frame and its picture (frame_cache.cpp), reprojection (frame_cache_reproject.cpp), and what each
// pixel needs, chosen and traced (frame_cache_needs.cpp). Not for use outside them.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "core/hash.h"
#include "renders/view/frame_cache.h"
#include "renders/view/view_projection.h"

namespace wangscape {

namespace frame_cache_detail {

constexpr float kInf = std::numeric_limits<float>::infinity();
constexpr float kNone = std::numeric_limits<float>::quiet_NaN();  // a pixel without a sample
constexpr std::uint64_t kNoKey = ~std::uint64_t{0};
constexpr float kNearest = 0.05f;  // meters: samples nearer the eye are dropped (the renderer's near plane)
// A sample is seen through a gap in a nearer surface (the surface magnified, its samples spread)
// when at least kGapNeighbours of its eight neighbours are nearer by more than kGapDepth of its
// depth; beside a thin stem at most three are, inside a gap of a spread surface five to eight.
constexpr int kGapNeighbours = 5;
constexpr float kGapDepth = 0.1f;
// Every sample is traced anew once every kRefreshPeriod frames (its slot's turn) or when it
// is kMaxAge frames old: the rotating share that catches what reprojection cannot see (a thin
// stem a pixel centre missed before, now in front of it).
constexpr std::uint32_t kRefreshPeriod = 32;
constexpr std::uint8_t kMaxAge = 64;
// A still camera's samples are scheduled in kStillSlots slots: a frame takes the next slots. Fine
// enough that one slot fits a frame's budget at 1280 x 720 (3,600 samples; with 64 slots a still
// frame there traced 14,400 and took 48.7 ms under load, 25.8 with 256).
constexpr std::uint32_t kStillSlots = 256;
// A camera that moved this far or turned this much since the last frame, or that leaves this
// share of the pixels empty, is drawn cold.
constexpr double kJumpMeters = 20;
constexpr double kJumpCosine = 0.866;  // 30 degrees
constexpr double kColdHoleShare = 0.5;
// Holes beyond this share of the pixels are traced whatever the budget says. Where a frame's passes
// alone outrun its time (1280 x 720 at 30 frames/s: 41 ms of 33), the budget's floor of one pixel
// in 256 let 20,000 to 60,000 holes gather each frame, shown as their neighbours, until every
// twelfth frame or so was drawn cold (300 ms, a p95 five times the median).
constexpr double kMaxHoleShare = 0.2;
// In motion, a pixel's colour is reconstructed from the kept samples of its 3 x 3 neighbourhood,
// each weighted by a tent of this radius (pixels) about the pixel's centre, at the sample's own
// position. Kept samples lie anywhere in their pixels (copies beyond): shown as they were, every
// edge was a saw of half-pixel steps. Radius 1 leaves samples at pixel centres as they are; 1.5
// also weighs each neighbour's centre a third (a mild anti-aliasing, as the 64-sample truth has).
// The walk at 640 x 360, frames 120, 240, 360 and 480 against the truth (PSNR / SSIM): shown as
// they were 19.63 / 0.662, 22.69 / 0.708, 20.85 / 0.695, 21.83 / 0.707; radius 1: +0.6 to +1.2 dB;
// 1.5: 20.98 / 0.730, 24.65 / 0.784, 22.72 / 0.778, 23.95 / 0.797; 2 (cut to 3 x 3): within 0.2 dB
// of 1.5. A still mean (two samples or more) is shown as it is.
constexpr float kReconstructionRadius = 1.5f;
// The reconstruction's weight along one axis of a sample `offset` pixels from the pixel's centre.
inline float tent_weight(float offset) {
  return std::max(1.0f - std::abs(offset) * (1.0f / kReconstructionRadius), 0.0f);
}
// Positions within the pixel are kept in 1/kSubScale of a pixel.
constexpr float kSubScale = 60;  // (a copy's lies up to kMaxStretch / 2 + 0.5 pixels out: within 127 / 60)

// What a frame does with a pixel, in the order the budget serves them.
enum Need : std::uint8_t {
  kProbe = 0,      // one pixel of each 4 x 4 in the band the camera moves toward (EnteringBand)
  kHole = 1,       // no sample (none arrived, or it was seen through a gap): traced, or filled
  kStretched = 2,  // a magnified neighbour's sample covers it: shown, and traced soon
  kStale = 3,      // an approximation (a cold frame's LDIs, a found surface's neighbour): traced soon
  kRefresh = 4,    // its turn in the rotating share, or too old
  kKeep = 5,
  kNeeds = 6,
  kSkyFill = 7,   // (transient) a hole among sky: the sky
  kTraced = 8,    // traced this frame
  kFound = 9,     // traced this frame, nearer than the sample it replaced: something came into view
  kHidden = 10,   // (transient) kept, but seen through a gap in a surface traced this frame
  kCovered = 11,  // (transient) kept, but a found surface beside it is nearer: shows that surface
  kFarMove = 12,  // (transient, of a previous frame's pixel) its sample moved beyond its band's reach: placed last
};
// In motion, objects nearer than the samples at the edge the camera moves toward come into view
// over them (a sideways step past a flower 1.5 m away moves it 9 pixels a frame at 640 x 360):
// reprojection knows nothing of them and sees no hole there. The band where an object
// kEnteringDepth away or farther may have come in is probed (a ray in each 4 x 4 pixels, before
// any other need), and a fresh sample that finds a surface nearer than the sample it replaced
// lends it to the samples behind it within kLendReach (kCovered) until they are traced. Before, a flower head
// entering at the right edge stayed missing for seconds, the sky's samples reprojected over it.
constexpr double kEnteringDepth = 0.5;  // meters
constexpr int kProbeSpacing = 4;        // pixels between probes, across and down
constexpr int kLendReach = 2;           // pixels from a found sample that it lends to: a 5 x 5
// The band's width at each edge, pixels.
struct EnteringBand {
  int left = 0, right = 0, top = 0, bottom = 0;
  bool holds(int x, int y, int width, int height) const {
    return x < left || x >= width - right || y < top || y >= height - bottom;
  }
};
// A reprojected sample covers the pixels whose centres lie in a square of its footprint's size
// (one pixel at its old depth) times kCopySplatScale, up to kMaxStretch pixels. Without such copies,
// samples that met in one pixel were lost and the holes they left grew frame after frame (in the
// field at 640 x 360: 5,000 in the first frame, 35,000 by the tenth, every one traced). A pixel
// prefers a sample of its own (whose position lies in it) to any neighbour's copy: copies only
// fill what no sample reached (with a copy nearer by a quarter winning, every edge of a near stem
// or leaf grew by a copy in a quarter of its pixels each frame, 15,000 pixels to trace after a
// pure turn). A copy keeps its true position, so nothing drifts. Background seen where a nearer
// surface has a gap is found by the gap test, before tracing and again after it.
constexpr float kCopySplatScale = 1.25f;
constexpr float kMaxStretch = 3.0f;
constexpr std::uint64_t kCopyBit = 1ull << 63;  // in a key: a neighbour's copy (above every depth)
// A pixel whose sample lies more than this far from its centre (pixels, either axis) is stretched.
constexpr float kStretchedOffset = 0.5f;
constexpr float kAdoptedOffset = 1.25f;  // an adopted sample (below) may lie this far
// The same offsets in 1/kSubScale pixels (the keys and the samples hold them so).
constexpr int kPixelCode = int(kSubScale), kStretchedCode = int(kStretchedOffset * kSubScale),
              kAdoptedCode = int(kAdoptedOffset * kSubScale);
// Reprojection scatters the rows in this many bands (reproject()), and a footprint reaches this
// many rows above or below its sample's pixel (kMaxStretch / 2 + 0.5, rounded up).
constexpr int kScatterBands = 16;
constexpr int kFootprintRows = 2;
constexpr int kBlock = 4;  // fresh samples are listed by 4 x 4 blocks: 16 of one block make a packet of rays

inline bool is_none(float depth) { return std::isnan(depth); }
// floor() of a value above -64, without a call into libm (the baseline x86-64 build has no
// rounding instruction): the frame's inner loops round several times a pixel.
inline int floor_above(float v) { return int(v + 64.0f) - 64; }
inline int ceil_above(float v) { return 64 - int(64.0f - v); }
inline std::int8_t sub_code(float offset) {  // offset in pixels -> 1/kSubScale, rounded, clamped
  return std::int8_t(floor_above(std::clamp(offset * kSubScale, -127.0f, 127.0f) + 0.5f));
}
inline std::uint32_t pixel_hash(std::uint64_t p, std::uint64_t salt) {
  return std::uint32_t(mix64(p * 0x100000001B3ull + salt) >> 32);
}

// Where objects kEnteringDepth away or farther may have come into view moving from `from` to `to`.
EnteringBand entering_band(const ViewProjection& from, const ViewProjection& to, int frame_width, int frame_height);

// One kept sample: all of it moves together, so it is one 24-byte record (FrameCache::bytes_per_pixel
// counts it twice with the keys, needs, fresh list and lattice: 63 bytes a pixel).
struct Sample {
  float depth = kNone;                  // camera depth (m); +inf: sky; NaN: none
  std::array<float, 3> color{0, 0, 0};  // linear RGB (the sky's own along the sample's ray)
  std::int8_t sub_x = 0, sub_y = 0;     // position from the pixel's centre, 1/kSubScale pixels
  std::uint16_t count = 0;              // still samples averaged in color (0: not still)
  std::uint8_t age = 0;                 // frames since traced
  SampleSource source = SampleSource::sky;
};
static_assert(sizeof(Sample) == 24);

// The samples a still camera's mean at this pixel already holds: its still samples, or the view's
// own ray (its sky share baked, not sampled: biased a little, far less noisy than one sky ray)
// as the first; a cold frame's LDI pixel, the sky and a hole start afresh.
inline int still_samples(const Sample& s) {
  if (std::isnan(s.depth)) return 0;
  if (s.source == SampleSource::still) return s.count;
  return s.source == SampleSource::ray ? 1 : 0;
}
using KeptSamples = std::vector<Sample>;

}  // namespace frame_cache_detail

struct FrameCache::Impl {
  int width = 0, height = 0;
  frame_cache_detail::KeptSamples kept[2];
  int current = 0;                   // kept[current]: the last frame's samples
  std::vector<std::uint64_t> keys;   // reprojection: (depth bits, previous pixel), the smallest wins
  std::vector<std::uint8_t> need;    // per pixel, Need
  std::vector<std::uint32_t> fresh;  // the pixels traced this frame, block by block
  // In motion, where in its pixel each fresh sample is traced (1/kSubScale pixels): where the
  // samples around it lie, so that it joins their lattice (traced at pixel centres among samples
  // that moved a fraction of a pixel, two met in one pixel every few frames and the samples thinned
  // out: in a pure turn 15,000 pixels of 230,400 showed a neighbour's sample after one frame,
  // 60,000 after thirty).
  std::vector<std::array<std::int8_t, 2>> lattice;
  std::vector<std::array<std::uint32_t, frame_cache_detail::kNeeds>> row_needs;
  std::vector<std::uint32_t> row_fresh;
  std::vector<std::uint8_t> row_has_holes;  // resolve(): a row fill_holes() must visit
  std::vector<std::uint8_t> block_due;      // select_still(): per kBlock x kBlock block, its turn this frame
  ViewProjection projection;                // the last frame's
  std::uint32_t still_slot = 0;
  // FrameBudget::adaptive: the last moving frames' costs per fresh sample and per pixel (their
  // passes), smoothed.
  double measured_sample_ns = 0, measured_pixel_ns = 0;

  std::size_t pixels() const { return std::size_t(width) * std::size_t(height); }
  frame_cache_detail::KeptSamples& now() { return kept[current]; }
  void resize(int w, int h) {
    width = w;
    height = h;
    for (frame_cache_detail::KeptSamples& k : kept) k.assign(pixels(), frame_cache_detail::Sample{});
    keys.assign(pixels(), frame_cache_detail::kNoKey);
    need.assign(pixels(), frame_cache_detail::kKeep);
    fresh.assign(pixels(), 0);
    lattice.assign(pixels(), {0, 0});
    row_needs.assign(std::size_t(h), {});
    row_fresh.assign(std::size_t(h) + 1, 0);
    row_has_holes.assign(std::size_t(h), 0);
    block_due.assign(
        std::size_t(blocks_wide()) * std::size_t((h + frame_cache_detail::kBlock - 1) / frame_cache_detail::kBlock), 0);
  }
  int blocks_wide() const { return (width + frame_cache_detail::kBlock - 1) / frame_cache_detail::kBlock; }
  std::size_t bytes() const {
    return (kept[0].size() + kept[1].size()) * sizeof(frame_cache_detail::Sample) + keys.size() * 8 + need.size() +
           fresh.size() * 4 + lattice.size() * 2 + row_needs.size() * sizeof(row_needs[0]) + row_fresh.size() * 4 +
           row_has_holes.size() + block_due.size();
  }

  void reproject(const ViewProjection& to);
  void classify(std::uint64_t frame, bool still, const frame_cache_detail::EnteringBand& band);
  std::array<std::uint64_t, frame_cache_detail::kNeeds> count_needs() const;
  void drop_hidden(std::size_t n);
  std::size_t select(const std::array<std::uint64_t, frame_cache_detail::kNeeds>& needs, std::uint64_t budget,
                     std::uint64_t frame);
  std::size_t select_still(std::uint64_t budget);
  template <class Take>
  std::size_t gather_fresh(const Take& take);
  void trace(LdiRenderer& renderer, std::size_t n, bool still);
  std::uint64_t fill_holes(ImageRgb8& image) const;
  void resolve(const ViewWorld& world, ImageRgb8& image);
};

}  // namespace wangscape
