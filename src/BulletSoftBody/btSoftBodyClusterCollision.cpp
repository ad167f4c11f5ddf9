// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// Cluster contacts: the convex hull of each cluster's nodes against rigid convex shapes (CL_RS), against
// the clusters of other soft bodies (CL_SS) and against the body's own clusters that share no node
// (CL_SELF), by GJK/EPA (btGjkEpaSolver2). Solved by the cluster stage (btSoftBodyJoints.cpp).

#include "BulletCollision/CollisionDispatch/btCollisionObjectWrapper.h"
#include "BulletCollision/CollisionShapes/btCompoundShape.h"
#include "BulletCollision/CollisionShapes/btConvexPointCloudShape.h"
#include "BulletCollision/NarrowPhaseCollision/btGjkEpa2.h"
#include "btSoftBodyClusters.h"
#include "btSoftBodyInternal.h"

namespace
{
using caliber::Box;

Box clusterBox(const btSoftBody::Cluster& c, btScalar grow)
{
	Box b{c.m_nodes[0]->m_x, c.m_nodes[0]->m_x};
	for (int j = 1; j < c.m_nodes.size(); ++j)
	{
		b.lo.setMin(c.m_nodes[j]->m_x);
		b.hi.setMax(c.m_nodes[j]->m_x);
	}
	const btVector3 g(grow, grow, grow);
	b.lo -= g;
	b.hi += g;
	return b;
}

// The cluster's hull: its nodes relative to its centre (the shape is placed at the centre).
void fillHull(const btSoftBody::Cluster& c, btAlignedObjectArray<btVector3>& points, btConvexPointCloudShape& hull,
              btScalar margin)
{
	points.resize(c.m_nodes.size());
	for (int j = 0; j < c.m_nodes.size(); ++j) points[j] = c.m_nodes[j]->m_x - c.m_com;
	hull.setPoints(&points[0], points.size(), true);
	hull.setMargin(margin);
}

// True when one of body's joints joins its cluster c to other.
bool joined(const btSoftBody& body, const btSoftBody::Cluster* c, const btSoftBody::Cluster* other)
{
	for (int i = 0; i < body.m_joints.size(); ++i)
	{
		const btSoftBody::Joint* j = body.m_joints[i];
		if (j->m_bodies[0].m_soft == c && j->m_bodies[1].m_soft == other) return true;
	}
	return false;
}

// A split factor in [0, 1]; NaN is 1 (no recovery turns into velocity: never adds energy).
btScalar splitFactor(btScalar split)
{
	return split == split ? btClamped(split, btScalar(0), btScalar(1)) : btScalar(1);
}

btTransform at(const btVector3& origin)
{
	btTransform t;
	t.setIdentity();
	t.setOrigin(origin);
	return t;
}

// What one rigid convex shape's cluster contacts share.
struct ConvexTarget
{
	const btCollisionObject* object;
	const btConvexShape* shape;
	btTransform t, inverse;
	Box shapeBox;
	btScalar reach, hardness, split, friction;
};

// The contacts of one cluster with the shape, appended to out: its deepest point (the manifold's first
// contact, whose patch counts them) and every node within reach over the shape.
void clusterAgainstConvex(const ConvexTarget& g, btSoftBody::Cluster& c, btAlignedObjectArray<btVector3>& points,
                          btAlignedObjectArray<caliber::ClusterContact>& out)
{
	if (!c.m_collide || c.m_nodes.size() == 0 || !g.shapeBox.overlaps(clusterBox(c, g.reach))) return;
	btConvexPointCloudShape hull;
	fillHull(c, points, hull, 0);
	btGjkEpaSolver2::sResults res;
	const btTransform hullAt = at(c.m_com);
	// Signed distance between the surfaces (margins included); contacts are kept within reach, so that
	// a cluster closing in during the step is held too.
	if (!btGjkEpaSolver2::SignedDistance(&hull, hullAt, g.shape, g.t, c.m_com - g.t.getOrigin(), res) ||
	    !(res.distance < g.reach))
		return;
	caliber::ClusterContact contact;
	contact.cluster = &c;
	contact.other = 0;
	contact.object = g.object;
	contact.node = 0;
	contact.distance = 0;
	contact.weightsA = contact.weightsB = -1;
	contact.localA = c.m_framexform.inverse() * res.witnesses[0];
	contact.localB = g.inverse * res.witnesses[1];
	contact.normal = g.inverse.getBasis() * res.normal;  // from the shape towards the cluster, in its frame
	contact.hardness = g.hardness;
	contact.split = g.split;
	contact.friction = g.friction;
	contact.maxCorrection = BT_LARGE_FLOAT;
	contact.patch = 1;
	const int head = out.size();
	out.push_back(contact);
	contact.patch = 0;
	// The deepest point alone lets a cluster rest on one point and tip its other nodes through the
	// surface: every node within reach of the contact plane is held too (a contact manifold on the plane).
	const btScalar r = g.reach / 8;  // the plane lies on the box's face, give or take rounding
	const btVector3 slack(r, r, r);
	const btVector3& n = res.normal;
	for (int j = 0; j < c.m_nodes.size(); ++j)
	{
		btSoftBody::Node* node = c.m_nodes[j];
		const btScalar d = n.dot(node->m_x - res.witnesses[1]);
		if (d >= g.reach || node->m_im <= 0) continue;
		// Only nodes over the shape: beside a small shape the contact plane is not its surface.
		const btVector3 onPlane = node->m_x - n * d;
		if (!Box{onPlane - slack, onPlane + slack}.overlaps(g.shapeBox)) continue;
		contact.localA = c.m_framexform.inverse() * node->m_x;
		contact.localB = g.inverse * onPlane;
		contact.node = node;
		out.push_back(contact);
		++out[head].patch;
	}
}

// Clusters [begin, end) of the candidates on the task scheduler, each into its own list.
struct ClusterGather : btIParallelForBody
{
	const ConvexTarget* target;
	btSoftBody* body;
	caliber::ClusterState* state;
	void forLoop(int begin, int end) const override
	{
		for (int k = begin; k < end; ++k)
		{
			state->lists[k].resize(0);
			clusterAgainstConvex(*target, *body->m_clusters[state->near[k]], state->hulls[k], state->lists[k]);
		}
	}
};

// Below this many candidate clusters the contacts are found on the calling thread.
const int kParallelClusters = 4;

void collideWithConvex(btSoftBody& body, caliber::ClusterState& state, const btCollisionObject* object,
                       const btConvexShape* shape, const btTransform& t)
{
	ConvexTarget g;
	g.object = object;
	g.shape = shape;
	g.t = t;
	g.inverse = t.inverse();
	shape->getAabb(t, g.shapeBox.lo, g.shapeBox.hi);
	g.reach = body.getCollisionShape()->getMargin();
	const bool fixed = object->isStaticOrKinematicObject();
	g.hardness = btClamped(fixed ? body.m_cfg.kSKHR_CL : body.m_cfg.kSRHR_CL, btScalar(0), btScalar(1));
	g.split = splitFactor(fixed ? body.m_cfg.kSK_SPLT_CL : body.m_cfg.kSR_SPLT_CL);
	g.friction = body.m_cfg.kDF * object->getFriction();
	// The tree's candidates, in index order (the exact test is the one a scan of all clusters makes).
	caliber::clustersNear(body, g.shapeBox.lo, g.shapeBox.hi, state.near);
	const int m = state.near.size();
	if (m < kParallelClusters)
	{
		for (int k = 0; k < m; ++k)
			clusterAgainstConvex(g, *body.m_clusters[state.near[k]], state.points, state.contacts);
		return;
	}
	// Several clusters: on the task scheduler, each cluster's contacts into its own list, joined in order (the
	// contacts and their order are those of one thread).
	if (state.lists.size() < m)
	{
		state.lists.resize(m);
		state.hulls.resize(m);
	}
	ClusterGather gather;
	gather.target = &g;
	gather.body = &body;
	gather.state = &state;
	btParallelFor(0, m, 1, gather);
	for (int k = 0; k < m; ++k)
		for (int i = 0; i < state.lists[k].size(); ++i) state.contacts.push_back(state.lists[k][i]);
}
}  // namespace

bool caliber::collideClustersWithRigid(btSoftBody& body, const btCollisionObjectWrapper& rigid)
{
	const btCollisionObject* object = rigid.getCollisionObject();
	const btCollisionShape* shape = rigid.getCollisionShape();
	if (!object || !shape) return true;
	if (!object->hasContactResponse()) return true;
	ClusterState& state = clusterState(body);
	if (shape->isConvex())
	{
		collideWithConvex(body, state, object, static_cast<const btConvexShape*>(shape), rigid.getWorldTransform());
		return true;
	}
	if (shape->isCompound())
	{
		const btCompoundShape* compound = static_cast<const btCompoundShape*>(shape);
		bool any = false;
		for (int i = 0; i < compound->getNumChildShapes(); ++i)
		{
			const btCollisionShape* child = compound->getChildShape(i);
			if (!child->isConvex()) continue;
			any = true;
			collideWithConvex(body, state, object, static_cast<const btConvexShape*>(child),
			                  rigid.getWorldTransform() * compound->getChildTransform(i));
		}
		return any;
	}
	return false;
}

void caliber::collideClustersWithClusters(btSoftBody& a, btSoftBody& b)
{
	const bool self = &a == &b;
	// Hulls keep half the smaller margin between them (each is grown by a quarter), as node-face contacts do.
	const btScalar thickness =
	    btScalar(0.25) * btMin(a.getCollisionShape()->getMargin(), b.getCollisionShape()->getMargin());
	const btScalar hardness =
	    btClamped(btScalar(0.5) * (a.m_cfg.kSSHR_CL + b.m_cfg.kSSHR_CL), btScalar(0), btScalar(1));
	const btScalar split = btScalar(0.5) * (splitFactor(a.m_cfg.kSS_SPLT_CL) + splitFactor(b.m_cfg.kSS_SPLT_CL));
	const btScalar friction = btMax(a.m_cfg.kDF, b.m_cfg.kDF);
	const btScalar reach = btMin(a.getCollisionShape()->getMargin(), b.getCollisionShape()->getMargin());
	ClusterState& state = clusterState(a);
	const int countA = a.m_clusters.size();
	btConvexPointCloudShape hullA, hullB;
	for (int i = 0; i < countA; ++i)
	{
		btSoftBody::Cluster& ca = *a.m_clusters[i];
		if (!ca.m_collide || ca.m_nodes.size() == 0) continue;
		const Box boxA = clusterBox(ca, thickness + reach);
		bool filled = false;
		// b's clusters near ca by b's cluster tree, in index order; the exact box test follows.
		caliber::clustersNear(b, boxA.lo, boxA.hi, state.near);
		for (int k = 0; k < state.near.size(); ++k)
		{
			const int j = state.near[k];
			if (self && j <= i) continue;
			btSoftBody::Cluster& cb = *b.m_clusters[j];
			if (!cb.m_collide || cb.m_nodes.size() == 0 || !boxA.overlaps(clusterBox(cb, thickness + reach))) continue;
			if (self && a.m_clusterConnectivity.size() == countA * countA && a.m_clusterConnectivity[i + j * countA])
				continue;  // neighbours share nodes: they touch by construction
			if (joined(a, &ca, &cb) || joined(b, &cb, &ca)) continue;  // a joint holds them together: no contact
			if (!filled) fillHull(ca, state.points, hullA, thickness);
			filled = true;
			fillHull(cb, state.points2, hullB, thickness);
			btGjkEpaSolver2::sResults res;
			if (!btGjkEpaSolver2::SignedDistance(&hullA, at(ca.m_com), &hullB, at(cb.m_com), ca.m_com - cb.m_com,
			                                     res) ||
			    !(res.distance < reach))
				continue;
			caliber::ClusterContact contact;
			contact.cluster = &ca;
			contact.other = &cb;
			contact.object = 0;
			contact.node = 0;
			contact.normal = res.normal;  // from b's hull towards a's
			contact.hardness = hardness;
			contact.split = split;
			contact.patch = 1;  // each point its own friction (the points lie on both hulls)
			contact.friction = friction;
			contact.maxCorrection =
			    self ? btMin(ca.m_maxSelfCollisionImpulse, cb.m_maxSelfCollisionImpulse) : BT_LARGE_FLOAT;
			// A contact at point, followed on each side as a material point of its cluster.
			auto add = [&](const btVector3& point, btScalar distance)
			{
				contact.distance = distance;
				contact.weightsA = caliber::materialPointWeights(ca, point, state.weights);
				contact.weightsB = caliber::materialPointWeights(cb, point, state.weights);
				contact.localA = caliber::materialPoint(ca, state.weights, contact.weightsA);
				contact.localB = caliber::materialPoint(cb, state.weights, contact.weightsB);
				state.contacts.push_back(contact);
			};
			const int first = state.contacts.size();
			// The deepest point alone lets a cluster rest on one point and tip (as against rigid shapes): every
			// node of either hull within reach of the contact plane, over the other hull, is held too.
			const btVector3& n = res.normal;
			const Box overA = clusterBox(ca, thickness), overB = clusterBox(cb, thickness);
			for (int k = 0; k < ca.m_nodes.size(); ++k)
			{
				const btVector3& x = ca.m_nodes[k]->m_x;
				const btScalar d = n.dot(x - res.witnesses[1]) - thickness;  // A's grown surface to B's
				const btVector3 onPlane = x - n * (d + thickness);
				if (d < reach && ca.m_nodes[k]->m_im > 0 && Box{onPlane, onPlane}.overlaps(overB))
					add(onPlane + n * ((d + thickness) / 2), d);
			}
			for (int k = 0; k < cb.m_nodes.size(); ++k)
			{
				const btVector3& x = cb.m_nodes[k]->m_x;
				const btScalar d = n.dot(res.witnesses[0] - x) - thickness;
				const btVector3 onPlane = x + n * (d + thickness);
				if (d < reach && cb.m_nodes[k]->m_im > 0 && Box{onPlane, onPlane}.overlaps(overA))
					add(onPlane - n * ((d + thickness) / 2), d);
			}
			if (state.contacts.size() == first) add((res.witnesses[0] + res.witnesses[1]) / 2, res.distance);
		}
	}
}
