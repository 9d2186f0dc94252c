// What the scene-file tests share: a scene file's text parsed (as test.toml in /base), or the
// message it is refused with.
#pragma once

#include <string>

#include "core/error.h"
#include "scene/scene_file.h"

namespace wangscape::scene_file_test {

inline SceneConfig parse(const std::string& text) { return parse_scene_config(text, "test.toml", "/base"); }

inline std::string error_of(const std::string& text) {
  try {
    parse(text);
  } catch (const Error& e) {
    return e.what();
  }
  return "(no error)";
}

}  // namespace wangscape::scene_file_test
