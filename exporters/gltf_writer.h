// glTF 2.0 binary (.glb) for DCC tools and viewers: the terrain, one mesh per model variant
// with pbrMetallicRoughness materials, and the flowers through EXT_mesh_gpu_instancing (one
// node per variant; listed in extensionsUsed, never required, so readers without it still
// load the file and show one flower per variant). glTF is y-up: ENU (x east, y north, z up)
// becomes glTF (x, y, z) = (east, up, -north). The georeference goes in the scene's extras.
// With a [ground] look the terrain gets TEXCOORD_0 and its material the baked ground
// (Scene::ground_texture) as baseColorTexture, a PNG embedded in the binary chunk.
#pragma once

#include <cstdint>
#include <filesystem>
#include <memory>

#include "exporters/scene_writer.h"
#include "scene/scene.h"

namespace wangscape {

class EncodedGround;  // export_support.h

enum class GltfInstancing {
  gpu_instancing,     // EXT_mesh_gpu_instancing: one node per variant, instances in accessors
  node_per_instance,  // one node per flower (for tools without the extension; JSON grows with the count)
};

struct GltfOptions {
  GltfInstancing instancing = GltfInstancing::gpu_instancing;
  // The build's encoded ground.png (export_support.h); null: this writer encodes its own.
  std::shared_ptr<const EncodedGround> ground;
};

struct GltfSummary {
  std::filesystem::path file;
  std::uint64_t instance_count = 0;
  std::uint64_t bytes = 0;  // size of the .glb
};

// The .glb as a streaming writer: with gpu_instancing the instances go into per-variant
// temporary files beside `path` (never all in memory) and are copied into the binary chunk at
// finish(), which writes `path` atomically. Throws Error naming the file or value at fault
// (e.g. more than 4 GiB).
class GltfWriter final : public SceneWriter {
 public:
  GltfWriter(const Scene& scene, const std::filesystem::path& path, const GltfOptions& options = {});
  ~GltfWriter() override;
  void append(const InstanceBatch& batch) override;
  void finish(const StreamTotals& totals) override;
  const GltfSummary& summary() const;  // complete after finish()

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// A GltfWriter over the scene's own stream.
GltfSummary write_gltf(const Scene& scene, const std::filesystem::path& path, const GltfOptions& options = {});

}  // namespace wangscape
