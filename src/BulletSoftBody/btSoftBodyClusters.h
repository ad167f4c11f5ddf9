// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef CALIBER_SOFT_BODY_CLUSTERS_H
#define CALIBER_SOFT_BODY_CLUSTERS_H

// Clusters in the position solve: a cluster is moved as a rigid body by position impulses (each of its
// nodes by the displacement of a rigid body of the cluster's mass and inertia), so every correction
// conserves linear and angular momentum. Cluster contacts (CL_RS, CL_SS, CL_SELF) are found by the
// collision pass (btSoftBodyClusterCollision.cpp) and kept in a side table keyed by the body (btSoftBody
// declares what Bullet's does); joints live in btSoftBody::m_joints. docs/soft-bodies.md, "Clusters".

#include "BulletSoftBody/btSoftBody.h"
#include "LinearMath/btAlignedObjectArray.h"

namespace caliber
{
/// A contact of one of the body's clusters with a rigid object or another cluster, found this step.
/// Against an object the constraint is normal . (pA - pB) >= 0, pA the node (or the witness point carried
/// by the cluster's frame), pB carried by the object. Between clusters it is distance + normal . (the moves
/// since of each cluster's material point at the contact) >= 0, each point an affine combination of its
/// cluster's nodes (materialPointWeights): it moves exactly with the cluster's rigid motions and smoothly
/// as the nodes deform (a point carried by the cluster's frame would jump when the best-fit rotation
/// does). The push acts at the contact point, so an off-centre hit turns the clusters, and angular
/// momentum is conserved.
struct ClusterContact
{
	btSoftBody::Cluster* cluster;     // side A: a cluster of the body
	btSoftBody::Cluster* other;       // side B when a cluster (of this or another soft body), else 0
	const btCollisionObject* object;  // side B when a rigid object, else 0
	btSoftBody::Node* node;           // the node at pA (manifold points against objects), else 0
	btVector3 localA;                 // pA in A's frame (m_framexform); between clusters, A's material point when found
	btVector3 localB;                 // pB in the object's frame; between clusters, B's material point when found
	btScalar distance;                // between clusters: the signed distance when found
	int weightsA, weightsB;           // between clusters: where the material points' weights start (ClusterState)
	btVector3 normal;                 // from B towards A: world axes for clusters, B's frame for objects
	btScalar hardness;                // fraction of the error closed per solve
	btScalar split;                   // fraction of the push beyond stopping the approach that moves positions
	                                  // alone (Bullet's kS*_SPLT_CL); the rest changes velocities too
	btScalar friction;                // Coulomb coefficient
	btScalar maxCorrection;           // largest correction per solve (self-collision), in m
	int patch;                        // a manifold's first contact: its number of contacts, whose friction is
	                                  // solved together (1: this point's own friction); the others: 0
};

/// An axis-aligned box (of a cluster's nodes, or a shape).
struct Box
{
	btVector3 lo, hi;
	bool overlaps(const Box& o) const
	{
		return !(lo.x() > o.hi.x() || hi.x() < o.lo.x() || lo.y() > o.hi.y() || hi.y() < o.lo.y() ||
		         lo.z() > o.hi.z() || hi.z() < o.lo.z());
	}
};

struct ClusterState
{
	bool deferred = false;                          // solveConstraints leaves the cluster stage to the solver
	btAlignedObjectArray<ClusterContact> contacts;  // this step's, cleared in predictMotion
	btAlignedObjectArray<btVector3> points;         // scratch: a cluster's hull points
	btAlignedObjectArray<btVector3> points2;        // scratch: the other cluster's
	btAlignedObjectArray<btScalar> weights;         // material points of the contacts between clusters
	btAlignedObjectArray<int> near;                 // scratch: the clusters a tree query found
	btAlignedObjectArray<btAlignedObjectArray<ClusterContact>> lists;  // scratch: each candidate's contacts
	btAlignedObjectArray<btAlignedObjectArray<btVector3>> hulls;       // scratch: each candidate's hull points
};

/// The body's cluster state (contacts of this step).
ClusterState& clusterState(const btSoftBody& body);
/// Forgets the body's cluster state (its destructor).
void releaseClusterState(const btSoftBody& body);

/// The soft body that owns cluster (0 when the cluster is unknown: deleted with its body).
btSoftBody* clusterOwner(const btSoftBody::Cluster* cluster);

/// Recomputes a cluster's centre of mass, world inverse inertia, frame and velocities from its nodes'
/// current (x) and start (q) positions over a step of dt (dt <= 0: velocities from m_v).
void refreshCluster(btSoftBody::Cluster& c, btScalar dt);
/// Effective inverse mass of a cluster at offset r from its centre of mass along unit direction n.
btScalar clusterInverseMass(const btSoftBody::Cluster& c, const btVector3& r, const btVector3& n);
/// A cluster's centre of mass and its velocity over the step so far ((x - q) / dt), from its nodes now:
/// every move of a neighbour sharing nodes shows in them.
void clusterMotion(const btSoftBody::Cluster& c, btScalar dt, btVector3& com, btVector3& velocity);
/// Appends to weights one weight per node of c such that the sum of weight times node position is p now
/// and moves with every rigid motion of the cluster (an affine combination: the mass shares plus a first
/// moment towards p; a flat cluster keeps only p's part in its plane). Returns where they start.
int materialPointWeights(const btSoftBody::Cluster& c, const btVector3& p, btAlignedObjectArray<btScalar>& weights);
/// The point the weights at offset follow, from c's nodes now.
btVector3 materialPoint(const btSoftBody::Cluster& c, const btAlignedObjectArray<btScalar>& weights, int offset);
/// Effective inverse angular mass of a cluster about unit axis n.
btScalar clusterAngularInverseMass(const btSoftBody::Cluster& c, const btVector3& n);
/// Moves a cluster as a rigid body by the position impulse p (kg m) at offset r, over a step dt: its
/// nodes by the rigid displacement, its frame and tracked velocities with them. Velocities change by
/// velocityShare of the move (the rest moves positions alone, the nodes' start points with them).
void moveCluster(btSoftBody::Cluster& c, const btVector3& p, const btVector3& r, btScalar dt,
                 btScalar velocityShare = 1);
/// Turns a cluster by the angular position impulse l (kg m^2), as moveCluster.
void turnCluster(btSoftBody::Cluster& c, const btVector3& l, btScalar dt, btScalar velocityShare = 1);

/// Finds the contacts of body's clusters with one rigid object (CL_RS). Returns false when the object's
/// shape has no convex part (the caller then uses node contacts).
bool collideClustersWithRigid(btSoftBody& body, const btCollisionObjectWrapper& rigid);
/// Finds the contacts of a's clusters with b's (CL_SS), or with a's own clusters that share no node when
/// a == b (CL_SELF).
void collideClustersWithClusters(btSoftBody& a, btSoftBody& b);
/// Brings the body's cluster tree (m_cdbvt) up to date with its clusters' nodes now: one leaf per cluster
/// that collides (m_collide, with nodes), a fat box over the nodes grown by clusterTreeGrow; rebuilt when
/// clusters were made or released. Called by predictMotion and before self-collision
/// (btSoftBodyClusterTree.cpp).
void updateClusterTree(btSoftBody& body);
/// How far beyond its nodes a leaf of the body's cluster tree reaches at least (1.25 margins: the widest
/// box a cluster contact tests).
btScalar clusterTreeGrow(const btSoftBody& body);
/// The indices of the body's clusters whose leaves meet the box [lo, hi], in ascending order (a superset
/// of the clusters whose nodes' box grown by clusterTreeGrow meets it).
void clustersNear(const btSoftBody& body, const btVector3& lo, const btVector3& hi, btAlignedObjectArray<int>& out);
/// Takes a cluster's leaf out of the body's tree (the cluster is being released).
void removeClusterLeaf(btSoftBody& body, btSoftBody::Cluster& c);
/// The cluster stage of a step: citerations solves of the cluster contacts and joints, then shape
/// matching; called by solveConstraints after the node solvers.
void solveClusterStage(btSoftBody& body, btScalar dt);
/// The cluster stages of several bodies at once, their solves interleaved (each body's step is its
/// m_sst.sdt): called by btDefaultSoftBodySolver after the bodies' solveConstraints, for the bodies whose
/// stage it deferred (see deferClusterStage).
void solveClusterStages(btSoftBody* const* bodies, int count);
/// The end of solveConstraints after a deferred cluster stage: the node contacts' last solve.
void finishSoftSolve(btSoftBody& body);
/// A new cluster appended to body.m_clusters, registered as the body's (for readers that rebuild clusters
/// from stored data, btSoftBodySerialize.cpp).
btSoftBody::Cluster* appendCluster(btSoftBody& body);
}  // namespace caliber

#endif  // CALIBER_SOFT_BODY_CLUSTERS_H
