// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef BT_DISCRETE_COLLISION_DETECTOR1_INTERFACE_H
#define BT_DISCRETE_COLLISION_DETECTOR1_INTERFACE_H

/// btDiscreteCollisionDetectorInterface: the closest-points query of a pair of shapes at one instant.
/// btStorageResult lives here too, as in Bullet, so that user code finds it at the same path.

#include "LinearMath/btTransform.h"
#include "LinearMath/btVector3.h"

class btIDebugDraw;

/// Finds the closest points (or the deepest penetration) of two shapes placed by two transforms.
struct btDiscreteCollisionDetectorInterface
{
	/// Receives the contact points a detector finds.
	struct Result
	{
		/// Results are deleted through base pointers.
		virtual ~Result() {}
		/// Part and triangle index of shape A the next points belong to (for meshes and compounds).
		virtual void setShapeIdentifiersA(int partId0, int index0) = 0;
		/// Part and triangle index of shape B the next points belong to.
		virtual void setShapeIdentifiersB(int partId1, int index1) = 0;
		/// One contact: unit normal from B towards A, the point on B, and the signed distance
		/// (negative when penetrating).
		virtual void addContactPoint(const btVector3& normalOnBInWorld, const btVector3& pointInWorld,
		                             btScalar depth) = 0;
	};

	/// The placement of the two shapes and how far apart points may be and still be reported.
	struct ClosestPointInput
	{
		/// No distance limit.
		ClosestPointInput() : m_maximumDistanceSquared(btScalar(BT_LARGE_FLOAT)) {}
		/// World transform of shape A.
		btTransform m_transformA;
		/// World transform of shape B.
		btTransform m_transformB;
		/// Squared distance beyond which no point is reported.
		btScalar m_maximumDistanceSquared;
	};

	/// Detectors are deleted through base pointers.
	virtual ~btDiscreteCollisionDetectorInterface() {}

	/// Computes the closest points of the pair and reports them to output. swapResults asks the detector
	/// to report with A and B exchanged (detectors that cannot ignore it).
	virtual void getClosestPoints(const ClosestPointInput& input, Result& output, btIDebugDraw* debugDraw,
	                              bool swapResults = false) = 0;
};

/// A Result that keeps the single closest (or deepest) point reported.
struct btStorageResult : public btDiscreteCollisionDetectorInterface::Result
{
	/// Normal on B of the kept point.
	btVector3 m_normalOnSurfaceB;
	/// Point on B of the kept point.
	btVector3 m_closestPointInB;
	/// Signed distance of the kept point (BT_LARGE_FLOAT while none).
	btScalar m_distance;

protected:
	/// Nothing stored yet.
	btStorageResult() : m_normalOnSurfaceB(0, 0, 0), m_closestPointInB(0, 0, 0), m_distance(btScalar(BT_LARGE_FLOAT)) {}

public:
	/// Results are deleted through base pointers.
	~btStorageResult() override {}

	/// Keeps the point when it is closer (or deeper) than the one kept so far.
	void addContactPoint(const btVector3& normalOnBInWorld, const btVector3& pointInWorld, btScalar depth) override
	{
		if (depth < m_distance)
		{
			m_normalOnSurfaceB = normalOnBInWorld;
			m_closestPointInB = pointInWorld;
			m_distance = depth;
		}
	}
};

#endif  // BT_DISCRETE_COLLISION_DETECTOR1_INTERFACE_H
