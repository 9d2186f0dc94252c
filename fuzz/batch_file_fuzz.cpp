// libFuzzer target: the batch-file reader (the bounded text reader, the nesting check, toml++ and
// the batch schema with its ranges and the task count) on arbitrary bytes, through its file entry
// point. Expansion is left out: it loads every DEM the file names, which is the DEM fuzzer's part.
#include "fuzz/fuzz_input.h"
#include "renders/batch/batch_file.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const wangscape::fuzz::InputFile file(data, size);
  return wangscape::fuzz::refusals_are_fine([&] { wangscape::load_batch_config(file.path()); });
}
