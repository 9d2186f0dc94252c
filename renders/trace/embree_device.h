// Embree handles shared by the renderers of renders/ (the LDI build, the reference renderer):
// a device that keeps the first error Embree reports, an owning scene handle, triangle meshes
// and the models as prototype scenes for single-level instancing. Internal to renders/.
#pragma once

#include <embree3/rtcore.h>

#include <array>
#include <cstdint>
#include <mutex>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "templates/mesh.h"

namespace wangscape {

class EmbreeDevice {
 public:
  EmbreeDevice();  // throws Error when Embree cannot make a device
  ~EmbreeDevice();
  EmbreeDevice(const EmbreeDevice&) = delete;
  EmbreeDevice& operator=(const EmbreeDevice&) = delete;
  RTCDevice get() const { return device_; }
  // Throws the first error Embree reported, naming what we were doing.
  void check(std::string_view doing);

 private:
  static void on_error(void* user, RTCError code, const char* message);
  RTCDevice device_ = nullptr;
  std::mutex mutex_;
  std::string error_;
};

class EmbreeScene {
 public:
  explicit EmbreeScene(RTCDevice device) : scene_(rtcNewScene(device)) {}
  ~EmbreeScene() {
    if (scene_) rtcReleaseScene(scene_);
  }
  EmbreeScene(EmbreeScene&& o) noexcept : scene_(o.scene_) { o.scene_ = nullptr; }
  EmbreeScene(const EmbreeScene&) = delete;
  EmbreeScene& operator=(const EmbreeScene&) = delete;
  RTCScene get() const { return scene_; }

 private:
  RTCScene scene_ = nullptr;
};

// A triangle geometry holding copies of `positions` and `triangles` (Embree's own buffers carry
// the padding its 16-byte vertex loads need), with `filter` as its intersection filter when
// given; committed.
RTCGeometry triangle_geometry(RTCDevice device, std::span<const std::array<float, 3>> positions,
                              std::span<const std::array<std::uint32_t, 3>> triangles,
                              RTCFilterFunctionN filter = nullptr);

// One committed scene per model (its triangles as geometry 0; HIGH build quality: built once,
// instanced many times), with `filter` on every model's triangles. A model with cut-out
// materials (leaf cards) has its Mesh as the geometry's user pointer and reject_cutouts as its
// occlusion filter, and as its intersection filter when `filter` is null (a given filter must
// call in_cutout itself). The models must outlive the scenes. Throws Embree's errors.
std::vector<EmbreeScene> model_scenes(EmbreeDevice& device, std::span<const Mesh> models,
                                      RTCFilterFunctionN filter = nullptr);

// Whether the hit at barycentric (u, v) of triangle `prim` falls in a hole of its material's
// cutout: the alpha of the material's image at the interpolated uv below alpha_cutoff.
bool in_cutout(const Mesh& mesh, unsigned prim, float u, float v);

// Whether any material of `mesh` is a cutout with an image to cut by, and the mesh has uvs.
bool has_cutouts(const Mesh& mesh);

// Gives a model's triangle geometry its cutouts when it has any: `mesh` as the user pointer,
// reject_cutouts as the occlusion filter and, when `intersection`, as the intersection filter;
// commits it again. `mesh` must outlive the geometry.
void add_cutouts(RTCGeometry geometry, const Mesh& mesh, bool intersection);

// Embree filter: rejects the hits in_cutout finds, the geometry's user pointer being its Mesh.
void reject_cutouts(const RTCFilterFunctionNArguments* args);

}  // namespace wangscape
