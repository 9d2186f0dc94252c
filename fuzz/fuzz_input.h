// Shared by the fuzz targets: the input bytes as a file the readers open by path (an anonymous
// in-memory file, so the fuzzers test the readers' real file entry points without touching the
// disk), and the one rule of every target: a wangscape::Error is a refusal, a normal outcome.
#pragma once

#include <sys/mman.h>
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>

#include "core/error.h"

namespace wangscape::fuzz {

// The bytes as a regular file at /proc/self/fd/N, removed with the object.
class InputFile {
 public:
  InputFile(const std::uint8_t* data, std::size_t size) : fd_(::memfd_create("fuzz-input", MFD_CLOEXEC)) {
    if (fd_ < 0) std::abort();  // the harness itself failed: not a finding in the reader
    for (std::size_t done = 0; done < size;) {
      const ssize_t n = ::write(fd_, data + done, size - done);
      if (n <= 0) std::abort();
      done += std::size_t(n);
    }
  }
  ~InputFile() { ::close(fd_); }
  InputFile(const InputFile&) = delete;
  InputFile& operator=(const InputFile&) = delete;
  std::string path() const { return "/proc/self/fd/" + std::to_string(fd_); }

 private:
  int fd_;
};

// Runs `read`; an Error is the reader refusing the input. Any other exception escapes to
// libFuzzer, which reports it (with the input) as a finding, as it does crashes and hangs.
template <class Read>
int refusals_are_fine(Read&& read) {
  try {
    read();
  } catch (const Error&) {
  }
  return 0;
}

}  // namespace wangscape::fuzz
