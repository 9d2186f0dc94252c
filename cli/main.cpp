// wangscape: argv -> subcommand options -> one function per subcommand. Exit codes:
// 0 success, 1 runtime error (one line naming the file or value at fault), 2 usage error.
#include <clocale>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <new>
#include <string>

#include "cli/command.h"
#include "core/json_text.h"
#include "core/printable.h"
#include "core/run_cleanup.h"

int main(int argc, char** argv) {
  wangscape::install_run_cleanup();  // before any thread starts: SIGINT/SIGTERM remove this run's temporaries
  // Numbers we write for POV-Ray, Python and JSON must not depend on the user's locale.
  std::setlocale(LC_ALL, "C");

  CLI::App app{"Wangscape: Wang-tiled vegetation over real terrain, for POV-Ray, Blender and glTF", "wangscape"};
  app.set_version_flag("--version", std::string("wangscape ") + WANGSCAPE_VERSION);
  app.require_subcommand(1);
  app.fallthrough();

  wangscape::cli::GlobalOptions global;
  app.add_flag("-q,--quiet", global.quiet, "No progress bar or messages on stderr");

  wangscape::cli::register_tileset_command(app, global);
  wangscape::cli::register_tiling_command(app, global);
  wangscape::cli::register_build_command(app, global);
  wangscape::cli::register_render_command(app, global);
  wangscape::cli::register_demo_command(app, global);
  wangscape::cli::register_terrain_command(app, global);
  wangscape::cli::register_scatter_command(app, global);
  wangscape::cli::register_tiles_commands(app, global);
  wangscape::cli::register_batch_command(app, global);
  wangscape::cli::register_ldi_command(app, global);
  wangscape::cli::register_view_command(app, global);

  wangscape::cli::set_help_footer(&app, "see each command's --help; every command says what it wrote on stderr",
                                  {"wangscape build templates/scenes/small.toml --out small", "wangscape render small",
                                   "wangscape terrain height small 0,6570 --above 1.7"});

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? 0 : 2;
  } catch (const std::bad_alloc&) {
    // Sizes are estimated and refused before large allocations; this is the last line of defence.
    std::fprintf(stderr, "wangscape: error: out of memory: the request needs more memory than this machine has\n");
    return 1;
  } catch (const std::filesystem::filesystem_error& e) {
    // The last line of defence for a folder operation no reader checked: "PATH: cannot create
    // directories: Not a directory" instead of the library's "filesystem error: ... [PATH]".
    std::string what = e.what();
    if (what.starts_with("filesystem error: ")) what.erase(0, 18);
    if (const auto bracket = what.find(" ["); bracket != std::string::npos) what.erase(bracket);
    std::fprintf(stderr, "wangscape: error: %s: %s\n", wangscape::printable(e.path1().string(), true).c_str(),
                 wangscape::printable(what, true).c_str());
    return 1;
  } catch (const std::exception& e) {
    // Messages quote user text (names, paths): no control character reaches the terminal; a
    // nlohmann-json exception nothing caught loses its "[json.exception.NAME] " id.
    std::fprintf(stderr, "wangscape: error: %s\n", wangscape::printable(wangscape::json_error_text(e), true).c_str());
    return 1;
  }
  return 0;
}
