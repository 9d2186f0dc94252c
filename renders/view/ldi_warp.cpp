#include "renders/view/ldi_warp.h"

#include <algorithm>
#include <atomic>
#include <string>

#include "core/error.h"
#include "renders/view/vector_path.h"
#include "renders/view/view_world.h"

namespace wangscape::view_detail {

std::uint16_t owned_thresholds(float from, float to) {
  std::uint16_t mask = 0;
  for (int k = 0; k < 16; ++k) {
    const float th = (float(k) + 0.5f) / 16;
    if (th >= from && th < to) mask = std::uint16_t(mask | 1u << k);
  }
  return mask;
}

namespace {

// The projection runs in the widest vector lanes the CPU has (AVX-512 here: 16 depth pixels at a
// time); every path makes the same frame (renders/view/vector_path.h).
constexpr int kBatch = 256;
constexpr float kFarOff = 1e6f;  // pixels: farther off the screen than any splat reaches back

// Depth pixels gathered from an LDI, in the order its rows and spans hold them, and what their
// projection gives. The z-buffer keeps the nearest entry whatever the order, so no
// occlusion-compatible order (McMillan's) is needed, and a batch may run across rows.
struct Batch {
  int size = 0;
  alignas(64) float x[kBatch];            // LDI pixel column
  alignas(64) float y[kBatch];            // LDI pixel row
  alignas(64) float depth[kBatch];        // meters along the LDI's rays
  alignas(64) std::int32_t last[kBatch];  // 1: the pixel's last layer (where the ground plane is)
  std::uint32_t index[kBatch];            // into the LDI's depth pixels
  // Projected: camera depth and the screen pixels [x0, x1) x [y0, y1) the splat covers; keep 0
  // where nothing is drawn (behind the near plane, the ground plane, off the screen).
  alignas(64) float z[kBatch];
  alignas(64) std::int32_t x0[kBatch], x1[kBatch], y0[kBatch], y1[kBatch], keep[kBatch];
  alignas(64) std::int32_t cell[kBatch];  // of the tile's grid of plant rules, where the sample stands
};

// The least integer not below v, for |v| < 2^31: written with a truncation, which vectorizes
// (the compiler turns (int) std::ceil into a library call that does not).
inline std::int32_t ceil_to_int(float v) {
  const std::int32_t t = std::int32_t(v);
  return t + std::int32_t(float(t) < v);
}

// The greatest integer not above v, likewise.
inline std::int32_t floor_to_int(float v) {
  const std::int32_t t = std::int32_t(v);
  return t - std::int32_t(v < float(t));
}

// Each depth pixel of the batch moved onto the tile's terrain and projected. Branch-free, so the
// compiler runs it in vector lanes; the Warp's fields are copied to locals so that no store into
// the batch can alias them. Inlined into one function per vector path (below).
[[gnu::always_inline]] inline void project_batch(const Warp& w, Batch& b) {
  const float lb0 = w.local_base[0], lb1 = w.local_base[1], lb2 = w.local_base[2];
  const float lx0 = w.local_x[0], lx1 = w.local_x[1], lx2 = w.local_x[2];
  const float ly0 = w.local_y[0], ly1 = w.local_y[1], ly2 = w.local_y[2];
  const float ld0 = w.local_d[0], ld1 = w.local_d[1], ld2 = w.local_d[2];
  const float cb0 = w.base[0], cb1 = w.base[1], cb2 = w.base[2];
  const float cx0 = w.step_x[0], cx1 = w.step_x[1], cx2 = w.step_x[2];
  const float cy0 = w.step_y[0], cy1 = w.step_y[1], cy2 = w.step_y[2];
  const float cd0 = w.step_d[0], cd1 = w.step_d[1], cd2 = w.step_d[2];
  const float lift0 = w.lift[0], lift1 = w.lift[1], lift2 = w.lift[2];
  const float h00 = w.h00, h10 = w.h10, h01 = w.h01, h11 = w.h11, inverse_tile = w.inverse_tile;
  const float ground_below = w.ground_below, splat = w.splat;
  const float focal = w.screen.focal, cx = w.screen.cx, cy = w.screen.cy;
  const int width = w.screen.width, height = w.screen.height;
  const float max_splat = float(w.screen.max_splat);
  constexpr std::int32_t plant_cells = ViewWorld::Tiles::kPlantCells, last_cell = plant_cells - 1;
  constexpr float cells = float(plant_cells);
  const int n = b.size;
  for (int i = 0; i < n; ++i) {
    const float fx = b.x[i], fy = b.y[i], d = b.depth[i];
    // Tile-local and camera-space positions of the pixel, then along its ray.
    const float lz = lb2 + fx * lx2 + fy * ly2 + d * ld2;
    const float lx = lb0 + fx * lx0 + fy * ly0 + d * ld0, ly = lb1 + fx * lx1 + fy * ly1 + d * ld1;
    // The shear onto the tile's two terrain triangles (split along the SW-NE diagonal).
    const float u = std::min(std::max(lx * inverse_tile, 0.0f), 1.0f);
    const float t = std::min(std::max(ly * inverse_tile, 0.0f), 1.0f);
    const float h_east = h00 + u * (h10 - h00) + t * (h11 - h10), h_north = h00 + t * (h01 - h00) + u * (h11 - h01);
    const float h = u >= t ? h_east : h_north;
    b.cell[i] =
        std::min(std::int32_t(u * cells), last_cell) + std::min(std::int32_t(t * cells), last_cell) * plant_cells;
    const float camera_z = cb2 + fx * cx2 + fy * cy2 + d * cd2 + h * lift2;
    const float camera_x = cb0 + fx * cx0 + fy * cy0 + d * cd0 + h * lift0;
    const float camera_y = cb1 + fx * cx1 + fy * cy1 + d * cd1 + h * lift1;
    const float inv = 1.0f / camera_z;
    // Not the ground plane (the terrain draws it), not behind the near plane (there, the screen
    // position is set to 0 so that no conversion below overflows).
    const std::int32_t ground = std::int32_t(b.last[i] != 0) & std::int32_t(lz < ground_below);
    const std::int32_t drawn = (ground | std::int32_t(camera_z < kNear)) ^ 1;
    // (Clamped far beyond any screen, where it changes no pixel, so the conversions stay in range.)
    const float sx = drawn ? std::min(std::max(cx + focal * camera_x * inv, -kFarOff), kFarOff) : 0.0f;
    const float sy = drawn ? std::min(std::max(cy - focal * camera_y * inv, -kFarOff), kFarOff) : 0.0f;
    const float size = splat * inv;
    b.z[i] = camera_z;
    // Most splats at the pack's resolution: one pixel, the one the position falls in.
    const std::int32_t one = size <= 1.0f;
    const std::int32_t fx0 = floor_to_int(sx), fy0 = floor_to_int(sy);
    const std::int32_t inside = std::int32_t((fx0 | fy0) >= 0) & std::int32_t(fx0 < width) & std::int32_t(fy0 < height);
    const std::int32_t px = std::min(fx0, width - 1), py = std::min(fy0, height - 1);
    // Larger: the pixels whose centres the splat's square covers, about size^2 of them, not ceil(size)^2.
    const float half = 0.5f * std::min(size, max_splat);
    const std::int32_t xa = std::max(ceil_to_int(sx - half - 0.5f), 0);
    const std::int32_t xb = std::min(ceil_to_int(sx + half - 0.5f), width);
    const std::int32_t ya = std::max(ceil_to_int(sy - half - 0.5f), 0);
    const std::int32_t yb = std::min(ceil_to_int(sy + half - 0.5f), height);
    b.x0[i] = one ? px : xa;
    b.x1[i] = one ? px + 1 : xb;
    b.y0[i] = one ? py : ya;
    b.y1[i] = one ? py + 1 : yb;
    b.keep[i] = drawn & ((one & inside) | ((one ^ 1) & std::int32_t(xa < xb) & std::int32_t(ya < yb)));
  }
}

using Projection = void (*)(const Warp&, Batch&);

void project_baseline(const Warp& w, Batch& b) { project_batch(w, b); }
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
[[gnu::target("arch=x86-64-v3")]] void project_avx2(const Warp& w, Batch& b) { project_batch(w, b); }
[[gnu::target("arch=x86-64-v4")]] void project_avx512(const Warp& w, Batch& b) { project_batch(w, b); }
constexpr bool kVectorPaths = true;
#else
constexpr bool kVectorPaths = false;
#endif

VectorPath detect_widest_path() {
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
  __builtin_cpu_init();  // (this may run in a static initializer, before libgcc's own)
  if (__builtin_cpu_supports("x86-64-v4")) return VectorPath::avx512;
  if (__builtin_cpu_supports("x86-64-v3")) return VectorPath::avx2;
#endif
  return VectorPath::baseline;
}

std::atomic<VectorPath> chosen_path{widest_vector_path()};

Projection projection() {
  if constexpr (kVectorPaths) {
    switch (chosen_path.load(std::memory_order_relaxed)) {
      case VectorPath::avx512:
        return project_avx512;
      case VectorPath::avx2:
        return project_avx2;
      case VectorPath::baseline:
        break;
    }
  }
  return project_baseline;
}

// The batch's kept depth pixels written into the z-buffer.
void splat(const LdiView& v, const Warp& w, const Batch& b, ThreadDepths& out) {
  for (int i = 0; i < b.size; ++i) {
    if (!b.keep[i]) continue;
    const DepthPixel& p = v.depth_pixels[b.index[i]];
    if (w.plant_steps && p.plant != kAnyPlant &&
        (p.plant & (kPlantRankSteps - 1)) >= w.plant_steps[b.cell[i] * kPlantSpecies + (p.plant >> 5)])
      continue;  // a plant the field's rules or density leave out where it stands
    const std::uint64_t entry = pack_entry(b.z[i], p.r, p.g, p.b);
    if (b.x1[i] - b.x0[i] == 1 && b.y1[i] - b.y0[i] == 1) {
      if (owns(w.owned, b.x0[i], b.y0[i])) out.write_pixel(b.x0[i], b.y0[i], entry);  // else another LDI's pixel
    } else {
      out.write(b.x0[i], b.x1[i], b.y0[i], b.y1[i], entry, w.owned);
    }
  }
}

}  // namespace

std::uint64_t warp_ldi(const LdiView& v, const Warp& w, ThreadDepths& out) {
  Batch batch;
  const Projection project = projection();
  auto flush = [&] {
    project(w, batch);
    splat(v, w, batch, out);
    batch.size = 0;
  };
  const std::uint32_t rows = v.frame->height;
  for (std::uint32_t y = 0; y < rows; ++y)
    for (std::uint32_t s = v.row_spans[y]; s < v.row_spans[y + 1]; ++s) {
      const LdiSpan& span = v.spans[s];
      std::uint32_t index = span.first_depth;
      for (std::uint32_t k = 0; k < span.length; ++k) {
        const std::uint32_t count = v.counts[span.first_pixel + k];
        for (std::uint32_t layer = 0; layer < count; ++layer, ++index) {
          const DepthPixel& p = v.depth_pixels[index];
          const int i = batch.size++;
          batch.x[i] = float(span.x + k);
          batch.y[i] = float(y);
          batch.depth[i] = float(p.depth()) * w.depth_scale;
          batch.last[i] = layer + 1 == count;
          batch.index[i] = index;
          if (batch.size == kBatch) flush();
        }
      }
    }
  if (batch.size) flush();
  return v.depth_pixels.size();
}

}  // namespace wangscape::view_detail

namespace wangscape {

std::string_view to_string(VectorPath path) {
  switch (path) {
    case VectorPath::avx512:
      return "avx512";
    case VectorPath::avx2:
      return "avx2";
    case VectorPath::baseline:
      break;
  }
  return "baseline";
}

VectorPath widest_vector_path() {
  static const VectorPath widest = view_detail::detect_widest_path();
  return widest;
}

VectorPath vector_path() { return view_detail::chosen_path.load(); }

void set_vector_path(VectorPath path) {
  if (int(path) > int(widest_vector_path()))
    throw Error("vector path " + std::string(to_string(path)) + ": this CPU runs at most " +
                std::string(to_string(widest_vector_path())));
  view_detail::chosen_path.store(path);
}

}  // namespace wangscape
