#include "renders/ldi/ldi_sheet.h"

#include <algorithm>
#include <array>
#include <string>

#include "exporters/image_io.h"

namespace wangscape {

Rgb8 layer_count_color(int layers) {
  if (layers <= 0) return {0, 0, 0};
  // 1 layer dark blue ... 8 or more bright yellow, through purple and orange.
  static constexpr std::array<Rgb8, 5> ramp{
      {{20, 30, 120}, {110, 40, 160}, {210, 60, 90}, {245, 150, 30}, {250, 240, 80}}};
  const float u = std::min(1.0f, float(layers - 1) / 7.0f) * float(ramp.size() - 1);
  const int i = std::min(int(u), int(ramp.size()) - 2);
  const float f = u - float(i);
  auto mix = [&](std::uint8_t a, std::uint8_t b) { return std::uint8_t(float(a) + (float(b) - float(a)) * f + 0.5f); };
  return {mix(ramp[std::size_t(i)].r, ramp[std::size_t(i) + 1].r),
          mix(ramp[std::size_t(i)].g, ramp[std::size_t(i) + 1].g),
          mix(ramp[std::size_t(i)].b, ramp[std::size_t(i) + 1].b)};
}

ImageRgb8 draw_ldi_sheet(const LdiPack& pack, std::uint32_t tile, int cell) {
  const LdiPackInfo& info = pack.info();
  if (tile >= info.tiles)
    throw Error(pack.path(), "",
                "no tile " + std::to_string(tile) + " (the pack has " + std::to_string(info.tiles) + ")");
  cell = std::max(cell, 8);
  const int columns = int(info.directions);
  ImageRgb8 sheet(2 * columns * cell, int(info.levels) * cell, Rgb8{24, 24, 24});
  for (std::uint32_t level = 0; level < info.levels; ++level)
    for (std::uint32_t direction = 0; direction < info.directions; ++direction) {
      const LdiView v = pack.ldi(tile, level, direction);
      const int w = int(v.frame->width), h = int(v.frame->height);
      // Fit the LDI into the cell, centred, keeping square pixels.
      const double scale = double(cell - 2) / std::max(w, h);
      const int dw = std::max(1, int(w * scale)), dh = std::max(1, int(h * scale));
      const int x0 = int(direction) * cell + (cell - dw) / 2, y0 = int(level) * cell + (cell - dh) / 2;
      for (int y = 0; y < dh; ++y)
        for (int x = 0; x < dw; ++x) {
          const auto samples = v.pixel(std::min(w - 1, int(x / scale)), std::min(h - 1, int(y / scale)));
          if (!samples.empty()) sheet.set(x0 + x, y0 + y, {samples[0].r, samples[0].g, samples[0].b});
          sheet.set(x0 + columns * cell + x, y0 + y, layer_count_color(int(samples.size())));
        }
    }
  return sheet;
}

void write_ldi_sheet(const std::filesystem::path& pack_path, std::uint32_t tile, const std::filesystem::path& out,
                     int cell_pixels) {
  const LdiPack pack(pack_path);
  write_image(out, draw_ldi_sheet(pack, tile, cell_pixels));
}

}  // namespace wangscape
