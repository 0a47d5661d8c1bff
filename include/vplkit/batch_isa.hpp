// The instruction sets the CPU batch kernels (rsm_gather_batch.hpp, form_factor_grid.hpp) are
// compiled for, and the run-time choice between them.
//
// Why: the library is built for x86-64-v2 (SSE4.2, CMakeLists.txt), which every x86-64 CPU of
// the last decade runs; AVX2 doubles the lanes and adds per-lane shifts and gathers, which the
// batch kernels' loops use when the compiler may (measured in docs/performance.md). So each batch
// kernel's body is one always-inlined template, instantiated in a plain function and in one with
// `target("avx2")`, and called through the one the CPU runs (`__builtin_cpu_supports`). The two
// are the same source; AVX2 does not include FMA, and the kernels are compiled with
// -ffp-contract=off, so both paths round every operation as the scalar twin does (the tests of
// each kernel compare its paths bit for bit).
//
// GLSL twin: none (CPU dispatch).
#pragma once

#if (defined(__x86_64__) || defined(__i386__)) && (defined(__GNUC__) || defined(__clang__))
#define VPLKIT_BATCH_HAS_AVX2 1
#define VPLKIT_BATCH_TARGET_AVX2 __attribute__((target("avx2")))
#else
#define VPLKIT_BATCH_HAS_AVX2 0
#endif

#if defined(__GNUC__) || defined(__clang__)
#define VPLKIT_BATCH_ALWAYS_INLINE __attribute__((always_inline))
#else
#define VPLKIT_BATCH_ALWAYS_INLINE
#endif

namespace vplkit {

/// An instruction set a batch kernel runs with: `portable` is the build's own (x86-64-v2 here,
/// whatever the compiler targets elsewhere), `avx2` the AVX2 instantiation (x86 with GCC or clang).
enum class batch_isa { portable, avx2 };

/// Whether this build has `isa`'s instantiation and this CPU runs it.
inline bool batch_isa_supported(batch_isa isa) {
  switch (isa) {
    case batch_isa::portable:
      return true;
    case batch_isa::avx2:
#if VPLKIT_BATCH_HAS_AVX2
      return __builtin_cpu_supports("avx2") != 0;
#else
      return false;
#endif
  }
  return false;
}

/// The fastest supported instruction set (what the batch kernels use unless told otherwise).
inline batch_isa best_batch_isa() {
  static const batch_isa best = batch_isa_supported(batch_isa::avx2) ? batch_isa::avx2 : batch_isa::portable;
  return best;
}

}  // namespace vplkit
