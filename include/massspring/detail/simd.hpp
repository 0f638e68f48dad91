#pragma once
/// @file
/// @brief The AVX2 + FMA code paths: compiled with a target attribute, chosen at run time.
///
/// On x86-64 with GCC or Clang, the substitutions with the factor of Q
/// (storage/lower_factor_simd.hpp) have a version compiled for AVX2 and FMA next to the baseline
/// (SSE2) one, and run it when the CPU has both, whatever the compiler's -m flags. Defining
/// MASSSPRING_NO_SIMD before including any massspring header leaves those versions out.

#if defined(__GNUC__) && defined(__x86_64__) && !defined(MASSSPRING_NO_SIMD)
/// Defined when the AVX2 + FMA versions are compiled in.
#define MASSSPRING_HAVE_SIMD_PATH 1
/// The attribute of a function compiled for AVX2 and FMA.
#define MASSSPRING_TARGET_AVX2 __attribute__((target("avx2,fma")))
#include <immintrin.h>
#endif

/// Fully unrolls the loop that follows (a fixed count over the lanes of a few springs), so that
/// its arrays of registers stay in registers at -O2 too (otherwise a compiler may keep the loop and
/// put the arrays on the stack).
#if defined(__clang__)
#define MASSSPRING_UNROLL _Pragma("unroll")
#elif defined(__GNUC__)
#define MASSSPRING_UNROLL _Pragma("GCC unroll 8")
#else
#define MASSSPRING_UNROLL
#endif

#if defined(__GNUC__)
/// The same for a lambda (after its parameter list): the spring pass's per-pair lambda must not
/// be called with its arrays in memory.
#define MASSSPRING_LAMBDA_ALWAYS_INLINE __attribute__((always_inline))
/// A function the compiler must not inline: a hot loop called once per iteration from several
/// places, compiled once instead of at each (the call costs nothing next to the loop).
#define MASSSPRING_NOINLINE __attribute__((noinline))
#else
#define MASSSPRING_LAMBDA_ALWAYS_INLINE
#define MASSSPRING_NOINLINE
#endif

namespace massspring::detail {

/// @brief True when the AVX2 + FMA versions are compiled in and the CPU runs them (checked
/// once).
inline bool cpu_has_avx2_fma() {
#ifdef MASSSPRING_HAVE_SIMD_PATH
  static const bool has = __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
  return has;
#else
  return false;
#endif
}

}  // namespace massspring::detail
