// wangscape build SCENE.toml --out DIR: the whole pipeline from a scene file.
#include <unistd.h>

#include <cstdio>
#include <memory>

#include "cli/command.h"
#include "cli/progress.h"
#include "cli/scene_commands.h"
#include "renders/scene_build.h"

namespace wangscape::cli {

bool chatty(const GlobalOptions& global) { return !global.quiet && ::isatty(STDERR_FILENO); }

void run_build(const SceneConfig& config, const std::filesystem::path& out_dir, const GlobalOptions& global,
               bool say_written) {
  const WriteReport report(global.quiet || !say_written);
  SceneFolderObserver observer;
  std::unique_ptr<Progress> progress;
  if (!global.quiet)
    observer.warning = [&](const std::string& message) {
      progress.reset();
      std::fprintf(stderr, "wangscape: warning: %s\n", message.c_str());
    };
  if (chatty(global)) {
    observer.stage = [&](const std::string& message) {
      progress.reset();
      std::fprintf(stderr, "wangscape: %s\n", message.c_str());
    };
    constexpr std::uint64_t kSteps = 1000;  // the field's rows, as a fraction
    observer.placing = [&](double fraction) {
      if (!progress) progress = std::make_unique<Progress>("field", kSteps, global.quiet);
      progress->update(static_cast<std::uint64_t>(fraction * kSteps));
    };
  }
  std::unique_ptr<Progress> ldi_progress;
  const auto summary = build_scene(config, out_dir, {observer, ldi_terminal_observer(global, ldi_progress)});
  progress.reset();
  ldi_progress.reset();
  // One line: the folder, its flowers (with camera-aware export: the tiles and how the flowers were
  // drawn), its size and the time.
  std::string details = std::to_string(summary.instances) + " flowers";
  if (const auto& f = summary.field)
    details = "tiles: " + std::to_string(f->visible_tiles) + " visible, " + std::to_string(f->placed_tiles) +
              " placed, " + std::to_string(f->culled_tiles) + " culled; flowers: " + std::to_string(f->models) +
              " models, " + std::to_string(f->proxies) + " proxies";
  report.wrote(out_dir, details);
}

void register_build_command(CLI::App& app, const GlobalOptions& global) {
  auto* sub = app.add_subcommand("build", "Build a scene folder (POV-Ray and other exports) from a scene file");
  struct Options {
    std::string scene;
    std::string out;
  };
  auto options = std::make_shared<Options>();
  sub->add_option("scene", options->scene, "Scene file (TOML, see docs/scene-file.md)")->required();
  sub->add_option("--out,-o", options->out, "Output folder")->required();
  set_help_footer(sub,
                  "the folder --out, replaced whole: scene.pov, scene.ini and their includes for POV-Ray, scene.toml, "
                  "tiles.json, scene.cache (what render and view read back); blender/, scene.glb, tiles.ldi with "
                  "steep.ldi and sky.bin, and "
                  "plants.gpkg with cover.tif (for a GIS) when the scene's [exports] ask for them. One line on stderr "
                  "says what was written",
                  {"wangscape build templates/scenes/small.toml --out small",
                   "wangscape demo --print-scene > field.toml", "wangscape build field.toml --out field"});
  sub->callback([options, &global] { run_build(load_scene_config(options->scene), options->out, global); });
}

}  // namespace wangscape::cli
