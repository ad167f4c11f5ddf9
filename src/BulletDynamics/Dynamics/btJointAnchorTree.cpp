// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "btJointAnchorTree.h"

#include "BulletDynamics/ConstraintSolver/btJointBlockMath.h"
#include "BulletDynamics/ConstraintSolver/btJointPositionPass.h"
#include "BulletDynamics/Dynamics/btRigidBody.h"

namespace caliber
{
namespace
{
const int S = 6;  // storage stride of every node's dense blocks

bool movable(const btRigidBody& body) { return !body.isStaticOrKinematicObject() && body.isActive(); }

// The tree's algebra needs M itself: unit factors and a finite, invertible inertia.
bool eligible(const btRigidBody& body)
{
	const btVector3 one(1, 1, 1);
	const btVector3& inertia = body.getInvInertiaDiagLocal();
	return body.getInvMass() > 0 && body.getLinearFactor() == one && body.getAngularFactor() == one &&
	       inertia.x() > 0 && inertia.y() > 0 && inertia.z() > 0;
}

// Inverts the n x n block a (stride S); pivots are judged against the block's largest entry.
bool invert(const btScalar* a, int n, btScalar* inverse)
{
	btScalar scale = 0;
	for (int i = 0; i < n; ++i)
		for (int j = 0; j < n; ++j) scale = btMax(scale, btFabs(a[i * S + j]));
	if (!(scale > 0) || !(scale < SIMD_INFINITY)) return false;
	return invertDense(a, n, S, scale * btScalar(1e-7), inverse);
}

// The coupling block between a joint's three rows and one of its bodies (3 x 6, stride S): minus the
// Jacobian of the anchors' gap (A minus B) in that body's move (dp, dtheta): the anchor moves by
// dp - arm x dtheta, with sign +1 for body A and -1 for body B.
void coupling(btScalar sign, const btVector3& arm, btScalar* g)
{
	const btScalar skew[3][3] = {{0, -arm.z(), arm.y()}, {arm.z(), 0, -arm.x()}, {-arm.y(), arm.x(), 0}};
	for (int i = 0; i < 3; ++i)
		for (int j = 0; j < 3; ++j)
		{
			g[i * S + j] = i == j ? -sign : btScalar(0);
			g[i * S + 3 + j] = sign * skew[i][j];
		}
}
}  // namespace

int JointAnchorTree::find(int i)
{
	while (m_unionFind[i] != i)
	{
		m_unionFind[i] = m_unionFind[m_unionFind[i]];
		i = m_unionFind[i];
	}
	return i;
}

bool JointAnchorTree::solve(btTypedConstraint** joints, int numJoints, int minJoints, btScalar minGap,
                            btAlignedObjectArray<btTypedConstraint*>& leftOver,
                            btAlignedObjectArray<btRigidBody*>& movedBodies)
{
	btScalar largest = 0;
	const Status status = prepare(joints, numJoints, minJoints, minGap, leftOver, largest);
	if (status == kNothingToSolve) return false;
	if (status == kSingular)
	{
		abandon(leftOver);
		return false;
	}
	move(stepShare(largest), movedBodies);
	return true;
}

JointAnchorTree::Status JointAnchorTree::prepare(btTypedConstraint** joints, int numJoints, int minJoints,
                                                 btScalar minGap, btAlignedObjectArray<btTypedConstraint*>& leftOver,
                                                 btScalar& largest)
{
	largest = 0;
	gatherEdges(joints, numJoints, leftOver);
	if (m_edges.size() == 0) return kNothingToSolve;
	chooseArticulations(minJoints, minGap);
	if (!buildSpanningForest(leftOver)) return kNothingToSolve;
	orderNodesFromRoots();
	assembleBlocks();
	if (!eliminateLeavesFirst()) return kSingular;
	substituteRootsFirst();
	largest = largestTurn();
	return kPrepared;
}

void JointAnchorTree::abandon(btAlignedObjectArray<btTypedConstraint*>& leftOver) const
{
	for (int e = 0; e < m_edges.size(); ++e)
		if (m_edgeUsed[e]) leftOver.push_back(m_edges[e].joint);
}

btScalar JointAnchorTree::stepShare(btScalar largestTurn)
{
	// A linearised step is only trusted for small turns: if some body would turn by more than
	// kMaxTurn, the whole step is shortened (a damped Newton step), the Gauss-Seidel sweeps do the rest.
	// 0.1 rad: a whipping 20-link chain stays within 7 mm with two iterations (0.2 rad: 9 mm, and a
	// full step diverges there).
	const btScalar kMaxTurn = btScalar(0.1);
	return largestTurn > kMaxTurn ? kMaxTurn / largestTurn : btScalar(1);
}

void JointAnchorTree::gatherEdges(btTypedConstraint** joints, int numJoints,
                                  btAlignedObjectArray<btTypedConstraint*>& leftOver)
{
	m_bodies.resize(0);
	m_edges.resize(0);
	// Bodies get consecutive indices through their companion id (free outside the solver), reset at the end.
	auto indexOf = [&](btRigidBody& body) -> int
	{
		if (!movable(body)) return -1;
		if (!eligible(body)) return -2;
		const int id = body.getCompanionId();
		if (id >= 0 && id < m_bodies.size() && m_bodies[id] == &body) return id;
		body.setCompanionId(m_bodies.size());
		m_bodies.push_back(&body);
		return m_bodies.size() - 1;
	};
	for (int j = 0; j < numJoints; ++j)
	{
		btTypedConstraint* joint = joints[j];
		btVector3 anchorInA, anchorInB;
		if (!caliber::jointAnchors(*joint, anchorInA, anchorInB)) continue;
		btRigidBody& a = joint->getRigidBodyA();
		btRigidBody& b = joint->getRigidBodyB();
		const int ia = indexOf(a), ib = indexOf(b);
		if (ia == -2 || ib == -2)
		{
			leftOver.push_back(joint);
			continue;
		}
		if (ia < 0 && ib < 0) continue;
		Edge e;
		e.joint = joint;
		e.bodyA = ia;
		e.bodyB = ib;
		const btVector3 worldA = a.getWorldTransform()(anchorInA);
		const btVector3 worldB = b.getWorldTransform()(anchorInB);
		e.armA = worldA - a.getWorldTransform().getOrigin();
		e.armB = worldB - b.getWorldTransform().getOrigin();
		e.gap = worldA - worldB;
		m_edges.push_back(e);
	}
	for (int i = 0; i < m_bodies.size(); ++i) m_bodies[i]->setCompanionId(-1);
}

void JointAnchorTree::chooseArticulations(int minJoints, btScalar minGap)
{
	const int numBodies = m_bodies.size(), numEdges = m_edges.size();
	// Which articulations are worth an exact solve: those with at least minJoints joints (shorter ones
	// converge in a Gauss-Seidel sweep or two) and a gap above minGap. Components of bodies here do
	// not pass through the world.
	m_unionFind.resize(numBodies + 1);
	for (int i = 0; i <= numBodies; ++i) m_unionFind[i] = i;
	for (int e = 0; e < numEdges; ++e)
		if (m_edges[e].bodyA >= 0 && m_edges[e].bodyB >= 0)
		{
			const int ru = find(m_edges[e].bodyA), rv = find(m_edges[e].bodyB);
			if (ru != rv) m_unionFind[ru] = rv;
		}
	m_componentJoints.resize(0);
	m_componentJoints.resize(numBodies, 0);
	m_componentGap.resize(0);
	m_componentGap.resize(numBodies, 0);
	for (int e = 0; e < numEdges; ++e)
	{
		const int root = find(m_edges[e].bodyA >= 0 ? m_edges[e].bodyA : m_edges[e].bodyB);
		++m_componentJoints[root];
		m_componentGap[root] = btMax(m_componentGap[root], m_edges[e].gap.length2());
	}

	// A spanning forest of the chosen articulations: the world is one more vertex, so a tree hangs
	// from the world at most once.
	m_edgeUsed.resize(numEdges);
	for (int e = 0; e < numEdges; ++e)
	{
		const int root = find(m_edges[e].bodyA >= 0 ? m_edges[e].bodyA : m_edges[e].bodyB);
		m_edgeUsed[e] = m_componentJoints[root] >= minJoints && m_componentGap[root] > minGap * minGap;
	}
}

bool JointAnchorTree::buildSpanningForest(btAlignedObjectArray<btTypedConstraint*>& leftOver)
{
	const int numBodies = m_bodies.size(), numEdges = m_edges.size();
	for (int i = 0; i <= numBodies; ++i) m_unionFind[i] = i;
	m_edgeStart.resize(0);
	m_edgeStart.resize(numBodies + 1, 0);
	for (int e = 0; e < numEdges; ++e)
	{
		if (!m_edgeUsed[e])
		{
			leftOver.push_back(m_edges[e].joint);
			continue;
		}
		const int u = m_edges[e].bodyA < 0 ? numBodies : m_edges[e].bodyA;
		const int v = m_edges[e].bodyB < 0 ? numBodies : m_edges[e].bodyB;
		const int ru = find(u), rv = find(v);
		m_edgeUsed[e] = ru != rv;
		if (ru == rv)
		{
			leftOver.push_back(m_edges[e].joint);
			continue;
		}
		m_unionFind[ru] = rv;
		if (m_edges[e].bodyA >= 0) ++m_edgeStart[m_edges[e].bodyA + 1];
		if (m_edges[e].bodyB >= 0) ++m_edgeStart[m_edges[e].bodyB + 1];
	}
	for (int i = 0; i < numBodies; ++i) m_edgeStart[i + 1] += m_edgeStart[i];
	m_edgeList.resize(m_edgeStart[numBodies]);
	btAlignedObjectArray<int>& fill = m_bodyNode;  // reused as the fill counter, then as body -> node
	fill.resize(0);
	fill.resize(numBodies, 0);
	for (int e = 0; e < numEdges; ++e)
	{
		if (!m_edgeUsed[e]) continue;
		if (m_edges[e].bodyA >= 0) m_edgeList[m_edgeStart[m_edges[e].bodyA] + fill[m_edges[e].bodyA]++] = e;
		if (m_edges[e].bodyB >= 0) m_edgeList[m_edgeStart[m_edges[e].bodyB] + fill[m_edges[e].bodyB]++] = e;
	}

	bool anyUsed = false;
	for (int e = 0; e < numEdges && !anyUsed; ++e) anyUsed = m_edgeUsed[e] != 0;
	return anyUsed;
}

void JointAnchorTree::orderNodesFromRoots()
{
	const int numBodies = m_bodies.size(), numEdges = m_edges.size();
	// Breadth-first from the roots: a tree hanging from the world starts at its world joint, a free one
	// at its first body. Parents come before children, so the reverse order eliminates leaves first.
	m_nodes.resize(0);
	m_bodyNode.resize(0);
	m_bodyNode.resize(numBodies, -1);
	for (int e = 0; e < numEdges; ++e)
	{
		if (!m_edgeUsed[e] || (m_edges[e].bodyA >= 0 && m_edges[e].bodyB >= 0)) continue;
		Node root = {e, -1, -1};
		m_edgeUsed[e] = 2;  // visited
		m_nodes.push_back(root);
	}
	int nextRootCandidate = 0;
	for (int q = 0;; ++q)
	{
		if (q == m_nodes.size())
		{
			// Free trees start at a body; bodies without tree joints (all theirs left to Gauss-Seidel) are
			// not part of any tree.
			while (nextRootCandidate < numBodies &&
			       (m_bodyNode[nextRootCandidate] >= 0 ||
			        m_edgeStart[nextRootCandidate + 1] == m_edgeStart[nextRootCandidate]))
				++nextRootCandidate;
			if (nextRootCandidate == numBodies) break;
			Node root = {-1, nextRootCandidate, -1};
			m_bodyNode[nextRootCandidate] = m_nodes.size();
			m_nodes.push_back(root);
		}
		const Node node = m_nodes[q];
		if (node.edge >= 0)
		{
			const int ends[2] = {m_edges[node.edge].bodyA, m_edges[node.edge].bodyB};
			for (int k = 0; k < 2; ++k)
			{
				if (ends[k] < 0 || m_bodyNode[ends[k]] >= 0) continue;
				Node child = {-1, ends[k], q};
				m_bodyNode[ends[k]] = m_nodes.size();
				m_nodes.push_back(child);
			}
		}
		else
		{
			for (int k = m_edgeStart[node.body]; k < m_edgeStart[node.body + 1]; ++k)
			{
				const int e = m_edgeList[k];
				if (m_edgeUsed[e] != 1) continue;
				m_edgeUsed[e] = 2;
				Node child = {e, -1, q};
				m_nodes.push_back(child);
			}
		}
	}
}

void JointAnchorTree::assembleBlocks()
{
	// Diagonal blocks and right-hand sides: bodies M (mass, world inertia) and 0; joints 0 and the gap.
	const int numNodes = m_nodes.size();
	m_d.resize(numNodes * S * S);
	m_dInverse.resize(numNodes * S * S);
	m_z.resize(numNodes * S);
	m_y.resize(numNodes * S);
	for (int i = 0; i < numNodes; ++i)
	{
		btScalar* d = &m_d[i * S * S];
		btScalar* z = &m_z[i * S];
		for (int k = 0; k < S * S; ++k) d[k] = 0;
		for (int k = 0; k < S; ++k) z[k] = 0;
		if (m_nodes[i].body >= 0)
		{
			const btRigidBody& body = *m_bodies[m_nodes[i].body];
			const btScalar mass = btScalar(1) / body.getInvMass();
			const btMatrix3x3& basis = body.getWorldTransform().getBasis();
			const btVector3& invDiag = body.getInvInertiaDiagLocal();
			const btMatrix3x3 inertia =
			    basis.scaled(btVector3(1 / invDiag.x(), 1 / invDiag.y(), 1 / invDiag.z())) * basis.transpose();
			for (int k = 0; k < 3; ++k)
			{
				d[k * S + k] = mass;
				for (int l = 0; l < 3; ++l) d[(3 + k) * S + 3 + l] = inertia[k][l];
			}
		}
		else
		{
			const btVector3& gap = m_edges[m_nodes[i].edge].gap;
			for (int k = 0; k < 3; ++k) z[k] = gap[k];
		}
	}
}

void JointAnchorTree::couplingToParent(int i, btScalar* g) const
{
	const Node& node = m_nodes[i];
	const Node& parent = m_nodes[node.parent];
	const Edge& edge = m_edges[node.edge >= 0 ? node.edge : parent.edge];
	const int body = node.body >= 0 ? node.body : parent.body;
	const bool isA = edge.bodyA == body;
	coupling(isA ? btScalar(1) : btScalar(-1), isA ? edge.armA : edge.armB, g);
}

bool JointAnchorTree::eliminateLeavesFirst()
{
	const int numNodes = m_nodes.size();
	// Elimination, leaves first: each node's Schur complement goes to its parent.
	btScalar g[3 * S], product[S * S];
	for (int i = numNodes - 1; i >= 0; --i)
	{
		const Node& node = m_nodes[i];
		const int dim = node.body >= 0 ? 6 : 3;
		btScalar* inverse = &m_dInverse[i * S * S];
		if (!invert(&m_d[i * S * S], dim, inverse)) return false;
		if (node.parent < 0) continue;
		couplingToParent(i, g);
		btScalar* dParent = &m_d[node.parent * S * S];
		btScalar* zParent = &m_z[node.parent * S];
		const btScalar* z = &m_z[i * S];
		if (node.edge >= 0)
		{
			// Joint under a body: D_p -= G^T D^-1 G, z_p -= G^T D^-1 z (G: 3 x 6).
			for (int r = 0; r < 3; ++r)  // product = D^-1 G (3 x 6)
				for (int c = 0; c < 6; ++c)
				{
					btScalar sum = 0;
					for (int k = 0; k < 3; ++k) sum += inverse[r * S + k] * g[k * S + c];
					product[r * S + c] = sum;
				}
			for (int r = 0; r < 6; ++r)
				for (int c = 0; c < 6; ++c)
				{
					btScalar sum = 0;
					for (int k = 0; k < 3; ++k) sum += g[k * S + r] * product[k * S + c];
					dParent[r * S + c] -= sum;
				}
			btScalar dz[3];
			for (int r = 0; r < 3; ++r)
			{
				dz[r] = 0;
				for (int k = 0; k < 3; ++k) dz[r] += inverse[r * S + k] * z[k];
			}
			for (int r = 0; r < 6; ++r)
				for (int k = 0; k < 3; ++k) zParent[r] -= g[k * S + r] * dz[k];
		}
		else
		{
			// Body under a joint: D_p -= G D^-1 G^T, z_p -= G D^-1 z.
			for (int r = 0; r < 3; ++r)  // product = G D^-1 (3 x 6)
				for (int c = 0; c < 6; ++c)
				{
					btScalar sum = 0;
					for (int k = 0; k < 6; ++k) sum += g[r * S + k] * inverse[k * S + c];
					product[r * S + c] = sum;
				}
			for (int r = 0; r < 3; ++r)
				for (int c = 0; c < 3; ++c)
				{
					btScalar sum = 0;
					for (int k = 0; k < 6; ++k) sum += product[r * S + k] * g[c * S + k];
					dParent[r * S + c] -= sum;
				}
			for (int r = 0; r < 3; ++r)
				for (int k = 0; k < 6; ++k) zParent[r] -= product[r * S + k] * z[k];
		}
	}
	return true;
}

void JointAnchorTree::substituteRootsFirst()
{
	const int numNodes = m_nodes.size();
	btScalar g[3 * S];
	// Back substitution, roots first: y = D^-1 (z - H_{i,parent} y_parent).
	for (int i = 0; i < numNodes; ++i)
	{
		const Node& node = m_nodes[i];
		const int dim = node.body >= 0 ? 6 : 3;
		btScalar rhs[S];
		for (int k = 0; k < dim; ++k) rhs[k] = m_z[i * S + k];
		if (node.parent >= 0)
		{
			couplingToParent(i, g);
			const btScalar* yParent = &m_y[node.parent * S];
			if (node.edge >= 0)
				for (int r = 0; r < 3; ++r)
					for (int k = 0; k < 6; ++k) rhs[r] -= g[r * S + k] * yParent[k];
			else
				for (int r = 0; r < 6; ++r)
					for (int k = 0; k < 3; ++k) rhs[r] -= g[k * S + r] * yParent[k];
		}
		const btScalar* inverse = &m_dInverse[i * S * S];
		for (int r = 0; r < dim; ++r)
		{
			btScalar sum = 0;
			for (int k = 0; k < dim; ++k) sum += inverse[r * S + k] * rhs[k];
			m_y[i * S + r] = sum;
		}
	}
}

btScalar JointAnchorTree::largestTurn() const
{
	// Written as a comparison, not btMax, so that a NaN turn is skipped wherever it comes: the largest
	// turn of several trees is then the same whatever order they are taken in.
	btScalar largest = 0;
	for (int i = 0; i < m_nodes.size(); ++i)
		if (m_nodes[i].body >= 0)
		{
			const btScalar turn = btVector3(m_y[i * S + 3], m_y[i * S + 4], m_y[i * S + 5]).length();
			if (turn > largest) largest = turn;
		}
	return largest;
}

void JointAnchorTree::move(btScalar share, btAlignedObjectArray<btRigidBody*>& movedBodies)
{
	const int numNodes = m_nodes.size();
	// Move the bodies: y holds each body's (dp, dtheta).
	for (int i = 0; i < numNodes; ++i)
	{
		if (m_nodes[i].body < 0) continue;
		btRigidBody& body = *m_bodies[m_nodes[i].body];
		btScalar y[S];
		for (int k = 0; k < 6; ++k) y[k] = m_y[i * S + k] * share;
		btTransform& pose = body.getWorldTransform();
		pose.setOrigin(pose.getOrigin() + btVector3(y[0], y[1], y[2]));
		const btVector3 turn(y[3], y[4], y[5]);
		const btScalar angle = turn.length();
		if (angle > btScalar(1e-9) && angle < SIMD_PI)
		{
			btQuaternion q = btQuaternion(turn / angle, angle) * pose.getRotation();
			q.normalize();
			pose.setRotation(q);
		}
		movedBodies.push_back(&body);
	}
}
}  // namespace caliber
