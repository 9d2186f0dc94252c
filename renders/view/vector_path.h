// The vector instruction sets the view's LDI warp is compiled for. The program takes the widest
// its CPU has; a test (or a comparison of the paths) may choose a narrower one. Every path makes
// the same frame, byte for byte: the warp's file is compiled without fused multiply-adds
// (renders/view/CMakeLists.txt), so each computes the same values.
#pragma once

#include <string_view>

namespace wangscape {

enum class VectorPath {
  baseline,  // x86-64 (SSE2), or whatever the compiler's target is off x86-64
  avx2,      // x86-64-v3: 8 lanes of float
  avx512,    // x86-64-v4: 16 lanes
};

std::string_view to_string(VectorPath path);
// The widest path this CPU (and its operating system) runs.
VectorPath widest_vector_path();
// The path the warp runs now: the widest, unless set_vector_path chose another.
VectorPath vector_path();
// From now on, for every renderer of the process. Throws Error when the CPU lacks it.
void set_vector_path(VectorPath path);

}  // namespace wangscape
