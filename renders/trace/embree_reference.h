// The Embree reference renderer: ray traces a whole Scene (the terrain mesh and every flower as
// an Embree instance of its variant's model) with the one shading model of renders/trace/traced_shading.h.
// It is the ground truth the LDI view is measured against (renders/trace/image_compare.h) and a fast
// preview renderer of a scene folder (`wangscape render DIR --engine embree`).
//
// Interface kept stable for the LDI viewer (branch ldi-view):
//   - ReferenceOptions / render_reference(scene, options) -> ReferenceImage
//   - ReferenceImage::image (sRGB8), ::coverage (share of samples that met geometry, per
//     pixel), ::depth (meters from the eye to the nearest hit of the pixel's samples, +inf = sky)
//   - reference_camera_frame(camera, width, height): the pinhole model both renderers share.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <limits>
#include <memory>
#include <optional>
#include <vector>

#include "generator/image.h"
#include "renders/trace/traced_shading.h"
#include "scene/scene.h"

namespace wangscape {

// Limits of render_reference (docs/limits.md).
inline constexpr int kMaxReferenceSide = 16384;                    // pixels, width and height
inline constexpr std::uint64_t kMaxReferencePixels = 64ull << 20;  // width x height
inline constexpr int kMaxReferenceSamples = 1024;                  // samples per pixel

struct ReferenceOptions {
  std::optional<Camera> camera;  // empty = scene.camera (ENU meters, horizontal field of view)
  int width = 0, height = 0;     // 0 = scene.render's
  int samples_per_pixel = 0;     // 1..kMaxReferenceSamples; 0 = scene.render.antialias_samples squared
  std::optional<int> threads;    // empty = scene.render.threads; 0 = every core
  // The light. The scene's sun (with_sun) is applied on top: direction and strength come from
  // scene.sun, the rest (sky color, sky rays, exposure, plain ground color) from here.
  ShadingSettings shading;
  std::uint64_t seed = 0;   // of the jitter and the sky rays: the same seed, the same bytes
  double wind_seconds = 0;  // with the scene's wind: the time its flowers lean as at (scene/wind.h)
  // Pixels done of the total, now and then (from worker threads, one call at a time).
  std::function<void(std::uint64_t done, std::uint64_t total)> progress;
};

struct ReferenceStats {
  std::uint64_t instances = 0;       // flowers traced (each an Embree instance)
  std::uint64_t triangles = 0;       // terrain triangles + the models' triangles (each once)
  std::uint64_t primary_rays = 0;    // camera rays: width x height x samples
  std::uint64_t secondary_rays = 0;  // shadow and sky rays cast by shade()
  int samples_per_pixel = 0;
  int threads = 0;            // TBB's parallelism while tracing
  double build_seconds = 0;   // placing the instances and building Embree's scenes
  double render_seconds = 0;  // tracing and shading
  double seconds = 0;         // the whole call
};

struct ReferenceImage {
  ImageRgb8 image;              // sRGB, 8 bits, top row first
  std::vector<float> coverage;  // per pixel (row-major): 0..1 share of its samples that met geometry
  std::vector<float> depth;     // per pixel: meters from the eye to its samples' nearest hit, +inf = sky
  ReferenceStats stats;
};

// The pinhole camera of the reference (and of the LDI view, which must frame the same view):
// from `origin` (the eye), the image point (sx, sy) in pixels (top-left corner of the image at
// (0, 0), sy down; a pixel's centre at +0.5) looks along
//   forward + (2 sx / W - 1) * right + (1 - 2 sy / H) * up,
// where right and up already carry the tangent of half the horizontal field of view (up times
// H / W more). World up is ENU +z; right = forward x up (east when looking north), as POV-Ray's
// `look_at` camera frames it.
struct CameraFrame {
  std::array<double, 3> origin{}, forward{}, right{}, up{};  // forward unit; right, up scaled
};
// Throws Error when the camera is not finite, its target is its position, it looks straight up
// or down, or its field of view is outside (0, kMaxFieldOfViewDegrees) (core/vecmath.h).
CameraFrame reference_camera_frame(const Camera& camera, int width, int height);

// Renders `scene` as options say. Samples: one through each pixel's centre, or N jittered ones,
// one per cell of a ceil(sqrt N) x ceil(sqrt N) grid over the pixel (cells in row order, the last
// row partly used), averaged in linear light before the sRGB encoding. Each sample that meets
// geometry is shaded by shade() (sun with a shadow ray, options.shading.ao_rays sky rays); one
// that meets nothing sees sky_radiance(). A folder render takes its shading from the scene file
// (ldi_options(config).shading, the light of the folder's LDI pack): so should a comparison.
// Parallel over 16 x 16 pixel tiles (TBB); the bytes do not depend on the thread count. Runs scene.instances once. The
// terrain's color: the scene's baked ground (scene.ground_texture, bilinear over its extent) when it has one, else
// options.shading.ground_color. Throws Error for sizes, samples or a camera out of range, and
// for Embree's own errors.
ReferenceImage render_reference(const Scene& scene, const ReferenceOptions& options = {});

// Many frames of one scene (the frames of a path): the scene built into Embree once, about
// `origin` (ENU m: the first frame's eye keeps floats precise near it), then each frame traced
// as render_reference traces it (its stats' build_seconds then near 0). The scene must outlive
// it; render() is not to be called from several threads at once (with the scene's wind it first
// leans the flowers as they are at options.wind_seconds).
class ReferenceFrames {
 public:
  ReferenceFrames(const Scene& scene, const std::array<double, 3>& origin);
  ~ReferenceFrames();
  ReferenceFrames(const ReferenceFrames&) = delete;
  ReferenceFrames& operator=(const ReferenceFrames&) = delete;
  ReferenceImage render(const ReferenceOptions& options) const;

 private:
  struct Impl;
  const Scene& scene_;
  std::unique_ptr<Impl> impl_;
};

// The samples per pixel render_reference uses for `requested` (0 = from the scene) on `scene`.
int reference_samples(const RenderSettings& render, int requested);

}  // namespace wangscape
