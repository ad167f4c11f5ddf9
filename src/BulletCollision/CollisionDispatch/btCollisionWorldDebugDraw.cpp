// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "BulletCollision/CollisionDispatch/btCollisionWorld.h"
#include "BulletCollision/CollisionShapes/btBoxShape.h"
#include "BulletCollision/CollisionShapes/btCapsuleShape.h"
#include "BulletCollision/CollisionShapes/btCompoundShape.h"
#include "BulletCollision/CollisionShapes/btConcaveShape.h"
#include "BulletCollision/CollisionShapes/btConeShape.h"
#include "BulletCollision/CollisionShapes/btCylinderShape.h"
#include "BulletCollision/CollisionShapes/btMultiSphereShape.h"
#include "BulletCollision/CollisionShapes/btPolyhedralConvexShape.h"
#include "BulletCollision/CollisionShapes/btShapeGuards.h"
#include "BulletCollision/CollisionShapes/btSphereShape.h"
#include "BulletCollision/CollisionShapes/btStaticPlaneShape.h"
#include "BulletCollision/CollisionShapes/btTriangleCallback.h"
#include "BulletCollision/NarrowPhaseCollision/btPersistentManifold.h"
#include "LinearMath/btIDebugDraw.h"
#include "LinearMath/btQuickprof.h"

// Debug drawing of the world: shapes as wireframes, AABBs and contact points, as the drawer's mode asks.

namespace
{
// Draws the edges of each triangle a concave shape reports, placed in the world.
class WireframeTriangleCallback : public btTriangleCallback
{
public:
	WireframeTriangleCallback(btIDebugDraw* drawer, const btTransform& worldTransform, const btVector3& color)
	    : m_drawer(drawer), m_worldTransform(worldTransform), m_color(color)
	{
	}

	void processTriangle(btVector3* triangle, int partId, int triangleIndex) override
	{
		(void)partId;
		(void)triangleIndex;
		const btVector3 a = m_worldTransform * triangle[0];
		const btVector3 b = m_worldTransform * triangle[1];
		const btVector3 c = m_worldTransform * triangle[2];
		m_drawer->drawLine(a, b, m_color);
		m_drawer->drawLine(b, c, m_color);
		m_drawer->drawLine(c, a, m_color);
	}

private:
	btIDebugDraw* m_drawer;
	const btTransform& m_worldTransform;
	btVector3 m_color;
};

btVector3 activationColor(const btCollisionObject* colObj, const btIDebugDraw::DefaultColors& colors)
{
	btVector3 color;
	if (colObj->getCustomDebugColor(color)) return color;
	switch (colObj->getActivationState())
	{
		case ACTIVE_TAG:
			return colors.m_activeObject;
		case ISLAND_SLEEPING:
			return colors.m_deactivatedObject;
		case WANTS_DEACTIVATION:
			return colors.m_wantsDeactivationObject;
		case DISABLE_DEACTIVATION:
			return colors.m_disabledDeactivationObject;
		case DISABLE_SIMULATION:
			return colors.m_disabledSimulationObject;
		default:
			return btVector3(btScalar(1), btScalar(0), btScalar(0));
	}
}
}  // namespace

void btCollisionWorld::debugDrawObject(const btTransform& worldTransform, const btCollisionShape* shape,
                                       const btVector3& color)
{
	btIDebugDraw* drawer = getDebugDrawer();
	if (!drawer || !shape || !caliber::isFinite(worldTransform)) return;
	if (drawer->getDebugMode() & btIDebugDraw::DBG_DrawFrames) drawer->drawTransform(worldTransform, btScalar(0.1));

	switch (shape->getShapeType())
	{
		case COMPOUND_SHAPE_PROXYTYPE:
		{
			const btCompoundShape* compound = static_cast<const btCompoundShape*>(shape);
			for (int i = compound->getNumChildShapes() - 1; i >= 0; i--)
				debugDrawObject(worldTransform * compound->getChildTransform(i), compound->getChildShape(i), color);
			return;
		}
		case BOX_SHAPE_PROXYTYPE:
		{
			const btVector3 halfExtents = static_cast<const btBoxShape*>(shape)->getHalfExtentsWithMargin();
			drawer->drawBox(-halfExtents, halfExtents, worldTransform, color);
			return;
		}
		case SPHERE_SHAPE_PROXYTYPE:
			drawer->drawSphere(static_cast<const btSphereShape*>(shape)->getRadius(), worldTransform, color);
			return;
		case MULTI_SPHERE_SHAPE_PROXYTYPE:
		{
			const btMultiSphereShape* spheres = static_cast<const btMultiSphereShape*>(shape);
			for (int i = spheres->getSphereCount() - 1; i >= 0; i--)
			{
				btTransform sphereTransform = worldTransform;
				sphereTransform.setOrigin(worldTransform * spheres->getSpherePosition(i));
				drawer->drawSphere(spheres->getSphereRadius(i), sphereTransform, color);
			}
			return;
		}
		case CAPSULE_SHAPE_PROXYTYPE:
		{
			const btCapsuleShape* capsule = static_cast<const btCapsuleShape*>(shape);
			drawer->drawCapsule(capsule->getRadius(), capsule->getHalfHeight(), capsule->getUpAxis(), worldTransform,
			                    color);
			return;
		}
		case CONE_SHAPE_PROXYTYPE:
		{
			const btConeShape* cone = static_cast<const btConeShape*>(shape);
			drawer->drawCone(cone->getRadius(), cone->getHeight(), cone->getConeUpIndex(), worldTransform, color);
			return;
		}
		case CYLINDER_SHAPE_PROXYTYPE:
		{
			const btCylinderShape* cylinder = static_cast<const btCylinderShape*>(shape);
			const int upAxis = cylinder->getUpAxis();
			drawer->drawCylinder(cylinder->getRadius(), cylinder->getHalfExtentsWithMargin()[upAxis], upAxis,
			                     worldTransform, color);
			return;
		}
		case STATIC_PLANE_PROXYTYPE:
		{
			const btStaticPlaneShape* plane = static_cast<const btStaticPlaneShape*>(shape);
			drawer->drawPlane(plane->getPlaneNormal(), plane->getPlaneConstant(), worldTransform, color);
			return;
		}
		default:
			break;
	}

	if (shape->isPolyhedral())
	{
		const btPolyhedralConvexShape* polyhedral = static_cast<const btPolyhedralConvexShape*>(shape);
		for (int i = 0; i < polyhedral->getNumEdges(); i++)
		{
			btVector3 a, b;
			polyhedral->getEdge(i, a, b);
			drawer->drawLine(worldTransform * a, worldTransform * b, color);
		}
		return;
	}
	if (shape->isConcave())
	{
		// Every triangle: debug drawing is not a hot path, and a partial mesh would mislead.
		const btVector3 everywhere(BT_LARGE_FLOAT, BT_LARGE_FLOAT, BT_LARGE_FLOAT);
		WireframeTriangleCallback callback(drawer, worldTransform, color);
		static_cast<const btConcaveShape*>(shape)->processAllTriangles(&callback, -everywhere, everywhere);
	}
	// Other convex shapes (Minkowski sums, scaled shapes, ...) have no cheap wireframe; their AABB is
	// drawn with DBG_DrawAabb.
}

void btCollisionWorld::debugDrawWorld()
{
	BT_PROFILE("debugDrawWorld");
	btIDebugDraw* drawer = getDebugDrawer();
	if (!drawer) return;
	const int mode = drawer->getDebugMode();
	const btIDebugDraw::DefaultColors colors = drawer->getDefaultColors();

	if ((mode & btIDebugDraw::DBG_DrawContactPoints) && m_dispatcher1)
	{
		const int numManifolds = m_dispatcher1->getNumManifolds();
		for (int i = 0; i < numManifolds; i++)
		{
			const btPersistentManifold* manifold = m_dispatcher1->getManifoldByIndexInternal(i);
			for (int j = 0; j < manifold->getNumContacts(); j++)
			{
				const btManifoldPoint& point = manifold->getContactPoint(j);
				drawer->drawContactPoint(point.m_positionWorldOnB, point.m_normalWorldOnB, point.getDistance(),
				                         point.getLifeTime(), colors.m_contactPoint);
			}
		}
	}

	if (!(mode & (btIDebugDraw::DBG_DrawWireframe | btIDebugDraw::DBG_DrawAabb))) return;
	for (int i = 0; i < m_collisionObjects.size(); i++)
	{
		const btCollisionObject* colObj = m_collisionObjects[i];
		if (colObj->getCollisionFlags() & btCollisionObject::CF_DISABLE_VISUALIZE_OBJECT) continue;
		if (!colObj->getCollisionShape() || !caliber::isFinite(colObj->getWorldTransform())) continue;
		if (mode & btIDebugDraw::DBG_DrawWireframe)
			debugDrawObject(colObj->getWorldTransform(), colObj->getCollisionShape(), activationColor(colObj, colors));
		if (mode & btIDebugDraw::DBG_DrawAabb)
		{
			btVector3 aabbMin, aabbMax;
			colObj->getCollisionShape()->getAabb(colObj->getWorldTransform(), aabbMin, aabbMax);
			const btVector3 threshold(gContactBreakingThreshold, gContactBreakingThreshold, gContactBreakingThreshold);
			drawer->drawAabb(aabbMin - threshold, aabbMax + threshold, colors.m_aabb);
		}
	}
}
