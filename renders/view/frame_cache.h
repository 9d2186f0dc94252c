// The view in motion: each frame drawn from the previous frame's samples (docs/viewer-design.md, "The
// sample cache"), after the render cache of Walter, Drettakis and Parker (1999) and stable ray
// tracing (Dal Corso et al. 2017). Every pixel keeps one sample: its camera depth and sub-pixel
// position, its colour (linear), where it came from and its age. A frame reprojects the previous
// frame's samples into the new camera (the nearest wins each pixel), drops those seen through a
// gap in a nearer surface, and traces anew, with the whole scene's rays (the exact geometry, as
// `--engine embree` draws it), only what they leave: the empty pixels, the cold frame's LDI
// pixels, and a rotating share of all of them; as many as the frame's budget allows, the rest
// shown as their neighbours until a later frame traces them. While the camera holds still each
// frame adds samples at new sub-pixel positions (the R2 sequence) shaded as the reference shades
// them (sky rays included), averaged, so the picture converges to the anti-aliased truth. A first
// frame, a jump, a resize or a new field of view draws a whole frame with the LdiRenderer (a
// cold frame: the same bytes as LdiRenderer::render), and so does a moving camera whose last whole
// frame was LDIs alone (no near field: from above or afar, where that is the cheaper source).
//
// Deterministic: the fresh samples a frame may draw are a count (FrameBudget), not a clock, so a
// path gives the same bytes on any thread count; the window may size them by its clock instead.
// Buffers are sized with the frame (63 bytes a pixel): a frame allocates nothing. Prints nothing.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "generator/image.h"
#include "renders/view/ldi_renderer.h"

namespace wangscape {

inline constexpr double kDefaultViewFps = 60;
inline constexpr double kMinViewFps = 1, kMaxViewFps = 240;

// Where a kept sample came from.
enum class SampleSource : std::uint8_t {
  frame,  // a cold frame's pixel: LDIs, terrain and near-field rays (LdiRenderer's composite)
  ray,    // traced anew at the pixel centre by the view's rays (sun shadow ray, baked sky share)
  still,  // the mean of samples shaded as the reference shades them (sky rays), camera still
  sky,    // nothing there: the sky, drawn along the pixel's own ray
  lent,   // a nearer surface found beside it this frame: that sample's, shown until traced
};

// How many samples a frame may trace anew: sized to the frame time 1000 / fps ms from nominal
// costs measured on this machine (bench/view_cache_bench; docs/viewer-design.md), so that the count is
// the same on every run and thread count. With `adaptive` both costs (a pixel's passes, a fresh
// sample) are measured per moving frame instead (the window's own clock): the rate holds on any
// machine, the frames vary with it.
struct FrameBudget {
  double fps = kDefaultViewFps;
  double pixel_ns = 55;           // per pixel and frame: reprojection, tests, resolve (both threads)
  double still_pixel_ns = 8;      // the same while still (nothing to reproject; 6.3-7.9 measured)
  double sample_ns = 550;         // per fresh sample in motion (a primary and a shadow ray, shading)
  double still_sample_ns = 1400;  // per fresh sample while still (the reference's sky rays; 1,360-1,410)
  bool adaptive = false;
  // Throws Error for fps outside kMinViewFps .. kMaxViewFps.
  void check() const;
};

struct CachedFrameStats {
  double frame_ms = 0;
  double trace_ms = 0;  // of it: tracing the fresh samples (a cold frame: all of it)
  // Of a warm frame: reprojecting, judging and choosing the pixels to trace, tracing, resolving.
  std::array<double, 4> phase_ms{};
  bool cold = false;   // drawn whole by the LdiRenderer
  bool still = false;  // the camera held still: the fresh samples were accumulated
  std::uint64_t pixels = 0;
  std::uint64_t budget = 0;     // fresh samples this frame allowed
  std::uint64_t fresh = 0;      // samples traced anew (every pixel of a cold frame)
  std::uint64_t holes = 0;      // pixels no kept sample reached, or one seen through a gap
  std::uint64_t filled = 0;     // of the holes, those the budget left: shown as their neighbours
  std::uint64_t stretched = 0;  // pixels showing a neighbour's sample (magnified, or its own lost)
  std::uint64_t probes = 0;     // pixels probed at the edge the camera moves toward (objects coming in)
  std::uint64_t refresh = 0;    // pixels whose turn to be traced anew it was (or too old, or a cold frame's LDIs)
  int still_frames = 0;         // frames the camera has held still (0: moving)
  double fresh_share() const { return pixels ? double(fresh) / double(pixels) : 0; }
};

class FrameCache {
 public:
  // Draws with `renderer` (its size, its settings for cold frames); the renderer must outlive
  // the cache and not be drawn with by anyone else meanwhile.
  explicit FrameCache(LdiRenderer& renderer, const FrameBudget& budget = {});
  ~FrameCache();
  FrameCache(const FrameCache&) = delete;
  FrameCache& operator=(const FrameCache&) = delete;

  // Draws the frame of `camera` into image(). Throws Error for a camera LdiRenderer refuses.
  const CachedFrameStats& render(const Camera& camera);
  const ImageRgb8& image() const { return image_; }
  // The next frame is cold (drawn whole).
  void invalidate() { warm_ = false; }
  void set_budget(const FrameBudget& budget);
  const FrameBudget& budget() const { return budget_; }
  // The camera depth (meters) of the sample pixel (x, y) shows: +inf for the sky, NaN for a hole
  // shown as its neighbours.
  float depth_at(int x, int y) const;
  SampleSource source_at(int x, int y) const;
  // Bytes the cache holds per pixel (its buffers over width x height).
  double bytes_per_pixel() const;

 private:
  struct Impl;
  LdiRenderer& renderer_;
  std::unique_ptr<Impl> impl_;
  FrameBudget budget_;
  ImageRgb8 image_;
  CachedFrameStats stats_;
  bool warm_ = false;
  Camera previous_{};
  std::uint64_t frame_index_ = 0;
  int still_frames_ = 0;
  bool whole_is_cheaper_ = false;  // the last whole frame was LDIs alone: moving, draw whole
  // A whole frame's samples are taken from the renderer only when a frame reuses them: drawn
  // whole frame after frame (the flight), the copy cost 1.7 ms of 18.6 at 640 x 360.
  bool cold_samples_pending_ = false;
  SampleSource cold_source_ = SampleSource::frame;

  void draw_cold(const Camera& camera);
  void take_cold_samples();
  std::uint64_t fresh_budget(bool still) const;
};

}  // namespace wangscape
