// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
//
// SoftDemo: soft bodies in the soft-rigid world, headless, in scenes after Bullet's SoftDemo (our own
// set-ups): Cloth, Pressure, Volume, Ropes, RopeAttach, ClothAttach, Sticks, Collide, Collide2, Collide3,
// Friction, Impact, Aero, Aero2, Torus, TorusMatch, Bunny, BunnyMatch, Cutting1, TetraCube, and with clusters
// ClusterDeform, ClusterCollide1, ClusterCollide2, ClusterSocket, ClusterHinge, ClusterCombine, ClusterCar,
// ClusterRobot, ClusterStackSoft, ClusterStackMixed (checks of the later ones in SoftChecksMore.cpp). Each scene prints
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

#include "SoftChecks.h"

namespace
{
using namespace soft_checks;

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

bool clusterDeform(int frames)
{
	printf(
	    "ClusterDeform: a soft body (2 kg, soft links, 8 clusters matching their rest shape by 0.5 a step)\n"
	    "  falls 3 m, squashes on the ground and springs back.\n");
	Scene s;
	btSoftBody* b = soft_demo::buildClusterDeform(s).softs[0];
	const btScalar v0 = b->getVolume();
	btScalar lowest = BT_LARGE_FLOAT, squashed = v0;
	for (int i = 0; i < frames; ++i)
	{
		s.step(1);
		lowest = btMin(lowest, lowestNode(b));
		squashed = btMin(squashed, b->getVolume());
	}
	const btScalar v = b->getVolume();
	printf("  volume %.2f m^3 at rest, %.2f at the most squashed, %.2f at the end; lowest node %.4f m\n", double(v0),
	       double(squashed), double(v), double(lowest));
	return report(allFinite(b) && lowest > -0.01 && squashed < v0 && v > btScalar(0.9) * v0,
	              "no node 1 cm below the ground, the body squashes and gets 90% of its volume back");
}

bool clusterCollide1(int frames)
{
	printf("ClusterCollide1: two cluster balls (1 kg, 8 clusters, CL_SS) thrown at each other at 6 m/s.\n");
	Scene s;
	const std::vector<btSoftBody*> b = soft_demo::buildClusterCollide1(s).softs;
	btScalar overlap = 0;
	for (int i = 0; i < frames; ++i)
	{
		s.step(1);
		overlap = btMax(overlap, worstOverlap(b));
	}
	const btScalar apart = b[1]->evaluateCom().x() - b[0]->evaluateCom().x();
	printf("  deepest node of one ball inside the other %.4f m; centres %.2f m apart along x at the end\n",
	       double(overlap), double(apart));
	return report(allFinite(b[0]) && allFinite(b[1]) && overlap < 0.05 && apart > 1.5,
	              "the balls bounce off each other (no node 5 cm inside the other) and end apart");
}

bool clusterCollide2(int frames)
{
	printf("ClusterCollide2: four cluster balls (1 kg, 6 clusters, CL_SS) dropped on one another.\n");
	Scene s;
	const std::vector<btSoftBody*> b = soft_demo::buildClusterCollide2(s).softs;
	btScalar overlap = 0, lowest = BT_LARGE_FLOAT;
	bool finite = true;
	for (int i = 0; i < frames; ++i)
	{
		s.step(1);
		overlap = btMax(overlap, worstOverlap(b));
		for (btSoftBody* x : b) lowest = btMin(lowest, lowestNode(x));
	}
	for (btSoftBody* x : b) finite = finite && allFinite(x);
	printf("  deepest node of one ball inside another %.4f m; lowest node %.4f m\n", double(overlap), double(lowest));
	return report(finite && overlap < 0.05 && lowest > -0.01,
	              "no node 5 cm inside another ball, nor 1 cm below the ground");
}

bool clusterSocket(int frames)
{
	printf("ClusterSocket: a cluster ball held at a world point by a linear joint, pushed sideways at 4 m/s.\n");
	Scene s;
	btSoftBody* b = soft_demo::buildClusterSocket(s).softs[0];
	btScalar gap = 0, swing = 0;
	for (int i = 0; i < frames; ++i)
	{
		s.step(1);
		gap = btMax(gap, jointGap(b->m_joints[0]));
		swing = btMax(swing, b->evaluateCom().x());
	}
	printf("  the ball swung %.2f m out; the joint's worst gap %.4f m\n", double(swing), double(gap));
	return report(allFinite(b) && gap < 0.02 && swing > 0.5, "the socket holds within 2 cm while the ball swings");
}

bool clusterHinge(int frames)
{
	printf("ClusterHinge: a soft wheel on a post: an axle (linear joint) and a motor (angular joint, 3 rad/s).\n");
	Scene s;
	const soft_demo::Parts parts = soft_demo::buildClusterHinge(s);
	btSoftBody* w = parts.softs[0];
	s.step(frames);
	// The wheel's spin about its axle, from its nodes: L_z / I_zz about its centre of mass.
	const btVector3 com = w->evaluateCom();
	btScalar lz = 0, izz = 0;
	for (int i = 0; i < w->m_nodes.size(); ++i)
	{
		const btSoftBody::Node& n = w->m_nodes[i];
		const btVector3 r = n.m_x - com;
		lz += r.cross(n.m_v).z() / n.m_im;
		izz += (r.x() * r.x() + r.y() * r.y()) / n.m_im;
	}
	const btScalar spin = lz / izz;
	printf("  spin %.3f rad/s (motor 3); axle gap %.4f m; axle at y = %.3f m (4)\n", double(spin),
	       double(jointGap(w->m_joints[0])), double(com.y()));
	return report(allFinite(w) && btFabs(spin - 3) < 0.15 && jointGap(w->m_joints[0]) < 0.02,
	              "the motor spins the wheel within 5% of 3 rad/s and the axle holds within 2 cm");
}

bool clusterCombine(int frames)
{
	printf("ClusterCombine: two soft balls and a 1 kg box joined in a chain from a world point, swinging.\n");
	Scene s;
	const soft_demo::Parts parts = soft_demo::buildClusterCombine(s);
	btScalar gap = 0;
	for (int i = 0; i < frames; ++i)
	{
		s.step(1);
		for (btSoftBody* b : parts.softs)
			for (int j = 0; j < b->m_joints.size(); ++j) gap = btMax(gap, jointGap(b->m_joints[j]));
	}
	const btScalar y = parts.rigids[0]->getCenterOfMassPosition().y();
	printf("  the joints' worst gap %.4f m; the box at y = %.2f m (hanging below the pin at 8 m)\n", double(gap),
	       double(y));
	return report(allFinite(parts.softs[0]) && allFinite(parts.softs[1]) && gap < 0.05 && y < 8,
	              "the chain holds together within 5 cm and swings down");
}

bool clusterStack(const soft_demo::Parts& parts, Scene& s, int frames, btScalar height)
{
	btScalar overlap = 0;
	for (int i = 0; i < frames; ++i)
	{
		s.step(1);
		overlap = btMax(overlap, worstOverlap(parts.softs));
	}
	btScalar top = 0;
	bool finite = true;
	for (btSoftBody* b : parts.softs)
	{
		top = btMax(top, b->evaluateCom().y());
		finite = finite && allFinite(b);
	}
	for (btRigidBody* r : parts.rigids) top = btMax(top, r->getCenterOfMassPosition().y());
	printf("  the top of the stack at y = %.2f m (built at %.2f); deepest node of one disc inside another %.4f m\n",
	       double(top), double(height), double(overlap));
	return report(finite && top > btScalar(0.7) * height && overlap < 0.05,
	              "the stack stands (its top keeps 70% of its height) with no node 5 cm inside another disc");
}

bool clusterStackSoft(int frames)
{
	printf("ClusterStackSoft: four flat soft discs (2.4 x 0.9 m, 6 clusters, CL_SS) stacked.\n");
	Scene s;
	const soft_demo::Parts parts = soft_demo::buildClusterStackSoft(s);
	return clusterStack(parts, s, frames, btScalar(0.5 + 1.1 * 3));
}

bool clusterStackMixed(int frames)
{
	printf("ClusterStackMixed: soft disc, box, soft disc, box (flat 0.4 m discs of 6 clusters, 0.6 m boxes of 1 kg).\n");
	Scene s;
	const soft_demo::Parts parts = soft_demo::buildClusterStackMixed(s);
	s.step(frames);
	// Where the boxes would rest on rigid discs: 0.7 and 1.7 m. The lower disc's gas (P V = 200 J, 1.8 m^3)
	// carries 30 N on the box's 2.6 m^2 and gives about 11% of its 0.4 m (4 cm); the upper one about 1.5 cm.
	btScalar worst = 0;
	for (int k = 0; k < 2; ++k)
		worst = btMax(worst, btFabs(parts.rigids[size_t(k)]->getCenterOfMassPosition().y() - btScalar(0.7 + k)));
	const btVector3 top = parts.rigids[1]->getCenterOfMassPosition();
	printf("  the boxes at y = %.2f and %.2f m (rigid discs: 0.70 and 1.70), the worst %.3f m off; the top box %.2f m off the axis\n",
	       double(parts.rigids[0]->getCenterOfMassPosition().y()), double(top.y()), double(worst),
	       double(btVector3(top.x(), 0, top.z()).length()));
	// A box sinking into a disc or the stack falling over moves a box by tens of centimetres.
	return report(allFinite(parts.softs[0]) && allFinite(parts.softs[1]) && worst < btScalar(0.1) &&
	                  btVector3(top.x(), 0, top.z()).length() < btScalar(0.5),
	              "the discs carry the boxes within 10 cm of their rigid-stack heights; the top stays within 0.5 m of the axis");
}

struct Entry
{
	const char* name;
	bool (*run)(int);
	int frames;
};
const Entry kScenes[] = {{"Cloth", cloth, 240},
                         {"Pressure", pressure, 240},
                         {"Volume", volume, 240},
                         {"Ropes", ropes, 180},
                         {"RopeAttach", ropeAttach, 180},
                         {"ClothAttach", clothAttach, 180},
                         {"Sticks", sticks, 120},
                         {"Collide", collide, 150},
                         {"Collide2", collide2, 150},
                         {"Collide3", collide3, 120},
                         {"Friction", friction, 90},
                         {"Impact", impact, 240},
                         {"Aero", aero, 120},
                         {"Aero2", aero2, 90},
                         {"Torus", torus, 150},
                         {"TorusMatch", torusMatch, 150},
                         {"Bunny", bunny, 150},
                         {"BunnyMatch", bunnyMatch, 150},
                         {"Cutting1", cutting1, 150},
                         {"TetraCube", tetraCube, 150},
                         {"ClusterDeform", clusterDeform, 180},
                         {"ClusterCollide1", clusterCollide1, 120},
                         {"ClusterCollide2", clusterCollide2, 180},
                         {"ClusterSocket", clusterSocket, 180},
                         {"ClusterHinge", clusterHinge, 180},
                         {"ClusterCombine", clusterCombine, 180},
                         {"ClusterCar", clusterCar, 180},
                         {"ClusterRobot", clusterRobot, 180},
                         {"ClusterStackSoft", clusterStackSoft, 180},
                         {"ClusterStackMixed", clusterStackMixed, 120}};
}  // namespace

int main(int argc, char** argv)
{
	caliber::demo::DemoCommandLine commandLine;
	commandLine.name = "SoftDemo";
	commandLine.maxPositional = 2;
	commandLine.positionalUsage = "[scene[,scene...]|all] [frames]";
	caliber::demo::DemoPictures pictures(argc, argv, commandLine);
	if (!pictures.ok()) return pictures.exitCode();
	if (pictures.wanted()) soft_checks::g_pictures = &pictures;
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
