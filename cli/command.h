// The frame every wangscape subcommand plugs into: options shared by all subcommands,
// and the registration functions each cli/cmd_*.cpp file provides.
#pragma once

#include <CLI/CLI.hpp>

#include <array>
#include <cmath>
#include <cstdint>
#include <exception>
#include <filesystem>
#include <initializer_list>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "core/printable.h"
#include "scene/scene_ground.h"

namespace wangscape::cli {

// Options every subcommand understands (set on the top-level app, so they go anywhere
// on the command line).
struct GlobalOptions {
  bool quiet = false;  // no progress, no chatter on stderr
};

// True when progress and messages go to stderr: it is a terminal and --quiet is off.
bool chatty(const GlobalOptions& global);

// A CLI11 check that a number is finite (CLI11 itself reads "nan" and "inf").
inline CLI::Validator finite_number() {
  return CLI::Validator(
      [](std::string& text) {
        try {
          std::size_t used = 0;
          const double value = std::stod(text, &used);
          if (used == text.size() && std::isfinite(value)) return std::string();
        } catch (const std::exception&) {
        }
        return "'" + text + "' is not a finite number";
      },
      "NUMBER");
}

// A CLI11 check that a file or folder name is not empty (`--out ""` wrote nothing and said
// nothing, or wrote into the current folder): a usage error, exit 2.
inline CLI::Validator non_empty_path() {
  return CLI::Validator(
      [](std::string& text) { return text.empty() ? std::string("is empty; name a file or folder") : std::string(); },
      "PATH");
}

// A CLI11 check that a file to write is named and is not a folder: the finished file could not
// replace the folder, so the run would do all its work and fail only when publishing it ("rename
// failed"). A usage error, exit 2.
inline CLI::Validator output_file_path() {
  return CLI::Validator(
      [](std::string& text) {
        if (text.empty()) return std::string("is empty; name a file or folder");
        std::error_code ec;
        if (std::filesystem::is_directory(text, ec))
          return "'" + printable(text) + "' is a folder; name a file to write";
        return std::string();
      },
      "FILE");
}

// A CLI11 check for seeds: a whole number 0 .. 2^64 - 1 (CLI11 alone reads -1 as 2^64 - 1 and
// saturates larger numbers).
inline CLI::Validator seed_number() {
  return CLI::Validator(
      [](std::string& text) {
        const bool digits = !text.empty() && text.find_first_not_of("0123456789") == std::string::npos;
        if (digits && (text.size() < 20 || (text.size() == 20 && text <= "18446744073709551615"))) return std::string();
        return "'" + text + "' is not a seed (a whole number 0 .. 18446744073709551615)";
      },
      "SEED");
}

// A CLI11 check for --origin LAT,LON (a usage error, exit 2, when the text is not that).
inline CLI::Validator lat_lon_validator() {
  return CLI::Validator(
      [](std::string& text) {
        try {
          parse_lat_lon(text);
          return std::string();
        } catch (const std::exception& e) {
          return std::string(e.what());
        }
      },
      "LAT,LON");
}

// An option that takes one of an enum's names (`names`: each value with its name) and stores the
// value itself in `value`, parsed once here; any other name is a usage error (exit 2) that lists
// the names. The help shows `value`'s name as the default.
template <class Enum, std::size_t N>
CLI::Option* add_enum_option(CLI::App* sub, const std::string& name, Enum& value,
                             const std::array<std::pair<Enum, std::string_view>, N>& names, const std::string& help) {
  std::vector<std::string> choices;
  std::string shown;
  for (const auto& [v, text] : names) {
    choices.emplace_back(text);
    if (v == value) shown = text;
  }
  return sub
      ->add_option_function<std::string>(
          name,
          [&value, names](const std::string& text) {
            for (const auto& [v, known] : names)
              if (text == known) value = v;
          },
          help)
      ->check(CLI::IsMember(choices))
      ->default_str(shown);
}

// The end of a subcommand's --help: what it writes and where, then two or three examples that
// work from the repository root (data/SainteHelens.dem, templates/scenes/small.toml), each a
// command a user can paste; tests/cli/help_examples.sh runs every one of them.
// "A,B" or "A,B,C" as numbers, E,N,H in meters (a missing third is NaN); empty when it is not
// that. For --camera and --look-at (view, render).
std::optional<std::array<double, 3>> parse_enu_triple(const std::string& text, bool third_optional);

inline void set_help_footer(CLI::App* sub, const std::string& writes, std::initializer_list<const char*> examples) {
  std::string text = "Writes: " + writes + "\n\nExamples (from the repository root):\n";
  for (const char* line : examples) text += std::string("  ") + line + "\n";
  sub->footer(text);
}

// Registration: each subcommand file adds its CLI11 subcommand and sets a callback that
// does the work. Errors are thrown (std::exception); main() turns them into exit code 1.
void register_tileset_command(CLI::App& app, const GlobalOptions& global);
void register_tiling_command(CLI::App& app, const GlobalOptions& global);
void register_build_command(CLI::App& app, const GlobalOptions& global);
void register_render_command(CLI::App& app, const GlobalOptions& global);
void register_demo_command(CLI::App& app, const GlobalOptions& global);
void register_terrain_command(CLI::App& app, const GlobalOptions& global);
void register_scatter_command(CLI::App& app, const GlobalOptions& global);
void register_tiles_commands(CLI::App& app, const GlobalOptions& global);  // noise tiles, texture tiles
void register_batch_command(CLI::App& app, const GlobalOptions& global);
void register_ldi_command(CLI::App& app, const GlobalOptions& global);
void register_view_command(CLI::App& app, const GlobalOptions& global);

}  // namespace wangscape::cli
