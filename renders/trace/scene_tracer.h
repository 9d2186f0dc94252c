// A Scene in Embree, built once and traced many times: the terrain mesh and every flower of the
// scene's instance stream as an instance of its variant's model, shaded by the one shading model
// (renders/trace/traced_shading.h). What the reference renderer traces per sample and the real-time
// view's near field per pixel. Coordinates are ENU meters shifted by origin() (whole meters), so
// that floats keep millimetres near it. Tracing is thread-safe once built.
#pragma once

#include <array>
#include <cstdint>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "renders/trace/ground_colors.h"
#include "renders/trace/traced_shading.h"
#include "scene/scene.h"

namespace wangscape {

class SceneTracer {
 public:
  enum class Layout {
    whole,  // the terrain and every flower of scene.instances (run once) in one scene
    part,   // the terrain in a scene of its own; the flowers those of the last set_flowers()
  };
  // Throws Error for an instance of a model the scene does not have, and for Embree's own
  // errors. The scene must outlive the tracer.
  // With the scene's wind and a `wind_seconds`, every flower leans as it does then (scene/wind.h);
  // without a time the flowers stand still (the view's near field, the sky shares' estimate).
  SceneTracer(const Scene& scene, const std::array<double, 3>& origin, Layout layout = Layout::whole,
              std::optional<double> wind_seconds = std::nullopt);
  // The flowers leaned as the scene's wind has them at `seconds`: every flower's transform set
  // anew and the top level rebuilt (nothing without wind, or at the time they have). Not
  // thread-safe with tracing.
  void set_wind_time(double seconds);
  // Layout::part: the flowers traced from now on (the previous ones dropped); a rebuild of the top
  // level only (the models and the terrain stay built). Not thread-safe with tracing.
  void set_flowers(const InstanceStream& flowers);
  // For shading without sky rays (the view's near field): estimates the share of the sky each
  // side of each model triangle sees among the flowers traced now, from `rays` sky rays
  // (`shading`'s ao_distance) per side spread over up to `instances` flowers of that model, and
  // carries it to the vertices, so that a flower's surface() then carries it, interpolated
  // (SurfaceSample::sky; 1 before, on the ground, and when `shading` has no sky rays).
  // Self-shadowing and the neighbours' average are in it; one flower's own neighbours are not.
  void bake_sky(const ShadingSettings& shading, int rays = 32, int instances = 4);
  // That estimate, per model of the scene and per vertex: the share of the sky its front (the
  // triangles' winding) and its back see. Empty before bake_sky, or after it without sky rays.
  using SkyShares = std::vector<std::vector<std::array<float, 2>>>;
  const SkyShares& sky_shares() const;
  // Shades with an estimate made beforehand (another tracer's, or a scene folder's; empty: the
  // open sky). Throws Error when it does not hold every vertex of every model of the scene.
  void set_sky_shares(SkyShares shares);
  ~SceneTracer();
  SceneTracer(const SceneTracer&) = delete;
  SceneTracer& operator=(const SceneTracer&) = delete;

  const std::array<double, 3>& origin() const;  // ENU meters, whole
  std::uint64_t instances() const;              // flowers
  RTCSceneTy* scene() const;                    // the top-level scene: every occluder, for shade()
  // Throws the first error Embree reported while tracing, naming what we were doing.
  void check(std::string_view doing) const;

  struct Hit {
    float t, u, v;
    unsigned geom, inst, prim;  // inst: RTC_INVALID_GEOMETRY_ID (~0u) for the terrain
  };
  // The nearest hit of the ray from `from` (shifted frame) along the unit direction `d` with
  // t in [0, tfar].
  std::optional<Hit> intersect(const std::array<double, 3>& from, const std::array<double, 3>& d,
                               float tfar = std::numeric_limits<float>::infinity()) const;
  // 16 rays at once (one rtcIntersect16 packet; the same hits as intersect() one by one): from
  // the one point `from` along the unit directions `d`, each up to its tfar; lanes whose `valid`
  // is false are not traced. hit[l] is empty where lane l met nothing.
  void intersect16(const std::array<double, 3>& from, const std::array<double, 3>* d, const float* tfar,
                   const bool* valid, std::optional<Hit>* hit) const;
  // The surface at a hit of that ray: position (shifted frame), normal turned towards the
  // viewer, base color (the ground's from `ground`), translucency.
  SurfaceSample surface(const Hit& hit, const std::array<double, 3>& from, const std::array<double, 3>& d,
                        const GroundColors& ground) const;

 private:
  struct Impl;
  const Scene& scene_;
  std::unique_ptr<Impl> impl_;
};

}  // namespace wangscape
