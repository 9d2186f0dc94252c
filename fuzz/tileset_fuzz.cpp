// libFuzzer target: the tile-set JSON reader. A set it accepts must survive a write and a
// re-read unchanged: the writer's text, read back, gives the same text again (a refusal of the
// writer's own text is a finding too, so the round trip runs outside refusals_are_fine).
#include <cstdlib>
#include <optional>

#include "fuzz/fuzz_input.h"
#include "scene/tileset_file.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace wangscape;
  const fuzz::InputFile file(data, size);
  std::optional<TileSet> set;
  fuzz::refusals_are_fine([&] { set = read_tileset_json(file.path()); });
  if (!set) return 0;
  const std::string written = format_tileset_json(tileset_to_json(*set));
  const TileSet reread = tileset_from_json(Json::parse(written), "rewritten");
  if (format_tileset_json(tileset_to_json(reread)) != written) std::abort();  // the writer lost something
  return 0;
}
