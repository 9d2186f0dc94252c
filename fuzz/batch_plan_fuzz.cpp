// libFuzzer target: a batch's plan.json as `batch run-task` and `batch status` read it (the bounded
// text reader, the nesting check, nlohmann-json, the base scene's text, then every task's ids,
// scene key and numbers), on arbitrary bytes through the same calls as load_plan.
#include "core/text_file.h"
#include "fuzz/fuzz_input.h"
#include "renders/batch/batch_run.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace wangscape;
  const fuzz::InputFile file(data, size);
  return fuzz::refusals_are_fine([&] {
    const BatchPlan plan = parse_batch_plan(read_text_file(file.path(), kMaxPlanBytes, "batch plan"), file.path());
    // What a worker derives from an accepted plan stays a plain name inside the output folder.
    for (const BatchTask& t : plan.tasks)
      if (t.id.find_first_not_of("0123456789") != std::string::npos || t.scene_key.find('/') != std::string::npos)
        std::abort();
  });
}
