// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef BT_DISCRETE_DYNAMICS_WORLD_H
#define BT_DISCRETE_DYNAMICS_WORLD_H

/// btDiscreteDynamicsWorld: the rigid-body world. The step, stage by stage, with the file of each, is
/// drawn in docs/architecture.md; the dynamics in docs/rigid-body-dynamics.md.

#include "BulletDynamics/Dynamics/btDynamicsWorld.h"
#include "LinearMath/btAlignedObjectArray.h"
#include "LinearMath/btThreads.h"

class btCollisionConfiguration;
class btConstraintSolver;
class btSimulationIslandManager;
class btTypedConstraint;
class btPersistentManifold;
class btSerializer;
struct InplaceSolverIslandCallback;

/// Steps rigid bodies in fixed substeps: predict motion, find contacts, build islands, solve, integrate
/// (with continuous collision for fast bodies), update actions and sleeping, then hand interpolated
/// transforms to the motion states. Bad input (non-finite time steps, bodies whose state has become
/// non-finite, bodies added twice or never added) is reported through btReportWarning and rejected or
/// taken out of the simulation; the rest of the world keeps simulating.
ATTRIBUTE_ALIGNED16(class)
btDiscreteDynamicsWorld : public btDynamicsWorld
{
protected:
	/// This step's enabled joints grouped by island (see docs/architecture.md).
	btAlignedObjectArray<btTypedConstraint*> m_sortedConstraints;
	InplaceSolverIslandCallback* m_solverIslandCallback;
	btConstraintSolver* m_constraintSolver;
	btSimulationIslandManager* m_islandManager;
	/// The bodies that may move (dynamic and kinematic), in insertion order.
	btAlignedObjectArray<btRigidBody*> m_nonStaticRigidBodies;
	btVector3 m_gravity;
	/// Time accumulated towards the next fixed substep.
	btScalar m_localTime;
	btScalar m_fixedTimeStep;
	bool m_ownsIslandManager;
	bool m_ownsConstraintSolver;
	bool m_synchronizeAllMotionStates;
	bool m_applySpeculativeContactRestitution;
	btAlignedObjectArray<btActionInterface*> m_actions;
	int m_profileTimings;
	bool m_latencyMotionStateInterpolation;
	/// The joints, in the order they were added.
	btAlignedObjectArray<btTypedConstraint*> m_constraints;
	/// Manifolds made for one step by createPredictiveContacts, released at the start of the next.
	/// Caliber makes none (its speculative contacts and the time-of-impact clamp of integrateTransforms
	/// cover fast bodies), so the array stays empty unless a subclass fills it with manifolds from the
	/// dispatcher's getNewManifold; those are solved with the others and released by
	/// releasePredictiveContacts.
	btAlignedObjectArray<btPersistentManifold*> m_predictiveManifolds;
	/// Held while m_predictiveManifolds is changed from several threads.
	btSpinMutex m_predictiveManifoldsMutex;

	/// Integrates forces into velocities, applies damping and predicts the end-of-step transforms.
	virtual void predictUnconstraintMotion(btScalar timeStep);
	/// Moves the bodies to their end-of-step transforms, clamping fast ones at their time of impact.
	void integrateTransformsInternal(btRigidBody * *bodies, int numBodies, btScalar timeStep);
	virtual void integrateTransforms(btScalar timeStep);
	/// Unites touching bodies into islands (and sets their island tags).
	virtual void calculateSimulationIslands();
	/// Runs the solver on every awake island.
	virtual void solveConstraints(btContactSolverInfo & solverInfo);
	/// Sleeping: accumulates still time and lets islands that have been still long enough fall asleep.
	virtual void updateActivationState(btScalar timeStep);
	void updateActions(btScalar timeStep);
	void startProfiling(btScalar timeStep);
	/// One fixed substep: the whole pipeline.
	virtual void internalSingleStepSimulation(btScalar timeStep);
	/// Releases every manifold of m_predictiveManifolds through the dispatcher and empties the array.
	void releasePredictiveContacts();
	/// Predictive contacts for fast bodies among bodies[0..numBodies): Caliber makes none (see
	/// m_predictiveManifolds); kept for subclasses that call it.
	void createPredictiveContactsInternal(btRigidBody * *bodies, int numBodies, btScalar timeStep);
	/// Each substep before collision detection: releases last step's predictive manifolds, then, with
	/// continuous collision on (getDispatchInfo().m_useContinuous), calls createPredictiveContactsInternal
	/// for the non-static bodies. Override it to make predictive contacts of your own.
	virtual void createPredictiveContacts(btScalar timeStep);
	/// Reads kinematic bodies' motion states and derives their velocities.
	virtual void saveKinematicState(btScalar timeStep);
	/// Writes every rigid body, then every joint, as chunks.
	void serializeRigidBodies(btSerializer * serializer);
	/// Writes gravity and the solver settings (btDynamicsWorldData) as a chunk.
	void serializeDynamicsWorldInfo(btSerializer * serializer);

public:
	BT_DECLARE_ALIGNED_ALLOCATOR();

	/// A world over the given dispatcher, broadphase and configuration (none owned). A null solver makes
	/// the world create (and own) a btSequentialImpulseConstraintSolver.
	btDiscreteDynamicsWorld(btDispatcher * dispatcher, btBroadphaseInterface * pairCache,
	                        btConstraintSolver * constraintSolver, btCollisionConfiguration * collisionConfiguration);
	virtual ~btDiscreteDynamicsWorld();

	int stepSimulation(btScalar timeStep, int maxSubSteps = 1, btScalar fixedTimeStep = btScalar(1.) / btScalar(60.))
	    override;

	void synchronizeMotionStates() override;
	/// Hands body's interpolated transform to its motion state.
	void synchronizeSingleMotionState(btRigidBody * body);

	/// Adds a joint (not owned). With disableCollisionsBetweenLinkedBodies the two bodies stop colliding
	/// with each other. A null joint, a joint added twice and a joint between a body and itself are
	/// reported and ignored.
	void addConstraint(btTypedConstraint * constraint, bool disableCollisionsBetweenLinkedBodies = false) override;
	void removeConstraint(btTypedConstraint * constraint) override;
	int getNumConstraints() const override { return m_constraints.size(); }
	btTypedConstraint* getConstraint(int index) override { return m_constraints[index]; }
	const btTypedConstraint* getConstraint(int index) const override { return m_constraints[index]; }
	/// Draws a joint's frames (DBG_DrawConstraints) and limits (DBG_DrawConstraintLimits).
	virtual void debugDrawConstraint(btTypedConstraint * constraint);

	void addAction(btActionInterface*) override;
	void removeAction(btActionInterface*) override;

	btSimulationIslandManager* getSimulationIslandManager() { return m_islandManager; }
	const btSimulationIslandManager* getSimulationIslandManager() const { return m_islandManager; }

	btCollisionWorld* getCollisionWorld() { return this; }

	void setGravity(const btVector3& gravity) override;
	btVector3 getGravity() const override;

	/// Non-rigid objects default to the static filter group, colliding with everything non-static.
	void addCollisionObject(
	    btCollisionObject * collisionObject, int collisionFilterGroup = btBroadphaseProxy::StaticFilter,
	    int collisionFilterMask = btBroadphaseProxy::AllFilter ^ btBroadphaseProxy::StaticFilter) override;

	/// Dynamic bodies join the default group and collide with everything; static and kinematic ones
	/// join the static group and do not collide with each other. The body gets the world's gravity unless
	/// it has BT_DISABLE_WORLD_GRAVITY.
	void addRigidBody(btRigidBody * body) override;
	void addRigidBody(btRigidBody * body, int group, int mask) override;
	/// A body that still has joints in this world takes them out of the world with it (reported with a
	/// warning), so that the world never holds a joint to a body it no longer simulates.
	void removeRigidBody(btRigidBody * body) override;

	/// Rigid bodies are removed as by removeRigidBody.
	void removeCollisionObject(btCollisionObject * collisionObject) override;

	void debugDrawWorld() override;

	/// The old solver is deleted if the world owned it; the new one is not owned.
	void setConstraintSolver(btConstraintSolver * solver) override;
	btConstraintSolver* getConstraintSolver() override;

	btDynamicsWorldType getWorldType() const override { return BT_DISCRETE_DYNAMICS_WORLD; }

	void clearForces() override;

	/// Adds each awake dynamic body's gravity to its accumulated force.
	virtual void applyGravity();

	/// Kept for source compatibility; the world runs on the calling thread.
	virtual void setNumTasks(int numTasks) { (void)numTasks; }

	/// Older name for updating the actions.
	virtual void updateVehicles(btScalar timeStep) { updateActions(timeStep); }

	/// Writes the world into serializer as a complete .bullet file (docs/serialization.md).
	void serialize(btSerializer * serializer) override;

	void addVehicle(btActionInterface * vehicle) override;
	void removeVehicle(btActionInterface * vehicle) override;
	void addCharacter(btActionInterface * character) override;
	void removeCharacter(btActionInterface * character) override;

	/// When true, sleeping bodies' motion states are updated too (default false).
	void setSynchronizeAllMotionStates(bool synchronizeAll) { m_synchronizeAllMotionStates = synchronizeAll; }
	bool getSynchronizeAllMotionStates() const { return m_synchronizeAllMotionStates; }

	/// When true, the contacts of the predictive manifolds (m_predictiveManifolds, which only a subclass
	/// fills in Caliber) take their bodies' combined restitution and bounce like other contacts; when false
	/// (the default) they keep the restitution they were made with. Caliber's own speculative contacts
	/// bounce either way.
	void setApplySpeculativeContactRestitution(bool enable) { m_applySpeculativeContactRestitution = enable; }
	bool getApplySpeculativeContactRestitution() const { return m_applySpeculativeContactRestitution; }

	/// True (the default): motion states receive the pose interpolated between the last two substeps,
	/// one substep behind the simulation, so rendering is smooth without extrapolating. False: the pose
	/// extrapolated by the remaining accumulated time.
	void setLatencyMotionStateInterpolation(bool latencyInterpolation)
	{
		m_latencyMotionStateInterpolation = latencyInterpolation;
	}
	bool getLatencyMotionStateInterpolation() const { return m_latencyMotionStateInterpolation; }

	btAlignedObjectArray<btRigidBody*>& getNonStaticRigidBodies() { return m_nonStaticRigidBodies; }
	const btAlignedObjectArray<btRigidBody*>& getNonStaticRigidBodies() const { return m_nonStaticRigidBodies; }
};

#endif  // BT_DISCRETE_DYNAMICS_WORLD_H
