// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef CALIBER_SCRATCH_ARRAY_H
#define CALIBER_SCRATCH_ARRAY_H

// Sizing of the per-step scratch arrays of the hot stages. btAlignedObjectArray's resize reserves
// exactly the new size (Bullet's behaviour, which users may rely on for their own arrays), so a scratch
// array sized afresh every step of a growing scene (a pile still forming: a few more contacts each step)
// was reallocated, copied and its new pages faulted in at every step. These grow the capacity at least
// twofold instead; in steady state neither version allocates.

#include "LinearMath/btAlignedObjectArray.h"

namespace caliber
{
/// Makes room for at least count elements, at least doubling the capacity when it must grow.
template <class T>
void reserveScratch(btAlignedObjectArray<T>& array, int count)
{
	if (count > array.capacity()) array.reserve(count > 2 * array.capacity() ? count : 2 * array.capacity());
}

/// resizeNoInitialize with geometric growth (new plain-data elements are left uninitialised).
template <class T>
void resizeScratch(btAlignedObjectArray<T>& array, int count)
{
	reserveScratch(array, count);
	array.resizeNoInitialize(count);
}

/// Sets every one of count elements to fill, with geometric growth.
template <class T, class Fill>
void assignScratch(btAlignedObjectArray<T>& array, int count, const Fill& fill)
{
	reserveScratch(array, count);
	array.resize(0);
	array.resize(count, T(fill));
}
}  // namespace caliber

#endif
