// libFuzzer target: the tile-set JSON reader. A set it accepts must survive a write and a
// re-read unchanged (fuzz::accepted_values_round_trip).
#include "fuzz/fuzz_input.h"
#include "scene/tileset_file.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace wangscape;
  const fuzz::InputFile file(data, size);
  return fuzz::accepted_values_round_trip(
      [&] { return read_tileset_json(file.path()); },
      [](const TileSet& set) { return format_tileset_json(tileset_to_json(set)); },
      [](const std::string& text) { return tileset_from_json(Json::parse(text), "rewritten"); });
}
