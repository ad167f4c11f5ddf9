// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
//
// SoftDemo: soft bodies in the soft-rigid world, headless, in scenes after Bullet's SoftDemo (our own
// set-ups): Cloth, Pressure, Volume, Ropes, RopeAttach, ClothAttach, Friction, Impact. Each scene prints
// what it shows, the figures that show it and a check of its own.
// Usage: SoftDemo [scene[,scene...]|all] [frames] [--png PATH] (each scene has its own frame count by
// default; --png pictures the last scene's last frame). Exit 1 when a check fails.

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <memory>
#include <string>
#include <vector>

#include "DemoPictures.h"
#include "btBulletSoftBodyCommon.h"

namespace
{
const btScalar kStep = btScalar(1. / 60.);

// Pictures (--png): each scene's world is captured as it ends, so the picture shows the last scene run
// (soft bodies drawn by Demos/Common like everything else).
caliber::demo::DemoPictures* g_pictures = 0;

// One scene's world: the parts, the ground (top face at y = 0), and ownership of what is added.
struct Scene
{
	btSoftBodyRigidBodyCollisionConfiguration config;
	btCollisionDispatcher dispatcher{&config};
	btDbvtBroadphase broadphase;
	btSequentialImpulseConstraintSolver solver;
	btSoftRigidDynamicsWorld world{&dispatcher, &broadphase, &solver, &config};
	std::vector<std::unique_ptr<btCollisionShape>> shapes;
	std::vector<std::unique_ptr<btRigidBody>> bodies;
	std::vector<btSoftBody*> softs;

	Scene()
	{
		world.setGravity(btVector3(0, -10, 0));
		world.getWorldInfo().m_gravity = btVector3(0, -10, 0);
		addRigid(0, btVector3(0, -5, 0), own(new btBoxShape(btVector3(50, 5, 50))));
	}
	~Scene()
	{
		if (g_pictures && !softs.empty())
		{
			// The shared renderer draws the soft bodies and frames what moves, their nodes included.
			g_pictures->capture(world);
		}
		for (btSoftBody* s : softs)
		{
			world.removeSoftBody(s);
			delete s;
		}
		for (auto& b : bodies) world.removeRigidBody(b.get());
	}
	btCollisionShape* own(btCollisionShape* s)
	{
		shapes.emplace_back(s);
		return s;
	}
	btRigidBody* addRigid(btScalar mass, const btVector3& pos, btCollisionShape* shape)
	{
		return addRigid(mass, btTransform(btQuaternion::getIdentity(), pos), shape);
	}
	btRigidBody* addRigid(btScalar mass, const btTransform& pose, btCollisionShape* shape)
	{
		btVector3 inertia(0, 0, 0);
		if (mass > 0) shape->calculateLocalInertia(mass, inertia);
		btRigidBody::btRigidBodyConstructionInfo ci(mass, 0, shape, inertia);
		ci.m_startWorldTransform = pose;
		bodies.emplace_back(new btRigidBody(ci));
		world.addRigidBody(bodies.back().get());
		return bodies.back().get();
	}
	btSoftBody* addSoft(btSoftBody* s)
	{
		softs.push_back(s);
		world.addSoftBody(s);
		return s;
	}
	btSoftBodyWorldInfo& info() { return world.getWorldInfo(); }
	void step(int frames)
	{
		for (int i = 0; i < frames; ++i) world.stepSimulation(kStep, 1, kStep);
	}
};

btScalar lowestNode(const btSoftBody* s)
{
	btScalar y = BT_LARGE_FLOAT;
	for (int i = 0; i < s->m_nodes.size(); ++i) y = btMin(y, s->m_nodes[i].m_x.y());
	return y;
}

btScalar worstStretch(const btSoftBody* s)
{
	btScalar worst = 0;
	for (int i = 0; i < s->m_links.size(); ++i)
	{
		const btSoftBody::Link& l = s->m_links[i];
		if (l.m_rl > 0) worst = btMax(worst, (l.m_n[0]->m_x - l.m_n[1]->m_x).length() / l.m_rl);
	}
	return worst;
}

// Length of all links over their rest length (a rope's overall stretch).
btScalar overallStretch(const btSoftBody* s)
{
	btScalar length = 0, rest = 0;
	for (int i = 0; i < s->m_links.size(); ++i)
	{
		length += (s->m_links[i].m_n[0]->m_x - s->m_links[i].m_n[1]->m_x).length();
		rest += s->m_links[i].m_rl;
	}
	return rest > 0 ? length / rest : 1;
}

bool allFinite(const btSoftBody* s)
{
	for (int i = 0; i < s->m_nodes.size(); ++i)
		if (!caliber::isFinite(s->m_nodes[i].m_x)) return false;
	return true;
}

bool report(bool ok, const char* what)
{
	printf("  check: %s: %s\n", what, ok ? "PASS" : "FAIL");
	return ok;
}

bool cloth(int frames)
{
	printf("Cloth: an 8 m cloth of 31 x 31 nodes hangs from two corners and swings down.\n");
	Scene s;
	btSoftBody* c =
	    s.addSoft(btSoftBodyHelpers::CreatePatch(s.info(), btVector3(-4, 12, -4), btVector3(4, 12, -4),
	                                             btVector3(-4, 12, 4), btVector3(4, 12, 4), 31, 31, 1 + 2, true));
	c->m_cfg.piterations = 10;
	c->setTotalMass(2);
	const btVector3 pin = c->m_nodes[0].m_x;
	s.step(frames);
	const btScalar low = lowestNode(c), stretch = worstStretch(c);
	printf("  lowest node at y = %.2f m (hanging 8 m below the pins: 4 m), worst link stretch %.3f\n", double(low),
	       double(stretch));
	return report(allFinite(c) && c->m_nodes[0].m_x == pin && low < 5 && low > 2 && stretch < 1.15,
	              "pins hold, the cloth hangs about its length below them, links stretch < 15%");
}

bool pressure(int frames)
{
	printf("Pressure: a ball of gas (kPR = 1000, P V = kPR) falls 3 m onto the ground and bounces.\n");
	Scene s;
	btSoftBody* b =
	    s.addSoft(btSoftBodyHelpers::CreateEllipsoid(s.info(), btVector3(0, 4, 0), btVector3(1, 1, 1), 256));
	b->m_cfg.kPR = 1000;
	b->m_cfg.kDF = btScalar(0.5);
	b->m_cfg.piterations = 4;
	b->setTotalMass(1, true);
	const btScalar v0 = b->getVolume();
	btScalar lowest = BT_LARGE_FLOAT, minVolume = v0;
	for (int i = 0; i < frames; ++i)
	{
		s.step(1);
		lowest = btMin(lowest, lowestNode(b));
		minVolume = btMin(minVolume, b->getVolume());
	}
	printf("  volume %.2f m^3 at rest, smallest %.2f m^3 at impact; lowest node %.4f m; centre at rest %.2f m\n",
	       double(v0), double(minVolume), double(lowest), double(b->evaluateCom().y()));
	// With converged sweeps the fall's 30 J would compress the gas only until kPR ln(V0 / V) = 30 J
	// (V = 0.97 V0); four sweeps leave the volume constraint softer than that.
	return report(allFinite(b) && lowest > -1e-4 && minVolume > btScalar(0.9) * v0 && b->evaluateCom().y() < 1.5,
	              "no node below the ground, the gas keeps 90% of its volume, the ball lands");
}

bool volume(int frames)
{
	printf("Volume: a hollow ball of soft links keeps its volume (kVC = 500) under three 2 kg boxes.\n");
	Scene s;
	btSoftBody* b =
	    s.addSoft(btSoftBodyHelpers::CreateEllipsoid(s.info(), btVector3(0, 1.5, 0), btVector3(1.5, 1.5, 1.5), 256));
	b->m_materials[0]->m_kLST = btScalar(0.3);
	b->m_cfg.kVC = 500;
	b->m_cfg.piterations = 4;
	b->m_cfg.kDP = btScalar(0.02);
	b->setTotalMass(3);
	b->setPose(true, false);
	const btScalar v0 = b->getVolume();
	btCollisionShape* box = s.own(new btBoxShape(btVector3(0.4, 0.4, 0.4)));
	for (int i = 0; i < 3; ++i) s.addRigid(2, btVector3(btScalar(0.3) * (i - 1), btScalar(3.6 + i), 0), box);
	s.step(frames);
	const btScalar v = b->getVolume();
	printf("  rest volume %.2f m^3, now %.2f m^3 (%.1f%%)\n", double(v0), double(v), double(100 * v / v0));
	return report(allFinite(b) && v > btScalar(0.95) * v0 && lowestNode(b) > -1e-4,
	              "volume within 5% of rest, no node below the ground");
}

bool ropes(int frames)
{
	printf("Ropes: 15 ropes of 2 to 9 m, fixed at one end, fall from horizontal and swing.\n");
	Scene s;
	std::vector<btSoftBody*> r;
	for (int i = 0; i < 15; ++i)
	{
		const btScalar length = 2 + btScalar(i) / 2;
		btSoftBody* rope = s.addSoft(btSoftBodyHelpers::CreateRope(s.info(), btVector3(-7 + i, 10, 0),
		                                                           btVector3(-7 + i + length, 10, 0), 20 + 2 * i, 1));
		rope->m_cfg.piterations = 8;
		rope->setTotalMass(btScalar(0.1) * length);
		r.push_back(rope);
	}
	s.step(frames);
	btScalar stretch = 0;
	bool finite = true;
	for (btSoftBody* rope : r)
	{
		stretch = btMax(stretch, worstStretch(rope));
		finite = finite && allFinite(rope);
	}
	btScalar overall = 0;
	for (btSoftBody* rope : r) overall = btMax(overall, overallStretch(rope));
	printf("  worst link stretch %.3f, worst rope stretch %.3f; the longest rope's end at y = %.2f m\n",
	       double(stretch), double(overall), double(r.back()->m_nodes[r.back()->m_nodes.size() - 1].m_x.y()));
	return report(finite && overall < btScalar(1.05) && stretch < btScalar(1.25),
	              "ropes keep their length within 5% (links within 25%) while they whip");
}

bool ropeAttach(int frames)
{
	printf("RopeAttach: a 3 m rope fixed at its top carries a 2 kg box through an anchor (two-way).\n");
	Scene s;
	btSoftBody* rope =
	    s.addSoft(btSoftBodyHelpers::CreateRope(s.info(), btVector3(0, 10, 0), btVector3(3, 10, 0), 30, 1));
	rope->m_cfg.piterations = 10;
	rope->setTotalMass(btScalar(0.5));
	btRigidBody* box =
	    s.addRigid(2, btVector3(3, btScalar(9.75), 0), s.own(new btBoxShape(btVector3(0.25, 0.25, 0.25))));
	rope->appendAnchor(rope->m_nodes.size() - 1, box);
	btScalar worstReach = 0;
	for (int i = 0; i < frames; ++i)
	{
		s.step(1);
		worstReach = btMax(worstReach, (box->getCenterOfMassPosition() - btVector3(0, 10, 0)).length());
	}
	const btScalar reach = 3 + btScalar(0.25);
	printf("  the box swings at most %.2f m from the pin (rope 3 m + anchor offset 0.25 m); it hangs at y = %.2f\n",
	       double(worstReach), double(box->getCenterOfMassPosition().y()));
	return report(allFinite(rope) && worstReach < reach * btScalar(1.1) && box->getCenterOfMassPosition().y() < 8,
	              "the rope holds the box within 10% of its reach and the box swings down");
}

bool clothAttach(int frames)
{
	printf("ClothAttach: a cloth hangs from a 5 kg box at two corners; the box lies on the ground.\n");
	Scene s;
	btRigidBody* box = s.addRigid(5, btVector3(0, 4, 0), s.own(new btBoxShape(btVector3(1, 0.5, 1))));
	btSoftBody* c = s.addSoft(
	    btSoftBodyHelpers::CreatePatch(s.info(), btVector3(-1, btScalar(4.5), 1), btVector3(1, btScalar(4.5), 1),
	                                   btVector3(-1, btScalar(4.5), 3), btVector3(1, btScalar(4.5), 3), 9, 9, 0, true));
	c->m_cfg.piterations = 10;
	c->setTotalMass(btScalar(0.5));
	c->appendAnchor(0, box);
	c->appendAnchor(8, box);
	s.step(frames);
	btScalar error = 0;
	for (int i = 0; i < c->m_anchors.size(); ++i)
	{
		const btSoftBody::Anchor& a = c->m_anchors[i];
		error = btMax(error, (a.m_node->m_x - a.m_body->getWorldTransform() * a.m_local).length());
	}
	printf("  box at y = %.2f m (on the ground: 0.5), anchor error %.4f m, cloth lowest node %.2f m\n",
	       double(box->getCenterOfMassPosition().y()), double(error), double(lowestNode(c)));
	return report(
	    allFinite(c) && error < btScalar(0.01) && btFabs(box->getCenterOfMassPosition().y() - btScalar(0.5)) < 0.05,
	    "anchors hold within 1 cm and the box carries the cloth down to the ground");
}

bool friction(int frames)
{
	printf("Friction: three cloths slide down a 30 degree slope with kDF = 0.1, 0.5 and 0.9.\n");
	Scene s;
	const btScalar angle = SIMD_PI / 6;
	const btTransform t(btQuaternion(btVector3(0, 0, 1), angle), btVector3(0, 3, 0));
	s.addRigid(0, t, s.own(new btBoxShape(btVector3(8, 0.1, 3))));
	btScalar travelled[3];
	btSoftBody* cloths[3];
	const btScalar kDF[3] = {btScalar(0.1), btScalar(0.5), btScalar(0.9)};
	for (int i = 0; i < 3; ++i)
	{
		// A 1 m square laid on the slope (its top face is at 0.1 m above the slope's mid-plane).
		const btVector3 centre = t * btVector3(0, btScalar(0.12), btScalar(-2 + 2 * i));
		const btVector3 u = t.getBasis() * btVector3(0.5, 0, 0), w = btVector3(0, 0, 0.5);
		cloths[i] = s.addSoft(btSoftBodyHelpers::CreatePatch(s.info(), centre - u - w, centre + u - w, centre - u + w,
		                                                     centre + u + w, 6, 6, 0, true));
		cloths[i]->m_cfg.kDF = kDF[i];
		cloths[i]->m_cfg.piterations = 4;
		cloths[i]->setTotalMass(btScalar(0.2));
		travelled[i] = cloths[i]->evaluateCom().x();
	}
	s.step(frames);
	for (int i = 0; i < 3; ++i) travelled[i] = travelled[i] - cloths[i]->evaluateCom().x();
	// mu = kDF times the slope's friction (0.5): tan 30 = 0.58 > mu for all three, but the slides differ.
	printf("  slid %.2f, %.2f, %.2f m down the slope (mu = kDF x 0.5 = 0.05, 0.25, 0.45 < tan 30 = 0.58)\n",
	       double(travelled[0]), double(travelled[1]), double(travelled[2]));
	return report(travelled[0] > travelled[1] && travelled[1] > travelled[2] && travelled[2] > 0,
	              "more friction, shorter slide; all slide since mu < tan 30");
}

bool impact(int frames)
{
	printf("Impact: a 1 kg box falls 3 m onto a cloth (nodes 16 cm apart, kDF = 1) stretched over four posts.\n");
	Scene s;
	btSoftBody* c =
	    s.addSoft(btSoftBodyHelpers::CreatePatch(s.info(), btVector3(-2, 2, -2), btVector3(2, 2, -2),
	                                             btVector3(-2, 2, 2), btVector3(2, 2, 2), 26, 26, 1 + 2 + 4 + 8, true));
	c->m_cfg.kDF = 1;
	c->m_cfg.piterations = 10;
	c->m_cfg.kDP = btScalar(0.05);
	c->setTotalMass(1);
	btRigidBody* box = s.addRigid(1, btVector3(0, 5, 0), s.own(new btBoxShape(btVector3(0.3, 0.3, 0.3))));
	btScalar lowest = BT_LARGE_FLOAT;
	for (int i = 0; i < frames; ++i)
	{
		s.step(1);
		lowest = btMin(lowest, box->getCenterOfMassPosition().y());
	}
	printf("  the box sank to y = %.2f m, rests at %.2f m; cloth stretch %.3f\n", double(lowest),
	       double(box->getCenterOfMassPosition().y()), double(worstStretch(c)));
	return report(allFinite(c) && lowest > btScalar(0.3) && box->getCenterOfMassPosition().y() < 2,
	              "the cloth catches the box before it reaches the ground and carries it");
}

struct Entry
{
	const char* name;
	bool (*run)(int);
	int frames;
};
const Entry kScenes[] = {{"Cloth", cloth, 240},      {"Pressure", pressure, 240},     {"Volume", volume, 240},
                         {"Ropes", ropes, 180},      {"RopeAttach", ropeAttach, 180}, {"ClothAttach", clothAttach, 180},
                         {"Friction", friction, 90}, {"Impact", impact, 240}};
}  // namespace

int main(int argc, char** argv)
{
	caliber::demo::DemoCommandLine commandLine;
	commandLine.name = "SoftDemo";
	commandLine.maxPositional = 2;
	commandLine.positionalUsage = "[scene[,scene...]|all] [frames]";
	caliber::demo::DemoPictures pictures(argc, argv, commandLine);
	if (!pictures.ok()) return pictures.exitCode();
	if (pictures.wanted())
		g_pictures = &pictures;
	const std::vector<std::string>& positional = pictures.positional();
	const std::string filter = positional.size() > 0 ? positional[0] : "all";
	const int frames = positional.size() > 1 ? atoi(positional[1].c_str()) : 0;
	int failed = 0, ran = 0;
	for (const Entry& e : kScenes)
	{
		if (filter != "all" && ("," + filter + ",").find("," + std::string(e.name) + ",") == std::string::npos)
			continue;
		++ran;
		if (!e.run(frames > 0 ? frames : e.frames)) ++failed;
	}
	printf("SoftDemo: %d scenes, %d failed\n", ran, failed);
	return pictures.finish(failed ? 1 : 0);
}
