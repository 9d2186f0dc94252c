// wangscape build SCENE.toml --out DIR: the whole pipeline from a scene file.
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "cli/command.h"
#include "cli/progress.h"
#include "cli/scene_commands.h"
#include "core/number_text.h"
#include "renders/scene_build.h"

namespace wangscape::cli {

namespace {

// "stand-ins: tulip_0 proxy 120 of 1208 triangles, error 0.0042 m; ...": each of the first
// kShown, then how many more and their largest error.
std::string stand_ins_text(const std::vector<StandInFigures>& stand_ins) {
  constexpr std::size_t kShown = 8;
  std::string text;
  double rest_error = 0;
  for (std::size_t i = 0; i < stand_ins.size(); ++i) {
    const StandInFigures& s = stand_ins[i];
    if (i >= kShown) {
      rest_error = std::max(rest_error, s.error);
      continue;
    }
    text += (text.empty() ? "stand-ins: " : "; ") + s.name + " " + std::to_string(s.triangles) + " of " +
            std::to_string(s.model_triangles) + " triangles, error " + significant_text(s.error, 3) + " m";
  }
  if (stand_ins.size() > kShown)
    text += "; " + std::to_string(stand_ins.size() - kShown) + " more, error at most " +
            significant_text(rest_error, 3) + " m";
  return text;
}

}  // namespace

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
  if (!summary.stand_ins.empty()) details += "; " + stand_ins_text(summary.stand_ins);
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
                  "steep.ldi, sky.bin and ground_light.bin, and "
                  "plants.gpkg with cover.tif (for a GIS) when the scene's [exports] ask for them. One line on stderr "
                  "says what was written",
                  {"wangscape build templates/scenes/small.toml --out small",
                   "wangscape demo --print-scene > field.toml", "wangscape build field.toml --out field"});
  sub->callback([options, &global] { run_build(load_scene_config(options->scene), options->out, global); });
}

}  // namespace wangscape::cli
