// The sample cache's reprojection: each kept sample to where the new camera sees it.
#include "renders/view/frame_cache_impl.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <atomic>
#include <bit>

namespace wangscape {

using namespace frame_cache_detail;  // the cache's inner parts (frame_cache_impl.h)

// ---- reprojection: each kept sample to where the new camera sees it ------------------------

namespace {

// Where the new camera sees a kept sample: the change of camera in floats. Each worker copies it
// into its own registers: the keys' atomic writes (and the byte stores of the needs) otherwise make
// the compiler reload every constant through memory once a write (a third of reproject()).
struct Reprojection {
  float M[3][3], t[3];  // new camera coordinates = M * old camera coordinates + t (M = R_new^T R_old)
  float from_cx, from_cy, inv_focal, to_cx, to_cy, to_focal, stretch;
  // Where the new camera sees sample s of old pixel (x, y): screen (px, py), the footprint's side
  // (pixels) and the new depth (+inf: the sky; NaN: behind the eye).
  struct Seen {
    float px, py, side, depth;
  };
  Seen operator()(const Sample& s, int x, int y) const {
    constexpr float inv_sub = 1.0f / kSubScale;
    const float depth = s.depth;
    const float u = (float(x) + 0.5f - from_cx + float(s.sub_x) * inv_sub) * inv_focal;
    const float v = (from_cy - float(y) - 0.5f - float(s.sub_y) * inv_sub) * inv_focal;
    if (std::isinf(depth)) {  // a direction: turned, not moved
      const float n0 = M[0][0] * u + M[0][1] * v + M[0][2], n1 = M[1][0] * u + M[1][1] * v + M[1][2];
      const float n2 = M[2][0] * u + M[2][1] * v + M[2][2];
      if (!(n2 > 1e-6f)) return {0, 0, 0, kNone};
      const float inv = to_focal / n2;
      return {to_cx + n0 * inv, to_cy - n1 * inv, 1.0f, kInf};
    }
    const float c0 = u * depth, c1 = v * depth;
    const float n0 = M[0][0] * c0 + M[0][1] * c1 + M[0][2] * depth + t[0];
    const float n1 = M[1][0] * c0 + M[1][1] * c1 + M[1][2] * depth + t[1];
    const float n2 = M[2][0] * c0 + M[2][1] * c1 + M[2][2] * depth + t[2];
    if (!(n2 > kNearest)) return {0, 0, 0, kNone};
    const float inv = to_focal / n2;
    return {to_cx + n0 * inv, to_cy - n1 * inv, std::min(kMaxStretch, stretch * depth / n2), n2};
  }
};

Reprojection reprojection(const ViewProjection& from, const ViewProjection& to) {
  Reprojection r;
  const Vector3d* old_axes[3] = {&from.right, &from.up, &from.forward};
  const Vector3d* new_axes[3] = {&to.right, &to.up, &to.forward};
  const Vector3d shift{from.eye[0] - to.eye[0], from.eye[1] - to.eye[1], from.eye[2] - to.eye[2]};
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) r.M[i][j] = float(dot(*new_axes[i], *old_axes[j]));
    r.t[i] = float(dot(*new_axes[i], shift));
  }
  r.from_cx = from.cx;
  r.from_cy = from.cy;
  r.inv_focal = 1.0f / from.focal;
  r.to_cx = to.cx;
  r.to_cy = to.cy;
  r.to_focal = to.focal;
  r.stretch = kCopySplatScale * to.focal / from.focal;
  return r;
}

// key = min(key, k), whichever thread comes first.
inline void keep_smaller(std::uint64_t& key, std::uint64_t k) {
  std::atomic_ref<std::uint64_t> slot(key);
  std::uint64_t seen = slot.load(std::memory_order_relaxed);
  while (k < seen && !slot.compare_exchange_weak(seen, k, std::memory_order_relaxed)) {
  }
}

// A reprojection key: what a pixel keeps of the sample that wins it, the smallest winning. From
// the top bit: a neighbour's copy (1), the new depth's float bits (positive floats order as
// their bits do; all 31 up to 2^26 pixels, the high ones beyond), where the sample's own pixel
// lies from this one (-3 .. 3 across and down, 3 bits each) and its previous pixel (as many bits
// as the frame's pixels need). Its place within its own pixel is in its record (pass 1).
struct KeyLayout {
  int index_bits = 1, depth_shift = 0;
  static KeyLayout of(std::size_t pixels) {
    KeyLayout layout;
    layout.index_bits = std::max(1, int(std::bit_width(pixels - 1)));
    layout.depth_shift = std::max(0, 31 - (63 - 6 - layout.index_bits));
    return layout;
  }
  // A sample's key without where its own pixel lies: | home(dx, dy), and | kCopyBit for a copy.
  std::uint64_t key(float depth, std::uint32_t pixel) const {
    return std::uint64_t(std::bit_cast<std::uint32_t>(depth) >> depth_shift) << (6 + index_bits) | pixel;
  }
  // The bits saying the sample's own pixel lies (dx, dy) pixels from the keyed one.
  std::uint64_t home(int dx, int dy) const { return std::uint64_t((dx + 4) << 3 | (dy + 4)) << index_bits; }
  std::uint32_t source(std::uint64_t key) const { return std::uint32_t(key & ((1ull << index_bits) - 1)); }
  int home_x(std::uint64_t key) const { return int((key >> (index_bits + 3)) & 7) - 4; }
  int home_y(std::uint64_t key) const { return int((key >> index_bits) & 7) - 4; }
};

// Pass 1 of reproject(), one worker's copy (its members in registers: the keys' stores would
// otherwise reload them through memory).
struct Scatter {
  Reprojection project;
  KeyLayout layout;
  Sample* old;
  std::uint64_t* key;
  int w, h;
  // Projects the sample of pixel (x, y) once: its new depth goes into its own record (read again
  // only as a winner's, in pass 2), its place in each pixel it covers into that pixel's key, by
  // take(key, k). Returns false, placing nothing, when its footprint would reach rows outside
  // rows_from .. rows_to - 1.
  template <class Take>
  bool place(int x, int y, int rows_from, int rows_to, const Take& take) const {
    const std::size_t p = std::size_t(y) * std::size_t(w) + std::size_t(x);
    Sample& sample = old[p];
    if (is_none(sample.depth)) return true;
    const Reprojection::Seen s = project(sample, x, y);
    if (is_none(s.depth) || !(s.px > -kMaxStretch && s.py > -kMaxStretch && s.px < float(w) + kMaxStretch &&
                              s.py < float(h) + kMaxStretch)) {
      sample.depth = kNone;  // (never a winner: it placed no key)
      return true;
    }
    const int home_x = floor_above(s.px), home_y = floor_above(s.py);
    if (home_y - kFootprintRows < rows_from || home_y + kFootprintRows >= rows_to) return false;
    sample.depth = s.depth;
    // Its place within its own pixel, for pass 2 (the projection above was the record's last use
    // of its old place).
    const float from_x = s.px - 0.5f, from_y = s.py - 0.5f;
    sample.sub_x = sub_code(from_x - float(home_x));
    sample.sub_y = sub_code(from_y - float(home_y));
    // The pixels whose centres the footprint holds: the own pixel's key, the others' a copy's.
    const float half = s.side * 0.5f;
    const int x0 = std::max(0, ceil_above(from_x - half)), x1 = std::min(w - 1, floor_above(from_x + half));
    const int y0 = std::max(0, ceil_above(from_y - half)), y1 = std::min(h - 1, floor_above(from_y + half));
    const std::uint64_t sample_key = layout.key(s.depth, std::uint32_t(p));
    const auto at = [&](int qx, int qy) -> std::uint64_t& {
      return key[std::size_t(qy) * std::size_t(w) + std::size_t(qx)];
    };
    if (home_x >= 0 && home_y >= 0 && home_x < w && home_y < h)
      take(at(home_x, home_y), sample_key | layout.home(0, 0));
    for (int qy = y0; qy <= y1; ++qy)
      for (int qx = x0; qx <= x1; ++qx)
        if (qx != home_x || qy != home_y)
          take(at(qx, qy), sample_key | kCopyBit | layout.home(home_x - qx, home_y - qy));
    return true;
  }
};

}  // namespace

void FrameCache::Impl::reproject(const ViewProjection& to) {
  const Reprojection shared = reprojection(projection, to);
  const KeyLayout layout = KeyLayout::of(pixels());
  Sample* const old = now().data();
  Sample* const next = kept[1 - current].data();
  std::uint64_t* const key = keys.data();
  std::uint8_t* const needs = need.data();
  const int w = width, h = height;
  std::fill(keys.begin(), keys.end(), kNoKey);
  // The scatter without atomics: the rows in bands, the even bands at once, then the odd ones. A
  // sample reaching no farther than half a band beyond its own takes its pixels with plain
  // stores, as no other band of its parity reaches them; one that moves farther is marked and
  // placed after, with compare-and-swap (the keys end the same on any thread count: the
  // smallest wins). The atomics cost 10 ns a sample even uncontended, a third of the scatter.
  const int band_rows = (h + kScatterBands - 1) / kScatterBands, reach = band_rows / 2;
  const int bands = (h + band_rows - 1) / band_rows;
  std::atomic<bool> any_far{false};
  for (int parity = 0; parity < 2; ++parity)
    tbb::parallel_for(0, (bands - parity + 1) / 2, [&](int i) {
      Scatter scatter{shared, layout, old, key, w, h};
      const int band = 2 * i + parity, first = band * band_rows, last = std::min(h, first + band_rows);
      bool far = false;
      for (int y = first; y < last; ++y)
        for (int x = 0; x < w; ++x)
          if (!scatter.place(x, y, first - reach, last + reach,
                             [](std::uint64_t& slot, std::uint64_t k) { slot = std::min(slot, k); })) {
            needs[std::size_t(y) * std::size_t(w) + std::size_t(x)] = kFarMove;
            far = true;
          }
      if (far) any_far = true;
    });
  if (any_far)
    tbb::parallel_for(tbb::blocked_range<int>(0, h, 4), [&](const tbb::blocked_range<int>& r) {
      Scatter scatter{shared, layout, old, key, w, h};
      for (int y = r.begin(); y != r.end(); ++y)
        for (int x = 0; x < w; ++x)
          if (needs[std::size_t(y) * std::size_t(w) + std::size_t(x)] == kFarMove)
            scatter.place(x, y, std::numeric_limits<int>::min() / 2, std::numeric_limits<int>::max() / 2, keep_smaller);
    });
  tbb::parallel_for(tbb::blocked_range<int>(0, h, 4), [&](const tbb::blocked_range<int>& r) {
    const KeyLayout keys_of = layout;
    for (int y = r.begin(); y != r.end(); ++y)
      for (int x = 0; x < w; ++x) {
        const std::size_t q = std::size_t(y) * std::size_t(w) + std::size_t(x);
        needs[q] = kKeep;
        const std::uint64_t won = key[q];
        if (won == kNoKey) {
          next[q].depth = kNone;
          continue;
        }
        const std::uint32_t p = keys_of.source(won);
        const int home_x = x + keys_of.home_x(won), home_y = y + keys_of.home_y(won);
        Sample to_sample = old[p];  // (its depth and place already the new ones, in its own pixel)
        to_sample.age = std::uint8_t(std::min(255, to_sample.age + 1));
        to_sample.sub_x = std::int8_t(std::clamp(to_sample.sub_x + kPixelCode * (home_x - x), -127, 127));
        to_sample.sub_y = std::int8_t(std::clamp(to_sample.sub_y + kPixelCode * (home_y - y), -127, 127));
        // A copy of a sample that lost its own pixel to another (two met there) is adopted: it lives
        // on here, beside its pixel, so that the samples do not thin out frame after frame.
        const auto won_its_pixel = [&] {
          if (home_x < 0 || home_y < 0 || home_x >= w || home_y >= h) return false;
          const std::uint64_t there = key[std::size_t(home_y) * std::size_t(w) + std::size_t(home_x)];
          return there != kNoKey && !(there & kCopyBit) && keys_of.source(there) == p;
        };
        const bool orphan = (won & kCopyBit) && !won_its_pixel();
        const int allowed = orphan ? kAdoptedCode : kStretchedCode;
        if (std::abs(to_sample.sub_x) > allowed || std::abs(to_sample.sub_y) > allowed) needs[q] = kStretched;
        next[q] = to_sample;
      }
  });
  current = 1 - current;
}

}  // namespace wangscape
