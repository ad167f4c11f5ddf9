// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef CALIBER_DEMOS_SOFT_CHECKS_H
#define CALIBER_DEMOS_SOFT_CHECKS_H
// What SoftDemo's checks measure (main.cpp, SoftChecksMore.cpp): the scene wrapper that pictures its world,
// and figures of soft bodies.

#include <stdio.h>

#include <vector>

#include "DemoPictures.h"
#include "SoftScenes.h"

namespace soft_checks
{

// Pictures (--png): each scene's world is captured as it ends, so the picture shows the last scene run
// (soft bodies drawn by Demos/Common like everything else).
inline caliber::demo::DemoPictures* g_pictures = 0;

// A scene whose world is pictured (--png) as it ends, before its bodies are removed.
struct Scene : soft_demo::Scene
{
	~Scene() override
	{
		if (g_pictures && hasSoftBodies()) g_pictures->capture(world());
	}
};

inline btScalar lowestNode(const btSoftBody* s)
{
	btScalar y = BT_LARGE_FLOAT;
	for (int i = 0; i < s->m_nodes.size(); ++i) y = btMin(y, s->m_nodes[i].m_x.y());
	return y;
}

inline btScalar worstStretch(const btSoftBody* s)
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
inline btScalar overallStretch(const btSoftBody* s)
{
	btScalar length = 0, rest = 0;
	for (int i = 0; i < s->m_links.size(); ++i)
	{
		length += (s->m_links[i].m_n[0]->m_x - s->m_links[i].m_n[1]->m_x).length();
		rest += s->m_links[i].m_rl;
	}
	return rest > 0 ? length / rest : 1;
}

inline bool allFinite(const btSoftBody* s)
{
	for (int i = 0; i < s->m_nodes.size(); ++i)
		if (!caliber::isFinite(s->m_nodes[i].m_x)) return false;
	return true;
}

inline bool report(bool ok, const char* what)
{
	printf("  check: %s: %s\n", what, ok ? "PASS" : "FAIL");
	return ok;
}

// How deep the deepest node of a lies inside b, taking b as convex (behind all its faces' planes).
inline btScalar deepestInside(const btSoftBody* a, const btSoftBody* b)
{
	const btScalar sign = b->getVolume() < 0 ? btScalar(-1) : btScalar(1);
	btScalar deepest = 0;
	for (int i = 0; i < a->m_nodes.size(); ++i)
	{
		btScalar depth = BT_LARGE_FLOAT;
		for (int k = 0; k < b->m_faces.size() && depth > 0; ++k)
		{
			const btSoftBody::Face& f = b->m_faces[k];
			btVector3 n = (f.m_n[1]->m_x - f.m_n[0]->m_x).cross(f.m_n[2]->m_x - f.m_n[0]->m_x);
			if (n.length2() <= SIMD_EPSILON) continue;
			depth = btMin(depth, -sign * n.normalized().dot(a->m_nodes[i].m_x - f.m_n[0]->m_x));
		}
		deepest = btMax(deepest, depth);
	}
	return deepest;
}

// The deepest any node of one body of softs gets into another.
inline btScalar worstOverlap(const std::vector<btSoftBody*>& softs)
{
	btScalar worst = 0;
	for (size_t i = 0; i < softs.size(); ++i)
		for (size_t j = 0; j < softs.size(); ++j)
			if (i != j) worst = btMax(worst, deepestInside(softs[i], softs[j]));
	return worst;
}

// Where joint j's two points are now, apart.
inline btScalar jointGap(const btSoftBody::Joint* j)
{
	return (j->m_bodies[0].xform() * j->m_refs[0] - j->m_bodies[1].xform() * j->m_refs[1]).length();
}


// The checks of SoftChecksMore.cpp (frames: how many steps of 1/60 s).
bool sticks(int frames);
bool collide(int frames);
bool collide2(int frames);
bool collide3(int frames);
bool aero(int frames);
bool aero2(int frames);
bool torus(int frames);
bool torusMatch(int frames);
bool bunny(int frames);
bool bunnyMatch(int frames);
bool cutting1(int frames);
bool tetraCube(int frames);
bool clusterCar(int frames);
bool clusterRobot(int frames);
}  // namespace soft_checks

#endif
