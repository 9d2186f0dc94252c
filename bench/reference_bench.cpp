// The Embree reference renderer on the default scene (Mount St. Helens, its camera, 640 x 360 and
// other sizes), the Scene assembled once outside the timing:
//  - BM_ReferenceStill/W/H/SPP: one whole render_reference call (placement of every flower, the
//    Embree build, tracing with sun shadows and the [ldi] section's 8 sky rays per hit); counters
//    split it into build and trace seconds and give the rays per second.
// The end-to-end comparison with POV-Ray from a scene folder is bench/embree_vs_povray_bench.sh.
#include <benchmark/benchmark.h>

#include <algorithm>

#include "renders/ldi/ldi_scene.h"
#include "renders/trace/embree_reference.h"
#include "scene/scene.h"
#include "scene/scene_file.h"

namespace {

using namespace wangscape;

const Scene& default_scene() {
  static const Scene scene = make_scene(default_scene_config());
  return scene;
}

void BM_ReferenceStill(benchmark::State& state) {
  const Scene& scene = default_scene();
  ReferenceOptions o;
  o.width = int(state.range(0));
  o.height = int(state.range(1));
  o.samples_per_pixel = int(state.range(2));
  o.shading = ldi_options(default_scene_config()).shading;
  ReferenceStats total;
  for (auto _ : state) {
    const ReferenceStats s = render_reference(scene, o).stats;
    total.build_seconds += s.build_seconds;
    total.render_seconds += s.render_seconds;
    total.primary_rays += s.primary_rays;
    total.secondary_rays += s.secondary_rays;
    total.instances = s.instances;
  }
  const double n = double(state.iterations());
  state.counters["instances"] = double(total.instances);
  state.counters["build_s"] = total.build_seconds / n;
  state.counters["trace_s"] = total.render_seconds / n;
  state.counters["Mrays_per_s"] =
      double(total.primary_rays + total.secondary_rays) / 1e6 / std::max(1e-9, total.render_seconds);
}
BENCHMARK(BM_ReferenceStill)
    ->Args({640, 360, 4})
    ->Args({640, 360, 1})
    ->Args({1280, 720, 1})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->Iterations(1);

}  // namespace

BENCHMARK_MAIN();
