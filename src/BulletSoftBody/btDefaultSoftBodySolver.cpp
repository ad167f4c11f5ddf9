// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "BulletSoftBody/btDefaultSoftBodySolver.h"

#include "BulletSoftBody/btSoftBody.h"
#include "LinearMath/btThreads.h"
#include "btSoftBodyClusters.h"
#include "btSoftBodyInternal.h"

btDefaultSoftBodySolver::btDefaultSoftBodySolver() : m_updateSolverConstants(true) {}

btDefaultSoftBodySolver::~btDefaultSoftBodySolver() {}

bool btDefaultSoftBodySolver::checkInitialized() { return true; }

void btDefaultSoftBodySolver::optimize(btAlignedObjectArray<btSoftBody*>& softBodies, bool forceUpdate)
{
	(void)forceUpdate;
	m_softBodySet.copyFromArray(softBodies);
}

void btDefaultSoftBodySolver::copyBackToSoftBodies(bool bMove) { (void)bMove; }

namespace
{
// predictMotion and integrateMotion of the solver's bodies on the task scheduler's threads, one body per
// task: each touches its own body only (its side tables are locked maps), so the results are those of the
// loop on one thread, bit for bit. A body's own node loops run serially inside such a task (a loop started
// inside a loop body runs on its thread), in parallel when the world has a single soft body.
struct BodyStage : btIParallelForBody
{
	btSoftBody* const* bodies;
	btScalar dt;
	bool predict;
	void forLoop(int begin, int end) const override
	{
		for (int i = begin; i < end; ++i)
		{
			if (!bodies[i]->isActive()) continue;
			if (predict)
				bodies[i]->predictMotion(dt);
			else
				bodies[i]->integrateMotion();
		}
	}
};

void runStage(btAlignedObjectArray<btSoftBody*>& bodies, btScalar dt, bool predict)
{
	if (bodies.size() == 0) return;
	BodyStage stage;
	stage.bodies = &bodies[0];
	stage.dt = dt;
	stage.predict = predict;
	if (bodies.size() == 1)
		stage.forLoop(0, 1);
	else
		btParallelFor(0, bodies.size(), 1, stage);
}
}  // namespace

void btDefaultSoftBodySolver::predictMotion(btScalar solverdt) { runStage(m_softBodySet, solverdt, true); }

void btDefaultSoftBodySolver::solveConstraints(btScalar solverdt)
{
	(void)solverdt;  // each body keeps the step of its predictMotion
	// Bodies with clusters leave their cluster stage (contacts and joints) to solveClusterStages, which
	// solves them all together: clusters of different bodies pressed together are solved in one sweep.
	static thread_local btAlignedObjectArray<btSoftBody*> clustered;
	clustered.resize(0);
	for (int i = 0; i < m_softBodySet.size(); ++i)
	{
		btSoftBody* body = m_softBodySet[i];
		if (!body->isActive()) continue;
		const bool defer = body->m_clusters.size() > 0 || body->m_joints.size() > 0;
		if (defer)
		{
			caliber::clusterState(*body).deferred = true;
			clustered.push_back(body);
		}
		body->solveConstraints();
	}
	if (clustered.size() == 0) return;
	caliber::solveClusterStages(&clustered[0], clustered.size());
	for (int i = 0; i < clustered.size(); ++i)
	{
		caliber::clusterState(*clustered[i]).deferred = false;
		caliber::finishSoftSolve(*clustered[i]);
	}
}

void btDefaultSoftBodySolver::updateSoftBodies() { runStage(m_softBodySet, 0, false); }

void btDefaultSoftBodySolver::processCollision(btSoftBody* softBody,
                                               const btCollisionObjectWrapper* collisionObjectWrap)
{
	if (softBody) softBody->defaultCollisionHandler(collisionObjectWrap);
}

void btDefaultSoftBodySolver::processCollision(btSoftBody* softBody, btSoftBody* otherSoftBody)
{
	if (softBody) softBody->defaultCollisionHandler(otherSoftBody);
}

void btDefaultSoftBodySolver::copySoftBodyToVertexBuffer(const btSoftBody* const softBody,
                                                         btVertexBufferDescriptor* vertexBuffer)
{
	(void)softBody;
	(void)vertexBuffer;
	caliber::softBodyWarning(
	    "Caliber: btDefaultSoftBodySolver::copySoftBodyToVertexBuffer is not implemented yet; nothing copied\n");
}
