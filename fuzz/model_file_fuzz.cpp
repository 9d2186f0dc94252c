// libFuzzer target: a user's model read through Assimp (templates/mesh_io.h, read_model) from
// memory. The first byte picks the format Assimp is told (OBJ, PLY, glTF, GLB, Collada, FBX), the
// rest is the file; images must be held by the bytes (none is looked for on disk). Assimp is large
// and some of its readers slow on big inputs, so inputs are bounded to kMaxModelBytes.
#include <array>
#include <cstddef>
#include <cstdint>
#include <span>

#include "fuzz/fuzz_input.h"
#include "templates/mesh_io.h"

namespace {

constexpr std::array<const char*, 6> kFormats = {".obj", ".ply", ".gltf", ".glb", ".dae", ".fbx"};
constexpr std::size_t kMaxModelBytes = 32768;

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 1 || size > kMaxModelBytes + 1) return 0;
  const char* format = kFormats[data[0] % kFormats.size()];
  const std::span<const std::uint8_t> bytes(data + 1, size - 1);
  return wangscape::fuzz::refusals_are_fine([&] {
    const wangscape::Mesh mesh = wangscape::read_model(bytes, format, "fuzz");
    // What the exporters rely on: every index inside, one normal per position, uvs none or one each.
    for (const auto& triangle : mesh.triangles)
      for (const std::uint32_t v : triangle)
        if (v >= mesh.positions.size()) std::abort();
    for (const std::uint16_t m : mesh.triangle_material)
      if (m >= mesh.materials.size()) std::abort();
    if (mesh.normals.size() != mesh.positions.size()) std::abort();
    if (!mesh.uvs.empty() && mesh.uvs.size() != mesh.positions.size()) std::abort();
    for (const wangscape::Material& material : mesh.materials)
      if (material.base_color_map) (void)material.base_color_map->at(0.5f, 0.5f);
  });
}
