// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef CALIBER_JOINT_ANCHOR_TREE_H
#define CALIBER_JOINT_ANCHOR_TREE_H

// An exact position solve for joints that hold one point of a body on one point of another (ball,
// hinge and cone-twist anchors), over every tree of such joints at once: chains, ropes, ragdolls.
// Gauss-Seidel (one joint after the other) carries a correction along a 20-link chain one link per
// sweep; a tree can instead be solved exactly in time linear in its size by eliminating from the
// leaves to the root (Baraff, "Linear-time dynamics using Lagrange multipliers", SIGGRAPH 1996). The
// system is the linearised one: bodies move by M^-1 J^T mu with J dq = -C (C: the anchors' gaps), one
// Newton step per call. Joints that close a loop (a second path between two bodies, or a second
// attachment of one tree to the world) are left out and reported, for the caller's Gauss-Seidel.

#include "BulletDynamics/ConstraintSolver/btTypedConstraint.h"
#include "LinearMath/btAlignedObjectArray.h"

namespace caliber
{
class JointAnchorTree
{
public:
	/// Solves the anchor joints in joints of every articulation with at least minJoints joints and a gap
	/// wider than minGap, and moves their bodies; the other joints, those that close loops and those that
	/// touch a body the tree cannot take (scaled linear or angular factors, infinite inertia) are appended
	/// to leftOver (joints without anchors are skipped). Returns true if any body moved.
	bool solve(btTypedConstraint** joints, int numJoints, int minJoints, btScalar minGap,
	           btAlignedObjectArray<btTypedConstraint*>& leftOver, btAlignedObjectArray<btRigidBody*>& movedBodies);

	// solve in three parts, for a caller that solves several disjoint sets of joints (independent
	// articulations) with one tree each, maybe on different threads, and shortens all their steps alike:
	// prepare each, take the largest turn of all, then move (or, when some tree had a singular block,
	// abandon) each. solve is prepare, then move by stepShare(largestTurn) or abandon.
	enum Status
	{
		kNothingToSolve,  // no articulation worth the exact solve (nothing to move or abandon)
		kPrepared,        // the step is computed; move or abandon
		kSingular         // some block was singular; abandon
	};
	/// Everything up to the bodies' moves; leftOver as for solve. largestTurn: the largest turn the step
	/// gives a body (non-finite turns are ignored, so the largest of several sets is the same in any order).
	Status prepare(btTypedConstraint** joints, int numJoints, int minJoints, btScalar minGap,
	               btAlignedObjectArray<btTypedConstraint*>& leftOver, btScalar& largestTurn);
	/// The share of the computed step to take when the largest turn of all trees is largestTurn.
	static btScalar stepShare(btScalar largestTurn);
	/// Moves the bodies of the prepared trees by share of their step.
	void move(btScalar share, btAlignedObjectArray<btRigidBody*>& movedBodies);
	/// Appends the prepared trees' joints to leftOver (no body moves).
	void abandon(btAlignedObjectArray<btTypedConstraint*>& leftOver) const;

private:
	struct Edge
	{
		btTypedConstraint* joint;
		int bodyA, bodyB;  // indices into m_bodies, -1 for the world
		btVector3 armA, armB;
		btVector3 gap;  // world anchor A minus world anchor B
	};
	struct Node
	{
		int edge;    // >= 0: a joint node (3 rows)
		int body;    // >= 0: a body node (6 coordinates)
		int parent;  // node index, -1 for a root
	};
	btAlignedObjectArray<btRigidBody*> m_bodies;
	btAlignedObjectArray<Edge> m_edges;
	btAlignedObjectArray<int> m_unionFind;
	btAlignedObjectArray<int> m_edgeStart, m_edgeList;  // per body, its tree edges
	btAlignedObjectArray<Node> m_nodes;
	btAlignedObjectArray<int> m_bodyNode;
	btAlignedObjectArray<char> m_edgeUsed;
	btAlignedObjectArray<int> m_componentJoints;
	btAlignedObjectArray<btScalar> m_componentGap;
	btAlignedObjectArray<btScalar> m_d, m_dInverse, m_z, m_y;  // 36, 36, 6, 6 per node

	int find(int i);

	// The steps of solve, in order.
	/// One edge per anchor joint with a movable body (bodies indexed in m_bodies); joints touching a body
	/// the tree cannot take go to leftOver.
	void gatherEdges(btTypedConstraint** joints, int numJoints, btAlignedObjectArray<btTypedConstraint*>& leftOver);
	/// Marks (m_edgeUsed) the edges of the articulations worth an exact solve.
	void chooseArticulations(int minJoints, btScalar minGap);
	/// Keeps a spanning forest of the marked edges (the world as one more vertex) and lists each body's
	/// forest edges; loop-closing and unmarked joints go to leftOver. False if no edge is kept.
	bool buildSpanningForest(btAlignedObjectArray<btTypedConstraint*>& leftOver);
	/// Lays out m_nodes breadth-first from the roots, parents before children.
	void orderNodesFromRoots();
	/// Fills each node's diagonal block (bodies: mass and world inertia) and right-hand side (joints: gap).
	void assembleBlocks();
	/// The 3 x 6 coupling block between node i and its parent, into g (stride 6).
	void couplingToParent(int i, btScalar* g) const;
	/// Eliminates leaves first, each node's Schur complement into its parent; false on a singular block.
	bool eliminateLeavesFirst();
	/// Back substitution, roots first, into m_y.
	void substituteRootsFirst();
	/// The largest turn in m_y (non-finite ones ignored).
	btScalar largestTurn() const;
};
}  // namespace caliber

#endif  // CALIBER_JOINT_ANCHOR_TREE_H
