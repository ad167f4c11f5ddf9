// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef BT_OBB_BOX_MINKOWSKI_H
#define BT_OBB_BOX_MINKOWSKI_H

#include "BulletCollision/CollisionShapes/btPolyhedralConvexShape.h"
#include "LinearMath/btVector3.h"

/// A box centred on the origin, given by its half extents. As in Bullet the margin lies inside these
/// dimensions: the core is the box shrunk by the margin on every side, and localGetSupportingVertex gives
/// the corners of the full box. The default margin is min(CONVEX_DISTANCE_MARGIN, 0.1 * smallest half
/// extent); setMargin keeps the outer size and clamps the margin to the smallest half extent, so the core
/// never turns inside out. Negative half extents assert and are made positive; non-finite ones assert and
/// become 0 (a zero-size box is a point).
ATTRIBUTE_ALIGNED16(class)
btBoxShape : public btPolyhedralConvexShape
{
public:
	BT_DECLARE_ALIGNED_ALLOCATOR();

	/// A box of the given half extents (margin included).
	btBoxShape(const btVector3& boxHalfExtents);

	/// The scaled half extents, margin included.
	btVector3 getHalfExtentsWithMargin() const
	{
		const btScalar m = getMargin();
		return getHalfExtentsWithoutMargin() + btVector3(m, m, m);
	}
	/// The scaled half extents of the core (margin excluded).
	const btVector3& getHalfExtentsWithoutMargin() const { return m_implicitShapeDimensions; }

	/// The sphere around the box's local bounding box (the same sphere as the base class finds, without the
	/// bounding-box pass: the dispatcher asks for it for every turning pair in every step).
	void getBoundingSphere(btVector3 & center, btScalar & radius) const override;

	/// The corner of the full box (margin included) farthest along vec (a negative side for a zero or NaN
	/// component).
	btVector3 localGetSupportingVertex(const btVector3& vec) const override;
	/// The corner of the core farthest along vec.
	btVector3 localGetSupportingVertexWithoutMargin(const btVector3& vec) const override;
	/// localGetSupportingVertexWithoutMargin for each direction.
	void batchedUnitVectorGetSupportingVertexWithoutMargin(const btVector3* vectors, btVector3* supportVerticesOut,
	                                                       int numVectors) const override;

	/// Sets the margin and keeps the outer size (clamped as described above).
	void setMargin(btScalar collisionMargin) override;
	/// Sets the scaling and rescales the outer size.
	void setLocalScaling(const btVector3& scaling) override;

	/// The exact world AABB of the full box.
	void getAabb(const btTransform& t, btVector3& aabbMin, btVector3& aabbMax) const override;

	/// Solid box of the full size: m (b^2 + c^2) / 12 and so on, with b, c the full side lengths. A negative
	/// or non-finite mass asserts and gives (0, 0, 0).
	void calculateLocalInertia(btScalar mass, btVector3 & inertia) const override;

	/// Face plane i (0..5: +x, -x, +y, -y, +z, -z) as an outward normal and a point of the full box on it
	/// (an index outside 0..5 asserts and gives face 0).
	void getPlane(btVector3 & planeNormal, btVector3 & planeSupport, int i) const override;
	/// 6.
	int getNumPlanes() const override { return 6; }
	/// 8.
	int getNumVertices() const override { return 8; }
	/// 12.
	int getNumEdges() const override { return 12; }
	/// Corner i (0..7) of the full box: bit 0, 1, 2 of i set means the negative side on x, y, z.
	void getVertex(int i, btVector3& vtx) const override;
	/// Plane equation of face i of the core: (normal, -half extent), so normal . x + w = 0 on the face
	/// (an index outside 0..5 asserts and gives face 0).
	virtual void getPlaneEquation(btVector4 & plane, int i) const;
	/// The end points (corners of the full box) of edge i, 0..11 (other indices assert and give edge 0).
	void getEdge(int i, btVector3& pa, btVector3& pb) const override;
	/// True when pt lies in the core grown by tolerance.
	bool isInside(const btVector3& pt, btScalar tolerance) const override;

	/// "Box".
	const char* getName() const override { return "Box"; }

	/// 6: the face normals.
	int getNumPreferredPenetrationDirections() const override { return 6; }
	/// Face normal index (0..5: +x, -x, +y, -y, +z, -z); other indices assert and give (0, 0, 0).
	void getPreferredPenetrationDirection(int index, btVector3& penetrationVector) const override;
};

#endif  // BT_OBB_BOX_MINKOWSKI_H
