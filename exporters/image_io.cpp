#include "exporters/image_io.h"

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include <string>

#include "core/atomic_file.h"

namespace wangscape {

namespace {
// Writes `channels` x width x height pixels of `type` through a temporary file and a rename.
void write_pixels(const std::filesystem::path& path, int width, int height, int channels, OIIO::TypeDesc type,
                  const void* pixels) {
  const std::string name = path.string();
  if (width < 1 || height < 1) throw Error("cannot write '" + name + "': the image is empty");
  auto output = OIIO::ImageOutput::create(name);  // chooses the format from the target's extension
  if (!output)
    throw Error("cannot write '" + name + "': no image format for extension '" + path.extension().string() + "' (" +
                OIIO::geterror() + ")");
  const OIIO::ImageSpec spec(width, height, channels, type);
  if (output->supports("ioproxy")) {
    // Encoded in memory, then written through AtomicFile, which checks every write and the
    // close: OIIO's PNG writer reports no error when the disk fills (a truncated file).
    std::vector<unsigned char> bytes;
    OIIO::Filesystem::IOVecOutput proxy(bytes);
    if (!output->set_ioproxy(&proxy) || !output->open(name, spec) || !output->write_image(type, pixels) ||
        !output->close())
      throw Error("cannot write '" + name + "': " + output->geterror());
    AtomicFile file(path);
    file.stream().write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
    file.commit();
    return;
  }
  AtomicPath atomic(path);
  const std::string temp = atomic.temp_path().string();
  if (!output->open(temp, spec) || !output->write_image(type, pixels) || !output->close())
    throw Error("cannot write '" + name + "': " + output->geterror());
  atomic.commit();
}
}  // namespace

void write_image(const std::filesystem::path& path, const ImageRgb8& image) {
  write_pixels(path, image.width, image.height, 3, OIIO::TypeDesc::UINT8, image.pixels.data());
}

void write_image_gray16(const std::filesystem::path& path, const ImageGray16& image) {
  write_pixels(path, image.width, image.height, 1, OIIO::TypeDesc::UINT16, image.pixels.data());
}

ImageGray16 read_image_gray16(const std::filesystem::path& path) {
  const std::string name = path.string();
  auto input = OIIO::ImageInput::open(name);
  if (!input) throw Error("cannot read image '" + name + "': " + OIIO::geterror());
  const OIIO::ImageSpec& spec = input->spec();
  ImageGray16 image(spec.width, spec.height);
  if (!input->read_image(0, 0, 0, 1, OIIO::TypeDesc::UINT16, image.pixels.data()))
    throw Error("cannot read image '" + name + "': " + input->geterror());
  return image;
}

std::string encode_png(const ImageRgb8& image) {
  if (image.width < 1 || image.height < 1) throw Error("cannot encode a PNG: the image is empty");
  std::vector<unsigned char> bytes;
  OIIO::Filesystem::IOVecOutput proxy(bytes);
  auto output = OIIO::ImageOutput::create("memory.png");
  const OIIO::ImageSpec spec(image.width, image.height, 3, OIIO::TypeDesc::UINT8);
  if (!output || !output->set_ioproxy(&proxy) || !output->open("memory.png", spec) ||
      !output->write_image(OIIO::TypeDesc::UINT8, image.pixels.data()) || !output->close())
    throw Error(std::string("cannot encode a PNG: ") + (output ? output->geterror() : OIIO::geterror()));
  return std::string(bytes.begin(), bytes.end());
}

ImageRgb8 read_image(const std::filesystem::path& path) {
  const std::string name = path.string();
  auto input = OIIO::ImageInput::open(name);
  if (!input) throw Error("cannot read image '" + name + "': " + OIIO::geterror());
  const OIIO::ImageSpec& spec = input->spec();
  ImageRgb8 image(spec.width, spec.height);
  const int channels = spec.nchannels;
  std::vector<std::uint8_t> raw(static_cast<std::size_t>(spec.width) * static_cast<std::size_t>(spec.height) *
                                static_cast<std::size_t>(channels));
  if (!input->read_image(0, 0, 0, channels, OIIO::TypeDesc::UINT8, raw.data()))
    throw Error("cannot read image '" + name + "': " + input->geterror());
  for (std::size_t p = 0, q = 0; p < image.pixels.size(); p += 3, q += static_cast<std::size_t>(channels))
    for (std::size_t c = 0; c < 3; ++c) image.pixels[p + c] = raw[q + (channels >= 3 ? c : 0)];
  return image;
}

}  // namespace wangscape
