// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef BT_MANIFOLD_RESULT_H
#define BT_MANIFOLD_RESULT_H

/// btManifoldResult: turns the points a narrowphase reports into persistent manifold points.

#include "BulletCollision/CollisionDispatch/btCollisionObject.h"
#include "BulletCollision/CollisionDispatch/btCollisionObjectWrapper.h"
#include "BulletCollision/NarrowPhaseCollision/btDiscreteCollisionDetectorInterface.h"
#include "BulletCollision/NarrowPhaseCollision/btPersistentManifold.h"

class btManifoldPoint;

/// Called for each new or refreshed point when either object has CF_CUSTOM_MATERIAL_CALLBACK; may edit
/// the point (friction, restitution, ...). The return value is ignored.
typedef bool (*ContactAddedCallback)(btManifoldPoint& cp, const btCollisionObjectWrapper* colObj0Wrap, int partId0,
                                     int index0, const btCollisionObjectWrapper* colObj1Wrap, int partId1, int index1);
/// Global contact-added hook (null: none).
extern ContactAddedCallback gContactAddedCallback;

/// Combines a material property of two objects.
typedef btScalar (*CalculateCombinedCallback)(const btCollisionObject* body0, const btCollisionObject* body1);
/// Restitution combiner (default: btManifoldResult::calculateCombinedRestitution).
extern CalculateCombinedCallback gCalculateCombinedRestitutionCallback;
/// Friction combiner (default: btManifoldResult::calculateCombinedFriction).
extern CalculateCombinedCallback gCalculateCombinedFrictionCallback;
/// Rolling friction combiner (default: btManifoldResult::calculateCombinedRollingFriction).
extern CalculateCombinedCallback gCalculateCombinedRollingFrictionCallback;
/// Spinning friction combiner (default: btManifoldResult::calculateCombinedSpinningFriction).
extern CalculateCombinedCallback gCalculateCombinedSpinningFrictionCallback;
/// Contact damping combiner (default: btManifoldResult::calculateCombinedContactDamping).
extern CalculateCombinedCallback gCalculateCombinedContactDampingCallback;
/// Contact stiffness combiner (default: btManifoldResult::calculateCombinedContactStiffness).
extern CalculateCombinedCallback gCalculateCombinedContactStiffnessCallback;

/// The Result that algorithms report to: stores points in a persistent manifold in the manifold's body
/// order (swapping when the algorithm's body 0 is the manifold's body 1), with combined materials.
class btManifoldResult : public btDiscreteCollisionDetectorInterface::Result
{
protected:
	/// The manifold points go to (null: points are dropped).
	btPersistentManifold* m_manifoldPtr;
	/// First object of the query.
	const btCollisionObjectWrapper* m_body0Wrap;
	/// Second object of the query.
	const btCollisionObjectWrapper* m_body1Wrap;
	/// Part id of the next points on body 0.
	int m_partId0;
	/// Part id of the next points on body 1.
	int m_partId1;
	/// Child/triangle index of the next points on body 0.
	int m_index0;
	/// Child/triangle index of the next points on body 1.
	int m_index1;

public:
	/// A result with no bodies and no manifold.
	btManifoldResult()
	    : m_manifoldPtr(0),
	      m_body0Wrap(0),
	      m_body1Wrap(0),
	      m_partId0(-1),
	      m_partId1(-1),
	      m_index0(-1),
	      m_index1(-1),
	      m_closestPointDistanceThreshold(0)
	{
	}
	/// A result for the pair (body0Wrap, body1Wrap), part ids and indices taken from the wrappers.
	btManifoldResult(const btCollisionObjectWrapper* body0Wrap, const btCollisionObjectWrapper* body1Wrap);
	/// Results are deleted through base pointers.
	~btManifoldResult() override {}

	/// Sets the manifold points go to.
	void setPersistentManifold(btPersistentManifold* manifoldPtr) { m_manifoldPtr = manifoldPtr; }
	/// The manifold points go to.
	const btPersistentManifold* getPersistentManifold() const { return m_manifoldPtr; }
	/// The manifold points go to.
	btPersistentManifold* getPersistentManifold() { return m_manifoldPtr; }

	/// Part and index of body 0 for the next points.
	void setShapeIdentifiersA(int partId0, int index0) override
	{
		m_partId0 = partId0;
		m_index0 = index0;
	}
	/// Part and index of body 1 for the next points.
	void setShapeIdentifiersB(int partId1, int index1) override
	{
		m_partId1 = partId1;
		m_index1 = index1;
	}

	/// Adds a point: normal from the manifold's body 1 towards its body 0, the point on body 1 and the
	/// signed distance. Points farther than the breaking threshold (plus m_closestPointDistanceThreshold)
	/// are ignored; non-finite input asserts and is ignored in release. Without a manifold it does nothing.
	void addContactPoint(const btVector3& normalOnBInWorld, const btVector3& pointInWorld, btScalar depth) override;

	/// Refreshes the manifold's points with the bodies' current transforms (in the manifold's order).
	void refreshContactPoints();

	/// First object of the query.
	const btCollisionObjectWrapper* getBody0Wrap() const { return m_body0Wrap; }
	/// Second object of the query.
	const btCollisionObjectWrapper* getBody1Wrap() const { return m_body1Wrap; }
	/// Replaces the first object (compound algorithms point it at a child).
	void setBody0Wrap(const btCollisionObjectWrapper* obj0Wrap) { m_body0Wrap = obj0Wrap; }
	/// Replaces the second object.
	void setBody1Wrap(const btCollisionObjectWrapper* obj1Wrap) { m_body1Wrap = obj1Wrap; }
	/// The first object.
	const btCollisionObject* getBody0Internal() const { return m_body0Wrap->getCollisionObject(); }
	/// The second object.
	const btCollisionObject* getBody1Internal() const { return m_body1Wrap->getCollisionObject(); }

	/// Extra distance beyond the breaking threshold at which points are still reported (closest-point
	/// queries set it; 0 for the simulation).
	btScalar m_closestPointDistanceThreshold;

	/// restitution0 * restitution1.
	static btScalar calculateCombinedRestitution(const btCollisionObject* body0, const btCollisionObject* body1);
	/// friction0 * friction1, clamped to [-10, 10].
	static btScalar calculateCombinedFriction(const btCollisionObject* body0, const btCollisionObject* body1);
	/// rolling0 * friction1 + friction0 * rolling1, clamped to [-10, 10].
	static btScalar calculateCombinedRollingFriction(const btCollisionObject* body0, const btCollisionObject* body1);
	/// spinning0 * friction1 + friction0 * spinning1, clamped to [-10, 10].
	static btScalar calculateCombinedSpinningFriction(const btCollisionObject* body0, const btCollisionObject* body1);
	/// damping0 + damping1.
	static btScalar calculateCombinedContactDamping(const btCollisionObject* body0, const btCollisionObject* body1);
	/// The stiffness of two springs in series: 1 / (1 / stiffness0 + 1 / stiffness1).
	static btScalar calculateCombinedContactStiffness(const btCollisionObject* body0, const btCollisionObject* body1);
};

#endif  // BT_MANIFOLD_RESULT_H
