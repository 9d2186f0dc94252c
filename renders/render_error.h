// The error type of renders/: running an external renderer (POV-Ray, Blender) or sampling
// failed. The message names the scene folder or tool at fault and quotes the tool's own error.
#pragma once

#include <stdexcept>

namespace wangscape {

class RenderError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace wangscape
