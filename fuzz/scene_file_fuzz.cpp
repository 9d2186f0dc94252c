// libFuzzer target: the scene-file reader (read_text_file, the nesting check, toml++ and the
// schema with its ranges) on arbitrary bytes, through its file entry point.
#include "fuzz/fuzz_input.h"
#include "scene/scene_file.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const wangscape::fuzz::InputFile file(data, size);
  return wangscape::fuzz::refusals_are_fine([&] { wangscape::load_scene_config(file.path()); });
}
