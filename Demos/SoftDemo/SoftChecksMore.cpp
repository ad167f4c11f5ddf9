// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// SoftDemo's checks of the scenes in SoftScenesMore.cpp: each prints what it shows, its figures and a
// pass/fail check of a physical property.
#include <numeric>
#include <set>

#include "SoftChecks.h"
#include "SoftMeshes.h"

namespace soft_checks
{
namespace
{
// The pieces of a body: connected components of its nodes through links; label[i] is node i's piece.
int pieces(const btSoftBody* s, std::vector<int>& label)
{
	std::vector<int> parent(size_t(s->m_nodes.size()));
	std::iota(parent.begin(), parent.end(), 0);
	auto find = [&parent](int i)
	{
		while (parent[size_t(i)] != i) i = parent[size_t(i)] = parent[size_t(parent[size_t(i)])];
		return i;
	};
	for (int i = 0; i < s->m_links.size(); ++i)
		parent[size_t(find(int(s->m_links[i].m_n[0] - &s->m_nodes[0])))] =
		    find(int(s->m_links[i].m_n[1] - &s->m_nodes[0]));
	std::set<int> roots;
	label.resize(parent.size());
	for (size_t i = 0; i < parent.size(); ++i) roots.insert(label[i] = find(int(i)));
	return int(roots.size());
}

bool allFiniteAll(const std::vector<btSoftBody*>& softs)
{
	for (const btSoftBody* b : softs)
		if (!soft_checks::allFinite(b)) return false;
	return true;
}

btScalar lowestOf(const std::vector<btSoftBody*>& softs)
{
	btScalar y = BT_LARGE_FLOAT;
	for (const btSoftBody* b : softs) y = btMin(y, lowestNode(b));
	return y;
}

// Drops a closed body and measures its volume: the smallest on the way and the last.
struct VolumeRun
{
	btScalar rest, smallest, last, lowest;
};
VolumeRun dropAndMeasure(Scene& s, btSoftBody* b, int frames, btScalar (*volume)(const btSoftBody*))
{
	VolumeRun r;
	r.rest = r.smallest = volume(b);
	r.lowest = BT_LARGE_FLOAT;
	for (int i = 0; i < frames; ++i)
	{
		s.step(1);
		r.smallest = btMin(r.smallest, volume(b));
		r.lowest = btMin(r.lowest, lowestNode(b));
	}
	r.last = volume(b);
	printf("  volume %.3f m^3 at rest, %.3f at the smallest, %.3f at the end (%.1f%%); lowest node %.4f m\n",
	       double(r.rest), double(r.smallest), double(r.last), double(100 * r.last / r.rest), double(r.lowest));
	return r;
}

btScalar surfaceVolume(const btSoftBody* b) { return b->getVolume(); }
btScalar tetraVolume(const btSoftBody* b) { return soft_demo::tetraVolume(*b); }
}  // namespace

bool sticks(int frames)
{
	printf("Sticks: 25 sticks of 1.5 m (ropes with bending links) fixed at the ground, leaning 10 degrees, bend over.\n");
	Scene s;
	const std::vector<btSoftBody*> sticks = soft_demo::buildSticks(s).softs;
	std::vector<btVector3> base, top;
	for (btSoftBody* b : sticks)
	{
		base.push_back(b->m_nodes[0].m_x);
		top.push_back(b->m_nodes[b->m_nodes.size() - 1].m_x);
	}
	s.step(frames);
	btScalar drop = 0, stretch = 0;
	bool held = true;
	for (size_t i = 0; i < sticks.size(); ++i)
	{
		const btSoftBody* b = sticks[i];
		drop += (top[i].y() - b->m_nodes[b->m_nodes.size() - 1].m_x.y()) / btScalar(sticks.size());
		held = held && b->m_nodes[0].m_x == base[i];
		stretch = btMax(stretch, overallStretch(b));
	}
	printf("  the tops sank %.2f m on average; worst stick length %.3f of rest; bases %s\n", double(drop),
	       double(stretch), held ? "held" : "moved");
	// overallStretch sums the bending links too: a bent stick shortens them, so it stays below 1.
	return report(allFiniteAll(sticks) && held && drop > btScalar(0.1) && stretch < btScalar(1.05),
	              "the bases hold, the sticks bend under their weight, no stick stretches 5%");
}

bool collide(int frames)
{
	printf("Collide: two gas balls (1 kg, kPR = 100, VF_SS) thrown at each other at 6 m/s meet in the air.\n");
	Scene s;
	const std::vector<btSoftBody*> b = soft_demo::buildCollide(s).softs;
	btScalar overlap = 0, closest = BT_LARGE_FLOAT;
	for (int i = 0; i < frames; ++i)
	{
		s.step(1);
		overlap = btMax(overlap, worstOverlap(b));
		closest = btMin(closest, b[1]->evaluateCom().x() - b[0]->evaluateCom().x());
	}
	const btScalar apart = b[1]->evaluateCom().x() - b[0]->evaluateCom().x();
	printf("  deepest node of one ball inside the other %.4f m; centres at least %.2f m apart along x, %.2f at the end\n",
	       double(overlap), double(closest), double(apart));
	// Each ball has a radius of 1 m: they met (centres closer than 2.2 m) and bounced back apart.
	return report(allFiniteAll(b) && overlap < btScalar(0.05) && closest < btScalar(2.2) && apart > closest + 1 &&
	                  lowestOf(b) > -0.01,
	              "the balls collide (no node 5 cm inside the other) and bounce apart");
}

bool collide2(int frames)
{
	printf("Collide2: three soft volumes (soft links, kVC = 200, VF_SS) fall on one another.\n");
	Scene s;
	const std::vector<btSoftBody*> b = soft_demo::buildCollide2(s).softs;
	std::vector<btScalar> v0;
	for (btSoftBody* x : b) v0.push_back(x->getVolume());
	btScalar overlap = 0, lowest = BT_LARGE_FLOAT;
	for (int i = 0; i < frames; ++i)
	{
		s.step(1);
		overlap = btMax(overlap, worstOverlap(b));
		lowest = btMin(lowest, lowestOf(b));
	}
	btScalar worstVolume = 1;
	for (size_t i = 0; i < b.size(); ++i) worstVolume = btMin(worstVolume, b[i]->getVolume() / v0[i]);
	printf("  deepest node inside another body %.4f m; lowest node %.4f m; smallest volume %.1f%% of rest\n",
	       double(overlap), double(lowest), double(100 * worstVolume));
	return report(allFiniteAll(b) && overlap < btScalar(0.05) && lowest > -0.01 && worstVolume > btScalar(0.85),
	              "no node 5 cm inside another body nor 1 cm below the ground; each keeps 85% of its volume");
}

bool collide3(int frames)
{
	printf("Collide3: a free cloth falls onto a cloth pinned at its corners (VF_SS) and lies on it.\n");
	Scene s;
	const std::vector<btSoftBody*> c = soft_demo::buildCollide3(s).softs;
	btSoftBody* lower = c[0];
	btSoftBody* upper = c[1];
	// The upper cloth is smaller than the lower one, so each of its nodes has lower-cloth nodes around it:
	// how far it is above the lower cloth's nearest node (horizontally), at worst.
	btScalar worstAbove = BT_LARGE_FLOAT;
	for (int f = 0; f < frames; ++f)
	{
		s.step(1);
		for (int i = 0; i < upper->m_nodes.size(); ++i)
		{
			const btVector3& x = upper->m_nodes[i].m_x;
			btScalar best = BT_LARGE_FLOAT, below = 0;
			for (int k = 0; k < lower->m_nodes.size(); ++k)
			{
				const btVector3 d = lower->m_nodes[k].m_x - x;
				const btScalar h = d.x() * d.x() + d.z() * d.z();
				if (h < best)
				{
					best = h;
					below = -d.y();
				}
			}
			worstAbove = btMin(worstAbove, below);
		}
	}
	printf("  the free cloth's nodes stay at least %.3f m above the pinned cloth's nearest node; its lowest at %.2f m\n",
	       double(worstAbove), double(lowestNode(upper)));
	// The pinned cloth's nodes are 0.29 m apart: a node of the free cloth between them may sit a little
	// below the nearest one while above the face; 5 cm allows for that sag.
	return report(allFiniteAll(c) && worstAbove > btScalar(-0.05) && lowestNode(upper) > 1,
	              "the pinned cloth holds the free one up (no node of it 5 cm below the pinned cloth, none below 1 m)");
}

bool aero(int frames)
{
	printf("Aero: a 2 m flag hanging from two corners in a 10 m/s wind along +x (drag and lift on nodes).\n");
	Scene s;
	btSoftBody* c = soft_demo::buildAero(s).softs[0];
	const btVector3 start = c->evaluateCom();
	s.step(frames);
	const btVector3 end = c->evaluateCom();
	printf("  the flag's centre moved %.2f m downwind (x) and %.2f m up; worst link stretch %.3f\n",
	       double(end.x() - start.x()), double(end.y() - start.y()), double(worstStretch(c)));
	return report(allFinite(c) && end.x() - start.x() > btScalar(0.5) && worstStretch(c) < btScalar(1.2),
	              "the wind blows the flag 0.5 m downwind; it stays finite and whole");
}

bool aero2(int frames)
{
	printf("Aero2: four free 1 m sheets (50 g) fall through a 4 m/s wind along +z, with drag and lift on faces.\n");
	Scene s;
	const std::vector<btSoftBody*> sheets = soft_demo::buildAero2(s).softs;
	std::vector<btVector3> start;
	for (btSoftBody* b : sheets) start.push_back(b->evaluateCom());
	s.step(frames);
	const btScalar t = btScalar(frames) * soft_demo::kStep, freeFall = 10 * t * t / 2;
	btScalar leastDrift = BT_LARGE_FLOAT, mostFall = 0;
	for (size_t i = 0; i < sheets.size(); ++i)
	{
		const btVector3 d = sheets[i]->evaluateCom() - start[i];
		leastDrift = btMin(leastDrift, d.z());
		mostFall = btMax(mostFall, -d.y());
	}
	printf("  each sheet drifted at least %.2f m downwind and fell at most %.2f m (free fall: %.2f m in %.1f s)\n",
	       double(leastDrift), double(mostFall), double(freeFall), double(t));
	return report(allFiniteAll(sheets) && leastDrift > btScalar(0.3) && mostFall < btScalar(0.7) * freeFall,
	              "the air slows the fall (under 70% of free fall) and the wind carries every sheet downwind");
}

bool torus(int frames)
{
	printf("Torus: a torus of soft links (our procedural mesh, 160 nodes) keeping its volume by kVC = 100, dropped 3 m.\n");
	Scene s;
	btSoftBody* t = soft_demo::buildTorus(s).softs[0];
	const VolumeRun r = dropAndMeasure(s, t, frames, surfaceVolume);
	return report(allFinite(t) && r.rest > 0 && btFabs(r.last - r.rest) < btScalar(0.05) * r.rest && r.lowest > -0.01,
	              "the volume comes back within 5% of rest after the landing; no node 1 cm below the ground");
}

bool torusMatch(int frames)
{
	printf("TorusMatch: the torus with soft links and pose matching (kMT = 0.2) instead of kVC, dropped 3 m.\n");
	Scene s;
	btSoftBody* t = soft_demo::buildTorusMatch(s).softs[0];
	const VolumeRun r = dropAndMeasure(s, t, frames, surfaceVolume);
	return report(allFinite(t) && r.rest > 0 && btFabs(r.last - r.rest) < btScalar(0.1) * r.rest && r.lowest > -0.01,
	              "pose matching restores the rest volume within 10%; no node 1 cm below the ground");
}

bool bunny(int frames)
{
	printf("Bunny: a lumpy blob of gas (our own mesh standing in for Bullet's bunny, kPR = 500), dropped 3 m.\n");
	Scene s;
	btSoftBody* b = soft_demo::buildBunny(s).softs[0];
	const VolumeRun r = dropAndMeasure(s, b, frames, surfaceVolume);
	return report(allFinite(b) && btFabs(r.last - r.rest) < btScalar(0.1) * r.rest && r.lowest > -0.01,
	              "the gas keeps the volume within 10% after the landing; no node 1 cm below the ground");
}

bool bunnyMatch(int frames)
{
	printf("BunnyMatch: the blob with soft links and pose matching (kMT = 0.2), dropped 3 m.\n");
	Scene s;
	btSoftBody* b = soft_demo::buildBunnyMatch(s).softs[0];
	const VolumeRun r = dropAndMeasure(s, b, frames, surfaceVolume);
	return report(allFinite(b) && btFabs(r.last - r.rest) < btScalar(0.1) * r.rest && r.lowest > -0.01,
	              "pose matching restores the rest volume within 10%; no node 1 cm below the ground");
}

namespace
{
// The plane x = 0.05 (between two columns of the cloth's nodes), positive on the +x side.
struct CutPlane : btSoftBody::ImplicitFn
{
	btScalar Eval(const btVector3& x) override { return x.x() - btScalar(0.05); }
};
}  // namespace

bool cutting1(int frames)
{
	printf("Cutting1: a cloth hanging from its two top corners is cut down the middle (refine with cut) after 1 s.\n");
	Scene s;
	btSoftBody* c = soft_demo::buildCutting1(s).softs[0];
	const btScalar mass = c->getTotalMass();
	const int before = c->m_nodes.size();
	s.step(60);
	CutPlane plane;
	c->refine(&plane, btScalar(1e-3), true);
	s.step(btMax(0, frames - 60));
	std::vector<int> label;
	const int count = pieces(c, label);
	// Each piece's centre of mass: the pieces swing apart, each under its own pin.
	btVector3 com[2] = {btVector3(0, 0, 0), btVector3(0, 0, 0)};
	btScalar m[2] = {0, 0};
	for (int i = 0; i < c->m_nodes.size(); ++i)
	{
		const int k = label[size_t(i)] == label[0] ? 0 : 1;
		const btScalar mi = c->m_nodes[i].m_im > 0 ? 1 / c->m_nodes[i].m_im : 0;
		com[k] += c->m_nodes[i].m_x * mi;
		m[k] += mi;
	}
	for (int k = 0; k < 2; ++k) com[k] /= btMax(m[k], SIMD_EPSILON);
	printf("  %d nodes became %d; %d piece(s); mass %.4f kg (was %.4f); the pieces' centres at x = %.2f and %.2f m\n",
	       before, c->m_nodes.size(), count, double(c->getTotalMass()), double(mass), double(com[0].x()),
	       double(com[1].x()));
	return report(allFinite(c) && count == 2 && btFabs(c->getTotalMass() - mass) < btScalar(1e-4) * mass &&
	                  com[0].x() < -0.5 && com[1].x() > 0.5 && lowestNode(c) > 0,
	              "the cut leaves two pieces of the same total mass, each hanging from its own corner");
}

bool tetraCube(int frames)
{
	printf("TetraCube: a 1 m cube of 162 tetras (TetGen text made here; links on the tetras' edges, each tetra's\n"
	       "  volume held by kVST = 1) dropped 2 m.\n");
	Scene s;
	btSoftBody* c = soft_demo::buildTetraCube(s).softs[0];
	const VolumeRun r = dropAndMeasure(s, c, frames, tetraVolume);
	// kVST is not used by Caliber (docs/soft-bodies.md): the edge links alone keep the volume.
	return report(allFinite(c) && r.smallest > btScalar(0.85) * r.rest && btFabs(r.last - r.rest) < btScalar(0.05) * r.rest &&
	                  r.lowest > -0.01,
	              "the tetras keep 85% of their volume at impact and come back within 5%; no node 1 cm below the ground");
}

bool clusterCar(int frames)
{
	printf("ClusterCar: a 3 kg chassis on four soft wheels (one cluster each), motors at -6 rad/s about the axles.\n");
	Scene s;
	const soft_demo::Parts parts = soft_demo::buildClusterCar(s);
	btRigidBody* chassis = parts.rigids[0];
	const btVector3 start = chassis->getCenterOfMassPosition();
	btScalar gap = 0;
	for (int i = 0; i < frames; ++i)
	{
		s.step(1);
		for (btSoftBody* w : parts.softs) gap = btMax(gap, jointGap(w->m_joints[0]));
	}
	const btVector3 d = chassis->getCenterOfMassPosition() - start;
	const btScalar up = chassis->getWorldTransform().getBasis().getColumn(1).y();
	const btScalar t = btScalar(frames) * soft_demo::kStep;
	printf("  the car drove %.2f m along x (%.2f m sideways) in %.1f s (wheels at 6 rad/s x 0.5 m: up to 3 m/s); "
	       "upright %.2f; worst axle gap %.4f m\n",
	       double(d.x()), double(d.z()), double(t), double(up), double(gap));
	return report(allFiniteAll(parts.softs) && d.x() > 1 && up > btScalar(0.9) && gap < btScalar(0.05),
	              "the motors drive the car forward (more than 1 m), upright, axles within 5 cm");
}

bool clusterRobot(int frames)
{
	printf("ClusterRobot: a 1 kg hub on three soft feet (linear joints) tumbles down a 15 degree slope.\n");
	Scene s;
	const soft_demo::Parts parts = soft_demo::buildClusterRobot(s);
	btRigidBody* hub = parts.rigids[0];
	const btVector3 start = hub->getCenterOfMassPosition();
	btScalar gap = 0;
	for (int i = 0; i < frames; ++i)
	{
		s.step(1);
		for (btSoftBody* f : parts.softs) gap = btMax(gap, jointGap(f->m_joints[0]));
	}
	const btVector3 d = hub->getCenterOfMassPosition() - start;
	printf("  the hub moved %.2f m down the slope (x) and %.2f m down; worst joint gap %.4f m\n", double(-d.x()),
	       double(-d.y()), double(gap));
	// The feet are balls of 0.4 m radius: a gap of a quarter of that still holds the robot together.
	return report(allFiniteAll(parts.softs) && -d.x() > 1 && gap < btScalar(0.1),
	              "the robot travels down the slope (more than 1 m) and holds together (joints within 10 cm)");
}
}  // namespace soft_checks
