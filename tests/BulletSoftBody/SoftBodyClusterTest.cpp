// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// Clusters (docs/soft-bodies.md, "Clusters"): the partition, momentum of cluster impulses, cluster
// contacts with rigid bodies (CL_RS), other soft bodies (CL_SS) and the body itself (CL_SELF), and the
// cluster joints.

#include <gtest/gtest.h>

#include <vector>

#include "BulletDynamics/Dynamics/DynamicsWorldTestUtil.h"  // WarningCounter
#include "SoftBodyTestUtil.h"

using caliber_test::lowestNodeY;
using caliber_test::rigidSoftBox;
using caliber_test::SoftTestWorld;
using caliber_test::WarningCounter;

namespace
{
const btScalar kStep = btScalar(1) / 60;
const btScalar kGravity = 10;

// A closed ball of about res nodes and mass 1 that keeps its shape (inextensible links, a pressurised
// gas), with clusters.
btSoftBody* clusterBall(SoftTestWorld& w, const btVector3& centre, btScalar radius, int res, int clusters)
{
	btSoftBody* b = btSoftBodyHelpers::CreateEllipsoid(w.info(), centre, btVector3(radius, radius, radius), res);
	b->setTotalMass(1, true);
	b->m_cfg.kPR = 100;
	b->m_cfg.piterations = 4;
	b->generateClusters(clusters);
	return b;
}

// How deep the deepest node of a lies inside b, taking b as convex (the depth behind all its faces' planes;
// 0 when every node of a is outside).
btScalar deepestInside(const btSoftBody& a, const btSoftBody& b)
{
	const btScalar sign = b.getVolume() < 0 ? btScalar(-1) : btScalar(1);  // outward normals
	btScalar deepest = 0;
	for (int i = 0; i < a.m_nodes.size(); ++i)
	{
		btScalar depth = BT_LARGE_FLOAT;
		for (int k = 0; k < b.m_faces.size(); ++k)
		{
			const btSoftBody::Face& f = b.m_faces[k];
			btVector3 n = (f.m_n[1]->m_x - f.m_n[0]->m_x).cross(f.m_n[2]->m_x - f.m_n[0]->m_x);
			if (n.length2() <= SIMD_EPSILON) continue;
			n = n.normalized() * sign;
			depth = btMin(depth, -n.dot(a.m_nodes[i].m_x - f.m_n[0]->m_x));
		}
		deepest = btMax(deepest, depth);
	}
	return deepest;
}

// Angular momentum of the free nodes about p.
btVector3 angularMomentum(const btSoftBody& s, const btVector3& p)
{
	btVector3 l(0, 0, 0);
	for (int i = 0; i < s.m_nodes.size(); ++i)
		if (s.m_nodes[i].m_im > 0) l += (s.m_nodes[i].m_x - p).cross(s.m_nodes[i].m_v / s.m_nodes[i].m_im);
	return l;
}
}  // namespace

TEST(SoftBodyClusters, KMeansClustersCoverEveryNodeAndCarryTheirMasses)
{
	SoftTestWorld w;
	btSoftBody* b = w.addSoft(clusterBall(w, btVector3(0, 2, 0), 1, 128, 8), false);
	ASSERT_EQ(b->clusterCount(), 8);
	std::vector<int> memberships(b->m_nodes.size(), 0);
	for (int i = 0; i < b->clusterCount(); ++i)
		for (int j = 0; j < b->m_clusters[i]->m_nodes.size(); ++j) ++memberships[b->m_clusters[i]->m_nodes[j]->index];
	btScalar clusterMasses = 0;
	for (int i = 0; i < b->clusterCount(); ++i)
	{
		const btSoftBody::Cluster& c = *b->m_clusters[i];
		EXPECT_EQ(c.m_clusterIndex, i);
		ASSERT_EQ(c.m_masses.size(), c.m_nodes.size());
		btScalar mass = 0;
		btVector3 com(0, 0, 0);
		for (int j = 0; j < c.m_nodes.size(); ++j)
		{
			// A node shared by n clusters gives each 1/n of its mass.
			const int n = memberships[c.m_nodes[j]->index];
			EXPECT_FLOAT_EQ(c.m_masses[j] * n, 1 / c.m_nodes[j]->m_im);
			mass += c.m_masses[j];
			com += c.m_nodes[j]->m_x * c.m_masses[j];
		}
		EXPECT_NEAR(c.m_imass * mass, 1, 1e-5);
		// The centre of mass of the cluster is the mass-weighted mean of its nodes.
		EXPECT_LT((com / mass - b->clusterCom(i)).length(), 1e-5);
		clusterMasses += mass;
	}
	for (int i = 0; i < b->m_nodes.size(); ++i) EXPECT_GE(memberships[i], 1) << "node " << i << " is in no cluster";
	// The clusters' masses add up to the body's: every node's mass is counted once.
	EXPECT_NEAR(clusterMasses, b->getTotalMass(), 1e-5);
	// Neighbours share their border nodes (k-means clusters take in the faces that cross their border).
	int shared = 0;
	for (int i = 0; i < b->m_nodes.size(); ++i) shared += memberships[i] > 1;
	EXPECT_GT(shared, 0);
	// k <= 0: one cluster per face of a surface without tetras.
	EXPECT_EQ(b->generateClusters(0), b->m_faces.size());
	EXPECT_EQ(b->generateClusters(-3), b->m_faces.size());
	// Neighbours (sharing a node) are marked connected; self-collision skips them.
	const int n = b->clusterCount();
	ASSERT_EQ(b->m_clusterConnectivity.size(), n * n);
	EXPECT_TRUE(b->m_clusterConnectivity[0]);
}

TEST(SoftBodyClusters, ClusterImpulsesConserveMomentum)
{
	// A cluster moves its nodes as one rigid body: the nodes' momentum changes by the impulse J and their
	// angular momentum about the cluster's centre by r x J. (The cluster's inertia is regularised by 1e-4
	// of its trace, so angular momentum holds to that relative tolerance.)
	SoftTestWorld w;
	btSoftBody* b = w.addSoft(clusterBall(w, btVector3(0, 2, 0), 1, 64, 3), false);
	ASSERT_EQ(b->clusterCount(), 3);
	btSoftBody::Cluster* c = b->m_clusters[1];
	const btVector3 com = b->clusterCom(1);
	const btVector3 p0 = caliber_test::nodeMomentum(*b), l0 = angularMomentum(*b, com);
	const btVector3 j(0.3, -0.2, 0.5), r(0.1, 0.4, -0.2);
	btSoftBody::Impulse impulse;
	impulse.m_velocity = j;
	impulse.m_asVelocity = 1;
	btSoftBody::clusterImpulse(c, r, impulse);
	b->applyClusters(false);
	const btVector3 dp = caliber_test::nodeMomentum(*b) - p0, dl = angularMomentum(*b, com) - l0;
	EXPECT_LT((dp - j).length(), 1e-5);
	EXPECT_LT((dl - r.cross(j)).length(), 1e-3 * r.cross(j).length());
	EXPECT_EQ(c->m_nvimpulses, 0);
	// A position impulse moves the nodes' mass-weighted sum by J dt (the impulse's velocity over the step).
	btVector3 before(0, 0, 0), after(0, 0, 0);
	for (int i = 0; i < b->m_nodes.size(); ++i) before += b->m_nodes[i].m_x / b->m_nodes[i].m_im;
	btSoftBody::clusterDCImpulse(c, j);
	b->applyClusters(true);
	for (int i = 0; i < b->m_nodes.size(); ++i) after += b->m_nodes[i].m_x / b->m_nodes[i].m_im;
	EXPECT_LT((after - before - j * b->m_sst.sdt).length(), 1e-5);
}

TEST(SoftBodyClusters, ClusterBallRestsOnABoxWithoutSinking)
{
	SoftTestWorld w;
	w.addGround();
	btSoftBody* b = w.addSoft(clusterBall(w, btVector3(0, 1.5, 0), 1, 128, 8));
	b->m_cfg.collisions = btSoftBody::fCollision::CL_RS;  // clusters only: no node contacts
	btScalar lowest = BT_LARGE_FLOAT;
	for (int i = 0; i < 180; ++i)
	{
		w.step(1);
		if (i >= 60) lowest = btMin(lowest, lowestNodeY(*b));  // after landing
	}
	// The nodes of each cluster within reach of its contact plane end every step's cluster stage on the
	// box's surface; a node that was out of reach when the contacts were found can fall at most one step
	// of gravity from rest, g h^2 = 2.8 mm, below it before the next step finds it.
	EXPECT_GT(lowest, -kGravity * kStep * kStep);
	EXPECT_LT(lowest, 0.05);  // resting on the box, not held above it
}

TEST(SoftBodyClusters, ClusterBallsCollideWithoutInterpenetrating)
{
	for (int withClusters = 1; withClusters >= 0; --withClusters)
	{
		SoftTestWorld w;
		w.addGround();
		btSoftBody* lower = w.addSoft(clusterBall(w, btVector3(0, 1, 0), 1, 128, 8));
		btSoftBody* upper = w.addSoft(clusterBall(w, btVector3(0, 3.5, 0), 1, 128, 8));
		for (btSoftBody* s : {lower, upper})
			s->m_cfg.collisions = btSoftBody::fCollision::CL_RS | (withClusters ? btSoftBody::fCollision::CL_SS : 0);
		btScalar closest = BT_LARGE_FLOAT, deepest = 0;
		for (int i = 0; i < 90; ++i)
		{
			w.step(1);
			closest = btMin(closest, (upper->getCenterOfMass() - lower->getCenterOfMass()).length());
			if (i >= 16 && i % 2 == 0) deepest = btMax(deepest, deepestInside(*upper, *lower));  // from the first touch
		}
		if (withClusters)
		{
			// Cluster hulls are kept apart: no node of the upper ball ever enters the lower one, which holds
			// it up (two balls of radius 1 squashed by their weight and the landing).
			EXPECT_EQ(deepest, 0);
			EXPECT_GT(closest, 1.2);
			EXPECT_GT(lowestNodeY(*upper), 1);
		}
		else
			EXPECT_GT(deepest, 0.3);  // without CL_SS the upper ball falls into the lower one
	}
}

namespace
{
// Momentum, angular momentum about the origin and kinetic energy of the nodes of some bodies.
struct Motion
{
	btVector3 p{0, 0, 0}, l{0, 0, 0};
	btScalar energy = 0;
};
Motion motion(const std::vector<btSoftBody*>& bodies)
{
	Motion m;
	for (const btSoftBody* b : bodies)
		for (int i = 0; i < b->m_nodes.size(); ++i)
		{
			const btSoftBody::Node& n = b->m_nodes[i];
			const btScalar mass = 1 / n.m_im;
			m.p += n.m_v * mass;
			m.l += n.m_x.cross(n.m_v) * mass;
			m.energy += mass * n.m_v.length2() / 2;
		}
	return m;
}
}  // namespace

TEST(SoftBodyClusters, OffCentreClusterHitSpinsTheBodyKeepingMomentumAndAngularMomentum)
{
	// In zero gravity a 1 kg cube (0.4 m) at 4 m/s hits a resting 1 kg bar (0.2 x 2 m, upright) 0.7 m above
	// the bar's centre, face on, without friction (CL_SS, one cluster each). The push at the contact turns
	// the bar: with I = 1.01 kg m^2 (8 corners of 1/8 kg at 0.1 and 1 m) and r = 0.7 m, the impulse of a
	// perfectly inelastic hit is J = v0 / (1/mA + 1/mB + r^2 / I) = 1.61 N s, an elastic one twice that; the
	// bar's spin r J / I lies between 1.12 and 2.23 rad/s (clockwise about z) for any restitution. Momentum
	// and angular momentum (about any point) are kept by the contact: the pushes on the two sides are
	// opposite and act at one point; the bar's links turning at 1-2 rad/s lose a little of the latter by
	// their position projection (0.1% over the second measured).
	SoftTestWorld w(btVector3(0, 0, 0));
	btSoftBody* bar = rigidSoftBox(w, btVector3(0, 5, 0), btVector3(0.1, 1, 0.1), 1, btSoftBody::fCollision::CL_SS);
	btSoftBody* cube =
	    rigidSoftBox(w, btVector3(-1.5, 5.7, 0), btVector3(0.2, 0.2, 0.2), 1, btSoftBody::fCollision::CL_SS);
	cube->setVelocity(btVector3(4, 0, 0));
	const std::vector<btSoftBody*> both = {bar, cube};
	const Motion before = motion(both);
	w.step(60);
	const Motion after = motion(both);
	EXPECT_NEAR(after.p.x(), before.p.x(), 1e-3 * before.p.x());
	EXPECT_NEAR(after.p.y(), 0, 1e-3 * before.p.x());
	EXPECT_LT((after.l - before.l).length(), 2e-3 * before.l.length());
	EXPECT_LT(after.energy, before.energy);  // no collision adds energy
	// The bar's spin about z: its angular momentum about its centre over its moment of inertia.
	const btVector3 com = bar->evaluateCom();
	btScalar lz = 0, izz = 0;
	for (int i = 0; i < bar->m_nodes.size(); ++i)
	{
		const btSoftBody::Node& n = bar->m_nodes[i];
		const btVector3 r = n.m_x - com;
		lz += r.cross(n.m_v).z() / n.m_im;
		izz += (r.x() * r.x() + r.y() * r.y()) / n.m_im;
	}
	const btScalar spin = lz / izz;
	EXPECT_LT(spin, btScalar(-1.12 * 0.98));
	EXPECT_GT(spin, btScalar(-2.23 * 1.02));
}

TEST(SoftBodyClusters, FoldedClothDoesNotPassThroughItselfWithClusterSelfCollision)
{
	for (int self = 1; self >= 0; --self)
	{
		SoftTestWorld w;
		w.addGround();
		// A strip folded in two: the lower layer on the ground, the upper layer 0.3 m above it, joined at x = 2.
		const int segments = 12;
		const btScalar length = 2, width = 0.5, height = 0.3;
		btSoftBody* s = new btSoftBody(&w.info());
		for (int i = 0; i <= 2 * segments + 1; ++i)
		{
			const bool upperLayer = i > segments;
			const btScalar x = upperLayer ? length * (2 * segments + 1 - i) / segments : length * i / segments;
			const btScalar y = upperLayer ? height + btScalar(0.02) : btScalar(0.02);
			s->appendNode(btVector3(x, y, 0), 0.01);
			s->appendNode(btVector3(x, y, width), 0.01);
		}
		for (int i = 0; i <= 2 * segments; ++i)
		{
			const int a = 2 * i, b = a + 1, c = a + 2, d = a + 3;
			s->appendLink(a, b, 0, true);
			s->appendLink(a, c);
			s->appendLink(b, d);
			s->appendLink(a, d);
			s->appendFace(a, c, d);
			s->appendFace(a, d, b);
		}
		s->appendLink(2 * (2 * segments + 1), 2 * (2 * segments + 1) + 1);
		s->getCollisionShape()->setMargin(0.1);
		s->m_cfg.piterations = 4;
		s->generateClusters(0);
		if (self) s->m_cfg.collisions |= btSoftBody::fCollision::CL_SELF;
		w.addSoft(s);
		w.step(45);  // the upper layer lands after 15 steps
		btScalar upperLow = BT_LARGE_FLOAT, lowerHigh = -BT_LARGE_FLOAT;
		for (int i = 0; i < s->m_nodes.size(); ++i)
		{
			if (s->m_nodes[i].m_x.x() > length / 2) continue;  // away from the fold
			if (i / 2 > segments)
				upperLow = btMin(upperLow, s->m_nodes[i].m_x.y());
			else
				lowerHigh = btMax(lowerHigh, s->m_nodes[i].m_x.y());
		}
		// Face clusters' hulls are grown by a quarter of the margin (0.025 m each), so with CL_SELF the
		// layers stay 0.05 m apart (at least half that at the end of a step: contacts are found at the
		// predicted positions); without it the upper layer falls through to the ground.
		if (self)
			EXPECT_GT(upperLow - lowerHigh, 0.025);
		else
			EXPECT_LT(upperLow - lowerHigh, 0.01);
	}
}

namespace
{
// Bullet's SoftDemo motor: turns towards goal by at most maxStep (rad/s) per solve.
struct Motor : btSoftBody::AJoint::IControl
{
	btScalar goal = 0, maxStep = 1;
	btScalar Speed(btSoftBody::AJoint*, btScalar current) override
	{
		return current + btMin(maxStep, btMax(-maxStep, goal - current));
	}
};
}  // namespace

TEST(SoftBodyClusters, LinearJointsHoldWithinTheirErp)
{
	// A soft ball hangs from a world point by a linear joint at its top and carries a 1 kg box by another
	// at its bottom. Each step gravity moves the chain (ball and box, 1 kg each) 2 g h^2 = 5.6 mm away from
	// where the joints hold it, and the citerations = 4 solves close at least k = 1 - (1 - erp)^4 of what
	// they see: each gap stays within 2 g h^2 / k, and a weaker erp leaves larger gaps.
	btScalar previousGap = 0;
	for (btScalar erp : {btScalar(1), btScalar(0.2)})
	{
		SoftTestWorld w;
		btSoftBody* b = w.addSoft(clusterBall(w, btVector3(0, 5, 0), 0.5, 64, 1));
		btRigidBody* box = w.addRigid(1, btVector3(0, 4, 0), w.shape<btBoxShape>(btVector3(0.3, 0.3, 0.3)));
		btSoftBody::LJoint::Specs top, bottom;
		top.position = btVector3(0, 5.5, 0);
		top.erp = erp;
		bottom.position = btVector3(0, 4.3, 0);
		bottom.erp = erp;
		b->appendLinearJoint(top);  // to the world
		b->appendLinearJoint(bottom, btSoftBody::Body(box));
		ASSERT_EQ(b->m_joints.size(), 2);
		w.step(120);
		const btVector3 ballTop = b->m_clusters[0]->m_framexform * b->m_joints[0]->m_refs[0];
		const btVector3 ballBottom = b->m_clusters[0]->m_framexform * b->m_joints[1]->m_refs[0];
		const btVector3 boxTop = box->getWorldTransform() * b->m_joints[1]->m_refs[1];
		const btScalar k = 1 - btPow(1 - erp, btScalar(b->m_cfg.citerations));
		const btScalar bound = 2 * kGravity * kStep * kStep / k;
		const btScalar topGap = (ballTop - top.position).length(), bottomGap = (ballBottom - boxTop).length();
		EXPECT_LT(topGap, bound) << "erp " << erp;
		EXPECT_LT(bottomGap, bound) << "erp " << erp;
		EXPECT_GT(topGap, previousGap) << "erp " << erp;
		previousGap = topGap;
	}
}

TEST(SoftBodyClusters, AngularJointMotorReachesItsSpeed)
{
	SoftTestWorld w(btVector3(0, 0, 0));
	btSoftBody* b = w.addSoft(clusterBall(w, btVector3(0, 2, 0), 0.5, 64, 1));
	Motor motor;
	motor.goal = 2;
	btSoftBody::AJoint::Specs hinge;
	hinge.axis = btVector3(0, 1, 0);
	hinge.icontrol = &motor;
	b->appendAngularJoint(hinge);
	btSoftBody::LJoint::Specs pin;
	pin.position = btVector3(0, 2, 0);
	b->appendLinearJoint(pin);
	w.step(60);
	// The turn rate about the axis from the nodes: L_y / I_yy about the centre of mass.
	const btVector3 com = b->getCenterOfMass();
	btScalar iyy = 0;
	for (int i = 0; i < b->m_nodes.size(); ++i)
	{
		const btVector3 r = b->m_nodes[i].m_x - com;
		iyy += (r.x() * r.x() + r.z() * r.z()) / b->m_nodes[i].m_im;
	}
	const btScalar rate = angularMomentum(*b, com).y() / iyy;
	// The motor sets the turn rate each solve; the links of the spinning ball take a little of it back
	// (their pull towards the axis as the nodes move along their tangents): 1% is allowed.
	EXPECT_NEAR(rate, motor.goal, 0.01 * motor.goal);
}

// ---- bad input (docs/bad-input.md, "Soft bodies") ---------------------------------------------------

TEST(SoftBodyClustersBadInput, GenerateClustersWithNonsenseCountsWarnsAndNeverCrashes)
{
	btSoftBodyWorldInfo info;
	WarningCounter warnings;
	btSoftBody empty(&info);
	EXPECT_EQ(empty.generateClusters(4), 0);  // no nodes
	EXPECT_EQ(warnings.count(), 1);
	const btVector3 x[3] = {btVector3(0, 0, 0), btVector3(1, 0, 0), btVector3(0, 1, 0)};
	btSoftBody loose(&info, 3, x, 0);
	EXPECT_EQ(loose.generateClusters(-1), 0);  // a cluster per tetra, face or link: it has none
	EXPECT_EQ(warnings.count(), 2);
	EXPECT_EQ(loose.generateClusters(10), 3);  // more clusters than nodes: one per node
	EXPECT_EQ(warnings.count(), 3);
	EXPECT_EQ(loose.generateClusters(2, 0), 2);  // no k-means rounds asked for: one round
	EXPECT_EQ(warnings.count(), 4);
	loose.appendFace(0, 1, 2);
	EXPECT_EQ(loose.generateClusters(-5), 1);  // k <= 0 is Bullet's "one per face": no warning
	EXPECT_EQ(warnings.count(), 4);
}

TEST(SoftBodyClustersBadInput, JointsToMissingBodiesOrClustersAreNotAdded)
{
	SoftTestWorld w;
	btSoftBody* plain =
	    w.addSoft(btSoftBodyHelpers::CreateEllipsoid(w.info(), btVector3(0, 2, 0), btVector3(1, 1, 1), 32));
	btSoftBody* clustered = w.addSoft(clusterBall(w, btVector3(3, 2, 0), 1, 32, 2));
	btSoftBody::LJoint::Specs lj;
	lj.position = btVector3(0, 3, 0);
	btSoftBody::AJoint::Specs aj;
	aj.axis = btVector3(0, 1, 0);
#if CALIBER_ASSERTS_ENABLED
	EXPECT_DEATH(plain->appendLinearJoint(lj), "without clusters");
	EXPECT_DEATH(clustered->appendLinearJoint(lj, static_cast<btSoftBody*>(nullptr)), "null soft body");
	EXPECT_DEATH(clustered->appendAngularJoint(aj, plain), "without clusters");
	EXPECT_DEATH(plain->appendLinearJoint(lj, clustered->m_clusters[0], btSoftBody::Body()), "missing cluster");
	EXPECT_DEATH(clustered->releaseCluster(5), "out of range");
	EXPECT_DEATH(clustered->clusterCom(-1), "out of range");
	aj.axis = btVector3(0, 0, 0);
	EXPECT_DEATH(clustered->appendAngularJoint(aj), "zero or non-finite axis");
#else
	WarningCounter warnings;
	plain->appendLinearJoint(lj);
	clustered->appendLinearJoint(lj, static_cast<btSoftBody*>(nullptr));
	clustered->appendAngularJoint(aj, plain);
	plain->appendLinearJoint(lj, clustered->m_clusters[0], btSoftBody::Body());
	clustered->releaseCluster(5);
	EXPECT_EQ(clustered->clusterCom(-1), btVector3(0, 0, 0));
	aj.axis = btVector3(0, 0, 0);
	clustered->appendAngularJoint(aj);
	EXPECT_EQ(warnings.count(), 7);
	EXPECT_EQ(plain->m_joints.size(), 0);
	EXPECT_EQ(clustered->m_joints.size(), 0);
	EXPECT_EQ(clustered->clusterCount(), 2);
	w.step(2);
#endif
}

TEST(SoftBodyClustersBadInput, JointsToRemovedBodiesAreDropped)
{
	SoftTestWorld w;
	btSoftBody* ball = w.addSoft(clusterBall(w, btVector3(0, 5, 0), 0.5, 32, 2));
	btRigidBody* box = w.addRigid(1, btVector3(0, 4, 0), w.shape<btBoxShape>(btVector3(0.3, 0.3, 0.3)));
	btSoftBody* other = w.addSoft(clusterBall(w, btVector3(0, 7, 0), 0.5, 32, 2));
	btSoftBody::LJoint::Specs lj;
	lj.position = btVector3(0, 4.4, 0);
	ball->appendLinearJoint(lj, btSoftBody::Body(box));
	lj.position = btVector3(0, 6, 0);
	ball->appendLinearJoint(lj, other);
	ASSERT_EQ(ball->m_joints.size(), 2);
	w.step(2);
	w.world().removeRigidBody(box);
#if CALIBER_ASSERTS_ENABLED
	EXPECT_DEATH(w.step(1), "removed from the world");
#else
	WarningCounter warnings;
	w.step(1);
	EXPECT_EQ(ball->m_joints.size(), 1);
	EXPECT_EQ(warnings.count(), 1);
	// The other soft body deleted: its clusters are gone, and so is the joint to them.
	w.world().removeSoftBody(other);
	other->releaseClusters();
	w.step(1);
	EXPECT_EQ(ball->m_joints.size(), 0);
	EXPECT_EQ(warnings.count(), 2);
	w.step(5);
	EXPECT_EQ(warnings.count(), 2);
#endif
	w.world().addRigidBody(box);  // back, so that the test world removes it
}

namespace
{
struct LineCounter : btIDebugDraw
{
	int lines = 0;
	void drawLine(const btVector3&, const btVector3&, const btVector3&) override { ++lines; }
	void drawContactPoint(const btVector3&, const btVector3&, btScalar, int, const btVector3&) override {}
	void reportErrorWarning(const char*) override {}
	void draw3dText(const btVector3&, const char*) override {}
	void setDebugMode(int) override {}
	int getDebugMode() const override { return 0; }
};
}  // namespace

TEST(SoftBodyClusters, ClustersAndJointsAreDrawnWhenAskedFor)
{
	SoftTestWorld w;
	btSoftBody* b = w.addSoft(clusterBall(w, btVector3(0, 2, 0), 1, 32, 2), false);
	int spokes = 0;
	for (int i = 0; i < b->clusterCount(); ++i) spokes += b->m_clusters[i]->m_nodes.size();
	LineCounter clusters, joints, tree;
	btSoftBodyHelpers::Draw(b, &clusters, fDrawFlags::Clusters);
	EXPECT_EQ(clusters.lines, spokes);  // one spoke per node of each cluster
	btSoftBody::LJoint::Specs lj;
	lj.position = btVector3(0, 3, 0);
	b->appendLinearJoint(lj);
	btSoftBodyHelpers::Draw(b, &joints, fDrawFlags::Joints);
	EXPECT_EQ(joints.lines, 4);  // a cross at the joint and the line between its sides
	// The cluster tree (m_cdbvt): a box per node, 2n - 1 for n leaves; from depth 1, the two clusters' leaves.
	btSoftBodyHelpers::DrawClusterTree(b, &tree);
	EXPECT_EQ(tree.lines, 12 * (2 * b->clusterCount() - 1));
	LineCounter leaves;
	btSoftBodyHelpers::DrawClusterTree(b, &leaves, 1);
	EXPECT_EQ(leaves.lines, 12 * b->clusterCount());
}
