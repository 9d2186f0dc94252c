#include "renders/window/view_program.h"

#include <tbb/global_control.h>

#include <optional>

#include "renders/window/ldi_window.h"

namespace wangscape {

int run_view(const ViewRequest& request) {
  check_view_request(request);
  const bool window = wants_window(request);
  if (window) {
    check_view_script(request.script);  // refused before the scene is assembled
    check_display();
  }
  std::optional<tbb::global_control> threads;
  if (request.threads > 0) threads.emplace(tbb::global_control::max_allowed_parallelism, std::size_t(request.threads));

  // Frames too large for memory fail before the folder loads (the scene's own size: after).
  if (request.width) check_view_memory(request, request.width, request.height, window);
  // A bad path file fails before the folder loads.
  std::optional<ViewPath> path;
  if (!request.path.empty()) path = read_view_path(request.path);
  const auto world = load_view_world(request);
  if (!window) return run_view_frames(world, request, path ? &*path : nullptr);
  const Camera camera = view_camera(*world, request);
  ViewWindowOptions options;
  options.width = request.width ? request.width : kDefaultWindowWidth;
  options.height = request.height ? request.height : kDefaultWindowHeight;
  check_view_memory(request, options.width, options.height, true);
  if (!request.record.empty()) options.record = request.record;
  options.script = request.script;
  options.quiet = request.quiet;
  options.settings = request.settings;
  options.fps = request.fps.value_or(kDefaultViewFps);
  run_view_window(world, camera, options);
  return 0;
}

}  // namespace wangscape
