// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "BulletSoftBody/btDefaultSoftBodySolver.h"

#include "BulletSoftBody/btSoftBody.h"
#include "LinearMath/btThreads.h"
#include "btSoftBodyClusters.h"
#include "btSoftBodyInternal.h"
#include "btSoftBodySolveGroups.h"

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

namespace
{
// The position solves of the bodies members[0, count) (indices into bodies, ascending), as one thread runs
// them: each body's node solve, then the cluster stages of those with clusters or joints together (clusters
// of different bodies pressed together are solved in one sweep), then their last contact pass.
void solveBodies(btSoftBody* const* bodies, const int* members, int count)
{
	static thread_local btAlignedObjectArray<btSoftBody*> clustered;
	clustered.resize(0);
	for (int i = 0; i < count; ++i)
	{
		btSoftBody* body = bodies[members[i]];
		if (body->m_clusters.size() > 0 || body->m_joints.size() > 0)
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

// Groups of bodies that share nothing their solves write (btSoftBodySolveGroups.h), a group per task.
struct GroupSolve : btIParallelForBody
{
	btSoftBody* const* bodies;
	const caliber::SoftSolveGroups* groups;
	void forLoop(int begin, int end) const override
	{
		for (int k = begin; k < end; ++k)
			solveBodies(bodies, &groups->members[groups->starts[k]], groups->starts[k + 1] - groups->starts[k]);
	}
};
}  // namespace

void btDefaultSoftBodySolver::solveConstraints(btScalar solverdt)
{
	(void)solverdt;  // each body keeps the step of its predictMotion
	const int count = m_softBodySet.size();
	if (count == 0) return;
	static thread_local btAlignedObjectArray<char> solve;
	static thread_local btAlignedObjectArray<int> members;
	static thread_local caliber::SoftSolveGroups groups;
	solve.resize(count);
	members.resize(0);
	for (int i = 0; i < count; ++i)
	{
		solve[i] = m_softBodySet[i]->isActive() ? 1 : 0;
		if (solve[i]) members.push_back(i);
	}
	if (members.size() == 0) return;
	// On one thread (or for one body) the bodies are solved in order; with several, the groups run at once
	// and give the same bits. A single group keeps the calling thread, so that its bodies' own loops (the
	// link sweeps' colour blocks, the node passes) spread over the threads instead.
	if (members.size() > 1 && btGetTaskScheduler() && btGetTaskScheduler()->getNumThreads() > 1)
	{
		caliber::findSoftSolveGroups(&m_softBodySet[0], &solve[0], count, groups);
		if (groups.groupCount() > 1)
		{
			GroupSolve stage;
			stage.bodies = &m_softBodySet[0];
			stage.groups = &groups;
			btParallelFor(0, groups.groupCount(), 1, stage);
			return;
		}
	}
	solveBodies(&m_softBodySet[0], &members[0], members.size());
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
