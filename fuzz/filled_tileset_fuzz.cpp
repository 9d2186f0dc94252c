// libFuzzer target: the filled tile-set JSON reader (colors and Poisson points). A set it
// accepts must survive a write and a re-read unchanged.
#include <cstdlib>

#include "fuzz/fuzz_input.h"
#include "scene/filled_tileset_file.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace wangscape;
  const fuzz::InputFile file(data, size);
  return fuzz::refusals_are_fine([&] {
    const std::string written =
        format_filled_tileset_json(filled_tileset_to_json(read_filled_tileset_json(file.path())));
    const FilledTileSet reread = filled_tileset_from_json(Json::parse(written), "rewritten");
    if (format_filled_tileset_json(filled_tileset_to_json(reread)) != written) std::abort();
  });
}
