// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "SoftScenes.h"

namespace soft_demo
{
Scene::Scene()
{
	m_world.setGravity(btVector3(0, -10, 0));
	m_world.getWorldInfo().m_gravity = btVector3(0, -10, 0);
	addRigid(0, btVector3(0, -5, 0), own(new btBoxShape(btVector3(50, 5, 50))));
}

Scene::~Scene()
{
	for (btSoftBody* s : m_softs)
	{
		m_world.removeSoftBody(s);
		delete s;
	}
	for (auto& b : m_bodies) m_world.removeRigidBody(b.get());
}

btCollisionShape* Scene::own(btCollisionShape* shape)
{
	m_shapes.emplace_back(shape);
	return shape;
}

btRigidBody* Scene::addRigid(btScalar mass, const btVector3& position, btCollisionShape* shape)
{
	return addRigid(mass, btTransform(btQuaternion::getIdentity(), position), shape);
}

btRigidBody* Scene::addRigid(btScalar mass, const btTransform& pose, btCollisionShape* shape)
{
	btVector3 inertia(0, 0, 0);
	if (mass > 0) shape->calculateLocalInertia(mass, inertia);
	btRigidBody::btRigidBodyConstructionInfo ci(mass, 0, shape, inertia);
	ci.m_startWorldTransform = pose;
	m_bodies.emplace_back(new btRigidBody(ci));
	m_world.addRigidBody(m_bodies.back().get());
	return m_bodies.back().get();
}

btSoftBody* Scene::addSoft(btSoftBody* body)
{
	m_softs.push_back(body);
	m_world.addSoftBody(body);
	return body;
}

void Scene::step(int frames)
{
	for (int i = 0; i < frames; ++i) m_world.stepSimulation(kStep, 1, kStep);
}

Parts buildCloth(Scene& s)
{
	Parts p;
	btSoftBody* c =
	    s.addSoft(btSoftBodyHelpers::CreatePatch(s.info(), btVector3(-4, 12, -4), btVector3(4, 12, -4),
	                                             btVector3(-4, 12, 4), btVector3(4, 12, 4), 31, 31, 1 + 2, true));
	c->m_cfg.piterations = 10;
	c->setTotalMass(2);
	p.softs.push_back(c);
	return p;
}

Parts buildPressure(Scene& s)
{
	Parts p;
	btSoftBody* b =
	    s.addSoft(btSoftBodyHelpers::CreateEllipsoid(s.info(), btVector3(0, 4, 0), btVector3(1, 1, 1), 256));
	b->m_cfg.kPR = 1000;
	b->m_cfg.kDF = btScalar(0.5);
	b->m_cfg.piterations = 4;
	b->setTotalMass(1, true);
	p.softs.push_back(b);
	return p;
}

Parts buildVolume(Scene& s)
{
	Parts p;
	btSoftBody* b =
	    s.addSoft(btSoftBodyHelpers::CreateEllipsoid(s.info(), btVector3(0, 1.5, 0), btVector3(1.5, 1.5, 1.5), 256));
	b->m_materials[0]->m_kLST = btScalar(0.3);
	b->m_cfg.kVC = 500;
	b->m_cfg.piterations = 4;
	b->m_cfg.kDP = btScalar(0.02);
	b->setTotalMass(3);
	b->setPose(true, false);
	p.softs.push_back(b);
	btCollisionShape* box = s.own(new btBoxShape(btVector3(0.4, 0.4, 0.4)));
	for (int i = 0; i < 3; ++i)
		p.rigids.push_back(s.addRigid(2, btVector3(btScalar(0.3) * (i - 1), btScalar(3.6 + i), 0), box));
	return p;
}

Parts buildRopes(Scene& s)
{
	Parts p;
	for (int i = 0; i < 15; ++i)
	{
		const btScalar length = 2 + btScalar(i) / 2;
		btSoftBody* rope = s.addSoft(btSoftBodyHelpers::CreateRope(s.info(), btVector3(-7 + i, 10, 0),
		                                                           btVector3(-7 + i + length, 10, 0), 20 + 2 * i, 1));
		rope->m_cfg.piterations = 8;
		rope->setTotalMass(btScalar(0.1) * length);
		p.softs.push_back(rope);
	}
	return p;
}

Parts buildRopeAttach(Scene& s)
{
	Parts p;
	btSoftBody* rope =
	    s.addSoft(btSoftBodyHelpers::CreateRope(s.info(), btVector3(0, 10, 0), btVector3(3, 10, 0), 30, 1));
	rope->m_cfg.piterations = 10;
	rope->setTotalMass(btScalar(0.5));
	btRigidBody* box =
	    s.addRigid(2, btVector3(3, btScalar(9.75), 0), s.own(new btBoxShape(btVector3(0.25, 0.25, 0.25))));
	rope->appendAnchor(rope->m_nodes.size() - 1, box);
	p.softs.push_back(rope);
	p.rigids.push_back(box);
	return p;
}

Parts buildClothAttach(Scene& s)
{
	Parts p;
	btRigidBody* box = s.addRigid(5, btVector3(0, 4, 0), s.own(new btBoxShape(btVector3(1, 0.5, 1))));
	btSoftBody* c = s.addSoft(
	    btSoftBodyHelpers::CreatePatch(s.info(), btVector3(-1, btScalar(4.5), 1), btVector3(1, btScalar(4.5), 1),
	                                   btVector3(-1, btScalar(4.5), 3), btVector3(1, btScalar(4.5), 3), 9, 9, 0, true));
	c->m_cfg.piterations = 10;
	c->setTotalMass(btScalar(0.5));
	c->appendAnchor(0, box);
	c->appendAnchor(8, box);
	p.softs.push_back(c);
	p.rigids.push_back(box);
	return p;
}

Parts buildFriction(Scene& s)
{
	Parts p;
	const btScalar angle = SIMD_PI / 6;
	const btTransform t(btQuaternion(btVector3(0, 0, 1), angle), btVector3(0, 3, 0));
	s.addRigid(0, t, s.own(new btBoxShape(btVector3(8, 0.1, 3))));
	const btScalar kDF[3] = {btScalar(0.1), btScalar(0.5), btScalar(0.9)};
	for (int i = 0; i < 3; ++i)
	{
		// A 1 m square laid on the slope (its top face is at 0.1 m above the slope's mid-plane).
		const btVector3 centre = t * btVector3(0, btScalar(0.12), btScalar(-2 + 2 * i));
		const btVector3 u = t.getBasis() * btVector3(0.5, 0, 0), w = btVector3(0, 0, 0.5);
		btSoftBody* cloth = s.addSoft(btSoftBodyHelpers::CreatePatch(s.info(), centre - u - w, centre + u - w,
		                                                             centre - u + w, centre + u + w, 6, 6, 0, true));
		cloth->m_cfg.kDF = kDF[i];
		cloth->m_cfg.piterations = 4;
		cloth->setTotalMass(btScalar(0.2));
		p.softs.push_back(cloth);
	}
	return p;
}

Parts buildImpact(Scene& s)
{
	Parts p;
	btSoftBody* c =
	    s.addSoft(btSoftBodyHelpers::CreatePatch(s.info(), btVector3(-2, 2, -2), btVector3(2, 2, -2),
	                                             btVector3(-2, 2, 2), btVector3(2, 2, 2), 26, 26, 1 + 2 + 4 + 8, true));
	c->m_cfg.kDF = 1;
	c->m_cfg.piterations = 10;
	c->m_cfg.kDP = btScalar(0.05);
	c->setTotalMass(1);
	p.softs.push_back(c);
	p.rigids.push_back(s.addRigid(1, btVector3(0, 5, 0), s.own(new btBoxShape(btVector3(0.3, 0.3, 0.3)))));
	return p;
}

namespace
{
// A closed soft body of about res nodes and mass kg with clusters that collide with rigid bodies and
// other soft bodies' clusters (kPR keeps its gas, the links are inextensible).
btSoftBody* clusterBody(Scene& s, const btVector3& centre, const btVector3& radius, int res, btScalar mass,
                        int clusters)
{
	btSoftBody* b = s.addSoft(btSoftBodyHelpers::CreateEllipsoid(s.info(), centre, radius, res));
	b->setTotalMass(mass, true);
	b->m_cfg.kPR = 200 * mass;
	b->m_cfg.kDF = btScalar(0.5);
	b->m_cfg.piterations = 4;
	b->m_cfg.collisions = btSoftBody::fCollision::CL_RS | btSoftBody::fCollision::CL_SS;
	b->generateClusters(clusters);
	return b;
}

Motor g_hingeMotor;  // outlives every scene (joints keep a pointer to their control)
}  // namespace

Parts buildClusterDeform(Scene& s)
{
	Parts p;
	btSoftBody* b = clusterBody(s, btVector3(0, 4, 0), btVector3(1.5, 0.8, 1.2), 200, 2, 8);
	b->m_cfg.kPR = 0;  // no gas: the clusters' shape matching alone brings the shape back
	b->m_materials[0]->m_kLST = btScalar(0.4);
	for (int i = 0; i < b->clusterCount(); ++i) b->m_clusters[i]->m_matching = btScalar(0.5);
	p.softs.push_back(b);
	return p;
}

Parts buildClusterCollide1(Scene& s)
{
	Parts p;
	btSoftBody* a = clusterBody(s, btVector3(-2, 3, 0), btVector3(1, 1, 1), 128, 1, 8);
	btSoftBody* b = clusterBody(s, btVector3(2, 3.3, 0), btVector3(1, 1, 1), 128, 1, 8);
	a->setVelocity(btVector3(6, 2, 0));
	b->setVelocity(btVector3(-6, 2, 0));
	p.softs.push_back(a);
	p.softs.push_back(b);
	return p;
}

Parts buildClusterCollide2(Scene& s)
{
	Parts p;
	for (int i = 0; i < 4; ++i)
		p.softs.push_back(clusterBody(s, btVector3(btScalar(0.3) * (i % 2), btScalar(1.2 + 2.3 * i), 0),
		                              btVector3(1, 1, 1), 96, 1, 6));
	return p;
}

Parts buildClusterSocket(Scene& s)
{
	Parts p;
	btSoftBody* b = clusterBody(s, btVector3(0, 6, 0), btVector3(0.8, 0.8, 0.8), 96, 1, 1);
	btSoftBody::LJoint::Specs socket;
	socket.position = btVector3(0, 6.8, 0);
	b->appendLinearJoint(socket);  // to the world
	b->setVelocity(btVector3(4, 0, 0));
	p.softs.push_back(b);
	return p;
}

Parts buildClusterHinge(Scene& s)
{
	Parts p;
	btRigidBody* post = s.addRigid(0, btVector3(0, 2, 0), s.own(new btBoxShape(btVector3(0.2, 2, 0.2))));
	btSoftBody* wheel = clusterBody(s, btVector3(0, 4, 1.2), btVector3(1.5, 1.5, 0.4), 160, 2, 1);
	btSoftBody::LJoint::Specs axle;
	axle.position = btVector3(0, 4, 1.2);
	wheel->appendLinearJoint(axle, btSoftBody::Body(post));
	g_hingeMotor.goal = 3;
	g_hingeMotor.maxStep = btScalar(0.05);
	btSoftBody::AJoint::Specs hinge;
	hinge.axis = btVector3(0, 0, 1);
	hinge.icontrol = &g_hingeMotor;
	wheel->appendAngularJoint(hinge, btSoftBody::Body(post));
	p.softs.push_back(wheel);
	p.rigids.push_back(post);
	return p;
}

Parts buildClusterCombine(Scene& s)
{
	Parts p;
	// A chain from a world point: soft ball, soft ball, 1 kg box, joined by linear joints.
	btSoftBody* a = clusterBody(s, btVector3(0, 8, 0), btVector3(0.6, 0.6, 0.6), 64, 1, 1);
	btSoftBody* b = clusterBody(s, btVector3(1.2, 8, 0), btVector3(0.6, 0.6, 0.6), 64, 1, 1);
	btRigidBody* box = s.addRigid(1, btVector3(2.4, 8, 0), s.own(new btBoxShape(btVector3(0.3, 0.3, 0.3))));
	btSoftBody::LJoint::Specs j;
	j.position = btVector3(-0.6, 8, 0);
	a->appendLinearJoint(j);
	j.position = btVector3(0.6, 8, 0);
	a->appendLinearJoint(j, b);
	j.position = btVector3(1.8, 8, 0);
	b->appendLinearJoint(j, btSoftBody::Body(box));
	p.softs.push_back(a);
	p.softs.push_back(b);
	p.rigids.push_back(box);
	return p;
}

namespace
{
// A flat soft disc (1 kg, 6 clusters, gas, CL_RS and CL_SS): the hull of three rings of 16 points and the
// two face centres, so that its faces are flat: flat faces rest on one another, where domed ones (ellipsoids)
// roll off each other once the contacts can turn the clusters.
btSoftBody* flatDisc(Scene& s, const btVector3& centre, btScalar radius, btScalar halfHeight)
{
	btVector3 points[50];
	int count = 0;
	for (int ring = 0; ring < 3; ++ring)
		for (int k = 0; k < 16; ++k)
		{
			const btScalar a = SIMD_2_PI * btScalar(k) / 16;
			points[count++] = centre + btVector3(radius * btCos(a), halfHeight * btScalar(ring - 1), radius * btSin(a));
		}
	points[count++] = centre + btVector3(0, halfHeight, 0);
	points[count++] = centre - btVector3(0, halfHeight, 0);
	btSoftBody* b = s.addSoft(btSoftBodyHelpers::CreateFromConvexHull(s.info(), points, count, false));
	b->setTotalMass(1, true);
	b->m_cfg.kPR = 200;
	b->m_cfg.kDF = btScalar(0.5);
	b->m_cfg.piterations = 4;
	b->m_cfg.collisions = btSoftBody::fCollision::CL_RS | btSoftBody::fCollision::CL_SS;
	b->generateClusters(6);
	return b;
}
}  // namespace

Parts buildClusterStackSoft(Scene& s)
{
	Parts p;
	for (int i = 0; i < 4; ++i)
		p.softs.push_back(flatDisc(s, btVector3(0, btScalar(0.5 + 1.1 * i), 0), btScalar(1.2), btScalar(0.45)));
	return p;
}

Parts buildClusterStackMixed(Scene& s)
{
	Parts p;
	// Soft disc, box, soft disc, box from the ground up (0.4 m discs, 0.6 m boxes of 1 kg): the lower box is
	// pressed between the two discs, whose cluster stages the solver runs together.
	btCollisionShape* box = s.own(new btBoxShape(btVector3(0.8, 0.3, 0.8)));
	p.softs.push_back(flatDisc(s, btVector3(0, 0.2, 0), btScalar(1.2), btScalar(0.2)));
	p.rigids.push_back(s.addRigid(1, btVector3(0, 0.75, 0), box));
	p.softs.push_back(flatDisc(s, btVector3(0, 1.3, 0), btScalar(1.2), btScalar(0.2)));
	p.rigids.push_back(s.addRigid(1, btVector3(0, 1.85, 0), box));
	return p;
}

namespace
{
struct Builder
{
	const char* name;
	Parts (*build)(Scene&);
};
const Builder kBuilders[] = {{"Cloth", buildCloth},
                             {"Pressure", buildPressure},
                             {"Volume", buildVolume},
                             {"Ropes", buildRopes},
                             {"RopeAttach", buildRopeAttach},
                             {"ClothAttach", buildClothAttach},
                             {"Sticks", buildSticks},
                             {"Collide", buildCollide},
                             {"Collide2", buildCollide2},
                             {"Collide3", buildCollide3},
                             {"Friction", buildFriction},
                             {"Impact", buildImpact},
                             {"Aero", buildAero},
                             {"Aero2", buildAero2},
                             {"Torus", buildTorus},
                             {"TorusMatch", buildTorusMatch},
                             {"Bunny", buildBunny},
                             {"BunnyMatch", buildBunnyMatch},
                             {"Cutting1", buildCutting1},
                             {"TetraCube", buildTetraCube},
                             {"ClusterDeform", buildClusterDeform},
                             {"ClusterCollide1", buildClusterCollide1},
                             {"ClusterCollide2", buildClusterCollide2},
                             {"ClusterSocket", buildClusterSocket},
                             {"ClusterHinge", buildClusterHinge},
                             {"ClusterCombine", buildClusterCombine},
                             {"ClusterCar", buildClusterCar},
                             {"ClusterRobot", buildClusterRobot},
                             {"ClusterStackSoft", buildClusterStackSoft},
                             {"ClusterStackMixed", buildClusterStackMixed}};
}  // namespace

std::vector<std::string> sceneNames()
{
	std::vector<std::string> names;
	for (const Builder& b : kBuilders) names.push_back(b.name);
	return names;
}

bool buildScene(Scene& scene, const std::string& name)
{
	for (const Builder& b : kBuilders)
		if (name == b.name)
		{
			b.build(scene);
			return true;
		}
	return false;
}
}  // namespace soft_demo
