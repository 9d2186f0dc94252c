// wangscape render DIR --engine povray|blender|embree [--width W --height H]: renders a built
// scene folder with the real renderer (POV-Ray: DIR/render.png; Blender: DIR/render_blender.png
// and DIR/scene.blend), keeping its log beside the image; or with the Embree reference renderer
// (DIR/render_embree.png, or --out, with --spp samples per pixel).
#include <cstdio>
#include <memory>

#include "cli/command.h"
#include "cli/progress.h"
#include "cli/scene_commands.h"
#include "renders/render_folder.h"
#include "renders/trace/embree_reference.h"

namespace wangscape::cli {

void run_render(const std::filesystem::path& dir, const RenderRequest& request, const GlobalOptions& global) {
  const WriteReport report(global.quiet);
  FolderRenderRequest folder{
      parse_render_engine(request.engine), request.width, request.height, request.out, request.spp, {}};
  std::unique_ptr<Progress> progress;
  if (chatty(global)) {
    std::fprintf(stderr, "wangscape: rendering %s with %s\n", dir.string().c_str(), request.engine.c_str());
    folder.on_progress = [&](std::uint64_t done, std::uint64_t total) {
      if (total == 0) return;
      if (!progress) progress = std::make_unique<Progress>("pixels", total, global.quiet);
      progress->update(done);
    };
  }
  const auto result = render_scene_folder(dir, folder);
  progress.reset();
  std::vector<std::filesystem::path> written{result.image};
  if (!result.blend.empty()) written.push_back(result.blend);
  report.wrote(written,
               request.engine + (result.log.empty() ? "; " + result.summary : "; log " + shown_path(result.log)));
}

void register_render_command(CLI::App& app, const GlobalOptions& global) {
  auto* sub = app.add_subcommand("render", "Render a scene folder written by `wangscape build` into DIR/render.png");
  auto request = std::make_shared<RenderRequest>();
  auto dir = std::make_shared<std::string>();
  sub->add_option("dir", *dir, "Scene folder")->required();
  sub->add_option("--engine", request->engine, "Renderer: povray, blender or embree")->capture_default_str();
  sub->add_option("--width", request->width, "Image width in pixels (default: the scene's; alone, the height follows)")
      ->check(CLI::Range(1, 32768));
  sub->add_option("--height", request->height,
                  "Image height in pixels (default: the scene's; alone, the width follows)")
      ->check(CLI::Range(1, 32768));
  sub->add_option("--out", request->out,
                  "The image to write (default: DIR/render_embree.png; povray and blender: a copy of the folder's)")
      ->check(output_file_path());
  sub->add_option("--spp", request->spp, "embree: samples per pixel (default: the scene's antialias squared)")
      ->check(CLI::Range(1, kMaxReferenceSamples));
  set_help_footer(sub,
                  "into the folder: render.png and povray.log (povray); scene.blend, render_blender.png and "
                  "blender.log (blender), with --out a copy there; render_embree.png or --out (embree)",
                  {"wangscape build templates/scenes/small.toml --out small", "wangscape render small",
                   "wangscape render small --engine embree --spp 4 --out small/embree.png"});
  sub->callback([dir, request, &global] { run_render(*dir, *request, global); });
}

}  // namespace wangscape::cli
