// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "BulletCollision/NarrowPhaseCollision/btConvexCast.h"

#include "BulletCollision/CollisionShapes/btConvexShape.h"
#include "BulletCollision/NarrowPhaseCollision/btGjkPairDetector.h"
#include "BulletCollision/NarrowPhaseCollision/btPointCollector.h"
#include "btConvexCastHelpers.h"

btConvexCast::~btConvexCast() {}

bool caliber::castClosestPoints(const btConvexShape* shapeA, const btConvexShape* shapeB, const btTransform& transA,
                                const btTransform& transB, btSimplexSolverInterface* simplexSolver,
                                btConvexPenetrationDepthSolver* depthSolver, const btVector3& axisHint,
                                btVector3& normal, btVector3& pointOnB, btScalar& distance)
{
	btGjkPairDetector detector(shapeA, shapeB, simplexSolver, depthSolver);
	if (!axisHint.fuzzyZero() && caliber::isFinite(axisHint)) detector.setCachedSeperatingAxis(axisHint);
	btDiscreteCollisionDetectorInterface::ClosestPointInput input;
	input.m_transformA = transA;
	input.m_transformB = transB;
	btPointCollector collector;
	detector.getClosestPointsNonVirtual(input, collector, nullptr);
	if (!collector.m_hasResult || !btIsFinite(collector.m_distance) ||
	    !caliber::isFinite(collector.m_normalOnBInWorld) || !caliber::isFinite(collector.m_pointInWorld))
		return false;
	normal = collector.m_normalOnBInWorld;
	pointOnB = collector.m_pointInWorld;
	distance = collector.m_distance;
	return true;
}
