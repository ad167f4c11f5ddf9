// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef CALIBER_CPU_FEATURES_H
#define CALIBER_CPU_FEATURES_H

// Second builds of hot SSE code for AVX2 processors. The code is compiled once more with AVX2 enabled
// (`#pragma GCC target("avx2")` or `__attribute__((target("avx2")))`) and chosen at run time: the VEX
// encoding's three operands save the register copies of two-operand SSE. Only AVX2 is enabled, never FMA:
// a fused multiply-add rounds once where the baseline rounds twice, so with FMA the bits would differ.
// Without it every operation rounds as in the baseline build, in the same order: the same results.

#include "LinearMath/btScalar.h"

#if defined(BT_USE_SSE) && !defined(BT_USE_DOUBLE_PRECISION) && (defined(__GNUC__) || defined(__clang__)) && \
    (defined(__x86_64__) || defined(__i386__))
#define CALIBER_AVX2_BUILDS 1
#else
#define CALIBER_AVX2_BUILDS 0
#endif

namespace caliber
{
/// Whether the processor runs AVX2 code. For a namespace-scope `const bool` initialised at load, so that
/// the choice is a plain load per call (a function-local static would add a guard and a stack frame);
/// read during other static initialisation the flag is still false and the baseline runs, with the same bits.
inline bool detectAvx2()
{
#if CALIBER_AVX2_BUILDS
	__builtin_cpu_init();  // needed when asked from a static initialiser
	return __builtin_cpu_supports("avx2") != 0;
#else
	return false;
#endif
}
}  // namespace caliber

#endif  // CALIBER_CPU_FEATURES_H
