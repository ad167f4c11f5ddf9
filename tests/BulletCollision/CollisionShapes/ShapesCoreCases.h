// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef CALIBER_TESTS_SHAPES_CORE_CASES_H
#define CALIBER_TESTS_SHAPES_CORE_CASES_H

// The primitive shapes of the shapes-core tests with brute-force descriptions of their surfaces.

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "BulletCollision/CollisionShapes/btCapsuleShape.h"
#include "BulletCollision/CollisionShapes/btConeShape.h"
#include "BulletCollision/CollisionShapes/btCylinderShape.h"
#include "BulletCollision/CollisionShapes/btSphereShape.h"
#include "BulletCollision/CollisionShapes/ShapesCoreTestUtil.h"

namespace shapes_core_test
{
// Rounding of the expressions below: values up to ~10 (sizes ~2, transforms up to 5), a few dozen
// operations each, so a few hundred SIMD_EPSILON in absolute terms.
const btScalar kShapeRounding = btScalar(512) * SIMD_EPSILON;
// Circles are sampled with this many points; the polygon of N points on a circle of radius r lies within
// r (1 - cos(pi / N)) of the circle in every direction, which bounds the brute-force error.
const int kCircleSamples = 720;

inline btScalar circleSamplingError(btScalar radius)
{
	return radius * (btScalar(1) - btCos(SIMD_PI / btScalar(kCircleSamples)));
}

// A convex shape and a brute-force description of it: points whose convex hull is the core (the shape
// without margin, up to the circle sampling error), the margin sphere around the core, and the distance
// from a point to the core.
struct ShapeCase
{
	std::string label;
	std::shared_ptr<btConvexInternalShape> shape;
	std::vector<btVector3> coreSamples;
	btScalar margin;
	btScalar samplingError;
	std::function<btScalar(const btVector3&)> distanceToCore;
};

inline void addCircle(std::vector<btVector3>& out, int upAxis, btScalar axial, btScalar radius)
{
	const int a = (upAxis + 1) % 3, b = (upAxis + 2) % 3;
	for (int i = 0; i < kCircleSamples; ++i)
	{
		const btScalar angle = SIMD_2_PI * btScalar(i) / btScalar(kCircleSamples);
		btVector3 p(0, 0, 0);
		p[upAxis] = axial;
		p[a] = radius * btCos(angle);
		p[b] = radius * btSin(angle);
		out.push_back(p);
	}
}

// Distance from p to the solid cylinder of radius r and half height h along upAxis.
inline btScalar distanceToCylinder(const btVector3& p, int upAxis, btScalar r, btScalar h)
{
	const int a = (upAxis + 1) % 3, b = (upAxis + 2) % 3;
	const btScalar radial = btSqrt(p[a] * p[a] + p[b] * p[b]);
	const btScalar dr = btMax(radial - r, btScalar(0)), dh = btMax(btFabs(p[upAxis]) - h, btScalar(0));
	return btSqrt(dr * dr + dh * dh);
}

// Distance from p to the solid cone (apex at +h/2, base radius r at -h/2) along upAxis.
inline btScalar distanceToCone(const btVector3& p, int upAxis, btScalar r, btScalar h)
{
	const int a = (upAxis + 1) % 3, b = (upAxis + 2) % 3;
	// Work in the 2D half plane (radial q >= 0, axial y): the cone is the triangle (0, h/2), (r, -h/2), (0, -h/2).
	const btScalar q = btSqrt(p[a] * p[a] + p[b] * p[b]), y = p[upAxis];
	const btScalar ax = 0, ay = h / 2, bx = r, by = -h / 2;
	// Inside test: below the slant line and above the base.
	const btScalar ex = bx - ax, ey = by - ay;
	const btScalar cross = ex * (y - ay) - ey * (q - ax);  // <= 0 on the inner side of the slant
	if (y >= -h / 2 && cross <= 0) return 0;
	btScalar best = SIMD_INFINITY;
	// Slant segment.
	{
		const btScalar len2 = ex * ex + ey * ey;
		btScalar s = len2 > 0 ? ((q - ax) * ex + (y - ay) * ey) / len2 : 0;
		s = btMax(btScalar(0), btMin(btScalar(1), s));
		const btScalar dx = q - (ax + s * ex), dy = y - (ay + s * ey);
		best = btMin(best, btSqrt(dx * dx + dy * dy));
	}
	// Base segment.
	{
		const btScalar cq = btMin(q, r);
		const btScalar dx = q - cq, dy = y + h / 2;
		best = btMin(best, btSqrt(dx * dx + dy * dy));
	}
	return best;
}

inline std::vector<ShapeCase> makeShapeCases()
{
	std::vector<ShapeCase> cases;
	{
		ShapeCase c;
		c.label = "sphere r=1.5";
		c.shape = std::make_shared<btSphereShape>(btScalar(1.5));
		c.coreSamples = {btVector3(0, 0, 0)};
		c.margin = btScalar(1.5);
		c.samplingError = 0;
		c.distanceToCore = [](const btVector3& p) { return p.length(); };
		cases.push_back(c);
	}
	for (int up = 0; up < 3; ++up)
	{
		const btScalar r = btScalar(0.5), height = btScalar(2);
		ShapeCase c;
		c.label = "capsule up=" + std::to_string(up);
		if (up == 0) c.shape = std::make_shared<btCapsuleShapeX>(r, height);
		if (up == 1) c.shape = std::make_shared<btCapsuleShape>(r, height);
		if (up == 2) c.shape = std::make_shared<btCapsuleShapeZ>(r, height);
		btVector3 end(0, 0, 0);
		end[up] = height / 2;
		c.coreSamples = {end, -end};
		c.margin = r;
		c.samplingError = 0;
		c.distanceToCore = [up, height](const btVector3& p)
		{
			btVector3 q(0, 0, 0);
			q[up] = btMax(-height / 2, btMin(height / 2, p[up]));
			return (p - q).length();
		};
		cases.push_back(c);
	}
	for (int up = 0; up < 3; ++up)
	{
		// Radius 0.8 on the radius axis, half height 1.2; the unused third half extent is 0.8 too.
		btVector3 halfExtents(btScalar(0.8), btScalar(0.8), btScalar(0.8));
		halfExtents[up] = btScalar(1.2);
		ShapeCase c;
		c.label = "cylinder up=" + std::to_string(up);
		if (up == 0) c.shape = std::make_shared<btCylinderShapeX>(halfExtents);
		if (up == 1) c.shape = std::make_shared<btCylinderShape>(halfExtents);
		if (up == 2) c.shape = std::make_shared<btCylinderShapeZ>(halfExtents);
		const btScalar m = CONVEX_DISTANCE_MARGIN;
		const btScalar rc = btScalar(0.8) - m, hc = btScalar(1.2) - m;
		addCircle(c.coreSamples, up, hc, rc);
		addCircle(c.coreSamples, up, -hc, rc);
		c.margin = m;
		c.samplingError = circleSamplingError(rc);
		c.distanceToCore = [up, rc, hc](const btVector3& p) { return distanceToCylinder(p, up, rc, hc); };
		cases.push_back(c);
	}
	for (int up = 0; up < 3; ++up)
	{
		const btScalar r = btScalar(0.7), h = btScalar(1.8);
		ShapeCase c;
		c.label = "cone up=" + std::to_string(up);
		if (up == 0) c.shape = std::make_shared<btConeShapeX>(r, h);
		if (up == 1) c.shape = std::make_shared<btConeShape>(r, h);
		if (up == 2) c.shape = std::make_shared<btConeShapeZ>(r, h);
		btVector3 apex(0, 0, 0);
		apex[up] = h / 2;
		c.coreSamples = {apex};
		addCircle(c.coreSamples, up, -h / 2, r);
		c.margin = CONVEX_DISTANCE_MARGIN;
		c.samplingError = circleSamplingError(r);
		c.distanceToCore = [up, r, h](const btVector3& p) { return distanceToCone(p, up, r, h); };
		cases.push_back(c);
	}
	return cases;
}

inline btScalar bruteForceMax(const std::vector<btVector3>& samples, const btVector3& dir)
{
	btScalar best = -SIMD_INFINITY;
	for (const btVector3& p : samples) best = btMax(best, p.dot(dir));
	return best;
}
}  // namespace shapes_core_test

#endif  // CALIBER_TESTS_SHAPES_CORE_CASES_H
