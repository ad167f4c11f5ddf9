// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "BulletSoftBody/btDefaultSoftBodySolver.h"

#include "BulletSoftBody/btSoftBody.h"
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

void btDefaultSoftBodySolver::predictMotion(btScalar solverdt)
{
	for (int i = 0; i < m_softBodySet.size(); ++i)
		if (m_softBodySet[i]->isActive()) m_softBodySet[i]->predictMotion(solverdt);
}

void btDefaultSoftBodySolver::solveConstraints(btScalar solverdt)
{
	(void)solverdt;  // each body keeps the step of its predictMotion
	for (int i = 0; i < m_softBodySet.size(); ++i)
		if (m_softBodySet[i]->isActive()) m_softBodySet[i]->solveConstraints();
}

void btDefaultSoftBodySolver::updateSoftBodies()
{
	for (int i = 0; i < m_softBodySet.size(); ++i)
		if (m_softBodySet[i]->isActive()) m_softBodySet[i]->integrateMotion();
}

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
