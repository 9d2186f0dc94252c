// Image files through OpenImageIO. Writes go through AtomicPath: a failed write leaves no file.
#pragma once

#include <cstdint>
#include <filesystem>
#include <span>
#include <string>

#include "generator/image.h"

namespace wangscape {

// Writes `image` in the format its extension names (.png, .tif, .jpg, ...). Throws Error
// naming the file when the format is unknown or the write fails.
void write_image(const std::filesystem::path& path, const ImageRgb8& image);

// `image` as the bytes of a PNG file (for containers such as .glb). Throws Error on failure.
std::string encode_png(const ImageRgb8& image);
// 8-bit pixels, `channels` (1 to 4) a pixel, row by row from the top, as the bytes of a PNG file.
std::string encode_png(int width, int height, int channels, std::span<const std::uint8_t> pixels);

// Reads any image OpenImageIO understands as 8-bit RGB (gray is replicated, alpha dropped).
// Throws Error naming the file.
ImageRgb8 read_image(const std::filesystem::path& path);

// 16-bit grey images (noise tiles), written atomically like write_image.
void write_image_gray16(const std::filesystem::path& path, const ImageGray16& image);
// Reads any image as 16-bit grey (the first channel). Throws Error naming the file.
ImageGray16 read_image_gray16(const std::filesystem::path& path);

}  // namespace wangscape
