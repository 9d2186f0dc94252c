// The renderers a scene folder can be rendered with, parsed once from the names users write
// (`wangscape render --engine`, a batch file's `engines`). Header only, no renderer linked.
#pragma once

#include <array>
#include <optional>
#include <string>
#include <string_view>

#include "core/error.h"

namespace wangscape {

enum class RenderEngine { povray, blender, embree };

inline constexpr std::array<RenderEngine, 3> kRenderEngines{RenderEngine::povray, RenderEngine::blender,
                                                            RenderEngine::embree};

// "povray", "blender", "embree".
constexpr std::string_view to_string(RenderEngine engine) {
  switch (engine) {
    case RenderEngine::povray:
      return "povray";
    case RenderEngine::blender:
      return "blender";
    case RenderEngine::embree:
      return "embree";
  }
  return "?";
}

// The engine `name` names, or nothing.
inline std::optional<RenderEngine> find_render_engine(std::string_view name) {
  for (const RenderEngine e : kRenderEngines)
    if (name == to_string(e)) return e;
  return std::nullopt;
}

// The engine `name` names; throws Error("render: engine 'NAME' is not available in this
// wangscape (known: povray, blender, embree)").
inline RenderEngine parse_render_engine(std::string_view name) {
  if (const auto e = find_render_engine(name)) return *e;
  throw Error("render: engine '" + std::string(name) +
              "' is not available in this wangscape (known: povray, blender, embree)");
}

}  // namespace wangscape
