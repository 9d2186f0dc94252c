// Helpers shared by the generator tests.
#pragma once

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

}  // namespace wangscape::testing
