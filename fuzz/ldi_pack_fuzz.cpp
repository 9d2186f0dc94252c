// libFuzzer target: the LDI pack reader. Opening validates the whole pack; a pack it accepts is
// then read everywhere a viewer would (every pixel of every LDI, the statistics), so a check
// that lets a bad offset through shows up as an out-of-bounds read.
#include "fuzz/fuzz_input.h"
#include "renders/ldi_pack.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace wangscape;
  const fuzz::InputFile file(data, size);
  return fuzz::refusals_are_fine([&] {
    const LdiPack pack(file.path());
    const LdiPackInfo& info = pack.info();
    std::uint64_t layers = 0;
    for (std::uint32_t t = 0; t < info.tiles; ++t)
      for (std::uint32_t l = 0; l < info.levels; ++l)
        for (std::uint32_t d = 0; d < info.directions; ++d) {
          const LdiView v = pack.ldi(t, l, d);
          for (int y = 0; y < int(v.frame->height); ++y)
            for (int x = 0; x < int(v.frame->width); ++x)
              for (const DepthPixel& p : v.pixel(x, y)) layers += p.depth() & 1;
        }
    const LdiPackStats stats = ldi_pack_stats(pack);
    if (stats.depth_pixels < layers) std::abort();  // more layers read than the pack holds
  });
}
