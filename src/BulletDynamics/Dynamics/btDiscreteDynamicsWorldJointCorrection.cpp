// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// The joint position correction stage (after integrateTransforms). Velocity rows keep a joint's
// anchors moving together, but they see motion only to first order: an anchor on a turning body
// moves along a circle, the rows along its tangent, so every fast-turning joint opens a little each
// step, and error reduction (ERP) closes it only by adding velocity, which costs energy and lets long
// chains stretch. This stage instead moves the bodies themselves, Gauss-Seidel over the joints, each
// joint's equality rows solved as one block at the bodies' current poses (nonlinear Gauss-Seidel on
// positions). Velocities are left alone, so no energy is added.
#include "BulletDynamics/ConstraintSolver/btJointBlockMath.h"
#include "BulletDynamics/ConstraintSolver/btJointPositionPass.h"
#include "BulletDynamics/ConstraintSolver/btJointRowSetup.h"
#include "BulletDynamics/ConstraintSolver/btTypedConstraint.h"
#include "BulletDynamics/Dynamics/btDiscreteDynamicsWorld.h"
#include "BulletDynamics/Dynamics/btJointCorrection.h"
#include "BulletDynamics/Dynamics/btWorldStepContext.h"
#include "LinearMath/btQuickprof.h"
#include "LinearMath/btThreads.h"

namespace
{
using caliber::joint_correction::kNegligibleGap;
using caliber::joint_correction::kTreeMinJoints;
using caliber::joint_correction::movable;
const btScalar kUnbounded = btScalar(1e30) < SIMD_INFINITY ? btScalar(1e30) : SIMD_INFINITY;

// Equality rows, one-sided limit rows, and at most how many rows of one joint take part.
const int kMaxRows = 8;
bool isEquality(const btSolverConstraint& row)
{
	return row.m_lowerLimit <= -kUnbounded && row.m_upperLimit >= kUnbounded && row.m_cfm == btScalar(0);
}
bool isOneSided(const btSolverConstraint& row)
{
	return row.m_lowerLimit == btScalar(0) && row.m_upperLimit >= kUnbounded && row.m_cfm == btScalar(0);
}

// Rows' mutual coupling: row i's change per unit impulse of row j, J_i M^-1 J_j^T.
btScalar coupling(const btSolverConstraint& ri, const btSolverConstraint& rj, const btSolverBody& a,
                  const btSolverBody& b)
{
	return ri.m_contactNormal1.dot(rj.m_contactNormal1 * a.m_invMass) +
	       ri.m_relpos1CrossNormal.dot(rj.m_angularComponentA * a.m_angularFactor) +
	       ri.m_contactNormal2.dot(rj.m_contactNormal2 * b.m_invMass) +
	       ri.m_relpos2CrossNormal.dot(rj.m_angularComponentB * b.m_angularFactor);
}

// Position impulses for rows [0, n) (equalities, exact through invK) and [n, m) (one-sided, >= 0): block
// Gauss-Seidel between the equality block and the limit rows. With no limit rows this is the exact solve.
void solvePositionRows(const btSolverConstraint* rows, int n, int m, const btSolverBody& a, const btSolverBody& b,
                       const btScalar* invK, btScalar* lambda)
{
	const int S = caliber::SolverJointBlock::MAX_ROWS;
	btScalar k[kMaxRows][kMaxRows];
	for (int i = 0; i < m; ++i)
		for (int j = 0; j < m; ++j) k[i][j] = (i < n && j < n) ? btScalar(0) : coupling(rows[i], rows[j], a, b);
	// The equality block, given the limit rows' current impulses.
	auto solveBlock = [&]()
	{
		btScalar residual[S];
		for (int i = 0; i < n; ++i)
		{
			residual[i] = rows[i].m_rhs;
			for (int j = n; j < m; ++j) residual[i] -= k[i][j] * lambda[j];
		}
		for (int i = 0; i < n; ++i)
		{
			lambda[i] = 0;
			for (int j = 0; j < n; ++j) lambda[i] += invK[i * S + j] * residual[j];
		}
	};
	solveBlock();
	for (int pass = 0; pass < 4 && m > n; ++pass)
	{
		// Each limit row, kept from pulling; then the block again, so the joint itself ends exact.
		for (int i = n; i < m; ++i)
		{
			if (!(k[i][i] > SIMD_EPSILON)) continue;
			btScalar achieved = 0;
			for (int j = 0; j < m; ++j) achieved += k[i][j] * lambda[j];
			lambda[i] = btMax(btScalar(0), lambda[i] + (rows[i].m_rhs - achieved) / k[i][i]);
		}
		solveBlock();
	}
}

// A solver-body stand-in carrying what the block algebra reads of a body: its inverse mass per axis
// and its angular factor.
btSolverBody massOf(const btRigidBody& body)
{
	btSolverBody b;
	if (movable(body))
	{
		b.m_invMass = body.getLinearFactor() * body.getInvMass();
		b.m_angularFactor = body.getAngularFactor();
	}
	else
	{
		b.m_invMass.setZero();
		b.m_angularFactor.setZero();
	}
	return b;
}

// Moves body by the position impulse (linear part linear, angular part turn = I^-1 F angular).
void displace(btRigidBody& body, const btVector3& linear, const btVector3& turn)
{
	btTransform& pose = body.getWorldTransform();
	pose.setOrigin(pose.getOrigin() + linear * body.getLinearFactor() * body.getInvMass());
	const btScalar angle = turn.length();
	if (angle > btScalar(1e-9))
	{
		btQuaternion q = btQuaternion(turn / angle, angle) * pose.getRotation();
		q.normalize();
		pose.setRotation(q);
	}
}
// The anchor-only correction: moves A and B so that the world anchors meet, as one 3x3 solve (the
// point constraint's effective mass). Cheap enough to run every step for every joint: no rows, no angles.
// Returns false when neither body can move or the system is singular.
bool closeAnchors(btRigidBody& a, btRigidBody& b, const btVector3& anchorInA, const btVector3& anchorInB)
{
	const bool moveA = movable(a), moveB = movable(b);
	if (!moveA && !moveB) return false;
	const btVector3 worldA = a.getWorldTransform()(anchorInA);
	const btVector3 worldB = b.getWorldTransform()(anchorInB);
	const btVector3 gap = worldB - worldA;
	if (!(gap.length2() > kNegligibleGap * kNegligibleGap)) return false;
	const btVector3 armA = worldA - a.getWorldTransform().getOrigin();
	const btVector3 armB = worldB - b.getWorldTransform().getOrigin();
	// Response of the anchors' separation to a unit impulse along each axis (+ on A, - on B).
	btMatrix3x3 k;
	k.setValue(0, 0, 0, 0, 0, 0, 0, 0, 0);
	for (int axis = 0; axis < 3; ++axis)
	{
		btVector3 e(0, 0, 0);
		e[axis] = 1;
		btVector3 response(0, 0, 0);
		if (moveA)
			response += e * a.getLinearFactor() * a.getInvMass() +
			            (a.getInvInertiaTensorWorld() * (armA.cross(e) * a.getAngularFactor()) * a.getAngularFactor())
			                .cross(armA);
		if (moveB)
			response += e * b.getLinearFactor() * b.getInvMass() +
			            (b.getInvInertiaTensorWorld() * (armB.cross(e) * b.getAngularFactor()) * b.getAngularFactor())
			                .cross(armB);
		for (int row = 0; row < 3; ++row) k[row][axis] = response[row];
	}
	const btScalar det = k.determinant();
	if (!(btFabs(det) > SIMD_EPSILON * SIMD_EPSILON)) return false;
	const btVector3 impulse = k.inverse() * gap;
	if (moveA)
		displace(a, impulse,
		         a.getInvInertiaTensorWorld() * (armA.cross(impulse) * a.getAngularFactor()) * a.getAngularFactor());
	if (moveB)
		displace(b, -impulse,
		         b.getInvInertiaTensorWorld() * (armB.cross(-impulse) * b.getAngularFactor()) * b.getAngularFactor());
	return true;
}
}  // namespace

// One Gauss-Seidel correction of a joint the trees left out: its anchors closed directly, or its
// equality rows (and the one-sided limits among them) solved as a block at the current positions.
// Lists the two bodies when it moved them.
bool caliber::joint_correction::correctLeftOverJoint(btTypedConstraint* constraint, int numIterations,
                                                     btConstraintArray& rowScratch,
                                                     btAlignedObjectArray<btRigidBody*>& correctedBodies)
{
	const int S = caliber::SolverJointBlock::MAX_ROWS;
	btRigidBody& a = constraint->getRigidBodyA();
	btRigidBody& b = constraint->getRigidBodyB();
	if (!movable(a) && !movable(b)) return false;
	btVector3 anchorInA, anchorInB;
	if (caliber::jointAnchors(*constraint, anchorInA, anchorInB))
	{
		if (!closeAnchors(a, b, anchorInA, anchorInB)) return false;
		correctedBodies.push_back(&a);
		correctedBodies.push_back(&b);
		return true;
	}
	btTypedConstraint::btConstraintInfo1 info1;
	info1.m_numConstraintRows = 0;
	info1.nub = 0;
	constraint->getInfo1(&info1);
	if (info1.m_numConstraintRows <= 0) return false;

	rowScratch.resizeNoInitialize(info1.m_numConstraintRows);
	btSolverConstraint* rows = &rowScratch[0];
	// fps = erp = 1: each row's "velocity" target is then its position error itself.
	caliber::JointRowParameters parameters;
	parameters.fps = btScalar(1);
	parameters.erp = btScalar(1);
	parameters.cfm = btScalar(0);
	parameters.numIterations = numIterations;
	parameters.damping = btScalar(1);
	parameters.solverBodyIdA = -1;
	parameters.solverBodyIdB = -1;
	parameters.rowIterations = numIterations;
	{
		caliber::JointPositionPassScope positionPass;
		caliber::setUpJointRows(*constraint, rows, info1.m_numConstraintRows, parameters);
	}

	// The equality rows (leading, unbounded), solved exactly as a block, and the one-sided limit rows
	// ([0, inf) bounds), which must not be pushed through by the block's correction. Motor rows
	// (bounded both ways) are velocity goals and take no part.
	int n = 0;
	while (n < info1.m_numConstraintRows && n < S && isEquality(rows[n])) ++n;
	int m = n;
	for (int j = n; j < info1.m_numConstraintRows && m < kMaxRows; ++j)
		if (isOneSided(rows[j])) rows[m++] = rows[j];
	if (n == 0) return false;
	bool finite = true;
	for (int j = 0; j < m; ++j)
	{
		rows[j].m_angularComponentA =
		    movable(a) ? a.getInvInertiaTensorWorld() * (rows[j].m_relpos1CrossNormal * a.getAngularFactor())
		               : btVector3(0, 0, 0);
		rows[j].m_angularComponentB =
		    movable(b) ? b.getInvInertiaTensorWorld() * (rows[j].m_relpos2CrossNormal * b.getAngularFactor())
		               : btVector3(0, 0, 0);
		finite = finite && rows[j].m_rhs == rows[j].m_rhs && btFabs(rows[j].m_rhs) < SIMD_INFINITY;
	}
	if (!finite) return false;
	const btSolverBody massA = massOf(a), massB = massOf(b);
	btScalar invK[S * S];
	if (!caliber::buildBlockInverse(rows, n, massA, massB, invK)) return false;
	btScalar lambda[kMaxRows] = {0};
	solvePositionRows(rows, n, m, massA, massB, invK, lambda);
	btVector3 linearA(0, 0, 0), turnA(0, 0, 0), linearB(0, 0, 0), turnB(0, 0, 0);
	for (int i = 0; i < m; ++i)
	{
		linearA += rows[i].m_contactNormal1 * lambda[i];
		turnA += rows[i].m_angularComponentA * (lambda[i] * a.getAngularFactor());
		linearB += rows[i].m_contactNormal2 * lambda[i];
		turnB += rows[i].m_angularComponentB * (lambda[i] * b.getAngularFactor());
	}
	if (movable(a)) displace(a, linearA, turnA);
	if (movable(b)) displace(b, linearB, turnB);
	correctedBodies.push_back(&a);
	correctedBodies.push_back(&b);
	return true;
}

namespace
{
using caliber::joint_correction::correctLeftOverJoint;
using caliber::joint_correction::islandOfJoint;
using caliber::joint_correction::kMinJointsForParallelCorrection;
// Islands per chunk of the left-over sweep on the threads.
const int kIslandsPerCorrectionTask = 8;

// The left-over joints grouped by island (joints of different islands move different bodies): each
// island's joints keep their order, so every body sees the corrections of the serial sweep in the same
// order, and islands go to the threads, each chunk of islands with its own row scratch and list of
// moved bodies (caliber::JointCorrectionChunk).
struct CorrectIslands : public btIParallelForBody
{
	const btAlignedObjectArray<btTypedConstraint*>* joints;  // grouped by island
	const btAlignedObjectArray<int>* islandStart;            // per island, and one past the last
	btAlignedObjectArray<caliber::JointCorrectionChunk>* chunks;
	int numIterations;

	int numIslands;

	// Over chunk numbers: a user's scheduler may split the loop anywhere, and each chunk has its scratch.
	void forLoop(int chunkBegin, int chunkEnd) const override
	{
		for (int k = chunkBegin; k < chunkEnd; ++k)
		{
			caliber::JointCorrectionChunk& chunk = (*chunks)[k];
			chunk.corrected.resize(0);
			chunk.moved = false;
			const int islandEnd = btMin(numIslands, (k + 1) * kIslandsPerCorrectionTask);
			for (int island = k * kIslandsPerCorrectionTask; island < islandEnd; ++island)
				for (int j = (*islandStart)[island]; j < (*islandStart)[island + 1]; ++j)
					if (correctLeftOverJoint((*joints)[j], numIterations, chunk.rows, chunk.corrected))
						chunk.moved = true;
		}
	}
};

// Sweeps the left-over joints once, on the threads when they are many and fall into islands; true when a
// body moved.
bool sweepLeftOverJoints(btDiscreteDynamicsWorld& world, const btAlignedObjectArray<btTypedConstraint*>& leftOver,
                         caliber::WorldStepContext& context, btAlignedObjectArray<btRigidBody*>& correctedBodies)
{
	const int numIterations = world.getSolverInfo().m_numIterations;
	btITaskScheduler* scheduler = btGetTaskScheduler();
	bool parallel = leftOver.size() >= kMinJointsForParallelCorrection && scheduler && scheduler->getNumThreads() > 1;
	const int numObjects = world.getNumCollisionObjects();
	btAlignedObjectArray<int>& islandOf = context.jointCorrectionIslandOf;
	if (parallel)
	{
		islandOf.resizeNoInitialize(leftOver.size());
		for (int c = 0; c < leftOver.size() && parallel; ++c)
		{
			// A joint that moves no body is corrected by nobody: any island will do.
			islandOf[c] = islandOfJoint(*leftOver[c], numObjects);
			if (islandOf[c] == -2) islandOf[c] = 0;
			parallel = islandOf[c] >= 0;
		}
	}
	if (!parallel)
	{
		bool moved = false;
		for (int c = 0; c < leftOver.size(); ++c)
			if (correctLeftOverJoint(leftOver[c], numIterations, context.jointCorrectionRows, correctedBodies))
				moved = true;
		return moved;
	}
	// A stable counting sort by island tag; then the used islands' starts.
	btAlignedObjectArray<int>& count = context.jointCorrectionIslandCount;
	btAlignedObjectArray<int>& islandStart = context.jointCorrectionIslandStart;
	btAlignedObjectArray<btTypedConstraint*>& grouped = context.jointCorrectionGrouped;
	btAlignedObjectArray<caliber::JointCorrectionChunk>& chunks = context.jointCorrectionChunks;
	count.resize(0);
	count.resize(numObjects + 1, 0);
	for (int c = 0; c < leftOver.size(); ++c) ++count[islandOf[c] + 1];
	islandStart.resize(0);
	for (int t = 0; t < numObjects; ++t)
	{
		if (count[t + 1] > 0) islandStart.push_back(count[t]);
		count[t + 1] += count[t];
	}
	islandStart.push_back(leftOver.size());
	grouped.resizeNoInitialize(leftOver.size());
	for (int c = 0; c < leftOver.size(); ++c) grouped[count[islandOf[c]]++] = leftOver[c];
	const int numIslands = islandStart.size() - 1;
	const int numChunks = (numIslands + kIslandsPerCorrectionTask - 1) / kIslandsPerCorrectionTask;
	if (chunks.size() < numChunks) chunks.resize(numChunks);
	CorrectIslands correct;
	correct.joints = &grouped;
	correct.islandStart = &islandStart;
	correct.chunks = &chunks;
	correct.numIterations = numIterations;
	correct.numIslands = numIslands;
	btParallelFor(0, numChunks, 1, correct);
	bool moved = false;
	for (int k = 0; k < numChunks; ++k)
	{
		const caliber::JointCorrectionChunk& chunk = chunks[k];
		for (int i = 0; i < chunk.corrected.size(); ++i) correctedBodies.push_back(chunk.corrected[i]);
		moved = moved || chunk.moved;
	}
	return moved;
}
}  // namespace

void caliber::correctJointPositions(btDiscreteDynamicsWorld& world,
                                    const btAlignedObjectArray<btTypedConstraint*>& constraints,
                                    WorldStepContext& context)
{
	const int sweeps = context.jointPositionIterations;
	if (sweeps <= 0 || constraints.size() == 0) return;
	BT_PROFILE("correctJointPositions");
	btAlignedObjectArray<btRigidBody*>& correctedBodies = context.jointCorrectedBodies;
	btAlignedObjectArray<btTypedConstraint*>& joints = context.jointCorrectionJoints;
	btAlignedObjectArray<btTypedConstraint*>& leftOver = context.jointCorrectionLeftOver;
	bool anyMoved = false;
	correctedBodies.resize(0);

	// Each iteration solves every long articulation of anchor joints (chains, ropes) exactly, in linear
	// time, as one (damped) Newton step. The joints the trees leave out (short articulations such as
	// ragdolls, joints that close loops, joints without a single anchor, bodies with scaled factors) get
	// one Gauss-Seidel sweep, in the first iteration: measured on ragdolls136, a second sweep costs 0.4
	// ms per step and gains nothing visible (pivot errors 2.4 mm max, 0.1 mm mean, after one).
	caliber::joint_correction::selectJoints(world, constraints, joints, context);
	if (joints.size() == 0) return;
	// With threads, independent articulations are corrected on them, island by island.
	if (caliber::joint_correction::correctByIsland(world, joints, context)) return;
	bool treeMoved = true;
	for (int sweep = 0; sweep < sweeps; ++sweep)
	{
		// When no long articulation needed a correction, further iterations would find none either.
		if (!treeMoved) break;
		leftOver.resize(0);
		treeMoved = context.jointAnchorTree.solve(&joints[0], joints.size(), kTreeMinJoints, kNegligibleGap, leftOver,
		                                          correctedBodies);
		anyMoved = anyMoved || treeMoved;
		if (sweep > 0) continue;
		for (int c = 0; c < joints.size(); ++c)
		{
			btVector3 unusedA, unusedB;
			if (!caliber::jointAnchors(*joints[c], unusedA, unusedB)) leftOver.push_back(joints[c]);
		}
		if (sweepLeftOverJoints(world, leftOver, context, correctedBodies)) anyMoved = true;
	}
	if (!anyMoved) return;
	// The moved poses are the step's result. A body is listed once per joint that moved it.
	for (int i = 0; i < correctedBodies.size(); ++i) caliber::joint_correction::writeBackPose(*correctedBodies[i]);
	for (int i = 0; i < correctedBodies.size(); ++i) correctedBodies[i]->setCompanionId(-1);
}
