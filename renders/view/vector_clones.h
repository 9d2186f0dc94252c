// WANGSCAPE_VECTOR_CLONES before a function: GCC compiles it for AVX-512, AVX2 and the baseline,
// and the program takes the widest its CPU has when it starts. Files that use it are compiled
// without fused multiply-adds (renders/view/CMakeLists.txt), so every variant computes the same
// values, byte for byte. Internal to renders/view.
#pragma once

#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
#define WANGSCAPE_VECTOR_CLONES __attribute__((target_clones("arch=x86-64-v4", "arch=x86-64-v3", "default")))
#else
#define WANGSCAPE_VECTOR_CLONES
#endif
