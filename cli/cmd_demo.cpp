// wangscape demo [--out DIR]: the main job on the embedded default scene (a sunflower field on
// Mount St. Helens, templates/scenes/default.toml), built and rendered with POV-Ray.
#include <cstdio>
#include <memory>

#include "cli/command.h"
#include "cli/scene_commands.h"

namespace wangscape::cli {

void register_demo_command(CLI::App& app, const GlobalOptions& global) {
  auto* sub = app.add_subcommand("demo", "Build and render the default scene (sunflowers on Mount St. Helens)");
  struct Options {
    std::string out = "out/demo";
    bool print_scene = false;
  };
  auto options = std::make_shared<Options>();
  sub->add_option("--out,-o", options->out, "Output folder")->capture_default_str();
  sub->add_flag("--print-scene", options->print_scene,
                "Print the default scene file (data paths made absolute) and exit");
  set_help_footer(sub,
                  "the default scene's folder --out (default out/demo) with its POV-Ray image render.png; "
                  "--print-scene: the scene file on stdout",
                  {"wangscape demo --print-scene > field.toml", "wangscape demo --out demo"});
  sub->callback([options, &global] {
    if (options->print_scene) {
      const std::string text = default_scene_text_for_saving();
      std::fwrite(text.data(), 1, text.size(), stdout);
      return;
    }
    run_build(default_scene_config(), options->out, global, false);
    run_render(options->out, RenderRequest{}, global);  // "wangscape: wrote DIR/render.png (...)"
    if (!global.quiet) std::printf("%s\n", (std::filesystem::path(options->out) / "render.png").string().c_str());
  });
}

}  // namespace wangscape::cli
