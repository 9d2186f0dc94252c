// Blender export: a folder holding manifest.json and little-endian binary arrays (terrain,
// one mesh per model variant, instances as separate arrays) that the Wangscape add-on
// (templates/blender_addon) imports with numpy. The layout: docs/blender-format.md.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string_view>

#include "exporters/scene.h"

namespace wangscape {

inline constexpr std::string_view kBlenderFormatName = "wangscape-blender";
inline constexpr int kBlenderFormatVersion = 1;

struct BlenderExportOptions {
  bool write_addon_zip = true;  // wangscape_import.zip beside the manifest
  int cycles_samples = 0;       // 0: 16 x max(1, scene.render.antialias_samples)
};

struct BlenderExportSummary {
  std::filesystem::path manifest;  // <folder>/manifest.json
  std::uint64_t instance_count = 0;
  std::uint64_t bytes_written = 0;  // arrays + manifest
};

// Writes the scene into `folder` (created if missing). Instances are streamed batch by
// batch from scene.instances, never held at once. Every file is written atomically and the
// manifest last, so a manifest present means a complete export. Throws Error naming
// the file or value at fault (e.g. the stream's count differs from scene.instance_count).
BlenderExportSummary export_blender(const Scene& scene, const std::filesystem::path& folder,
                                    const BlenderExportOptions& options = {});

// The Cycles sample count the manifest records for `render`.
int blender_cycles_samples(const RenderSettings& render, const BlenderExportOptions& options = {});

}  // namespace wangscape
