// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "BulletCollision/CollisionShapes/btConvexShape.h"

#include "BulletCollision/CollisionShapes/btBoxShape.h"
#include "BulletCollision/CollisionShapes/btCapsuleShape.h"
#include "BulletCollision/CollisionShapes/btCylinderShape.h"
#include "BulletCollision/CollisionShapes/btShapeGuards.h"
#include "BulletCollision/CollisionShapes/btSphereShape.h"

btConvexShape::btConvexShape() {}

btConvexShape::~btConvexShape() {}

void btConvexShape::project(const btTransform& trans, const btVector3& dir, btScalar& minProj, btScalar& maxProj,
                            btVector3& witnesPtMin, btVector3& witnesPtMax) const
{
	// The extremes along a world direction are the supports along that direction in local coordinates.
	const btVector3 localDir = dir * trans.getBasis();
	witnesPtMax = trans(localGetSupportingVertex(localDir));
	witnesPtMin = trans(localGetSupportingVertex(-localDir));
	maxProj = witnesPtMax.dot(dir);
	minProj = witnesPtMin.dot(dir);
	if (minProj > maxProj)
	{
		btSwap(minProj, maxProj);
		btSwap(witnesPtMin, witnesPtMax);
	}
}

// The non-virtual entry points dispatch on the shape type for the primitives whose headers this file
// includes, and fall back to the virtual function for every other shape, so they are always correct.

btVector3 btConvexShape::localGetSupportVertexWithoutMarginNonVirtual(const btVector3& vec) const
{
	switch (m_shapeType)
	{
		case SPHERE_SHAPE_PROXYTYPE:
			return btVector3(btScalar(0), btScalar(0), btScalar(0));
		case BOX_SHAPE_PROXYTYPE:
			return static_cast<const btBoxShape*>(this)->btBoxShape::localGetSupportingVertexWithoutMargin(vec);
		case CAPSULE_SHAPE_PROXYTYPE:
			return static_cast<const btCapsuleShape*>(this)->btCapsuleShape::localGetSupportingVertexWithoutMargin(vec);
		case CYLINDER_SHAPE_PROXYTYPE:
			return static_cast<const btCylinderShape*>(this)->btCylinderShape::localGetSupportingVertexWithoutMargin(
			    vec);
		default:
			return localGetSupportingVertexWithoutMargin(vec);
	}
}

btVector3 btConvexShape::localGetSupportVertexNonVirtual(const btVector3& vec) const
{
	btVector3 dir = caliber::supportDirection(vec);
	const btVector3 core = localGetSupportVertexWithoutMarginNonVirtual(dir);
	return core + getMarginNonVirtual() * dir.safeNormalize();
}

btScalar btConvexShape::getMarginNonVirtual() const
{
	switch (m_shapeType)
	{
		case SPHERE_SHAPE_PROXYTYPE:
			return static_cast<const btSphereShape*>(this)->getRadius();
		case BOX_SHAPE_PROXYTYPE:
		case CAPSULE_SHAPE_PROXYTYPE:
		case CYLINDER_SHAPE_PROXYTYPE:
			return static_cast<const btConvexInternalShape*>(this)->getMarginNV();
		default:
			return getMargin();
	}
}

void btConvexShape::getAabbNonVirtual(const btTransform& t, btVector3& aabbMin, btVector3& aabbMax) const
{
	switch (m_shapeType)
	{
		case SPHERE_SHAPE_PROXYTYPE:
			static_cast<const btSphereShape*>(this)->btSphereShape::getAabb(t, aabbMin, aabbMax);
			return;
		case BOX_SHAPE_PROXYTYPE:
			static_cast<const btBoxShape*>(this)->btBoxShape::getAabb(t, aabbMin, aabbMax);
			return;
		case CAPSULE_SHAPE_PROXYTYPE:
			static_cast<const btCapsuleShape*>(this)->btCapsuleShape::getAabb(t, aabbMin, aabbMax);
			return;
		case CYLINDER_SHAPE_PROXYTYPE:
			static_cast<const btCylinderShape*>(this)->btCylinderShape::getAabb(t, aabbMin, aabbMax);
			return;
		default:
			getAabb(t, aabbMin, aabbMax);
			return;
	}
}
