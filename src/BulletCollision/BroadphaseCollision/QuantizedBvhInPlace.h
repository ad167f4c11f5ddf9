// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef CALIBER_QUANTIZED_BVH_IN_PLACE_H
#define CALIBER_QUANTIZED_BVH_IN_PLACE_H

// Internal: Bullet's in-place BVH buffer (btQuantizedBvh::serialize(buffer, size, swapEndian) and
// deSerializeInPlace, btOptimizedBvh::serializeInPlace / deSerializeInPlace), in a layout of
// Caliber's own (docs/meshes-heightfields-and-compounds.md, "In-place buffers"):
//   [object region]  room for the btQuantizedBvh or btOptimizedBvh that loading constructs there
//   [header]         magic, version, btScalar size, counts, quantization box (InPlaceBvhHeader)
//   [nodes]          the contiguous tree (quantized or not), 16-byte aligned
//   [subtree headers]
// Loading checks everything, byte-swaps when asked, and points the object's arrays into the buffer.

#include "BulletCollision/BroadphaseCollision/btQuantizedBvh.h"

namespace caliber
{
/// Bytes before the header: room for the object loading constructs in the buffer.
constexpr unsigned kInPlaceBvhObjectBytes = (unsigned(sizeof(btQuantizedBvh)) + 15u) & ~15u;

/// Checks an in-place buffer (and byte-swaps it to this machine's order when swapEndian); on success
/// returns null and leaves the buffer in native order, else returns the reason and leaves the buffer
/// as it was.
const char* prepareInPlaceBvh(void* buffer, unsigned bufferSize, bool swapEndian);

/// Points bvh, just constructed in a prepared buffer's object region, at the buffer's tree (its arrays
/// adopt the buffer's memory and never free it).
void adoptInPlaceBvh(btQuantizedBvh& bvh, void* buffer);

/// Reports a refused buffer through btReportWarning, naming the caller.
void warnInPlaceBvh(const char* caller, const char* problem);
}  // namespace caliber

#endif  // CALIBER_QUANTIZED_BVH_IN_PLACE_H
