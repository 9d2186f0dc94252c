// wangscape render DIR --engine povray|blender [--width W --height H]: renders a built scene
// folder with the real renderer (POV-Ray: DIR/render.png; Blender: DIR/render_blender.png and
// DIR/scene.blend), keeping its log beside the image.
#include <cstdio>
#include <memory>

#include "cli/command.h"
#include "cli/progress.h"
#include "cli/scene_commands.h"
#include "renders/blender_render.h"
#include "renders/povray_render.h"

namespace wangscape::cli {

namespace {
// Blender: the add-on imports DIR/blender/manifest.json, Cycles renders on the CPU.
void run_blender_render(const std::filesystem::path& dir, const RenderRequest& request, const GlobalOptions& global) {
  BlenderRenderOptions options;
  options.width = request.width;
  options.height = request.height;
  if (chatty(global))
    std::fprintf(stderr, "wangscape: rendering %s with Blender (Cycles, CPU)\n", dir.string().c_str());
  const auto result = render_blender(dir, options);
  if (chatty(global))
    std::fprintf(stderr, "wangscape: wrote %s and %s in %.1f s (log: %s)\n", result.image.string().c_str(),
                 result.blend.string().c_str(), result.seconds, result.log.string().c_str());
}
}  // namespace

void run_render(const std::filesystem::path& dir, const RenderRequest& request, const GlobalOptions& global) {
  if (request.engine == "blender") return run_blender_render(dir, request, global);
  if (request.engine != "povray")
    throw Error("render: engine '" + request.engine + "' is not available in this wangscape (known: povray, blender)");
  PovrayRenderOptions options;
  options.width = request.width;
  options.height = request.height;
  std::unique_ptr<Progress> progress;
  if (chatty(global)) {
    std::fprintf(stderr, "wangscape: rendering %s with POV-Ray\n", dir.string().c_str());
    options.on_progress = [&](std::uint64_t done, std::uint64_t total) {
      if (total == 0) return;
      if (!progress) progress = std::make_unique<Progress>("pixels", total, global.quiet);
      progress->update(done);
    };
  }
  const auto result = render_povray(dir, options);
  progress.reset();
  if (chatty(global))
    std::fprintf(stderr, "wangscape: wrote %s in %.1f s (log: %s)\n", result.image.string().c_str(), result.seconds,
                 result.log.string().c_str());
}

void register_render_command(CLI::App& app, const GlobalOptions& global) {
  auto* sub = app.add_subcommand("render", "Render a scene folder written by `wangscape build` into DIR/render.png");
  auto request = std::make_shared<RenderRequest>();
  auto dir = std::make_shared<std::string>();
  sub->add_option("dir", *dir, "Scene folder")->required();
  sub->add_option("--engine", request->engine, "Renderer: povray or blender")->capture_default_str();
  sub->add_option("--width", request->width, "Image width in pixels (default: the scene's)")
      ->check(CLI::Range(1, 32768));
  sub->add_option("--height", request->height, "Image height in pixels (default: the scene's)")
      ->check(CLI::Range(1, 32768));
  sub->callback([dir, request, &global] { run_render(*dir, *request, global); });
}

}  // namespace wangscape::cli
