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
#include "SoftScenes.h"

namespace
{
// Pictures (--png): each scene's world is captured as it ends, so the picture shows the last scene run
// (soft bodies drawn by Demos/Common like everything else).
caliber::demo::DemoPictures* g_pictures = 0;

// A scene whose world is pictured (--png) as it ends, before its bodies are removed.
struct Scene : soft_demo::Scene
{
	~Scene() override
	{
		if (g_pictures && hasSoftBodies()) g_pictures->capture(world());
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
	btSoftBody* c = soft_demo::buildCloth(s).softs[0];
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
	btSoftBody* b = soft_demo::buildPressure(s).softs[0];
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
	btSoftBody* b = soft_demo::buildVolume(s).softs[0];
	const btScalar v0 = b->getVolume();
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
	const std::vector<btSoftBody*> r = soft_demo::buildRopes(s).softs;
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
	const soft_demo::Parts parts = soft_demo::buildRopeAttach(s);
	btSoftBody* rope = parts.softs[0];
	btRigidBody* box = parts.rigids[0];
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
	const soft_demo::Parts parts = soft_demo::buildClothAttach(s);
	btRigidBody* box = parts.rigids[0];
	btSoftBody* c = parts.softs[0];
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
	const std::vector<btSoftBody*> cloths = soft_demo::buildFriction(s).softs;
	btScalar travelled[3];
	for (int i = 0; i < 3; ++i) travelled[i] = cloths[size_t(i)]->evaluateCom().x();
	s.step(frames);
	for (int i = 0; i < 3; ++i) travelled[i] = travelled[i] - cloths[size_t(i)]->evaluateCom().x();
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
	const soft_demo::Parts parts = soft_demo::buildImpact(s);
	btSoftBody* c = parts.softs[0];
	btRigidBody* box = parts.rigids[0];
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
