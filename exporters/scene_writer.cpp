#include "exporters/scene_writer.h"

#include <string>

namespace wangscape {

StreamTotals run_scene_stream(const Scene& scene, std::span<SceneWriter* const> writers,
                              const std::function<void(const InstanceBatch&)>& on_batch) {
  StreamTotals totals;
  totals.per_variant.assign(scene.models.size(), 0);
  if (scene.instances) {
    scene.instances([&](const InstanceBatch& batch) {
      const std::size_t n = batch.size();
      if (batch.y.size() != n || batch.z.size() != n || batch.yaw.size() != n || batch.scale.size() != n ||
          batch.variant.size() != n || batch.tile.size() != n || batch.rank.size() != n)
        throw Error("scene '" + scene.name + "': an instance batch has arrays of different lengths");
      for (const std::uint16_t variant : batch.variant) {
        if (variant >= scene.models.size())
          throw Error("scene '" + scene.name + "': instance variant " + std::to_string(variant) +
                      " but the scene has " + std::to_string(scene.models.size()) + " models");
        ++totals.per_variant[variant];
      }
      totals.instances += n;
      for (SceneWriter* writer : writers) writer->append(batch);
      if (on_batch) on_batch(batch);
    });
  }
  for (SceneWriter* writer : writers) writer->finish(totals);
  return totals;
}

}  // namespace wangscape
