// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef BT_CONVEX_INTERNAL_SHAPE_H
#define BT_CONVEX_INTERNAL_SHAPE_H

#include "BulletCollision/CollisionShapes/btCollisionMargin.h"
#include "BulletCollision/CollisionShapes/btConvexShape.h"
#include "LinearMath/btAabbUtil2.h"

/// A convex shape that stores its local scaling, its implicit dimensions (half extents, radius, ...)
/// and a collision margin. Bad input is sanitised: negative scaling components are made positive,
/// non-finite scaling is ignored, negative or non-finite margins become 0 (each asserts first).
ATTRIBUTE_ALIGNED16(class)
btConvexInternalShape : public btConvexShape
{
protected:
	/// The local scaling (components >= 0).
	btVector3 m_localScaling;
	/// The shape's own dimensions (half extents, radius...), meaning set by the derived shape.
	btVector3 m_implicitShapeDimensions;
	/// The collision margin.
	btScalar m_collisionMargin;
	/// Padding (kept for Bullet's layout).
	btScalar m_padding;

	/// Scaling (1, 1, 1), zero dimensions, margin CONVEX_DISTANCE_MARGIN.
	btConvexInternalShape();

public:
	BT_DECLARE_ALIGNED_ALLOCATOR();

	/// Shapes are deleted through base pointers.
	virtual ~btConvexInternalShape();

	/// The margin-free support plus getMargin() along the normalised vec. A zero, tiny or non-finite vec
	/// is replaced by (-1, -1, -1), so the result is always a finite point on the surface.
	btVector3 localGetSupportingVertex(const btVector3& vec) const override;

	/// The implicit dimensions (their meaning depends on the shape).
	const btVector3& getImplicitShapeDimensions() const { return m_implicitShapeDimensions; }
	/// Sets the implicit dimensions directly, with no margin adjustment (Bullet's expert setter).
	void setImplicitShapeDimensions(const btVector3& dimensions) { m_implicitShapeDimensions = dimensions; }

	/// Lowers the margin to defaultMarginMultiplier * minDimension if that is smaller than the current one,
	/// so that thin shapes keep a margin smaller than themselves.
	void setSafeMargin(btScalar minDimension, btScalar defaultMarginMultiplier = btScalar(0.1));
	/// setSafeMargin with the smallest of the half extents.
	void setSafeMargin(const btVector3& halfExtents, btScalar defaultMarginMultiplier = btScalar(0.1));

	/// The world AABB by support points (getAabbSlow); shapes override it with closed forms.
	void getAabb(const btTransform& t, btVector3& aabbMin, btVector3& aabbMax) const override
	{
		getAabbSlow(t, aabbMin, aabbMax);
	}
	/// The tight world AABB of the shape with margin, from its support points along the six world axes.
	/// A non-finite t asserts and gives [-BT_LARGE_FLOAT, BT_LARGE_FLOAT]^3 in release builds.
	void getAabbSlow(const btTransform& t, btVector3& aabbMin, btVector3& aabbMax) const override;

	/// Sets the scaling to |scaling| per component; a non-finite scaling asserts and is ignored.
	void setLocalScaling(const btVector3& scaling) override;
	/// The local scaling.
	const btVector3& getLocalScaling() const override { return m_localScaling; }
	/// The local scaling, non-virtual.
	const btVector3& getLocalScalingNV() const { return m_localScaling; }

	/// Sets the margin; a negative or non-finite margin asserts and becomes 0.
	void setMargin(btScalar margin) override;
	/// The margin.
	btScalar getMargin() const override { return m_collisionMargin; }
	/// The margin, non-virtual.
	btScalar getMarginNV() const { return m_collisionMargin; }

	/// No preferred penetration directions by default.
	int getNumPreferredPenetrationDirections() const override { return 0; }
	/// Asserts (there are none); gives (0, 0, 0) in release builds.
	void getPreferredPenetrationDirection(int index, btVector3& penetrationVector) const override;
};

/// A btConvexInternalShape that caches its local AABB (for shapes whose support function is costly).
ATTRIBUTE_ALIGNED16(class)
btConvexInternalAabbCachingShape : public btConvexInternalShape
{
	btVector3 m_localAabbMin;
	btVector3 m_localAabbMax;
	bool m_isLocalAabbValid;

protected:
	/// An empty, invalid cache.
	btConvexInternalAabbCachingShape();

	/// Stores the local AABB (margin excluded).
	void setCachedLocalAabb(const btVector3& aabbMin, const btVector3& aabbMax)
	{
		m_isLocalAabbValid = true;
		m_localAabbMin = aabbMin;
		m_localAabbMax = aabbMax;
	}
	/// The stored local AABB (asserts when the cache is invalid).
	void getCachedLocalAabb(btVector3 & aabbMin, btVector3 & aabbMax) const
	{
		btAssert(m_isLocalAabbValid);
		aabbMin = m_localAabbMin;
		aabbMax = m_localAabbMax;
	}
	/// The world AABB from the cached local AABB grown by margin under trans.
	void getNonvirtualAabb(const btTransform& trans, btVector3& aabbMin, btVector3& aabbMax, btScalar margin) const;

public:
	BT_DECLARE_ALIGNED_ALLOCATOR();

	/// Sets the scaling and recomputes the cached AABB.
	void setLocalScaling(const btVector3& scaling) override;
	/// The world AABB from the cache (margin included).
	void getAabb(const btTransform& t, btVector3& aabbMin, btVector3& aabbMax) const override;
	/// Recomputes the cached local AABB from the margin-free support along the six local axes.
	void recalcLocalAabb();
};

#endif  // BT_CONVEX_INTERNAL_SHAPE_H
