// The frame every wangscape subcommand plugs into: options shared by all subcommands,
// and the registration functions each cli/cmd_*.cpp file provides.
#pragma once

#include <CLI/CLI.hpp>

#include <cstdint>
#include <string>

namespace wangscape::cli {

// Options every subcommand understands (set on the top-level app, so they go anywhere
// on the command line).
struct GlobalOptions {
  bool quiet = false;  // no progress, no chatter on stderr
};

// Sets the pipeline's Blender and glTF exporter hooks (cli/blender_exports.cpp).
void register_blender_gltf_exporters();

// Registration: each subcommand file adds its CLI11 subcommand and sets a callback that
// does the work. Errors are thrown (std::exception); main() turns them into exit code 1.
void register_tileset_command(CLI::App& app, const GlobalOptions& global);
void register_tiling_command(CLI::App& app, const GlobalOptions& global);
void register_build_command(CLI::App& app, const GlobalOptions& global);
void register_render_command(CLI::App& app, const GlobalOptions& global);
void register_demo_command(CLI::App& app, const GlobalOptions& global);
void register_terrain_command(CLI::App& app, const GlobalOptions& global);
void register_scatter_command(CLI::App& app, const GlobalOptions& global);

}  // namespace wangscape::cli
