// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef BT_SOFT_BODY_DEFAULT_SOLVER_H
#define BT_SOFT_BODY_DEFAULT_SOLVER_H

/// btDefaultSoftBodySolver: steps the soft bodies with btSoftBody's own solver: their prediction and velocity
/// update on the task scheduler (the same bits at any thread count), their solves on the calling thread.

#include "BulletSoftBody/btSoftBodySolvers.h"

/// The solver btSoftRigidDynamicsWorld makes when it is given none.
class btDefaultSoftBodySolver : public btSoftBodySolver
{
protected:
	bool m_updateSolverConstants;                     ///< Constants must be recomputed.
	btAlignedObjectArray<btSoftBody*> m_softBodySet;  ///< The bodies of the current step.

public:
	btDefaultSoftBodySolver();
	virtual ~btDefaultSoftBodySolver();

	/// DEFAULT_SOLVER.
	virtual SolverTypes getSolverType() const { return DEFAULT_SOLVER; }
	/// Always ready.
	virtual bool checkInitialized();
	/// Remembers the bodies to step.
	virtual void optimize(btAlignedObjectArray<btSoftBody*>& softBodies, bool forceUpdate = false);
	/// Nothing to copy: the solver works on the bodies.
	virtual void copyBackToSoftBodies(bool bMove = true);
	/// btSoftBody::predictMotion of each body.
	virtual void predictMotion(btScalar solverdt);
	/// btSoftBody::solveConstraints of each body.
	virtual void solveConstraints(btScalar solverdt);
	/// btSoftBody::integrateMotion of each body.
	virtual void updateSoftBodies();
	/// btSoftBody::defaultCollisionHandler(rigid).
	virtual void processCollision(btSoftBody*, const btCollisionObjectWrapper*);
	/// btSoftBody::defaultCollisionHandler(soft).
	virtual void processCollision(btSoftBody*, btSoftBody*);
	/// Writes node positions (and normals) into vertexBuffer (not implemented yet: a warning).
	virtual void copySoftBodyToVertexBuffer(const btSoftBody* const softBody, btVertexBufferDescriptor* vertexBuffer);
};

#endif  // BT_SOFT_BODY_DEFAULT_SOLVER_H
