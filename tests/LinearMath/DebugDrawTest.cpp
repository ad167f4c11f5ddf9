// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "LinearMath/btIDebugDraw.h"

#include <gtest/gtest.h>

#include <set>
#include <utility>
#include <vector>

namespace
{
// Geometric tolerance relative to the size drawn. Each endpoint comes from a handful of sin/cos,
// multiplications by a rotation and additions (a few float ulps each, 1.2e-7 relative), so 1e-5 of
// the size is a wide margin in float and very wide in double.
const btScalar kRelativeTolerance = btScalar(1e-5);

struct Line
{
	btVector3 from, to, color;
};

// Records every line; the other pure virtuals do nothing.
class RecordingDrawer : public btIDebugDraw
{
public:
	using btIDebugDraw::drawLine;  // keep the two-colour overload visible
	void drawLine(const btVector3& from, const btVector3& to, const btVector3& color) override
	{
		lines.push_back(Line{from, to, color});
	}
	void drawContactPoint(const btVector3&, const btVector3&, btScalar, int, const btVector3&) override {}
	void reportErrorWarning(const char*) override {}
	void draw3dText(const btVector3&, const char*) override {}
	void setDebugMode(int debugMode) override { mode = debugMode; }
	int getDebugMode() const override { return mode; }

	// All endpoints, in drawing order.
	std::vector<btVector3> endpoints() const
	{
		std::vector<btVector3> points;
		for (const Line& line : lines)
		{
			points.push_back(line.from);
			points.push_back(line.to);
		}
		return points;
	}

	std::vector<Line> lines;
	int mode = 0;
};

bool isFinite(const btVector3& v) { return btIsFinite(v.x()) && btIsFinite(v.y()) && btIsFinite(v.z()); }

void expectAllFinite(const RecordingDrawer& drawer)
{
	for (const btVector3& p : drawer.endpoints()) EXPECT_TRUE(isFinite(p)) << p.x() << " " << p.y() << " " << p.z();
}

// A rotated and moved frame, so that shapes are not tested only in the world axes.
btTransform testTransform()
{
	btMatrix3x3 basis;
	basis.setEulerZYX(btScalar(0.3), btScalar(-0.7), btScalar(1.1));
	return btTransform(basis, btVector3(btScalar(1.5), btScalar(-2), btScalar(0.25)));
}

btVector3 component(const btVector3& v, int axis)
{
	btVector3 out(0, 0, 0);
	out[axis] = v[axis];
	return out;
}
}  // namespace

TEST(DebugDrawTest, ModeBitsAndDefaultColoursMatchTheBulletApi)
{
	static_assert(btIDebugDraw::DBG_NoDebug == 0 && btIDebugDraw::DBG_DrawWireframe == 1, "mode bits");
	static_assert(btIDebugDraw::DBG_DrawAabb == 2 && btIDebugDraw::DBG_DrawFeaturesText == 4, "mode bits");
	static_assert(btIDebugDraw::DBG_DrawContactPoints == 8 && btIDebugDraw::DBG_NoDeactivation == 16, "mode bits");
	static_assert(btIDebugDraw::DBG_NoHelpText == 32 && btIDebugDraw::DBG_DrawText == 64, "mode bits");
	static_assert(btIDebugDraw::DBG_ProfileTimings == 128 && btIDebugDraw::DBG_EnableSatComparison == 256, "bits");
	static_assert(btIDebugDraw::DBG_DisableBulletLCP == 512 && btIDebugDraw::DBG_EnableCCD == 1024, "mode bits");
	static_assert(btIDebugDraw::DBG_DrawConstraints == 2048 && btIDebugDraw::DBG_DrawConstraintLimits == 4096, "bits");
	static_assert(btIDebugDraw::DBG_FastWireframe == 8192 && btIDebugDraw::DBG_DrawNormals == 16384, "mode bits");
	static_assert(btIDebugDraw::DBG_DrawFrames == 32768 && btIDebugDraw::DBG_MAX_DEBUG_DRAW_MODE == 32769, "bits");

	RecordingDrawer drawer;
	const btIDebugDraw::DefaultColors defaults = drawer.getDefaultColors();
	EXPECT_EQ(defaults.m_activeObject, btVector3(1, 1, 1));
	EXPECT_EQ(defaults.m_deactivatedObject, btVector3(0, 1, 0));
	EXPECT_EQ(defaults.m_aabb, btVector3(1, 0, 0));

	btIDebugDraw::DefaultColors custom;
	custom.m_aabb = btVector3(0, 0, 1);
	custom.m_contactPoint = btVector3(btScalar(0.5), 0, 0);
	drawer.setDefaultColors(custom);
	EXPECT_EQ(drawer.getDefaultColors().m_aabb, btVector3(0, 0, 1));
	EXPECT_EQ(drawer.getDefaultColors().m_contactPoint, btVector3(btScalar(0.5), 0, 0));

	drawer.setDebugMode(btIDebugDraw::DBG_DrawWireframe | btIDebugDraw::DBG_DrawAabb);
	EXPECT_EQ(drawer.getDebugMode(), 3);
	drawer.clearLines();
	drawer.flushLines();
	EXPECT_TRUE(drawer.lines.empty());
}

TEST(DebugDrawTest, TwoColourLineAndTrianglesReduceToLines)
{
	RecordingDrawer drawer;
	const btVector3 red(1, 0, 0), blue(0, 0, 1);
	drawer.drawLine(btVector3(0, 0, 0), btVector3(1, 2, 3), red, blue);
	ASSERT_EQ(drawer.lines.size(), 1u);
	EXPECT_EQ(drawer.lines[0].color, red);

	drawer.lines.clear();
	const btVector3 v0(0, 0, 0), v1(1, 0, 0), v2(0, 1, 0), n(0, 0, 1);
	drawer.drawTriangle(v0, v1, v2, n, n, n, blue, btScalar(0.5));
	drawer.drawTriangle(v0, v1, v2, blue, btScalar(1));
	ASSERT_EQ(drawer.lines.size(), 6u);
	for (int t = 0; t < 2; ++t)
	{
		EXPECT_EQ(drawer.lines[3 * t + 0].from, v0);
		EXPECT_EQ(drawer.lines[3 * t + 0].to, v1);
		EXPECT_EQ(drawer.lines[3 * t + 1].to, v2);
		EXPECT_EQ(drawer.lines[3 * t + 2].to, v0);
	}
}

TEST(DebugDrawTest, SphereEndpointsLieAtTheRadius)
{
	const btScalar radius = btScalar(2.5);
	RecordingDrawer drawer;
	const btTransform transform = testTransform();
	drawer.drawSphere(radius, transform, btVector3(1, 1, 1));
	ASSERT_GE(drawer.lines.size(), 3u * 8u);
	for (const btVector3& p : drawer.endpoints())
	{
		EXPECT_NEAR(p.distance(transform.getOrigin()), radius, kRelativeTolerance * radius);
	}

	drawer.lines.clear();
	const btVector3 center(-3, 4, btScalar(0.5));
	drawer.drawSphere(center, radius, btVector3(1, 1, 1));
	ASSERT_GE(drawer.lines.size(), 3u * 8u);
	for (const btVector3& p : drawer.endpoints()) EXPECT_NEAR(p.distance(center), radius, kRelativeTolerance * radius);
}

TEST(DebugDrawTest, AabbAndBoxDrawTwelveEdgesJoiningTheEightCorners)
{
	const btVector3 bbMin(-1, 2, btScalar(-0.5)), bbMax(3, btScalar(2.5), 4);
	for (int variant = 0; variant < 2; ++variant)
	{
		RecordingDrawer drawer;
		if (variant == 0)
			drawer.drawAabb(bbMin, bbMax, btVector3(1, 0, 0));
		else
			drawer.drawBox(bbMin, bbMax, btVector3(1, 0, 0));
		ASSERT_EQ(drawer.lines.size(), 12u);
		std::set<std::pair<int, int>> edges;
		std::set<int> cornersSeen;
		for (const Line& line : drawer.lines)
		{
			// Identify each endpoint as a corner: bit k set when it is at the max on axis k.
			int ids[2];
			const btVector3 ends[2] = {line.from, line.to};
			for (int e = 0; e < 2; ++e)
			{
				ids[e] = 0;
				for (int axis = 0; axis < 3; ++axis)
				{
					const bool atMin = ends[e][axis] == bbMin[axis];
					const bool atMax = ends[e][axis] == bbMax[axis];
					ASSERT_TRUE(atMin || atMax) << "endpoint not on a corner";
					if (atMax) ids[e] |= 1 << axis;
				}
				cornersSeen.insert(ids[e]);
			}
			const int differing = ids[0] ^ ids[1];
			EXPECT_TRUE(differing == 1 || differing == 2 || differing == 4) << "not a box edge";
			edges.insert(std::make_pair(std::min(ids[0], ids[1]), std::max(ids[0], ids[1])));
		}
		EXPECT_EQ(edges.size(), 12u);
		EXPECT_EQ(cornersSeen.size(), 8u);
	}
}

TEST(DebugDrawTest, TransformedBoxEdgesKeepTheBoxExtents)
{
	const btVector3 bbMin(-1, -2, -3), bbMax(1, 2, 3);
	const btTransform transform = testTransform();
	RecordingDrawer drawer;
	drawer.drawBox(bbMin, bbMax, transform, btVector3(0, 1, 0));
	ASSERT_EQ(drawer.lines.size(), 12u);
	int perAxis[3] = {0, 0, 0};
	for (const Line& line : drawer.lines)
	{
		const btVector3 a = transform.invXform(line.from), b = transform.invXform(line.to);
		// In the box's frame every edge is parallel to one axis and as long as the box on that axis.
		const btVector3 d = (b - a).absolute();
		const int axis = d.maxAxis();
		++perAxis[axis];
		EXPECT_NEAR(d[axis], bbMax[axis] - bbMin[axis], kRelativeTolerance * 10);
		EXPECT_NEAR(d[(axis + 1) % 3] + d[(axis + 2) % 3], 0, kRelativeTolerance * 10);
	}
	EXPECT_EQ(perAxis[0], 4);
	EXPECT_EQ(perAxis[1], 4);
	EXPECT_EQ(perAxis[2], 4);
}

TEST(DebugDrawTest, TransformDrawsThreeBasisAxesOfOrthoLen)
{
	const btTransform transform = testTransform();
	const btScalar orthoLen = btScalar(0.75);
	RecordingDrawer drawer;
	drawer.drawTransform(transform, orthoLen);
	ASSERT_EQ(drawer.lines.size(), 3u);
	for (int axis = 0; axis < 3; ++axis)
	{
		const Line& line = drawer.lines[size_t(axis)];
		EXPECT_EQ(line.from, transform.getOrigin());
		EXPECT_NEAR(line.from.distance(line.to), orthoLen, kRelativeTolerance);
		const btVector3 direction = (line.to - line.from) / orthoLen;
		EXPECT_NEAR(direction.dot(transform.getBasis().getColumn(axis)), btScalar(1), kRelativeTolerance);
		EXPECT_EQ(line.color[axis], btScalar(1));  // x red, y green, z blue
	}
}

TEST(DebugDrawTest, ArcPointsLieOnTheEllipseWithinTheAngleRange)
{
	const btVector3 center(1, 2, 3);
	const btVector3 normal = btVector3(1, 1, 0).normalized();
	const btVector3 axis = btVector3(1, -1, 1).normalized().cross(normal).normalized();
	const btVector3 sideways = normal.cross(axis);
	const btScalar radiusA = 2, radiusB = btScalar(0.5);
	const btScalar minAngle = btScalar(-0.5), maxAngle = btScalar(1.8);
	RecordingDrawer drawer;
	drawer.drawArc(center, normal, axis, radiusA, radiusB, minAngle, maxAngle, btVector3(1, 1, 0), false);
	ASSERT_EQ(drawer.lines.size(), size_t(ceil(btDegrees(maxAngle - minAngle) / 10)));
	for (size_t i = 0; i < drawer.lines.size(); ++i)
	{
		if (i > 0)
		{
			EXPECT_EQ(drawer.lines[i].from, drawer.lines[i - 1].to) << "arc segments are joined";
		}
	}
	for (const btVector3& p : drawer.endpoints())
	{
		const btVector3 local = p - center;
		EXPECT_NEAR(local.dot(normal), 0, kRelativeTolerance * radiusA);
		const btScalar x = local.dot(axis) / radiusA, y = local.dot(sideways) / radiusB;
		EXPECT_NEAR(x * x + y * y, btScalar(1), kRelativeTolerance * 10);
		const btScalar angle = btAtan2(y, x);
		EXPECT_GE(angle, minAngle - kRelativeTolerance);
		EXPECT_LE(angle, maxAngle + kRelativeTolerance);
	}
	const btVector3 first = drawer.lines.front().from - center, last = drawer.lines.back().to - center;
	EXPECT_NEAR(btAtan2(first.dot(sideways) / radiusB, first.dot(axis) / radiusA), minAngle, kRelativeTolerance);
	EXPECT_NEAR(btAtan2(last.dot(sideways) / radiusB, last.dot(axis) / radiusA), maxAngle, kRelativeTolerance);

	// A circular arc with its sector lines: those start at the centre and end on the arc's ends.
	drawer.lines.clear();
	drawer.drawArc(center, normal, axis, 1, 1, 0, SIMD_HALF_PI, btVector3(1, 1, 0), true, 15);
	ASSERT_EQ(drawer.lines.size(), 6u + 2u);
	const Line& sectStart = drawer.lines[6];
	const Line& sectEnd = drawer.lines[7];
	EXPECT_EQ(sectStart.from, center);
	EXPECT_EQ(sectEnd.from, center);
	EXPECT_NEAR(sectStart.to.distance(center + axis), 0, kRelativeTolerance);
	EXPECT_NEAR(sectEnd.to.distance(center + sideways), 0, kRelativeTolerance);
}

TEST(DebugDrawTest, ArcStepIsSanitisedAndNeverLoopsForever)
{
	const btVector3 center(0, 0, 0), normal(0, 0, 1), axis(1, 0, 0), color(1, 1, 1);
	struct Case
	{
		btScalar stepDegrees;
		size_t expectedSegments;
	};
	// A quarter turn: 10 degree steps give 9 segments; 0, negative and NaN steps mean 10 degrees;
	// steps below half a degree are raised to it (180 segments).
	const Case cases[] = {{10, 9}, {0, 9},   {-5, 9}, {BT_NAN, 9}, {BT_INFINITY, 9}, {btScalar(1e-30), 180},
	                      {45, 2}, {1000, 1}};
	for (const Case& c : cases)
	{
		RecordingDrawer drawer;
		drawer.drawArc(center, normal, axis, 1, 1, 0, SIMD_HALF_PI, color, false, c.stepDegrees);
		EXPECT_EQ(drawer.lines.size(), c.expectedSegments) << "step " << c.stepDegrees;
		expectAllFinite(drawer);
	}

	// More than a turn is drawn as one turn; a reversed range runs backwards; an empty one is a point.
	RecordingDrawer drawer;
	drawer.drawArc(center, normal, axis, 1, 1, 0, btScalar(1e6), color, false);
	EXPECT_EQ(drawer.lines.size(), 36u);
	drawer.lines.clear();
	drawer.drawArc(center, normal, axis, 1, 1, SIMD_HALF_PI, 0, color, false);
	EXPECT_EQ(drawer.lines.size(), 9u);
	drawer.lines.clear();
	drawer.drawArc(center, normal, axis, 1, 1, 1, 1, color, true);
	EXPECT_EQ(drawer.lines.size(), 3u);
	expectAllFinite(drawer);

	// Non-finite angles draw nothing.
	drawer.lines.clear();
	drawer.drawArc(center, normal, axis, 1, 1, BT_NAN, 1, color, true);
	drawer.drawArc(center, normal, axis, 1, 1, 0, BT_INFINITY, color, true);
	EXPECT_TRUE(drawer.lines.empty());
}

TEST(DebugDrawTest, SpherePatchPointsLieOnTheSphereWithinTheRanges)
{
	const btVector3 center(btScalar(0.5), -1, 2);
	const btVector3 up(0, 0, 1), axis(1, 0, 0), sideways = up.cross(axis);
	const btScalar radius = 3;
	const btScalar minTh = btScalar(-0.4), maxTh = btScalar(0.9), minPs = btScalar(-1), maxPs = btScalar(2);
	RecordingDrawer drawer;
	drawer.drawSpherePatch(center, up, axis, radius, minTh, maxTh, minPs, maxPs, btVector3(1, 0, 1));
	ASSERT_FALSE(drawer.lines.empty());
	int centreLines = 0;
	for (const Line& line : drawer.lines)
	{
		const btVector3 ends[2] = {line.from, line.to};
		for (const btVector3& p : ends)
		{
			if (p == center)
			{
				++centreLines;
				continue;
			}
			const btVector3 local = p - center;
			EXPECT_NEAR(local.length(), radius, kRelativeTolerance * radius);
			const btScalar latitude = btAsin(local.dot(up) / local.length());
			const btScalar longitude = btAtan2(local.dot(sideways), local.dot(axis));
			EXPECT_GE(latitude, minTh - kRelativeTolerance * 10);
			EXPECT_LE(latitude, maxTh + kRelativeTolerance * 10);
			EXPECT_GE(longitude, minPs - kRelativeTolerance * 10);
			EXPECT_LE(longitude, maxPs + kRelativeTolerance * 10);
		}
	}
	EXPECT_GT(centreLines, 0);  // drawCenter defaults to true

	// Without the centre lines, and for the whole sphere, every endpoint is on the sphere.
	drawer.lines.clear();
	drawer.drawSpherePatch(center, up, axis, radius, -SIMD_HALF_PI, SIMD_HALF_PI, 1, -1, btVector3(1, 0, 1), 30, false);
	drawer.drawSpherePatch(center, up, axis, radius, -SIMD_HALF_PI, SIMD_HALF_PI, 0, SIMD_2_PI, btVector3(1, 0, 1), 30,
	                       true);
	ASSERT_FALSE(drawer.lines.empty());
	for (const btVector3& p : drawer.endpoints())
	{
		EXPECT_NEAR(p.distance(center), radius, kRelativeTolerance * radius);
	}
}

TEST(DebugDrawTest, SpherePatchWithTinyOrInvalidStepsStaysBounded)
{
	const btVector3 center(0, 0, 0), up(0, 1, 0), axis(1, 0, 0), color(1, 1, 1);
	const btScalar steps[] = {0, -1, BT_NAN, btScalar(1e-20)};
	for (btScalar step : steps)
	{
		RecordingDrawer drawer;
		drawer.drawSpherePatch(center, up, axis, 1, -SIMD_HALF_PI, SIMD_HALF_PI, -SIMD_PI, SIMD_PI, color, step);
		// At the finest (half-degree) sampling a full sphere is 360 rings of 720 points: each point
		// has at most one ring line and one meridian line.
		EXPECT_LE(drawer.lines.size(), size_t(361 * 720 * 2)) << "step " << step;
		EXPECT_GT(drawer.lines.size(), 0u);
		expectAllFinite(drawer);
	}
	RecordingDrawer drawer;
	drawer.drawSpherePatch(center, up, axis, 1, BT_NAN, 1, 0, 1, color);
	drawer.drawSpherePatch(center, up, axis, 1, 0, 1, 0, BT_INFINITY, color);
	EXPECT_TRUE(drawer.lines.empty());
}

TEST(DebugDrawTest, CapsuleEndpointsLieOnItsSurface)
{
	const btTransform transform = testTransform();
	const btScalar radius = btScalar(0.75), halfHeight = btScalar(1.25);
	for (int upAxis = 0; upAxis < 3; ++upAxis)
	{
		RecordingDrawer drawer;
		drawer.drawCapsule(radius, halfHeight, upAxis, transform, btVector3(1, 1, 1));
		ASSERT_FALSE(drawer.lines.empty());
		bool reachesTip = false;
		for (const btVector3& p : drawer.endpoints())
		{
			// Distance from the capsule's core segment is the radius.
			const btVector3 local = transform.invXform(p);
			btScalar axial = local[upAxis];
			btClamp(axial, -halfHeight, halfHeight);
			btVector3 core(0, 0, 0);
			core[upAxis] = axial;
			EXPECT_NEAR(local.distance(core), radius, kRelativeTolerance * 4) << "upAxis " << upAxis;
			if (btFabs(local[upAxis]) > halfHeight + radius * btScalar(0.99)) reachesTip = true;
		}
		EXPECT_TRUE(reachesTip) << "the caps go over the poles";
	}
}

TEST(DebugDrawTest, CylinderEndpointsLieOnItsRims)
{
	const btTransform transform = testTransform();
	const btScalar radius = 2, halfHeight = btScalar(0.5);
	for (int upAxis = 0; upAxis < 3; ++upAxis)
	{
		RecordingDrawer drawer;
		drawer.drawCylinder(radius, halfHeight, upAxis, transform, btVector3(1, 1, 1));
		ASSERT_FALSE(drawer.lines.empty());
		for (const btVector3& p : drawer.endpoints())
		{
			const btVector3 local = transform.invXform(p);
			EXPECT_NEAR(btFabs(local[upAxis]), halfHeight, kRelativeTolerance * 4) << "upAxis " << upAxis;
			EXPECT_NEAR((local - component(local, upAxis)).length(), radius, kRelativeTolerance * 4);
		}
	}
}

TEST(DebugDrawTest, ConeEndpointsLieOnItsSurface)
{
	const btTransform transform = testTransform();
	const btScalar radius = btScalar(1.5), height = 3;
	for (int upAxis = 0; upAxis < 3; ++upAxis)
	{
		RecordingDrawer drawer;
		drawer.drawCone(radius, height, upAxis, transform, btVector3(1, 1, 1));
		ASSERT_FALSE(drawer.lines.empty());
		int apexCount = 0;
		for (const btVector3& p : drawer.endpoints())
		{
			const btVector3 local = transform.invXform(p);
			const btScalar axial = local[upAxis];
			EXPECT_GE(axial, -height / 2 - kRelativeTolerance * 4);
			EXPECT_LE(axial, height / 2 + kRelativeTolerance * 4);
			// The surface narrows linearly from the base radius at -height/2 to the apex at +height/2.
			const btScalar expectedRadius = radius * (height / 2 - axial) / height;
			EXPECT_NEAR((local - component(local, upAxis)).length(), expectedRadius, kRelativeTolerance * 4);
			if (btFabs(axial - height / 2) < kRelativeTolerance * 4) ++apexCount;
		}
		EXPECT_EQ(apexCount, 4);
	}
}

TEST(DebugDrawTest, PlaneLinesLieInThePlane)
{
	const btTransform transform = testTransform();
	const btVector3 normals[] = {btVector3(0, 1, 0), btVector3(1, 2, -2), btVector3(0, 0, -1),
	                             btVector3(btScalar(1e-3), 0, 0)};
	const btScalar planeConst = btScalar(1.5);
	for (const btVector3& normal : normals)
	{
		RecordingDrawer drawer;
		drawer.drawPlane(normal, planeConst, transform, btVector3(1, 1, 1));
		ASSERT_EQ(drawer.lines.size(), 6u);
		const btVector3 unit = normal.normalized();
		for (const btVector3& p : drawer.endpoints())
		{
			const btVector3 local = transform.invXform(p);
			// n.x = planeConst, measured as a distance along the unit normal. The endpoints are 100
			// units from the plane's centre, so the tolerance scales with that.
			EXPECT_NEAR(local.dot(unit), planeConst / normal.length(), kRelativeTolerance * 100);
		}
	}
	RecordingDrawer drawer;
	drawer.drawPlane(btVector3(0, 0, 0), 1, transform, btVector3(1, 1, 1));
	drawer.drawPlane(btVector3(BT_NAN, 0, 1), 1, transform, btVector3(1, 1, 1));
	EXPECT_TRUE(drawer.lines.empty()) << "a zero or NaN normal draws nothing";
}

TEST(DebugDrawTest, DegenerateSizesDrawFiniteLinesAndBadAxesDrawNothing)
{
	const btTransform transform = testTransform();
	RecordingDrawer drawer;
	drawer.drawSphere(0, transform, btVector3(1, 1, 1));
	drawer.drawCapsule(0, 0, 1, transform, btVector3(1, 1, 1));
	drawer.drawCylinder(0, 0, 2, transform, btVector3(1, 1, 1));
	drawer.drawCone(0, 0, 0, transform, btVector3(1, 1, 1));
	drawer.drawBox(btVector3(1, 1, 1), btVector3(1, 1, 1), btVector3(1, 1, 1));
	drawer.drawSpherePatch(btVector3(0, 0, 0), btVector3(0, 0, 0), btVector3(0, 0, 0), 0, -1, 1, -1, 1,
	                       btVector3(1, 1, 1));
	drawer.drawArc(btVector3(0, 0, 0), btVector3(0, 0, 0), btVector3(0, 0, 0), 0, 0, 0, 1, btVector3(1, 1, 1), true);
	EXPECT_FALSE(drawer.lines.empty());
	expectAllFinite(drawer);
	// Zero sizes collapse onto the shape's centre.
	for (int i = 0; i < 3 * 36; ++i)
	{
		EXPECT_EQ(drawer.lines[size_t(i)].from, transform.getOrigin());
	}

	// Negative radii and half heights draw the same capsule as their magnitudes.
	RecordingDrawer positive, negative;
	positive.drawCapsule(1, 2, 1, transform, btVector3(1, 1, 1));
	negative.drawCapsule(-1, -2, 1, transform, btVector3(1, 1, 1));
	ASSERT_EQ(positive.lines.size(), negative.lines.size());
	for (size_t i = 0; i < positive.lines.size(); ++i) EXPECT_EQ(positive.lines[i].from, negative.lines[i].from);

	RecordingDrawer nothing;
	nothing.drawCapsule(1, 1, 3, transform, btVector3(1, 1, 1));
	nothing.drawCylinder(1, 1, -1, transform, btVector3(1, 1, 1));
	nothing.drawCone(1, 1, 7, transform, btVector3(1, 1, 1));
	EXPECT_TRUE(nothing.lines.empty());
}
