// wangscape demo [--scene NAME] [--out DIR]: the main job on the embedded default scene (a
// sunflower field on Mount St. Helens, templates/scenes/default.toml) or on a shipped scene
// (templates/scenes/NAME.toml, e.g. the meadow), built and rendered with POV-Ray.
#include <cstdio>
#include <memory>

#include "cli/command.h"
#include "cli/scene_commands.h"
#include "core/text_file.h"
#include "scene/scene_file.h"

namespace wangscape::cli {

void register_demo_command(CLI::App& app, const GlobalOptions& global) {
  auto* sub = app.add_subcommand("demo", "Build and render the default scene (sunflowers on Mount St. Helens)");
  struct Options {
    std::string out = "out/demo";
    std::string scene = "default";
    bool print_scene = false;
  };
  auto options = std::make_shared<Options>();
  sub->add_option("--out,-o", options->out, "Output folder")->capture_default_str();
  sub->add_option("--scene", options->scene,
                  "The scene: default (embedded), or a shipped scene of templates/scenes: meadow (Shade 2002's meadow: "
                  "grass, dandelions and sunflowers following the terrain), small, whole-dem")
      ->capture_default_str();
  sub->add_flag("--print-scene", options->print_scene, "Print the scene file (data paths made absolute) and exit");
  set_help_footer(sub,
                  "the scene's folder --out (default out/demo) with its POV-Ray image render.png; "
                  "--print-scene: the scene file on stdout",
                  {"wangscape demo --print-scene > field.toml", "wangscape demo --out demo",
                   "wangscape demo --scene meadow --out meadow"});
  sub->callback([options, &global] {
    const bool shipped = options->scene != "default";
    const auto shipped_file = data_root() / "templates/scenes" / (options->scene + ".toml");
    if (shipped &&
        (options->scene.find_first_of("/.") != std::string::npos || !std::filesystem::is_regular_file(shipped_file)))
      throw Error("--scene '" + options->scene + "': expected default, meadow, small or whole-dem (no " +
                  shipped_file.string() + ")");
    if (options->print_scene) {
      std::string text = default_scene_text_for_saving();
      if (shipped) {
        // A shipped scene names its data relative to templates/scenes: made absolute to be saved anywhere.
        text = read_text_file(shipped_file, kMaxSceneFileBytes, "scene file");
        const std::string relative = "= \"../../data/", absolute = "= \"" + (data_root() / "data").string() + "/";
        for (auto at = text.find(relative); at != std::string::npos; at = text.find(relative, at + absolute.size()))
          text.replace(at, relative.size(), absolute);
      }
      std::fwrite(text.data(), 1, text.size(), stdout);
      return;
    }
    run_build(shipped ? load_scene_config(shipped_file) : default_scene_config(), options->out, global, false);
    run_render(options->out, RenderRequest{}, global);  // "wangscape: wrote DIR/render.png (...)"
    if (!global.quiet) std::printf("%s\n", (std::filesystem::path(options->out) / "render.png").string().c_str());
  });
}

}  // namespace wangscape::cli
