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

void run_build(const SceneConfig& config, const std::filesystem::path& out_dir, const GlobalOptions& global) {
  SceneFolderObserver observer;
  std::unique_ptr<Progress> progress;
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
  if (chatty(global))
    std::fprintf(stderr, "wangscape: wrote %s (%llu flowers, %.1f MB of POV-Ray files, %.1f s)\n",
                 out_dir.string().c_str(), static_cast<unsigned long long>(summary.instances),
                 double(summary.povray_bytes) / 1e6, summary.seconds);
  if (const auto& f = summary.field; f && !global.quiet)
    std::fprintf(stderr,
                 "wangscape: tiles: %llu visible, %llu placed, %llu culled; flowers: %llu models, %llu proxies\n",
                 (unsigned long long)f->visible_tiles, (unsigned long long)f->placed_tiles,
                 (unsigned long long)f->culled_tiles, (unsigned long long)f->models, (unsigned long long)f->proxies);
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
                  "tiles.json, scene.cache (what render and view read back); blender/, scene.glb and tiles.ldi when "
                  "the scene's [exports] ask for them. One line on stderr says what was written",
                  {"wangscape build templates/scenes/small.toml --out small",
                   "wangscape demo --print-scene > field.toml", "wangscape build field.toml --out field"});
  sub->callback([options, &global] { run_build(load_scene_config(options->scene), options->out, global); });
}

}  // namespace wangscape::cli
