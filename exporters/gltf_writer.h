// glTF 2.0 binary (.glb) for DCC tools and viewers: the terrain, one mesh per model variant
// with pbrMetallicRoughness materials, and the flowers through EXT_mesh_gpu_instancing (one
// node per variant; listed in extensionsUsed, never required, so readers without it still
// load the file and show one flower per variant). glTF is y-up: ENU (x east, y north, z up)
// becomes glTF (x, y, z) = (east, up, -north). The georeference goes in the scene's extras.
#pragma once

#include <cstdint>
#include <filesystem>

#include "exporters/scene.h"

namespace wangscape {

enum class GltfInstancing {
  gpu_instancing,     // EXT_mesh_gpu_instancing: one node per variant, instances in accessors
  node_per_instance,  // one node per flower (for tools without the extension; JSON grows with the count)
};

struct GltfOptions {
  GltfInstancing instancing = GltfInstancing::gpu_instancing;
};

struct GltfSummary {
  std::filesystem::path file;
  std::uint64_t instance_count = 0;
  std::uint64_t bytes = 0;  // size of the .glb
};

// Writes `path` (.glb) atomically. With gpu_instancing the instances are streamed once into
// per-variant temporary files beside `path` (never all in memory) and copied into the
// binary chunk. Throws Error naming the file or value at fault (e.g. more than 4 GiB).
GltfSummary write_gltf(const Scene& scene, const std::filesystem::path& path, const GltfOptions& options = {});

}  // namespace wangscape
