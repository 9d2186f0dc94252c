#include "exporters/image_io.h"

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include <fcntl.h>
#include <unistd.h>

#include <cstdio>
#include <cstring>
#include <memory>
#include <string>

#include "core/atomic_file.h"
#include "core/memory_budget.h"

namespace wangscape {

namespace {
// Writes `channels` x width x height pixels of `type` through a temporary file and a rename.
void write_pixels(const std::filesystem::path& path, int width, int height, int channels, OIIO::TypeDesc type,
                  const void* pixels) {
  const std::string name = path.string();
  if (width < 1 || height < 1) throw Error("cannot write '" + name + "': the image is empty");
  auto output = OIIO::ImageOutput::create(name);  // chooses the format from the target's extension
  if (!output) {
    OIIO::geterror();  // cleared: its text names OIIO, the message below says what to do
    throw Error("cannot write '" + name + "': no image format for extension '" + path.extension().string() +
                "'; name a .png, .tif, .jpg or .exr file");
  }
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
// The first line of an OIIO error ("PNG read error: Not enough image data\nPNG library error").
std::string first_line(std::string text) {
  text = text.substr(0, text.find('\n'));
  return text.empty() ? std::string("not an image this build reads") : text;
}

// While it lives, the process's stderr goes to /dev/null: libpng prints its own "libpng error:
// ..." line before OIIO reports the same error, which this program then says in its own words.
// Used only around decoding an input image, before any thread of the run starts.
class QuietStderr {
 public:
  QuietStderr() : saved_(::dup(2)) {
    std::fflush(stderr);
    const int null = ::open("/dev/null", O_WRONLY | O_CLOEXEC);
    if (saved_ >= 0 && null >= 0) ::dup2(null, 2);
    if (null >= 0) ::close(null);
  }
  ~QuietStderr() {
    std::fflush(stderr);
    if (saved_ >= 0) {
      ::dup2(saved_, 2);
      ::close(saved_);
    }
  }
  QuietStderr(const QuietStderr&) = delete;
  QuietStderr& operator=(const QuietStderr&) = delete;

 private:
  int saved_;
};

// Reads a whole image as `type` with `channels` channels (0: the file's own) after the checks
// OIIO does not make: a regular file (a FIFO would block, /dev/zero never ends) and the memory
// of its pixels estimated from the header, before decoding (bytes_per_sample of `type` plus
// `extra_per_pixel` bytes a pixel the caller keeps). Returns the spec and the pixels.
std::pair<OIIO::ImageSpec, std::vector<std::uint8_t>> read_pixels(const std::filesystem::path& path,
                                                                  OIIO::TypeDesc type, int channels,
                                                                  double extra_per_pixel) {
  const std::string name = path.string();
  std::error_code ec;
  const auto status = std::filesystem::status(path, ec);
  if (ec || !std::filesystem::exists(status)) throw Error("cannot read image '" + name + "': no such file");
  if (!std::filesystem::is_regular_file(status))
    throw Error("cannot read image '" + name + "': not a regular file (a folder, a pipe or a device)");
  const QuietStderr quiet;
  auto input = OIIO::ImageInput::open(name);
  if (!input) throw Error("cannot read image '" + name + "': " + first_line(OIIO::geterror()));
  const OIIO::ImageSpec spec = input->spec();
  const int n = channels > 0 ? channels : spec.nchannels;
  if (spec.width < 1 || spec.height < 1 || n < 1)
    throw Error("cannot read image '" + name + "': it declares " + std::to_string(spec.width) + " x " +
                std::to_string(spec.height) + " pixels");
  const double pixels = double(spec.width) * double(spec.height);
  check_memory_estimate(path,
                        "the image of " + std::to_string(spec.width) + " x " + std::to_string(spec.height) + " pixels",
                        pixels * (double(n) * double(type.size()) + extra_per_pixel));
  std::vector<std::uint8_t> raw(static_cast<std::size_t>(pixels) * std::size_t(n) * type.size());
  if (!input->read_image(0, 0, 0, n, type, raw.data()))
    throw Error("cannot read image '" + name + "': " + first_line(input->geterror()));
  return {spec, std::move(raw)};
}
}  // namespace

void write_image(const std::filesystem::path& path, const ImageRgb8& image) {
  write_pixels(path, image.width, image.height, 3, OIIO::TypeDesc::UINT8, image.pixels.data());
}

void write_image_gray16(const std::filesystem::path& path, const ImageGray16& image) {
  write_pixels(path, image.width, image.height, 1, OIIO::TypeDesc::UINT16, image.pixels.data());
}

ImageGray16 read_image_gray16(const std::filesystem::path& path) {
  const auto [spec, raw] = read_pixels(path, OIIO::TypeDesc::UINT16, 1, 0);
  ImageGray16 image(spec.width, spec.height);
  std::memcpy(image.pixels.data(), raw.data(), raw.size());
  return image;
}

std::string encode_png(int width, int height, int channels, std::span<const std::uint8_t> pixels) {
  if (width < 1 || height < 1) throw Error("cannot encode a PNG: the image is empty");
  if (pixels.size() != std::size_t(width) * std::size_t(height) * std::size_t(channels))
    throw Error("cannot encode a PNG: " + std::to_string(pixels.size()) + " bytes for " + std::to_string(width) +
                " x " + std::to_string(height) + " x " + std::to_string(channels));
  std::vector<unsigned char> bytes;
  OIIO::Filesystem::IOVecOutput proxy(bytes);
  auto output = OIIO::ImageOutput::create("memory.png");
  const OIIO::ImageSpec spec(width, height, channels, OIIO::TypeDesc::UINT8);
  if (!output || !output->set_ioproxy(&proxy) || !output->open("memory.png", spec) ||
      !output->write_image(OIIO::TypeDesc::UINT8, pixels.data()) || !output->close())
    throw Error(std::string("cannot encode a PNG: ") + (output ? output->geterror() : OIIO::geterror()));
  return std::string(bytes.begin(), bytes.end());
}

std::string encode_png(const ImageRgb8& image) {
  return encode_png(image.width, image.height, 3, std::span<const std::uint8_t>(image.pixels));
}

ImageRgb8 read_image(const std::filesystem::path& path) {
  const auto [spec, raw] = read_pixels(path, OIIO::TypeDesc::UINT8, 0, 3);  // and 3 bytes a pixel of RGB
  ImageRgb8 image(spec.width, spec.height);
  const int channels = spec.nchannels;
  for (std::size_t p = 0, q = 0; p < image.pixels.size(); p += 3, q += static_cast<std::size_t>(channels))
    for (std::size_t c = 0; c < 3; ++c) image.pixels[p + c] = raw[q + (channels >= 3 ? c : 0)];
  return image;
}

}  // namespace wangscape
