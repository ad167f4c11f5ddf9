// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef CALIBER_PREDICTION_PROLOGUE_H
#define CALIBER_PREDICTION_PROLOGUE_H

#include "BulletCollision/CollisionDispatch/btAabbChunkPrologue.h"
#include "LinearMath/btAlignedObjectArray.h"
#include "LinearMath/btScalar.h"

class btDiscreteDynamicsWorld;
class btRigidBody;
struct btContactSolverInfo;

namespace caliber
{
/// predictUnconstraintMotion's work, handed to the world's updateAabbs (caliber::setAabbChunkPrologue) so
/// that each chunk of objects is predicted just before its boxes are computed, in the loop where the
/// broadphase's tree moves run in order on one task (docs/threading.md, "The prediction in the box loop").
/// A body's prediction reads and writes only that body, and nothing between the prediction and the boxes
/// reads a prediction in the world classes themselves (createPredictiveContacts releases manifolds only),
/// so the bits are those of predicting first.
class PredictionPrologue : public AabbChunkPrologue
{
public:
	PredictionPrologue() : m_bodies(0), m_numBodies(0), m_firstObject(0), m_timeStep(0), m_solverInfo(0) {}
	/// Prepares the hand-over for world's substep of timeStep. False (nothing to hand over: the world predicts
	/// as usual) unless the world is exactly btDiscreteDynamicsWorld or btDiscreteDynamicsWorldMt (a subclass
	/// may predict or read predictions otherwise), the scheduler runs more than one thread, and the world's
	/// moving bodies are one run of its object array, in the same order (then an object chunk's bodies are
	/// one range of bodies).
	/// `bodies` are the world's moving bodies (the ones predictUnconstraintMotion predicts).
	bool begin(btDiscreteDynamicsWorld& world, const btAlignedObjectArray<btRigidBody*>& bodies, btScalar timeStep);
	void prepareObjects(int objectBegin, int objectEnd) const override;
	void prepareAll() const override;

private:
	btRigidBody* const* m_bodies;
	int m_numBodies;
	int m_firstObject;  ///< the object index of m_bodies[0]
	btScalar m_timeStep;
	const btContactSolverInfo* m_solverInfo;
};
}  // namespace caliber

#endif
