// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "BulletCollision/CollisionShapes/btScaledBvhTriangleMeshShape.h"

#include "LinearMath/btAabbUtil2.h"
#include "btShapeGuards.h"

namespace
{
// Scales the child's triangles on their way to the user's callback.
class ScaledTriangleCallback : public btTriangleCallback
{
public:
	ScaledTriangleCallback(btTriangleCallback* callback, const btVector3& scaling)
	    : m_callback(callback), m_scaling(scaling)
	{
	}
	void processTriangle(btVector3* triangle, int partId, int triangleIndex) override
	{
		btVector3 scaled[3] = {triangle[0] * m_scaling, triangle[1] * m_scaling, triangle[2] * m_scaling};
		m_callback->processTriangle(scaled, partId, triangleIndex);
	}

private:
	btTriangleCallback* m_callback;
	btVector3 m_scaling;
};

// The box [aabbMin, aabbMax] scaled per axis (negative factors swap the ends).
void scaleBox(const btVector3& aabbMin, const btVector3& aabbMax, const btVector3& scaling, btVector3& outMin,
              btVector3& outMax)
{
	const btVector3 a = aabbMin * scaling, b = aabbMax * scaling;
	outMin = a;
	outMin.setMin(b);
	outMax = a;
	outMax.setMax(b);
}
}  // namespace

btScaledBvhTriangleMeshShape::btScaledBvhTriangleMeshShape(btBvhTriangleMeshShape* childShape,
                                                           const btVector3& localScaling)
    : m_localScaling(1, 1, 1), m_bvhTriMeshShape(childShape)
{
	m_shapeType = SCALED_TRIANGLE_MESH_SHAPE_PROXYTYPE;
	btAssert(childShape != 0 && "btScaledBvhTriangleMeshShape: null child");
	setLocalScaling(localScaling);
}

btScaledBvhTriangleMeshShape::~btScaledBvhTriangleMeshShape() {}

void btScaledBvhTriangleMeshShape::setLocalScaling(const btVector3& scaling)
{
	btAssert(caliber::isFinite(scaling) && "setLocalScaling: non-finite scaling");
	if (caliber::isFinite(scaling)) m_localScaling = scaling;
}

void btScaledBvhTriangleMeshShape::getAabb(const btTransform& t, btVector3& aabbMin, btVector3& aabbMax) const
{
	if (!caliber::checkAabbTransform(t, aabbMin, aabbMax)) return;
	btVector3 localMin(0, 0, 0), localMax(0, 0, 0);
	btScalar margin = 0;
	if (m_bvhTriMeshShape)
	{
		scaleBox(m_bvhTriMeshShape->getLocalAabbMin(), m_bvhTriMeshShape->getLocalAabbMax(), m_localScaling, localMin,
		         localMax);
		margin = m_bvhTriMeshShape->getMargin();
	}
	btTransformAabb(localMin, localMax, margin, t, aabbMin, aabbMax);
}

void btScaledBvhTriangleMeshShape::calculateLocalInertia(btScalar mass, btVector3& inertia) const
{
	btAssert(mass == btScalar(0) && "triangle mesh shapes are static: use mass 0");
	(void)mass;
	inertia.setValue(0, 0, 0);
}

void btScaledBvhTriangleMeshShape::processAllTriangles(btTriangleCallback* callback, const btVector3& aabbMin,
                                                       const btVector3& aabbMax) const
{
	btAssert(callback != 0);
	if (!callback || !m_bvhTriMeshShape) return;
	const bool finite = caliber::isFinite(aabbMin) && caliber::isFinite(aabbMax);
	btAssert(finite && "processAllTriangles: non-finite box");
	if (!finite) return;
	// Map the query box into the child's space: divide by the scaling. A zero factor flattens that axis to
	// 0, so the box selects everything on that axis when it contains 0 and nothing otherwise.
	btVector3 childMin, childMax;
	for (int a = 0; a < 3; ++a)
	{
		const btScalar s = m_localScaling[a];
		if (s == btScalar(0))
		{
			if (aabbMin[a] > btScalar(0) || aabbMax[a] < btScalar(0)) return;
			childMin[a] = -BT_LARGE_FLOAT;
			childMax[a] = BT_LARGE_FLOAT;
			continue;
		}
		// A tiny factor may overflow the quotient; the clamp keeps the box finite (and still all-covering).
		const btScalar lo = aabbMin[a] / s, hi = aabbMax[a] / s;
		childMin[a] = btMax(btMin(lo, hi), -BT_LARGE_FLOAT);
		childMax[a] = btMin(btMax(lo, hi), BT_LARGE_FLOAT);
	}
	childMin[3] = childMax[3] = 0;
	ScaledTriangleCallback scaled(callback, m_localScaling);
	m_bvhTriMeshShape->processAllTriangles(&scaled, childMin, childMax);
}
