#include "exporters/image_io.h"

#include <OpenImageIO/imageio.h>

#include <string>

#include "core/atomic_file.h"

namespace wangscape {

void write_image(const std::filesystem::path& path, const ImageRgb8& image) {
  const std::string name = path.string();
  if (image.width < 1 || image.height < 1) throw Error("cannot write '" + name + "': the image is empty");
  AtomicPath atomic(path);
  auto output = OIIO::ImageOutput::create(name);  // chooses the format from the target's extension
  if (!output)
    throw Error("cannot write '" + name + "': no image format for extension '" + path.extension().string() + "' (" +
                OIIO::geterror() + ")");
  const OIIO::ImageSpec spec(image.width, image.height, 3, OIIO::TypeDesc::UINT8);
  const std::string temp = atomic.temp_path().string();
  if (!output->open(temp, spec) || !output->write_image(OIIO::TypeDesc::UINT8, image.pixels.data()) || !output->close())
    throw Error("cannot write '" + name + "': " + output->geterror());
  atomic.commit();
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
