// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// SoftDemo's scenes after Bullet's Sticks, Collide, Collide2, Collide3, Aero, Aero2, Torus, TorusMatch,
// Bunny, BunnyMatch, Cutting1, ClusterCar, ClusterRobot and TetraCube (our own set-ups and meshes).
#include "SoftMeshes.h"
#include "SoftScenes.h"

namespace soft_demo
{
namespace
{
btSoftBody* ball(Scene& s, const btVector3& centre, btScalar radius, int res, btScalar mass)
{
	btSoftBody* b = s.addSoft(
	    btSoftBodyHelpers::CreateEllipsoid(s.info(), centre, btVector3(radius, radius, radius), res));
	b->setTotalMass(mass, true);
	b->m_cfg.kPR = 100 * mass;
	b->m_cfg.kDF = btScalar(0.5);
	b->m_cfg.piterations = 4;
	b->m_cfg.collisions |= btSoftBody::fCollision::VF_SS;
	return b;
}

btSoftBody* patch(Scene& s, const btVector3& centre, btScalar half, int n, int fixeds)
{
	return s.addSoft(btSoftBodyHelpers::CreatePatch(
	    s.info(), centre + btVector3(-half, 0, -half), centre + btVector3(half, 0, -half),
	    centre + btVector3(-half, 0, half), centre + btVector3(half, 0, half), n, n, fixeds, true));
}

// A cluster body for the machines: kPR keeps its gas, its clusters collide with rigid bodies.
btSoftBody* clusterBall(Scene& s, const btVector3& centre, const btVector3& radius, int res, btScalar mass)
{
	btSoftBody* b = s.addSoft(btSoftBodyHelpers::CreateEllipsoid(s.info(), centre, radius, res));
	b->setTotalMass(mass, true);
	b->m_cfg.kPR = 200 * mass;
	b->m_cfg.kDF = 1;
	b->m_cfg.piterations = 4;
	b->m_cfg.collisions = btSoftBody::fCollision::CL_RS | btSoftBody::fCollision::CL_SS;
	b->generateClusters(1);
	return b;
}

Motor g_carMotor;  // outlives every scene (joints keep a pointer to their control)
}  // namespace

Parts buildSticks(Scene& s)
{
	Parts p;
	// 5 x 5 sticks of 1.5 m, fixed at the ground, leaning 10 degrees towards +x, with bending links.
	for (int i = 0; i < 5; ++i)
		for (int k = 0; k < 5; ++k)
		{
			const btVector3 base(btScalar(i - 2) * 0.6f, 0, btScalar(k - 2) * 0.6f);
			const btVector3 top = base + btVector3(btSin(0.17f), btCos(0.17f), 0) * 1.5f;
			btSoftBody* stick = s.addSoft(btSoftBodyHelpers::CreateRope(s.info(), base, top, 8, 1));
			stick->m_materials[0]->m_kLST = btScalar(0.9);
			stick->generateBendingConstraints(2);
			stick->m_cfg.piterations = 4;
			stick->setTotalMass(btScalar(0.1));
			p.softs.push_back(stick);
		}
	return p;
}

Parts buildCollide(Scene& s)
{
	Parts p;
	// Two gas balls (VF_SS) thrown at each other at 6 m/s, meeting in the air.
	btSoftBody* a = ball(s, btVector3(-2, 3, 0), 1, 128, 1);
	btSoftBody* b = ball(s, btVector3(2, btScalar(3.3), 0), 1, 128, 1);
	a->setVelocity(btVector3(6, 2, 0));
	b->setVelocity(btVector3(-6, 2, 0));
	p.softs.push_back(a);
	p.softs.push_back(b);
	return p;
}

Parts buildCollide2(Scene& s)
{
	Parts p;
	// Three soft volumes (soft links kept in volume by kVC) fall on one another.
	for (int i = 0; i < 3; ++i)
	{
		btSoftBody* b = ball(s, btVector3(btScalar(0.4) * (i % 2), btScalar(1 + 2.2 * i), 0), btScalar(0.9), 96, 1);
		b->m_cfg.kPR = 0;
		b->m_materials[0]->m_kLST = btScalar(0.5);
		b->m_cfg.kVC = 200;
		b->setPose(true, false);
		p.softs.push_back(b);
	}
	return p;
}

Parts buildCollide3(Scene& s)
{
	Parts p;
	// A cloth pinned at its four corners and a free cloth dropped onto it (VF_SS).
	btSoftBody* lower = patch(s, btVector3(0, 2, 0), 2, 15, 1 + 2 + 4 + 8);
	btSoftBody* upper = patch(s, btVector3(btScalar(0.2), btScalar(3.5), 0), btScalar(1.2), 9, 0);
	for (btSoftBody* c : {lower, upper})
	{
		c->m_cfg.piterations = 6;
		c->m_cfg.kDF = btScalar(0.5);
		c->m_cfg.collisions |= btSoftBody::fCollision::VF_SS;
		p.softs.push_back(c);
	}
	lower->setTotalMass(1);
	upper->setTotalMass(btScalar(0.3));
	return p;
}

Parts buildAero(Scene& s)
{
	Parts p;
	// A flag: a 2 m cloth hanging from two corners of its top edge, in a 10 m/s wind along +x.
	btSoftBody* c = s.addSoft(btSoftBodyHelpers::CreatePatch(
	    s.info(), btVector3(0, 6, -1), btVector3(0, 6, 1), btVector3(0, 4, -1), btVector3(0, 4, 1), 11, 11, 1 + 2,
	    true));
	c->m_cfg.aeromodel = btSoftBody::eAeroModel::V_TwoSided;
	c->m_cfg.kDG = btScalar(0.5);
	c->m_cfg.kLF = btScalar(0.05);
	c->m_cfg.piterations = 10;
	c->setTotalMass(btScalar(0.3));
	c->setWindVelocity(btVector3(10, 0, 0));
	p.softs.push_back(c);
	return p;
}

Parts buildAero2(Scene& s)
{
	Parts p;
	// Four free 1 m sheets, tilted, falling through a 4 m/s wind along +z (drag and lift on faces).
	for (int i = 0; i < 4; ++i)
	{
		const btVector3 c(btScalar(2 * i - 3), 10, 0);
		const btVector3 u = btVector3(btCos(0.4f), btSin(0.4f), 0) * 0.5f, w(0, 0, 0.5f);
		btSoftBody* sheet = s.addSoft(
		    btSoftBodyHelpers::CreatePatch(s.info(), c - u - w, c + u - w, c - u + w, c + u + w, 7, 7, 0, true));
		sheet->m_cfg.aeromodel = btSoftBody::eAeroModel::F_TwoSided;
		sheet->m_cfg.kDG = btScalar(0.8);
		sheet->m_cfg.kLF = btScalar(0.3);
		sheet->m_cfg.piterations = 4;
		sheet->setTotalMass(btScalar(0.05));
		sheet->setWindVelocity(btVector3(0, 0, 4));
		p.softs.push_back(sheet);
	}
	return p;
}

namespace
{
btSoftBody* torus(Scene& s, const btVector3& centre)
{
	btSoftBody* t = s.addSoft(makeTorus(s.info(), centre, btScalar(1.2), btScalar(0.45), 20, 8));
	t->generateBendingConstraints(2);
	t->m_cfg.piterations = 4;
	t->m_cfg.kDF = btScalar(0.5);
	t->setTotalMass(2, true);
	return t;
}
}  // namespace

Parts buildTorus(Scene& s)
{
	Parts p;
	// A torus of soft links whose volume is kept by kVC, dropped 3 m.
	btSoftBody* t = torus(s, btVector3(0, 3.5, 0));
	t->m_materials[0]->m_kLST = btScalar(0.5);
	t->m_cfg.kVC = 100;
	t->setPose(true, false);
	p.softs.push_back(t);
	return p;
}

Parts buildTorusMatch(Scene& s)
{
	Parts p;
	// The same torus without kVC: pose matching (kMT = 0.2) brings its rest shape back.
	btSoftBody* t = torus(s, btVector3(0, 3.5, 0));
	t->m_materials[0]->m_kLST = btScalar(0.3);
	t->m_cfg.kMT = btScalar(0.2);
	t->setPose(false, true);
	p.softs.push_back(t);
	return p;
}

Parts buildBunny(Scene& s)
{
	Parts p;
	// A blob (our lumpy stand-in for Bullet's bunny) of gas, kPR = 500, dropped 3 m.
	btSoftBody* b = s.addSoft(makeBlob(s.info(), btVector3(0, 4, 0), 1, 256));
	b->m_cfg.kPR = 500;
	b->m_cfg.kDF = btScalar(0.5);
	b->m_cfg.piterations = 4;
	b->setTotalMass(1, true);
	p.softs.push_back(b);
	return p;
}

Parts buildBunnyMatch(Scene& s)
{
	Parts p;
	// The blob with soft links and pose matching (kMT = 0.2) instead of gas.
	btSoftBody* b = s.addSoft(makeBlob(s.info(), btVector3(0, 4, 0), 1, 256));
	b->m_materials[0]->m_kLST = btScalar(0.3);
	b->m_cfg.kMT = btScalar(0.2);
	b->m_cfg.kDF = btScalar(0.5);
	b->m_cfg.piterations = 4;
	b->setTotalMass(1, true);
	b->setPose(false, true);
	p.softs.push_back(b);
	return p;
}

Parts buildCutting1(Scene& s)
{
	Parts p;
	// A 4 m cloth hanging from its two top corners; SoftDemo cuts it down the middle with refine.
	btSoftBody* c = s.addSoft(btSoftBodyHelpers::CreatePatch(s.info(), btVector3(-2, 8, 0), btVector3(2, 8, 0),
	                                                         btVector3(-2, 4, 0), btVector3(2, 4, 0), 17, 17,
	                                                         1 + 2, true));
	c->m_cfg.piterations = 6;
	c->setTotalMass(1);
	p.softs.push_back(c);
	return p;
}

Parts buildClusterCar(Scene& s)
{
	Parts p;
	// A 3 kg chassis on four soft wheels (one cluster each): a linear joint at each axle, an angular
	// joint with a motor (to -6 rad/s about z, rolling the car along +x).
	btRigidBody* chassis =
	    s.addRigid(3, btVector3(0, btScalar(1.1), 0), s.own(new btBoxShape(btVector3(1.2, 0.15, 0.6))));
	p.rigids.push_back(chassis);
	g_carMotor.goal = -6;
	g_carMotor.maxStep = btScalar(0.05);
	for (int i = 0; i < 4; ++i)
	{
		const btVector3 at(i < 2 ? btScalar(-1) : btScalar(1), btScalar(0.55), i % 2 ? btScalar(0.95) : btScalar(-0.95));
		btSoftBody* wheel = clusterBall(s, at, btVector3(0.5, 0.5, 0.2), 96, btScalar(0.5));
		btSoftBody::LJoint::Specs axle;
		axle.position = at;
		wheel->appendLinearJoint(axle, btSoftBody::Body(chassis));
		btSoftBody::AJoint::Specs drive;
		drive.axis = btVector3(0, 0, 1);
		drive.icontrol = &g_carMotor;
		wheel->appendAngularJoint(drive, btSoftBody::Body(chassis));
		p.softs.push_back(wheel);
	}
	return p;
}

Parts buildClusterRobot(Scene& s)
{
	Parts p;
	// A rigid hub (a 1 kg disc) carrying three soft balls at the corners of a triangle (linear joints),
	// set on a 15 degree slope: it tumbles down on its soft feet.
	const btScalar angle = btScalar(0.26);
	const btTransform slope(btQuaternion(btVector3(0, 0, 1), angle), btVector3(0, 2, 0));
	s.addRigid(0, slope, s.own(new btBoxShape(btVector3(8, 0.1, 3))));
	const btVector3 centre = slope * btVector3(4, 1.2f, 0);
	btTransform hubPose(slope.getRotation() * btQuaternion(btVector3(1, 0, 0), SIMD_HALF_PI), centre);
	btRigidBody* hub = s.addRigid(1, hubPose, s.own(new btCylinderShape(btVector3(0.5, 0.2, 0.5))));
	p.rigids.push_back(hub);
	for (int i = 0; i < 3; ++i)
	{
		const btScalar a = SIMD_2_PI * btScalar(i) / 3;
		const btVector3 foot = centre + slope.getBasis() * btVector3(btCos(a), btSin(a), 0) * 0.9f;
		btSoftBody* b = clusterBall(s, foot, btVector3(0.4f, 0.4f, 0.4f), 64, btScalar(0.3));
		btSoftBody::LJoint::Specs j;
		j.position = foot;
		b->appendLinearJoint(j, btSoftBody::Body(hub));
		p.softs.push_back(b);
	}
	return p;
}

Parts buildTetraCube(Scene& s)
{
	Parts p;
	// A 1 m cube of 3 x 3 x 3 cells, 6 tetras each, links along the tetras' edges, dropped 2 m.
	const TetGenText text = makeTetCube(btVector3(0, 2.5, 0), 1, 3);
	btSoftBody* c = s.addSoft(btSoftBodyHelpers::CreateFromTetGenData(s.info(), text.ele.c_str(), text.face.c_str(),
	                                                                  text.node.c_str(), false, true, false));
	c->m_materials[0]->m_kLST = btScalar(0.8);
	c->m_cfg.piterations = 4;
	c->m_cfg.kDF = btScalar(0.5);
	c->setVolumeMass(2);
	p.softs.push_back(c);
	return p;
}
}  // namespace soft_demo
