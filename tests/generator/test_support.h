// Helpers shared by the tests.
#pragma once

#include <unistd.h>

#include <filesystem>
#include <string>

#include "generator/tileset.h"

namespace wangscape::testing {

// Runs `body` and returns the Error message it throws ("" when it does not throw).
template <typename Body>
std::string error_of(Body&& body) {
  try {
    body();
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

// An empty folder of its own for a test: the temporary folder's "wangscape_<name>_<pid>", emptied.
inline std::filesystem::path fresh_folder(const std::string& name) {
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("wangscape_" + name + "_" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

}  // namespace wangscape::testing
