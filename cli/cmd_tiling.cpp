#include "cli/command.h"

namespace wangscape::cli {
void register_tiling_command(CLI::App& app, const GlobalOptions&) {
  auto* sub = app.add_subcommand("tiling", "Tile a window of the plane with a tile set");
  sub->callback([] {});
}
}  // namespace wangscape::cli
