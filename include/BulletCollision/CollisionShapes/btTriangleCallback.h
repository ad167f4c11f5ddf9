// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef BT_TRIANGLE_CALLBACK_H
#define BT_TRIANGLE_CALLBACK_H

#include "LinearMath/btVector3.h"

/// Receives the triangles of a concave shape (processAllTriangles) one at a time.
class btTriangleCallback
{
public:
	/// Callbacks are deleted through base pointers.
	virtual ~btTriangleCallback();
	/// One triangle: triangle[0..2] are its vertices, partId the mesh part, triangleIndex its index there.
	virtual void processTriangle(btVector3* triangle, int partId, int triangleIndex) = 0;
};

/// Receives triangles with their indices from a mesh interface (used to build BVHs over meshes).
/// Kept in this header, at Bullet's include path, with btTriangleCallback.
class btInternalTriangleIndexCallback
{
public:
	/// Callbacks are deleted through base pointers.
	virtual ~btInternalTriangleIndexCallback();
	/// One triangle: triangle[0..2] are its vertices, partId the mesh part, triangleIndex its index there.
	virtual void internalProcessTriangleIndex(btVector3* triangle, int partId, int triangleIndex) = 0;
};

#endif  // BT_TRIANGLE_CALLBACK_H
