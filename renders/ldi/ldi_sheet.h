// A picture of one tile's LDIs for the README and for checking a pack by eye: levels as rows,
// directions as columns; on the left the front layer of every pixel as it was shaded, on the
// right a heat map of the layer count.
#pragma once

#include <cstdint>
#include <filesystem>

#include "folder/ldi_pack.h"
#include "generator/image.h"

namespace wangscape {

// Each LDI is scaled (nearest pixel) to fit a cell of cell_pixels x cell_pixels, so low levels
// look blocky. The image is 2 * directions * cell_pixels wide and levels * cell_pixels high.
// Throws Error when the pack has no tile `tile`.
ImageRgb8 draw_ldi_sheet(const LdiPack& pack, std::uint32_t tile, int cell_pixels = 160);

// Opens the pack at `pack_path`, draws tile `tile`'s sheet and writes it as an image (PNG, or the
// format the extension names) through a temporary file. Throws Error naming the file at fault.
void write_ldi_sheet(const std::filesystem::path& pack_path, std::uint32_t tile, const std::filesystem::path& out,
                     int cell_pixels = 160);

// The heat map's color for a pixel with `layers` layers (0: empty).
Rgb8 layer_count_color(int layers);

}  // namespace wangscape
