// libFuzzer target: the LDI pack reader. Opening validates the whole pack; a pack it accepts is
// then read as a viewer would (every pixel of every span, both ends of every row, the
// statistics), so a check that lets a bad offset through shows up as an out-of-bounds read.
// The reads stay proportional to the file (a valid LDI may declare 65535 x 65535 empty pixels).
#include "folder/ldi_pack.h"
#include "fuzz/fuzz_input.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace wangscape;
  const fuzz::InputFile file(data, size);
  return fuzz::refusals_are_fine([&] {
    const LdiPack pack(file.path());
    const LdiPackInfo& info = pack.info();
    std::uint64_t edge_layers = 0, span_layers = 0;
    for (std::uint32_t t = 0; t < info.tiles; ++t)
      for (std::uint32_t l = 0; l < info.levels; ++l)
        for (std::uint32_t d = 0; d < info.directions; ++d) {
          const LdiView v = pack.ldi(t, l, d);
          const int width = int(v.frame->width);
          for (int y = 0; y < int(v.frame->height); ++y) {
            edge_layers += v.pixel(0, y).size() + v.pixel(width - 1, y).size();
            for (std::uint32_t s = v.row_spans[std::size_t(y)]; s < v.row_spans[std::size_t(y) + 1]; ++s)
              for (int x = v.spans[s].x; x < v.spans[s].x + v.spans[s].length; ++x) span_layers += v.pixel(x, y).size();
          }
        }
    // Every depth pixel belongs to one pixel of one span.
    if (ldi_pack_stats(pack).depth_pixels != span_layers || edge_layers > 2 * span_layers) std::abort();
  });
}
