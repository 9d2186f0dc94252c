// libFuzzer target: the filled tile-set JSON reader (colors and Poisson points). A set it
// accepts must survive a write and a re-read unchanged (fuzz::accepted_values_round_trip).
#include "fuzz/fuzz_input.h"
#include "scene/filled_tileset_file.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace wangscape;
  const fuzz::InputFile file(data, size);
  return fuzz::accepted_values_round_trip(
      [&] { return read_filled_tileset_json(file.path()); },
      [](const FilledTileSet& set) { return format_filled_tileset_json(filled_tileset_to_json(set)); },
      [](const std::string& text) { return filled_tileset_from_json(Json::parse(text), "rewritten"); });
}
