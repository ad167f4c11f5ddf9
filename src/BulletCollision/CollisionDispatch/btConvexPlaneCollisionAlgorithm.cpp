// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "BulletCollision/CollisionDispatch/btConvexPlaneCollisionAlgorithm.h"

#include "BulletCollision/CollisionDispatch/btAlgorithmUtil.h"
#include "BulletCollision/CollisionDispatch/btCollisionObject.h"
#include "BulletCollision/CollisionDispatch/btManifoldResult.h"
#include "BulletCollision/CollisionShapes/btConvexShape.h"
#include "BulletCollision/CollisionShapes/btPolyhedralConvexShape.h"
#include "BulletCollision/CollisionShapes/btStaticPlaneShape.h"

namespace
{
// Shape types known to derive from btPolyhedralConvexShape, whose vertices can be listed.
bool hasVertexList(int shapeType)
{
	switch (shapeType)
	{
		case BOX_SHAPE_PROXYTYPE:
		case TRIANGLE_SHAPE_PROXYTYPE:
		case TETRAHEDRAL_SHAPE_PROXYTYPE:
		case CONVEX_TRIANGLEMESH_SHAPE_PROXYTYPE:
		case CONVEX_HULL_SHAPE_PROXYTYPE:
		case CONVEX_POINT_CLOUD_SHAPE_PROXYTYPE:
			return true;
		default:
			return false;
	}
}

// The world plane of a static plane shape: unit normal and a point on it.
void worldPlane(const btCollisionObjectWrapper* planeWrap, btVector3& normal, btVector3& pointOnPlane)
{
	const btStaticPlaneShape* plane = static_cast<const btStaticPlaneShape*>(planeWrap->getCollisionShape());
	const btTransform& planeTransform = planeWrap->getWorldTransform();
	normal = planeTransform.getBasis() * plane->getPlaneNormal();
	pointOnPlane = planeTransform(plane->getPlaneNormal() * plane->getPlaneConstant());
}
}  // namespace

btConvexPlaneCollisionAlgorithm::btConvexPlaneCollisionAlgorithm(btPersistentManifold* mf,
                                                                 const btCollisionAlgorithmConstructionInfo& ci,
                                                                 const btCollisionObjectWrapper* body0Wrap,
                                                                 const btCollisionObjectWrapper* body1Wrap,
                                                                 bool isSwapped, int numPerturbationIterations,
                                                                 int minimumPointsPerturbationThreshold)
    : btCollisionAlgorithm(ci),
      m_ownManifold(false),
      m_manifoldPtr(mf),
      m_isSwapped(isSwapped),
      m_numPerturbationIterations(numPerturbationIterations),
      m_minimumPointsPerturbationThreshold(minimumPointsPerturbationThreshold)
{
	const btCollisionObjectWrapper* convexWrap = isSwapped ? body1Wrap : body0Wrap;
	const btCollisionObjectWrapper* planeWrap = isSwapped ? body0Wrap : body1Wrap;
	if (!m_manifoldPtr && m_dispatcher &&
	    m_dispatcher->needsCollision(convexWrap->getCollisionObject(), planeWrap->getCollisionObject()))
	{
		// Always (convex, plane): the algorithm reports with the plane as B.
		m_manifoldPtr = m_dispatcher->getNewManifold(convexWrap->getCollisionObject(), planeWrap->getCollisionObject());
		m_ownManifold = true;
	}
}

btConvexPlaneCollisionAlgorithm::~btConvexPlaneCollisionAlgorithm()
{
	if (m_ownManifold && m_manifoldPtr) m_dispatcher->releaseManifold(m_manifoldPtr);
}

void btConvexPlaneCollisionAlgorithm::collideSingleContact(const btQuaternion& perturbeRot,
                                                           const btCollisionObjectWrapper* body0Wrap,
                                                           const btCollisionObjectWrapper* body1Wrap,
                                                           const btDispatcherInfo&, btManifoldResult* resultOut)
{
	const btCollisionObjectWrapper* convexWrap = m_isSwapped ? body1Wrap : body0Wrap;
	const btCollisionObjectWrapper* planeWrap = m_isSwapped ? body0Wrap : body1Wrap;
	const btConvexShape* convex = static_cast<const btConvexShape*>(convexWrap->getCollisionShape());
	const btTransform& convexTransform = convexWrap->getWorldTransform();

	btVector3 normal, pointOnPlane;
	worldPlane(planeWrap, normal, pointOnPlane);

	// Support of the copy rotated by perturbeRot about its origin, in direction -normal: the direction
	// seen from the rotated frame is (R_q R_c)^T (-normal). The point is then placed with the real
	// transform, so its depth is the true depth of a point of the real surface.
	const btMatrix3x3 perturbedBasis = btMatrix3x3(perturbeRot) * convexTransform.getBasis();
	const btVector3 localDirection = perturbedBasis.transpose() * (-normal);
	const btVector3 support = convexTransform(convex->localGetSupportingVertex(localDirection));
	const btScalar distance = normal.dot(support - pointOnPlane);
	if (distance < m_manifoldPtr->getContactBreakingThreshold() + resultOut->m_closestPointDistanceThreshold)
		resultOut->addContactPoint(normal, support - normal * distance, distance);
}

void btConvexPlaneCollisionAlgorithm::processCollision(const btCollisionObjectWrapper* body0Wrap,
                                                       const btCollisionObjectWrapper* body1Wrap,
                                                       const btDispatcherInfo& dispatchInfo,
                                                       btManifoldResult* resultOut)
{
	if (!m_manifoldPtr || !resultOut) return;
	resultOut->setPersistentManifold(m_manifoldPtr);
	if (!caliber::pairIsUsable(body0Wrap, body1Wrap))
	{
		if (m_ownManifold) m_manifoldPtr->clearManifold();
		return;
	}
	const btCollisionObjectWrapper* convexWrap = m_isSwapped ? body1Wrap : body0Wrap;
	const btCollisionObjectWrapper* planeWrap = m_isSwapped ? body0Wrap : body1Wrap;
	const btConvexShape* convex = static_cast<const btConvexShape*>(convexWrap->getCollisionShape());
	const btTransform& convexTransform = convexWrap->getWorldTransform();
	const btScalar reach = m_manifoldPtr->getContactBreakingThreshold() + resultOut->m_closestPointDistanceThreshold;

	btVector3 normal, pointOnPlane;
	worldPlane(planeWrap, normal, pointOnPlane);

	if (hasVertexList(convex->getShapeType()))
	{
		// Every vertex near the plane is a contact, so resting faces get all their corners in the first
		// frame. Boxes list their corners at full size; other polyhedra list the core, and the margin
		// (a sphere around each vertex) reaches deepest at vertex - margin * normal.
		const btPolyhedralConvexShape* polyhedron = static_cast<const btPolyhedralConvexShape*>(convex);
		const btScalar margin = convex->getShapeType() == BOX_SHAPE_PROXYTYPE ? btScalar(0) : convex->getMargin();
		const int numVertices = polyhedron->getNumVertices();
		// The deepest vertex goes in first so that a full manifold always keeps it.
		int deepest = -1;
		btScalar deepestDistance = reach;
		for (int i = 0; i < numVertices; ++i)
		{
			btVector3 vertex;
			polyhedron->getVertex(i, vertex);
			const btScalar distance = normal.dot(convexTransform(vertex) - pointOnPlane) - margin;
			if (distance < deepestDistance)
			{
				deepestDistance = distance;
				deepest = i;
			}
		}
		if (deepest >= 0)
		{
			for (int pass = 0; pass < 2; ++pass)
			{
				for (int i = 0; i < numVertices; ++i)
				{
					if ((pass == 0) != (i == deepest)) continue;
					btVector3 vertex;
					polyhedron->getVertex(i, vertex);
					const btVector3 worldVertex = convexTransform(vertex) - normal * margin;
					const btScalar distance = normal.dot(worldVertex - pointOnPlane);
					if (distance < reach) resultOut->addContactPoint(normal, worldVertex - normal * distance, distance);
				}
			}
		}
	}
	else
	{
		collideSingleContact(btQuaternion::getIdentity(), body0Wrap, body1Wrap, dispatchInfo, resultOut);

		// Tilted copies find more of a flat contact (a cylinder's rim, a capsule's second cap). A sphere
		// touches at one point only, so tilting would only add spurious neighbours.
		const bool isSphere = convex->getShapeType() == SPHERE_SHAPE_PROXYTYPE;
		if (!isSphere && m_numPerturbationIterations > 0 &&
		    m_manifoldPtr->getNumContacts() < m_minimumPointsPerturbationThreshold)
		{
			btVector3 tangent0, tangent1;
			btPlaneSpace1(normal, tangent0, tangent1);
			// Tilt just enough that the support moves across the flat part, capped at 22.5 degrees.
			const btScalar angleLimit = btScalar(0.125) * SIMD_PI;
			const btScalar disc = convex->getAngularMotionDisc();
			btScalar tiltAngle = disc > SIMD_EPSILON ? gContactBreakingThreshold / disc : angleLimit;
			if (tiltAngle > angleLimit) tiltAngle = angleLimit;
			const btQuaternion tilt(tangent0, tiltAngle);
			for (int i = 0; i < m_numPerturbationIterations; ++i)
			{
				const btScalar spin = SIMD_2_PI * btScalar(i) / btScalar(m_numPerturbationIterations);
				const btQuaternion aroundNormal(normal, spin);
				const btQuaternion perturbeRot = aroundNormal.inverse() * tilt * aroundNormal;
				collideSingleContact(perturbeRot, body0Wrap, body1Wrap, dispatchInfo, resultOut);
			}
		}
	}

	if (m_ownManifold && m_manifoldPtr->getNumContacts()) resultOut->refreshContactPoints();
}

btScalar btConvexPlaneCollisionAlgorithm::calculateTimeOfImpact(btCollisionObject*, btCollisionObject*,
                                                                const btDispatcherInfo&, btManifoldResult*)
{
	return btScalar(1);
}

void btConvexPlaneCollisionAlgorithm::getAllContactManifolds(btManifoldArray& manifoldArray)
{
	if (m_manifoldPtr && m_ownManifold) manifoldArray.push_back(m_manifoldPtr);
}
