// libFuzzer target: the filled tile-set JSON reader (colors and Poisson points). A set it
// accepts must survive a write and a re-read unchanged (outside refusals_are_fine: the reader
// refusing what the writer wrote from an accepted set is a finding).
#include <cstdlib>
#include <optional>

#include "fuzz/fuzz_input.h"
#include "scene/filled_tileset_file.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace wangscape;
  const fuzz::InputFile file(data, size);
  std::optional<FilledTileSet> filled;
  fuzz::refusals_are_fine([&] { filled = read_filled_tileset_json(file.path()); });
  if (!filled) return 0;
  const std::string written = format_filled_tileset_json(filled_tileset_to_json(*filled));
  const FilledTileSet reread = filled_tileset_from_json(Json::parse(written), "rewritten");
  if (format_filled_tileset_json(filled_tileset_to_json(reread)) != written) std::abort();
  return 0;
}
