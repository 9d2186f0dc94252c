#include "renders/trace/terrain_shadows.h"

#include <embree3/rtcore.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <limits>

#include "renders/trace/embree_device.h"

namespace wangscape {

std::vector<float> terrain_sun_visibility(const Mesh& mesh, const std::array<float, 3>& sun) {
  std::vector<float> visible(mesh.positions.size(), sun[2] > 0 ? 1.0f : 0.0f);
  if (sun[2] <= 0 || mesh.triangles.empty()) return visible;
  EmbreeDevice device;
  EmbreeScene scene(device.get());
  RTCGeometry geometry = triangle_geometry(device.get(), mesh.positions, mesh.triangles);
  rtcAttachGeometry(scene.get(), geometry);
  rtcReleaseGeometry(geometry);
  rtcCommitScene(scene.get());
  device.check("building the terrain's shadow scene");
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, visible.size(), 2048), [&](const auto& r) {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    for (std::size_t v = r.begin(); v != r.end(); ++v) {
      const auto& p = mesh.positions[v];
      RTCRay ray{};
      ray.org_x = p[0];
      ray.org_y = p[1];
      ray.org_z = p[2] + 0.05f;  // above the vertex's own triangles
      ray.dir_x = sun[0];
      ray.dir_y = sun[1];
      ray.dir_z = sun[2];
      ray.tnear = 0.01f;
      ray.tfar = std::numeric_limits<float>::infinity();
      ray.mask = ~0u;
      rtcOccluded1(scene.get(), &context, &ray);
      if (ray.tfar < 0) visible[v] = 0;  // Embree's mark of an occluded ray
    }
  });
  device.check("tracing the terrain's shadows");
  return visible;
}

}  // namespace wangscape
