// The flowers' share of the open sky that the real-time view shades them with (its near field and
// its ray-cast frames: SceneTracer::bake_sky, sky rays too costly per pixel), estimated once per
// scene at one fixed place, and kept in a scene folder so that the view's first frame does not
// estimate it (0.74 s for the default scene's near field, and as much again for a ray-cast frame's
// whole scene, before both shared this one).
#pragma once

#include <filesystem>

#include "renders/trace/scene_tracer.h"
#include "scene/scene.h"

namespace wangscape {

// Among the flowers within kFieldSkyReach meters (plus 1.5 tiles) of the placed flower nearest the
// field's centre: where the view's near field at its default reach (8 m, a flower's 0.5 m and the
// sun's 4 m shadow margin) estimated it. `shading` is the view's light with the sun applied; empty
// without sky rays or without flowers. Deterministic.
inline constexpr double kFieldSkyReach = 12.5;
SceneTracer::SkyShares bake_field_sky(const Scene& scene, const ShadingSettings& shading);

// The shares in a file of their own (a scene folder's sky.bin): "WSCSKY\r\n", u32 version 1, u32
// models, per model u32 vertices, then per vertex two f32 (front, back), little endian. Written
// atomically; read back only for `scene`, whose models it must match vertex for vertex (or be
// none: the open sky), every
// share in [0, 1]: else an Error naming the file and what differs.
void write_sky_shares(const std::filesystem::path& path, const SceneTracer::SkyShares& shares);
SceneTracer::SkyShares read_sky_shares(const std::filesystem::path& path, const Scene& scene);

}  // namespace wangscape
