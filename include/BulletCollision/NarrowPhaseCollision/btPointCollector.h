// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef BT_POINT_COLLECTOR_H
#define BT_POINT_COLLECTOR_H

/// btPointCollector: a detector result that keeps the closest (or deepest) point.

#include "BulletCollision/NarrowPhaseCollision/btDiscreteCollisionDetectorInterface.h"

/// Keeps the reported point of smallest signed distance, with its normal.
struct btPointCollector : public btDiscreteCollisionDetectorInterface::Result
{
	/// Normal from B towards A of the kept point.
	btVector3 m_normalOnBInWorld;
	/// The kept point (on B).
	btVector3 m_pointInWorld;
	/// Signed distance of the kept point; BT_LARGE_FLOAT while none (negative when penetrating).
	btScalar m_distance;
	/// True once a point has been kept.
	bool m_hasResult;

	/// Nothing kept yet.
	btPointCollector()
	    : m_normalOnBInWorld(0, 0, 0), m_pointInWorld(0, 0, 0), m_distance(btScalar(BT_LARGE_FLOAT)), m_hasResult(false)
	{
	}

	/// Shape identifiers are not recorded.
	void setShapeIdentifiersA(int partId0, int index0) override
	{
		(void)partId0;
		(void)index0;
	}
	/// Shape identifiers are not recorded.
	void setShapeIdentifiersB(int partId1, int index1) override
	{
		(void)partId1;
		(void)index1;
	}

	/// Keeps the point when its depth is below the kept one.
	void addContactPoint(const btVector3& normalOnBInWorld, const btVector3& pointInWorld, btScalar depth) override
	{
		if (depth < m_distance)
		{
			m_hasResult = true;
			m_normalOnBInWorld = normalOnBInWorld;
			m_pointInWorld = pointInWorld;
			m_distance = depth;
		}
	}
};

#endif  // BT_POINT_COLLECTOR_H
