#include "renders/trace/embree_device.h"

#include <cstring>

#include "core/error.h"

namespace wangscape {

EmbreeDevice::EmbreeDevice() {
  device_ = rtcNewDevice(nullptr);
  if (!device_)
    throw Error("Embree: cannot create a device (error " + std::to_string(int(rtcGetDeviceError(nullptr))) + ")");
  rtcSetDeviceErrorFunction(device_, &EmbreeDevice::on_error, this);
}

EmbreeDevice::~EmbreeDevice() { rtcReleaseDevice(device_); }

void EmbreeDevice::check(std::string_view doing) {
  std::lock_guard lock(mutex_);
  if (!error_.empty()) throw Error("Embree error while " + std::string(doing) + ": " + error_);
}

void EmbreeDevice::on_error(void* user, RTCError code, const char* message) {
  auto* self = static_cast<EmbreeDevice*>(user);
  std::lock_guard lock(self->mutex_);
  if (self->error_.empty())
    self->error_ = std::string(message ? message : "?") + " (code " + std::to_string(int(code)) + ")";
}

RTCGeometry triangle_geometry(RTCDevice device, std::span<const std::array<float, 3>> positions,
                              std::span<const std::array<std::uint32_t, 3>> triangles, RTCFilterFunctionN filter) {
  RTCGeometry g = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
  auto* v = static_cast<float*>(
      rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), positions.size()));
  auto* t = static_cast<std::uint32_t*>(rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                                                3 * sizeof(std::uint32_t), triangles.size()));
  if (v) std::memcpy(v, positions.data(), positions.size_bytes());
  if (t) std::memcpy(t, triangles.data(), triangles.size_bytes());
  if (filter) rtcSetGeometryIntersectFilterFunction(g, filter);
  rtcCommitGeometry(g);
  return g;
}

std::vector<EmbreeScene> model_scenes(EmbreeDevice& device, std::span<const Mesh> models, RTCFilterFunctionN filter) {
  std::vector<EmbreeScene> scenes;
  scenes.reserve(models.size());
  for (const Mesh& m : models) {
    EmbreeScene scene(device.get());
    // Single-level instancing: the prototypes hold triangles only.
    rtcSetSceneBuildQuality(scene.get(), RTC_BUILD_QUALITY_HIGH);
    if (!m.triangles.empty()) {
      RTCGeometry g = triangle_geometry(device.get(), m.positions, m.triangles, filter);
      add_cutouts(g, m, filter == nullptr);
      rtcAttachGeometryByID(scene.get(), g, 0);
      rtcReleaseGeometry(g);
    }
    rtcCommitScene(scene.get());
    scenes.push_back(std::move(scene));
  }
  device.check("building the model scenes");
  return scenes;
}

void add_cutouts(RTCGeometry geometry, const Mesh& mesh, bool intersection) {
  if (!has_cutouts(mesh)) return;
  rtcSetGeometryUserData(geometry, const_cast<Mesh*>(&mesh));  // Embree's API is not const
  rtcSetGeometryOccludedFilterFunction(geometry, &reject_cutouts);
  if (intersection) rtcSetGeometryIntersectFilterFunction(geometry, &reject_cutouts);
  rtcCommitGeometry(geometry);
}

bool has_cutouts(const Mesh& mesh) {
  if (mesh.uvs.size() != mesh.positions.size()) return false;
  for (const Material& material : mesh.materials)
    if (material.alpha_cutoff > 0 && material.base_color_map) return true;
  return false;
}

bool in_cutout(const Mesh& mesh, unsigned prim, float u, float v) {
  if (prim >= mesh.triangle_material.size() || mesh.uvs.size() != mesh.positions.size()) return false;
  const std::uint16_t slot = mesh.triangle_material[prim];
  if (slot >= mesh.materials.size()) return false;
  const Material& material = mesh.materials[slot];
  if (!(material.alpha_cutoff > 0) || !material.base_color_map) return false;
  const auto& tri = mesh.triangles[prim];
  const float w = 1 - u - v;
  const float s = w * mesh.uvs[tri[0]][0] + u * mesh.uvs[tri[1]][0] + v * mesh.uvs[tri[2]][0];
  const float t = w * mesh.uvs[tri[0]][1] + u * mesh.uvs[tri[1]][1] + v * mesh.uvs[tri[2]][1];
  return material.base_color_map->at(s, t)[3] < material.alpha_cutoff;
}

void reject_cutouts(const RTCFilterFunctionNArguments* args) {
  const auto* mesh = static_cast<const Mesh*>(args->geometryUserPtr);
  if (mesh == nullptr) return;
  for (unsigned i = 0; i < args->N; ++i) {
    if (args->valid[i] == 0) continue;
    if (in_cutout(*mesh, RTCHitN_primID(args->hit, args->N, i), RTCHitN_u(args->hit, args->N, i),
                  RTCHitN_v(args->hit, args->N, i)))
      args->valid[i] = 0;
  }
}

}  // namespace wangscape
