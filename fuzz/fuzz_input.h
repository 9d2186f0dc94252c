// Shared by the fuzz targets: the input bytes as a file the readers open by path (an anonymous
// in-memory file, so the fuzzers test the readers' real file entry points without touching the
// disk), and the one rule of every target: a wangscape::Error is a refusal, a normal outcome.
#pragma once

#include <sys/mman.h>
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <optional>
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

// For a writer and its reader: what `read` accepts, `write` turns into text that `parse` reads
// back to a value written as the same text. A refusal of the writer's own text escapes
// (it runs outside refusals_are_fine), as does a difference (abort).
template <class Read, class Write, class Parse>
int accepted_values_round_trip(Read&& read, Write&& write, Parse&& parse) {
  std::optional<decltype(read())> value;
  refusals_are_fine([&] { value = read(); });
  if (!value) return 0;
  const std::string written = write(*value);
  if (write(parse(written)) != written) std::abort();  // the writer lost or changed something
  return 0;
}

}  // namespace wangscape::fuzz
