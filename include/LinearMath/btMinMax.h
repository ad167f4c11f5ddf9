// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef BT_GEN_MINMAX_H
#define BT_GEN_MINMAX_H

/// Min, max and clamp for any ordered type (btScalar, int, btVector3 through its own setMin/setMax).

#include "LinearMath/btScalar.h"

template <class T>
SIMD_FORCE_INLINE const T& btMin(const T& a, const T& b)
{
	return a < b ? a : b;
}

template <class T>
SIMD_FORCE_INLINE const T& btMax(const T& a, const T& b)
{
	return a > b ? a : b;
}

/// Clamps a to [lowerBound, upperBound].
template <class T>
SIMD_FORCE_INLINE const T& btClamped(const T& a, const T& lowerBound, const T& upperBound)
{
	return a < lowerBound ? lowerBound : (upperBound < a ? upperBound : a);
}

/// a = min(a, b).
template <class T>
SIMD_FORCE_INLINE void btSetMin(T& a, const T& b)
{
	if (b < a) a = b;
}

/// a = max(a, b).
template <class T>
SIMD_FORCE_INLINE void btSetMax(T& a, const T& b)
{
	if (a < b) a = b;
}

/// Clamps a in place to [lowerBound, upperBound].
template <class T>
SIMD_FORCE_INLINE void btClamp(T& a, const T& lowerBound, const T& upperBound)
{
	if (a < lowerBound)
		a = lowerBound;
	else if (upperBound < a)
		a = upperBound;
}

#endif  // BT_GEN_MINMAX_H
