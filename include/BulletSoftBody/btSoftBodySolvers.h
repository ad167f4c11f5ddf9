// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef BT_SOFT_BODY_SOLVERS_H
#define BT_SOFT_BODY_SOLVERS_H

/// btSoftBodySolver: the interface through which btSoftRigidDynamicsWorld steps its soft bodies.

#include "BulletCollision/BroadphaseCollision/btBroadphaseProxy.h"
#include "LinearMath/btAlignedObjectArray.h"
#include "LinearMath/btScalar.h"

class btSoftBody;
class btSoftBodyTriangleData;
class btSoftBodyLinkData;
class btSoftBodyVertexData;
class btVertexBufferDescriptor;
class btCollisionObject;
struct btCollisionObjectWrapper;

/// Steps a set of soft bodies: predict, solve, update; and finds their contacts.
class btSoftBodySolver
{
public:
	/// Which implementation a solver is.
	enum SolverTypes
	{
		DEFAULT_SOLVER,
		CPU_SOLVER,
		CL_SOLVER,
		CL_SIMD_SOLVER,
		DX_SOLVER,
		DX_SIMD_SOLVER,
		DEFORMABLE_SOLVER
	};

protected:
	int m_numberOfPositionIterations;  ///< Position iterations (informative; each body has its own).
	int m_numberOfVelocityIterations;  ///< Velocity iterations (informative).
	float m_timeScale;                 ///< Time scale.

public:
	btSoftBodySolver() : m_numberOfPositionIterations(10), m_numberOfVelocityIterations(0), m_timeScale(1) {}
	virtual ~btSoftBodySolver() {}

	/// Which implementation this is.
	virtual SolverTypes getSolverType() const = 0;
	/// True when the solver is ready to step.
	virtual bool checkInitialized() = 0;
	/// Takes the world's soft bodies (called before each substep).
	virtual void optimize(btAlignedObjectArray<btSoftBody*>& softBodies, bool forceUpdate = false) = 0;
	/// Copies solver data back to the bodies (nothing for a solver working on them directly).
	virtual void copyBackToSoftBodies(bool bMove = true) = 0;
	/// Predicts the bodies' motion over solverdt.
	virtual void predictMotion(btScalar solverdt) = 0;
	/// Solves constraints and contacts over solverdt.
	virtual void solveConstraints(btScalar solverdt) = 0;
	/// Finishes the step (bounds, normals).
	virtual void updateSoftBodies() = 0;
	/// Finds contacts of a soft body with a rigid object.
	virtual void processCollision(btSoftBody*, const btCollisionObjectWrapper*) = 0;
	/// Finds contacts between two soft bodies.
	virtual void processCollision(btSoftBody*, btSoftBody*) = 0;

	/// Sets the position iterations.
	virtual void setNumberOfPositionIterations(int iterations) { m_numberOfPositionIterations = iterations; }
	/// The position iterations.
	virtual int getNumberOfPositionIterations() { return m_numberOfPositionIterations; }
	/// Sets the velocity iterations.
	virtual void setNumberOfVelocityIterations(int iterations) { m_numberOfVelocityIterations = iterations; }
	/// The velocity iterations.
	virtual int getNumberOfVelocityIterations() { return m_numberOfVelocityIterations; }
	/// The time scale.
	float getTimeScale() { return m_timeScale; }
};

/// Copies soft body vertices into a renderer's buffer.
class btSoftBodySolverOutput
{
public:
	btSoftBodySolverOutput() {}
	virtual ~btSoftBodySolverOutput() {}
	/// Writes softBody's node positions (and normals) into vertexBuffer.
	virtual void copySoftBodyToVertexBuffer(const btSoftBody* const softBody,
	                                        btVertexBufferDescriptor* vertexBuffer) = 0;
};

#endif  // BT_SOFT_BODY_SOLVERS_H
