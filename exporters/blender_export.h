// Blender export: a folder holding manifest.json and little-endian binary arrays (terrain,
// one mesh per model variant, instances as separate arrays) that the Wangscape add-on
// (templates/blender_addon) imports with numpy. The layout: docs/blender-format.md.
#pragma once

#include <cstdint>
#include <filesystem>
#include <memory>
#include <string_view>

#include "exporters/scene_writer.h"
#include "scene/scene.h"

namespace wangscape {

class EncodedGround;  // export_support.h

inline constexpr std::string_view kBlenderFormatName = "wangscape-blender";
inline constexpr int kBlenderFormatVersion = 1;

struct BlenderExportOptions {
  bool write_addon_zip = true;  // wangscape_import.zip beside the manifest
  int cycles_samples = 0;       // 0: 16 x max(1, scene.render.antialias_samples)
  // The build's encoded ground.png (export_support.h); null: this writer encodes its own.
  std::shared_ptr<const EncodedGround> ground;
};

struct BlenderExportSummary {
  std::filesystem::path manifest;  // <folder>/manifest.json
  std::uint64_t instance_count = 0;
  std::uint64_t bytes_written = 0;  // arrays + manifest
};

// The Blender export as a streaming writer into `folder` (created if missing): meshes when it is
// made, instance arrays batch by batch (never held at once), the manifest at finish(). Every file
// is written atomically and the manifest last, so a manifest present means a complete export.
// Throws Error naming the file or value at fault.
class BlenderWriter final : public SceneWriter {
 public:
  BlenderWriter(const Scene& scene, const std::filesystem::path& folder, const BlenderExportOptions& options = {});
  ~BlenderWriter() override;
  void append(const InstanceBatch& batch) override;
  void finish(const StreamTotals& totals) override;
  const BlenderExportSummary& summary() const;  // complete after finish()

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// A BlenderWriter over the scene's own stream.
BlenderExportSummary export_blender(const Scene& scene, const std::filesystem::path& folder,
                                    const BlenderExportOptions& options = {});

// The Cycles sample count the manifest records for `render`.
int blender_cycles_samples(const RenderSettings& render, const BlenderExportOptions& options = {});

}  // namespace wangscape
