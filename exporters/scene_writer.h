// Writers are streaming appenders: each is made with the scene and where to write, is handed
// every batch of the scene's one placement pass, and is finished once with the totals of the
// stream. run_scene_stream runs the stream once and fans every batch out to every writer, so a
// scene folder with POV-Ray, Blender and glTF places its flowers once.
#pragma once

#include <cstdint>
#include <functional>
#include <span>
#include <vector>

#include "scene/scene.h"

namespace wangscape {

// What the stream produced, known when it closes.
struct StreamTotals {
  std::uint64_t instances = 0;
  std::vector<std::uint64_t> per_variant;  // one count per model variant
};

class SceneWriter {
 public:
  virtual ~SceneWriter() = default;
  // One batch of instances (checked: equal array sizes, variants below the model count).
  virtual void append(const InstanceBatch& batch) = 0;
  // The stream has closed: write what depends on the totals and publish every file. Until
  // then nothing is visible under the final names.
  virtual void finish(const StreamTotals& totals) = 0;
};

// Runs scene.instances once (an empty stream gives no instances), checks each batch, hands it
// to every writer in turn, then finishes every writer with the totals. `on_batch` (optional)
// sees each batch after the writers, e.g. for progress. Throws Error naming the scene.
StreamTotals run_scene_stream(const Scene& scene, std::span<SceneWriter* const> writers,
                              const std::function<void(const InstanceBatch&)>& on_batch = {});

// One writer alone (the single-format entry points and their tests).
inline StreamTotals run_scene_stream(const Scene& scene, SceneWriter& writer) {
  SceneWriter* writers[] = {&writer};
  return run_scene_stream(scene, writers);
}

}  // namespace wangscape
