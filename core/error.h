// The one error type of every Wangscape library. It carries what went wrong and where: the
// file at fault and the place in it (a line of a scene file, "tile 3, point 5" of a tile-set
// file, nothing for a DEM as a whole), so `main` catches it once and prints one line.
#pragma once

#include <filesystem>
#include <stdexcept>
#include <string>

namespace wangscape {

class Error : public std::runtime_error {
 public:
  // A message that already says what it is about (a value, a flag, a file named inline).
  explicit Error(const std::string& message) : std::runtime_error(message), message_(message) {}
  // "<file>:<place>: <message>", or "<file>: <message>" when the place is empty.
  Error(const std::filesystem::path& file, const std::string& place, const std::string& message)
      : std::runtime_error(join(file, place, message)), file_(file), place_(place), message_(message) {}

  const std::filesystem::path& file() const { return file_; }  // empty when none is known
  const std::string& place() const { return place_; }          // e.g. "12" (a line); may be empty
  const std::string& message() const { return message_; }      // without file and place

 private:
  static std::string join(const std::filesystem::path& file, const std::string& place, const std::string& message) {
    std::string out = file.string();
    if (!place.empty()) out += ":" + place;
    return out.empty() ? message : out + ": " + message;
  }
  std::filesystem::path file_;
  std::string place_;
  std::string message_;
};

}  // namespace wangscape
