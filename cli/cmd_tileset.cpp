#include "cli/command.h"
#include "generator/tileset.h"

namespace wangscape::cli {
void register_tileset_command(CLI::App& app, const GlobalOptions&) {
  auto* sub = app.add_subcommand("tileset", "Print, draw or fill a Wang tile set");
  sub->callback([] {});
}
}  // namespace wangscape::cli
