// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// btSoftRigidDynamicsWorld: soft bodies in the rigid step, contacts with rigid shapes of every kind,
// two-way coupling, filtering, ray tests and determinism.

#include <gtest/gtest.h>

#include "BulletCollision/CollisionShapes/btBvhTriangleMeshShape.h"
#include "BulletCollision/CollisionShapes/btTriangleMesh.h"
#include "SoftBodyTestUtil.h"

using caliber_test::SoftTestWorld;

namespace
{
btSoftBody* makeCloth(btSoftBodyWorldInfo& info, btScalar y, btScalar half, int res, int fixeds = 0)
{
	btSoftBody* c =
	    btSoftBodyHelpers::CreatePatch(info, btVector3(-half, y, -half), btVector3(half, y, -half),
	                                   btVector3(-half, y, half), btVector3(half, y, half), res, res, fixeds, true);
	c->setTotalMass(1);
	c->m_cfg.piterations = 4;
	return c;
}
}  // namespace

TEST(SoftRigidWorld, WorldStepsSoftBodiesWithGravity)
{
	// A free rope falls as a whole: after t = 0.5 s its centre has dropped g t^2 / 2 (semi-implicit
	// Euler at h = 1/60 s drops g t (t + h) / 2).
	SoftTestWorld w;
	btSoftBody* rope =
	    w.addSoft(btSoftBodyHelpers::CreateRope(w.info(), btVector3(0, 10, 0), btVector3(1, 10, 0), 8, 0));
	EXPECT_EQ(w.world().getSoftBodyArray().size(), 1);
	EXPECT_EQ(w.world().getWorldType(), BT_SOFT_RIGID_DYNAMICS_WORLD);
	w.step(30);
	const double t = 0.5, h = 1.0 / 60;
	// Float positions near 10 m are rounded to 1e-6 m, and velocities are taken from the moves: 5e-4.
	EXPECT_NEAR(rope->evaluateCom().y(), 10 - 10 * t * (t + h) / 2, 5e-4);
}

TEST(SoftRigidWorld, ClothRestsOnTheGroundAndNoNodeGoesBelowIt)
{
	SoftTestWorld w;
	w.addGround();
	btSoftBody* cloth = w.addSoft(makeCloth(w.info(), 1, 1, 10));
	btScalar lowest = BT_LARGE_FLOAT;
	for (int i = 0; i < 120; ++i)
	{
		w.step(1);
		lowest = btMin(lowest, caliber_test::lowestNodeY(*cloth));
	}
	// Contacts are solved to the surface itself; only float rounding at y ~ 0 remains.
	EXPECT_GE(lowest, -1e-5);
	EXPECT_LT(cloth->m_nodes[0].m_x.y(), 0.01);  // it lies on the ground
	EXPECT_LT(caliber_test::nodeMomentum(*cloth).length(), 1e-3);
}

TEST(SoftRigidWorld, FastClothDoesNotTunnelThroughAThinBoxOrAPlane)
{
	// Contacts are judged from where a node started its step, so any speed up to m_maxDisplacement per
	// step is caught: here 120 m/s (2 m per step) against a 4 cm thick board and a plane below it.
	SoftTestWorld w;
	w.addRigid(0, btVector3(0, 1, 0), w.shape<btBoxShape>(btVector3(3, btScalar(0.02), 3)));
	btSoftBody* cloth = w.addSoft(makeCloth(w.info(), 8, 1, 8));
	cloth->setVelocity(btVector3(0, -120, 0));
	SoftTestWorld w2;
	w2.addRigid(0, btVector3(0, 0, 0), w2.shape<btStaticPlaneShape>(btVector3(0, 1, 0), 0));
	btSoftBody* cloth2 = w2.addSoft(makeCloth(w2.info(), 8, 1, 8));
	cloth2->setVelocity(btVector3(0, -120, 0));
	btScalar lowest = BT_LARGE_FLOAT, lowest2 = BT_LARGE_FLOAT;
	for (int i = 0; i < 30; ++i)
	{
		w.step(1);
		w2.step(1);
		lowest = btMin(lowest, caliber_test::lowestNodeY(*cloth));
		lowest2 = btMin(lowest2, caliber_test::lowestNodeY(*cloth2));
	}
	EXPECT_GE(lowest, btScalar(1.02) - btScalar(1e-5));
	EXPECT_GE(lowest2, -1e-5);
}

TEST(SoftRigidWorld, ClothDrapesOverSphereCylinderAndTriangleMesh)
{
	// One cloth on each kind of shape path (analytic sphere, GJK convex, BVH mesh): no node ends up
	// inside the shape.
	SoftTestWorld w;
	w.addRigid(0, btVector3(-4, 0, 0), w.shape<btSphereShape>(btScalar(1)));
	w.addRigid(0, btVector3(0, 0, 0), w.shape<btCylinderShape>(btVector3(1, 1, 1)));
	btTriangleMesh* mesh = new btTriangleMesh();
	mesh->addTriangle(btVector3(3, 0, -2), btVector3(3, 0, 2), btVector3(7, 0, 2));
	mesh->addTriangle(btVector3(3, 0, -2), btVector3(7, 0, 2), btVector3(7, 0, -2));
	std::unique_ptr<btTriangleMesh> meshOwner(mesh);
	w.addRigid(0, btVector3(0, 0, 0), w.shape<btBvhTriangleMeshShape>(mesh, true));
	btSoftBody* onSphere = w.addSoft(makeCloth(w.info(), 2, 1.5, 12));
	onSphere->translate(btVector3(-4, 0, 0));
	btSoftBody* onCylinder = w.addSoft(makeCloth(w.info(), 2, 1.5, 12));
	btSoftBody* onMesh = w.addSoft(makeCloth(w.info(), 1, 1, 8));
	onMesh->translate(btVector3(5, 0, 0));
	w.step(90);
	for (int i = 0; i < onSphere->m_nodes.size(); ++i)
		EXPECT_GE((onSphere->m_nodes[i].m_x - btVector3(-4, 0, 0)).length(), 1 - 1e-4);
	const btScalar cylinderMargin = btScalar(0.04);  // the cylinder's default margin is part of its surface
	for (int i = 0; i < onCylinder->m_nodes.size(); ++i)
	{
		const btVector3& x = onCylinder->m_nodes[i].m_x;
		const bool inside =
		    btSqrt(x.x() * x.x() + x.z() * x.z()) < 1 - cylinderMargin - 1e-3 && btFabs(x.y()) < 1 - 1e-3;
		EXPECT_FALSE(inside) << "node " << i << " inside the cylinder at " << x.x() << " " << x.y() << " " << x.z();
	}
	EXPECT_GE(caliber_test::lowestNodeY(*onMesh), -1e-4);
	EXPECT_LT(caliber_test::lowestNodeY(*onMesh), 0.05);   // it landed on the mesh
	EXPECT_LT(caliber_test::lowestNodeY(*onSphere), 0.5);  // it draped down the sphere's sides
}

TEST(SoftRigidWorld, SoftRigidContactWithoutFrictionConservesMomentum)
{
	// Zero gravity, no friction: a soft ball hits a free box. Every contact moves the node and the box
	// by equal and opposite position impulses, so the total momentum stays 5 kg m/s.
	SoftTestWorld w(btVector3(0, 0, 0));
	btSoftBody* ball =
	    w.addSoft(btSoftBodyHelpers::CreateEllipsoid(w.info(), btVector3(0, 0, 0), btVector3(0.5, 0.5, 0.5), 64));
	ball->setTotalMass(1);
	ball->m_cfg.kDF = 0;
	ball->m_cfg.kPR = 50;
	ball->m_cfg.piterations = 4;
	ball->setVelocity(btVector3(5, 0, 0));
	btRigidBody* box = w.addRigid(2, btVector3(2, btScalar(0.1), 0), w.shape<btBoxShape>(btVector3(0.5, 0.5, 0.5)));
	box->setFriction(0);
	box->setActivationState(DISABLE_DEACTIVATION);
	w.step(60);
	const btVector3 total = caliber_test::nodeMomentum(*ball) + box->getLinearVelocity() * 2;
	EXPECT_GT(box->getLinearVelocity().x(), 0.5);  // the box was hit
	// Float rounding of node velocities taken as (x - q) / h: 1e-3 of the momentum.
	EXPECT_NEAR(total.x(), 5, 5e-3);
	EXPECT_NEAR(total.y(), 0, 5e-3);
	EXPECT_NEAR(total.z(), 0, 5e-3);
}

TEST(SoftRigidWorld, PinnedClothCarriesABoxAndBothComeToRest)
{
	// Two-way contact: a 1 kg box dropped onto a cloth pinned at its four corners bounces on it as on a
	// trampoline, comes to rest on it with the cloth sagging under it, and no node is ever inside it
	// (beyond the solver's residual).
	SoftTestWorld w;
	btSoftBody* cloth = w.addSoft(makeCloth(w.info(), 2, 1.5, 15, 1 + 2 + 4 + 8));
	cloth->m_cfg.piterations = 10;
	cloth->m_cfg.kDP = btScalar(0.1);
	const btVector3 half(0.3, 0.3, 0.3);
	btRigidBody* box = w.addRigid(1, btVector3(0, 3, 0), w.shape<btBoxShape>(half));
	box->setDamping(0, btScalar(0.5));  // the box's rocking in its pocket is damped by nothing else
	int inside = 0;
	btScalar lowY = BT_LARGE_FLOAT, highY = -BT_LARGE_FLOAT;
	for (int f = 0; f < 540; ++f)
	{
		w.step(1);
		if (f >= 480)
		{
			lowY = btMin(lowY, box->getCenterOfMassPosition().y());
			highY = btMax(highY, box->getCenterOfMassPosition().y());
		}
		for (int i = 0; i < cloth->m_nodes.size(); ++i)
		{
			const btVector3 local = box->getWorldTransform().invXform(cloth->m_nodes[i].m_x);
			// Within 2 mm: contacts are solved one after another, each moving the box (two-way), so a node
			// solved early can end up to a solver residual inside it at the impact (1.1 mm was seen once
			// corner-face contacts, which move the box too, came in).
			if (btFabs(local.x()) < half.x() - 2e-3 && btFabs(local.y()) < half.y() - 2e-3 &&
			    btFabs(local.z()) < half.z() - 2e-3)
				++inside;
		}
	}
	EXPECT_EQ(inside, 0);
	// At rest: the box rocks a little in its pocket, its height settled within a centimetre.
	EXPECT_LT(highY - lowY, 0.01);
	const btScalar boxY = box->getCenterOfMassPosition().y();
	EXPECT_LT(boxY, 2);  // the cloth sagged
	EXPECT_GT(boxY, 1);  // and holds the box well above the corners' 1.5 m reach below them
}

TEST(SoftRigidWorld, CoarseClothCatchesMostFallingBoxes)
{
	// A 2 kg box (60 cm) dropped 3, 5, 7 and 9 m onto a cloth whose nodes are 27 cm apart, pinned at its
	// corners, with no ground below. Node contacts alone let the box's corners and edges slip between
	// the nodes: they catch 1 of these 4 drops. With the box's corners, edge and face points held on the
	// faces' side the cloth catches them (4 of 4 when this was written; an edge can still slice between
	// two nodes, docs/soft-bodies.md). Caught, the box is above the cloth's lowest node after 2.5 s;
	// fallen through, it is in free fall, metres below.
	int caught = 0;
	for (int height = 3; height <= 9; height += 2)
	{
		SoftTestWorld w;
		btSoftBody* cloth = w.addSoft(makeCloth(w.info(), 2, 2, 16, 1 + 2 + 4 + 8));
		cloth->m_cfg.kDF = 1;
		cloth->m_cfg.piterations = 10;
		cloth->m_cfg.kDP = btScalar(0.05);
		btRigidBody* box =
		    w.addRigid(2, btVector3(0.05, 2 + height, 0.03), w.shape<btBoxShape>(btVector3(0.3, 0.3, 0.3)));
		w.step(150);
		btScalar lowestNode = BT_LARGE_FLOAT;
		for (int i = 0; i < cloth->m_nodes.size(); ++i) lowestNode = btMin(lowestNode, cloth->m_nodes[i].m_x.y());
		if (box->getCenterOfMassPosition().y() > lowestNode) ++caught;
	}
	EXPECT_GE(caught, 3);
}

TEST(SoftRigidWorld, ClothTentsOverASpikeBetweenItsNodes)
{
	// A static spike (a slender pyramid, a convex hull whose base is 10 cm wide and whose apex is at
	// y = 1) under a falling cloth whose nodes are 40 cm apart, the apex under the middle of a face:
	// no node touches it, so node contacts alone let the cloth fall past it to the ground. With the
	// apex held on the faces' side, the cloth hangs on it: the cloth surface above the apex's (x, z)
	// stays at the apex's height (within the 1 cm the hull's margin and the solve leave) after 1 s.
	SoftTestWorld w;
	w.addGround();
	btConvexHullShape* spike = w.shape<btConvexHullShape>();
	spike->addPoint(btVector3(-0.05, 0, -0.05));
	spike->addPoint(btVector3(0.05, 0, -0.05));
	spike->addPoint(btVector3(-0.05, 0, 0.05));
	spike->addPoint(btVector3(0.05, 0, 0.05));
	spike->addPoint(btVector3(0, 1, 0));
	const btVector3 apex(0.13, 1, 0.07);  // inside a face of the 6 x 6 grid (nodes at -1, -0.6, ..., 1)
	w.addRigid(0, apex - btVector3(0, 1, 0), spike);
	btSoftBody* cloth = w.addSoft(makeCloth(w.info(), 1.5, 1, 6));
	w.step(60);
	// The cloth's height above the apex: the face whose (x, z) projection holds it.
	btScalar height = -BT_LARGE_FLOAT;
	for (int k = 0; k < cloth->m_faces.size(); ++k)
	{
		const btVector3& a = cloth->m_faces[k].m_n[0]->m_x;
		const btVector3& b = cloth->m_faces[k].m_n[1]->m_x;
		const btVector3& c = cloth->m_faces[k].m_n[2]->m_x;
		// Barycentric weights of the apex in the (x, z) plane.
		const btScalar det = (b.x() - a.x()) * (c.z() - a.z()) - (c.x() - a.x()) * (b.z() - a.z());
		if (btFabs(det) < 1e-6) continue;
		const btScalar u = ((apex.x() - a.x()) * (c.z() - a.z()) - (c.x() - a.x()) * (apex.z() - a.z())) / det;
		const btScalar v = ((b.x() - a.x()) * (apex.z() - a.z()) - (apex.x() - a.x()) * (b.z() - a.z())) / det;
		if (u < 0 || v < 0 || u + v > 1) continue;
		height = btMax(height, a.y() + (b.y() - a.y()) * u + (c.y() - a.y()) * v);
	}
	EXPECT_GT(height, apex.y() - 0.01);
	EXPECT_LT(height, apex.y() + 0.1);  // resting on it, not floating
}

TEST(SoftRigidWorld, CollisionFilterLetsAClothPassThroughTheGround)
{
	// Added with a mask without the static group, the cloth ignores the (static) ground.
	SoftTestWorld w;
	w.addGround();
	btSoftBody* cloth = makeCloth(w.info(), 1, 1, 6);
	w.addSoft(cloth, false);
	w.world().addSoftBody(cloth, btBroadphaseProxy::DefaultFilter,
	                      btBroadphaseProxy::AllFilter ^ btBroadphaseProxy::StaticFilter);
	w.step(60);
	EXPECT_LT(caliber_test::lowestNodeY(*cloth), -1);
}

TEST(SoftRigidWorld, RayTestHitsTheClothBeforeTheGround)
{
	SoftTestWorld w;
	w.addGround();
	btSoftBody* cloth = w.addSoft(makeCloth(w.info(), 2, 1, 6));
	const btVector3 from(btScalar(0.1), 10, btScalar(0.13)), to(btScalar(0.1), -10, btScalar(0.13));
	btCollisionWorld::ClosestRayResultCallback hit(from, to);
	w.world().rayTest(from, to, hit);
	ASSERT_TRUE(hit.hasHit());
	EXPECT_EQ(hit.m_collisionObject, cloth);
	EXPECT_NEAR(hit.m_closestHitFraction, 0.4, 1e-5);  // y = 2 of a ray from 10 to -10
	EXPECT_NEAR(hit.m_hitNormalWorld.y(), 1, 1e-5);    // turned towards the ray
	// A ray whose mask leaves out the cloth's group reaches the ground at y = 0.
	btCollisionWorld::ClosestRayResultCallback past(from, to);
	past.m_collisionFilterMask = btBroadphaseProxy::StaticFilter;
	w.world().rayTest(from, to, past);
	ASSERT_TRUE(past.hasHit());
	EXPECT_NE(past.m_collisionObject, cloth);
	EXPECT_NEAR(past.m_closestHitFraction, 0.5, 1e-5);
}

TEST(SoftRigidWorld, RemovedSoftBodyStopsAndCanBeAddedAgain)
{
	SoftTestWorld w;
	btSoftBody* rope = w.addSoft(btSoftBodyHelpers::CreateRope(w.info(), btVector3(0, 5, 0), btVector3(1, 5, 0), 4, 0));
	w.world().removeSoftBody(rope);
	EXPECT_EQ(w.world().getSoftBodyArray().size(), 0);
	EXPECT_EQ(rope->getBroadphaseHandle(), nullptr);
	w.step(10);
	EXPECT_EQ(rope->m_nodes[0].m_x.y(), 5);
	w.world().addSoftBody(rope);
	w.step(10);
	EXPECT_LT(rope->m_nodes[0].m_x.y(), 5);
	// removeCollisionObject of a soft body removes it as removeSoftBody does.
	w.world().removeCollisionObject(rope);
	EXPECT_EQ(w.world().getSoftBodyArray().size(), 0);
}

TEST(SoftRigidWorld, SameSceneTwiceGivesBitIdenticalNodes)
{
	auto run = []()
	{
		SoftTestWorld w;
		btSoftBody* cloth = w.addSoft(makeCloth(w.info(), 2, 1.5, 12, 1 + 2 + 4 + 8));
		w.addRigid(1, btVector3(0, 3, 0), w.shape<btBoxShape>(btVector3(0.3, 0.3, 0.3)));
		w.step(60);
		return caliber_test::hashNodes(*cloth);
	};
	EXPECT_EQ(run(), run());
}

TEST(SoftRigidWorld, CutLinkSplitsARope)
{
	// A rope fixed at its top, cut in the middle: the lower half falls freely while the upper half hangs.
	SoftTestWorld w;
	btSoftBody* rope =
	    w.addSoft(btSoftBodyHelpers::CreateRope(w.info(), btVector3(0, 10, 0), btVector3(0, 0, 0), 9, 1));
	rope->setTotalMass(1);
	rope->m_cfg.piterations = 10;
	const int nodes = rope->m_nodes.size(), links = rope->m_links.size();
	ASSERT_TRUE(rope->cutLink(5, 6, btScalar(0.5)));
	EXPECT_EQ(rope->m_nodes.size(), nodes + 2);
	EXPECT_EQ(rope->m_links.size(), links + 1);
	EXPECT_FALSE(rope->cutLink(0, 9, btScalar(0.5)));  // no such link
	w.step(30);
	// The free half's bottom fell g t (t + h / 4) / 2 = 1.26 m in 0.5 s (each step of h is cut into 4 substeps:
	// 10 sweeps, at most 4 substeps); the top half barely moved.
	EXPECT_NEAR(rope->m_nodes[nodes - 1].m_x.y(), -10 * 0.5 * (0.5 + 1.0 / 240) / 2, 1e-3);
	EXPECT_NEAR(rope->m_nodes[5].m_x.y(), 5, 0.05);
}

TEST(SoftRigidWorld, SoftSoftContactHoldsTwoBallsApart)
{
	// Two pressurised balls of radius 0.5, one dropped onto the other resting on the ground. With VF_SS
	// each ball's nodes stay outside the other's faces, so the upper ball rests on the lower one; without
	// it they pass through each other and end side by side on the ground.
	auto separation = [](int collisions)
	{
		SoftTestWorld w;
		w.addGround();
		btSoftBody* balls[2];
		for (int i = 0; i < 2; ++i)
		{
			balls[i] = w.addSoft(btSoftBodyHelpers::CreateEllipsoid(w.info(), btVector3(0, btScalar(0.5 + 1.2 * i), 0),
			                                                        btVector3(0.5, 0.5, 0.5), 128));
			balls[i]->m_cfg.kPR = 2000;
			balls[i]->m_cfg.piterations = 4;
			balls[i]->m_cfg.kDP = btScalar(0.05);
			balls[i]->m_cfg.collisions = collisions;
			balls[i]->setTotalMass(1);
		}
		w.step(120);
		return balls[1]->evaluateCom().y() - balls[0]->evaluateCom().y();
	};
	const btScalar apart = separation(btSoftBody::fCollision::SDF_RS | btSoftBody::fCollision::VF_SS);
	const btScalar through = separation(btSoftBody::fCollision::SDF_RS);
	// The balls of links flatten under the load (no bending stiffness), but the upper one's centre stays
	// more than a radius above the lower one's, and at most a diameter plus the contact distance.
	EXPECT_GT(apart, 0.5);
	EXPECT_LT(apart, 1.125);
	EXPECT_LT(btFabs(through), 0.1);
}

TEST(SoftRigidWorld, SoftSoftFrictionStopsASlidingBlockAtTheCoulombDistance)
{
	// A soft block (8 nodes, inextensible links) slides at 2 m/s over a fixed soft sheet (VF_SS, kDF 0.5 on
	// both): Coulomb friction decelerates it at mu g, so it stops after v^2 / (2 mu g) = 0.4 m; without
	// friction it keeps sliding.
	auto slide = [](btScalar kDF)
	{
		SoftTestWorld w;
		btSoftBody* sheet =
		    w.addSoft(btSoftBodyHelpers::CreatePatch(w.info(), btVector3(-5, 0, -5), btVector3(5, 0, -5),
		                                             btVector3(-5, 0, 5), btVector3(5, 0, 5), 11, 11, 0, true));
		for (int i = 0; i < sheet->m_nodes.size(); ++i) sheet->setMass(i, 0);  // fixed: a floor
		const btScalar h = btScalar(0.2), y = btScalar(0.125) + h;             // resting at the contact distance
		const btVector3 corners[8] = {btVector3(-h, y - h, -h), btVector3(h, y - h, -h), btVector3(-h, y + h, -h),
		                              btVector3(h, y + h, -h),  btVector3(-h, y - h, h), btVector3(h, y - h, h),
		                              btVector3(-h, y + h, h),  btVector3(h, y + h, h)};
		btSoftBody* block = w.addSoft(btSoftBodyHelpers::CreateFromConvexHull(w.info(), corners, 8));
		block->setTotalMass(1);
		block->m_cfg.piterations = 4;
		for (btSoftBody* s : {sheet, block})
		{
			s->m_cfg.kDF = kDF;
			s->m_cfg.collisions = btSoftBody::fCollision::VF_SS;
		}
		block->setVelocity(btVector3(2, 0, 0));
		const btScalar x0 = block->evaluateCom().x();
		w.step(90);
		return block->evaluateCom().x() - x0;
	};
	const btScalar withFriction = slide(btScalar(0.5)), without = slide(0);
	EXPECT_NEAR(withFriction, 0.4, 0.08);  // 20%: the first step slides before the contact holds
	EXPECT_GT(without, 2.5);               // 1.5 s at 2 m/s, nothing slowing it
}
