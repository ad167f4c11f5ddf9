// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "LinearMath/btIDebugDraw.h"

#include "LinearMath/btAlignedObjectArray.h"

// Every default shape is reduced to btIDebugDraw::drawLine here, so a renderer that only draws lines
// sees everything. Curves are sampled at evenly spaced parameters and joined by straight segments;
// the sample points lie exactly on the curve (up to rounding), the segments are chords.

namespace
{
const btScalar kDefaultStepDegrees = btScalar(10);
// The finest sampling allowed: 720 segments per turn is smooth at any size on screen, and it bounds
// the work a tiny or denormal stepDegrees could ask for.
const btScalar kMinStepDegrees = btScalar(0.5);
// Half-size of the patch drawn for an infinite plane, in world units.
const btScalar kPlaneHalfSize = btScalar(100);
// Latitudes this close to a pole draw no ring: all its points coincide with the pole.
const btScalar kPoleEpsilon = btScalar(1e-6);

bool allFinite(btScalar a, btScalar b) { return btIsFinite(a) && btIsFinite(b); }

// Number of segments for a curve spanning spanRadians (any sign) at the requested step.
int segmentCount(btScalar spanRadians, btScalar stepDegrees)
{
	btScalar step = (btIsFinite(stepDegrees) && stepDegrees > btScalar(0)) ? stepDegrees : kDefaultStepDegrees;
	if (step < kMinStepDegrees) step = kMinStepDegrees;
	const btScalar segments = btDegrees(btFabs(spanRadians)) / step;
	// Spans are at most one turn by the time they get here, so this stays below 721 and the
	// conversion is safe. The slack keeps rounding (a quarter turn being 9.000001 steps of 10 degrees)
	// from adding a sliver of a segment.
	const int count = int(ceil(segments - btScalar(1e-3)));
	return count < 1 ? 1 : count;
}

// The point center + vx*cos(angle) + vy*sin(angle).
btVector3 ellipsePoint(const btVector3& center, const btVector3& vx, const btVector3& vy, btScalar angle)
{
	return center + vx * btCos(angle) + vy * btSin(angle);
}

// Draws the arc of center + vx*cos(t) + vy*sin(t) for t in [from, to] with the given number of segments.
void drawEllipticArc(btIDebugDraw& drawer, const btVector3& center, const btVector3& vx, const btVector3& vy,
                     btScalar from, btScalar to, int segments, const btVector3& color)
{
	btVector3 previous = ellipsePoint(center, vx, vy, from);
	for (int i = 1; i <= segments; ++i)
	{
		// The last sample is exactly 'to' (no accumulated stepping error).
		const btScalar angle = (i == segments) ? to : from + (to - from) * (btScalar(i) / btScalar(segments));
		const btVector3 next = ellipsePoint(center, vx, vy, angle);
		drawer.drawLine(previous, next, color);
		previous = next;
	}
}

// A full circle of the given radius around center in the plane spanned by the unit vectors u, v.
void drawCircle(btIDebugDraw& drawer, const btVector3& center, const btVector3& u, const btVector3& v, btScalar radius,
                const btVector3& color)
{
	drawEllipticArc(drawer, center, u * radius, v * radius, btScalar(0), SIMD_2_PI,
	                segmentCount(SIMD_2_PI, kDefaultStepDegrees), color);
}

// Two unit vectors perpendicular to the unit vector n and to each other (u, v, n right-handed).
void perpendicularBasis(const btVector3& n, btVector3& u, btVector3& v)
{
	// Cross with the world axis n is least aligned with: that axis is at most 55 degrees from
	// perpendicular, so the cross product is never short.
	const btScalar ax = btFabs(n.x()), ay = btFabs(n.y()), az = btFabs(n.z());
	btVector3 axis(0, 0, 0);
	if (ax <= ay && ax <= az)
		axis.setX(1);
	else if (ay <= az)
		axis.setY(1);
	else
		axis.setZ(1);
	u = axis.cross(n);
	u /= u.length();
	v = n.cross(u);
}

// The box corner selected by the bits of index (bit k set: max on axis k).
btVector3 boxCorner(const btVector3& bbMin, const btVector3& bbMax, int index)
{
	return btVector3((index & 1) ? bbMax.x() : bbMin.x(), (index & 2) ? bbMax.y() : bbMin.y(),
	                 (index & 4) ? bbMax.z() : bbMin.z());
}

// The 12 box edges join corners that differ in exactly one bit.
void drawBoxEdges(btIDebugDraw& drawer, const btVector3 corners[8], const btVector3& color)
{
	for (int i = 0; i < 8; ++i)
	{
		for (int axis = 0; axis < 3; ++axis)
		{
			const int bit = 1 << axis;
			if (!(i & bit)) drawer.drawLine(corners[i], corners[i | bit], color);
		}
	}
}

// The transform's basis columns for a shape along upAxis: up, then the two others in cyclic order
// (a, b, up) so that, for a rotation, a x b = up.
void shapeAxes(const btTransform& transform, int upAxis, btVector3& up, btVector3& a, btVector3& b)
{
	const btMatrix3x3& basis = transform.getBasis();
	up = basis.getColumn(upAxis);
	a = basis.getColumn((upAxis + 1) % 3);
	b = basis.getColumn((upAxis + 2) % 3);
}

bool validUpAxis(int upAxis) { return upAxis >= 0 && upAxis <= 2; }
}  // namespace

btIDebugDraw::~btIDebugDraw() {}

btIDebugDraw::DefaultColors btIDebugDraw::getDefaultColors() const { return m_defaultColors; }
void btIDebugDraw::setDefaultColors(const DefaultColors& colors) { m_defaultColors = colors; }

void btIDebugDraw::drawLine(const btVector3& from, const btVector3& to, const btVector3& fromColor,
                            const btVector3& toColor)
{
	(void)toColor;
	drawLine(from, to, fromColor);
}

void btIDebugDraw::drawSphere(btScalar radius, const btTransform& transform, const btVector3& color)
{
	const btVector3& center = transform.getOrigin();
	const btMatrix3x3& basis = transform.getBasis();
	radius = btFabs(radius);
	for (int axis = 0; axis < 3; ++axis)
	{
		drawCircle(*this, center, basis.getColumn(axis), basis.getColumn((axis + 1) % 3), radius, color);
	}
}

void btIDebugDraw::drawSphere(const btVector3& p, btScalar radius, const btVector3& color)
{
	btTransform transform;
	transform.setIdentity();
	transform.setOrigin(p);
	drawSphere(radius, transform, color);
}

void btIDebugDraw::drawTriangle(const btVector3& v0, const btVector3& v1, const btVector3& v2, const btVector3& n0,
                                const btVector3& n1, const btVector3& n2, const btVector3& color, btScalar alpha)
{
	(void)n0;
	(void)n1;
	(void)n2;
	drawTriangle(v0, v1, v2, color, alpha);
}

void btIDebugDraw::drawTriangle(const btVector3& v0, const btVector3& v1, const btVector3& v2, const btVector3& color,
                                btScalar alpha)
{
	(void)alpha;
	drawLine(v0, v1, color);
	drawLine(v1, v2, color);
	drawLine(v2, v0, color);
}

void btIDebugDraw::drawAabb(const btVector3& from, const btVector3& to, const btVector3& color)
{
	btVector3 corners[8];
	for (int i = 0; i < 8; ++i) corners[i] = boxCorner(from, to, i);
	drawBoxEdges(*this, corners, color);
}

void btIDebugDraw::drawTransform(const btTransform& transform, btScalar orthoLen)
{
	const btVector3& origin = transform.getOrigin();
	const btMatrix3x3& basis = transform.getBasis();
	drawLine(origin, origin + basis.getColumn(0) * orthoLen, btVector3(1, 0, 0));
	drawLine(origin, origin + basis.getColumn(1) * orthoLen, btVector3(0, 1, 0));
	drawLine(origin, origin + basis.getColumn(2) * orthoLen, btVector3(0, 0, 1));
}

void btIDebugDraw::drawArc(const btVector3& center, const btVector3& normal, const btVector3& axis, btScalar radiusA,
                           btScalar radiusB, btScalar minAngle, btScalar maxAngle, const btVector3& color,
                           bool drawSect, btScalar stepDegrees)
{
	if (!allFinite(minAngle, maxAngle)) return;
	// More than one turn would only retrace the ellipse.
	btScalar to = maxAngle;
	if (to - minAngle > SIMD_2_PI) to = minAngle + SIMD_2_PI;
	if (to - minAngle < -SIMD_2_PI) to = minAngle - SIMD_2_PI;

	const btVector3 vx = axis * radiusA;
	const btVector3 vy = normal.cross(axis) * radiusB;
	drawEllipticArc(*this, center, vx, vy, minAngle, to, segmentCount(to - minAngle, stepDegrees), color);
	if (drawSect)
	{
		drawLine(center, ellipsePoint(center, vx, vy, minAngle), color);
		drawLine(center, ellipsePoint(center, vx, vy, to), color);
	}
}

void btIDebugDraw::drawSpherePatch(const btVector3& center, const btVector3& up, const btVector3& axis, btScalar radius,
                                   btScalar minTh, btScalar maxTh, btScalar minPs, btScalar maxPs,
                                   const btVector3& color, btScalar stepDegrees, bool drawCenter)
{
	if (!allFinite(minTh, maxTh) || !allFinite(minPs, maxPs)) return;
	radius = btFabs(radius);
	btClamp(minTh, -SIMD_HALF_PI, SIMD_HALF_PI);
	btClamp(maxTh, -SIMD_HALF_PI, SIMD_HALF_PI);
	if (minTh > maxTh) btSwap(minTh, maxTh);
	const bool fullTurn = minPs > maxPs || maxPs - minPs >= SIMD_2_PI;
	if (minPs > maxPs)
	{
		minPs = -SIMD_PI;
		maxPs = SIMD_PI;
	}
	else if (fullTurn)
	{
		maxPs = minPs + SIMD_2_PI;
	}

	const int rows = segmentCount(maxTh - minTh, stepDegrees);
	const int columns = segmentCount(maxPs - minPs, stepDegrees);
	// A full turn closes on its first point instead of repeating it.
	const int pointsPerRow = fullTurn ? columns : columns + 1;
	const btVector3 sideways = up.cross(axis);

	btAlignedObjectArray<btVector3> rowStorage[2];
	rowStorage[0].resize(pointsPerRow, btVector3(0, 0, 0));
	rowStorage[1].resize(pointsPerRow, btVector3(0, 0, 0));
	for (int i = 0; i <= rows; ++i)
	{
		btAlignedObjectArray<btVector3>& row = rowStorage[i & 1];
		const btAlignedObjectArray<btVector3>& previousRow = rowStorage[(i + 1) & 1];
		const btScalar th = (i == rows) ? maxTh : minTh + (maxTh - minTh) * (btScalar(i) / btScalar(rows));
		const btScalar ringRadius = radius * btCos(th);
		const btVector3 ringCenter = center + up * (radius * btSin(th));
		for (int j = 0; j < pointsPerRow; ++j)
		{
			const btScalar ps = (j == columns) ? maxPs : minPs + (maxPs - minPs) * (btScalar(j) / btScalar(columns));
			row[j] = ellipsePoint(ringCenter, axis * ringRadius, sideways * ringRadius, ps);
		}

		const bool atPole = btFabs(th) >= SIMD_HALF_PI - kPoleEpsilon;
		if (!atPole)
		{
			for (int j = 0; j + 1 < pointsPerRow; ++j) drawLine(row[j], row[j + 1], color);
			if (fullTurn) drawLine(row[pointsPerRow - 1], row[0], color);
		}
		if (i > 0)
		{
			for (int j = 0; j < pointsPerRow; ++j) drawLine(previousRow[j], row[j], color);
		}
		if (drawCenter)
		{
			// Open edges of the patch: its first and last meridians, and its bottom and top rings
			// unless they are poles.
			if (!fullTurn)
			{
				drawLine(center, row[0], color);
				drawLine(center, row[pointsPerRow - 1], color);
			}
			if ((i == 0 || i == rows) && !atPole)
			{
				for (int j = fullTurn ? 0 : 1; j < (fullTurn ? pointsPerRow : pointsPerRow - 1); ++j)
				{
					drawLine(center, row[j], color);
				}
			}
		}
	}
}

void btIDebugDraw::drawBox(const btVector3& bbMin, const btVector3& bbMax, const btVector3& color)
{
	drawAabb(bbMin, bbMax, color);
}

void btIDebugDraw::drawBox(const btVector3& bbMin, const btVector3& bbMax, const btTransform& trans,
                           const btVector3& color)
{
	btVector3 corners[8];
	for (int i = 0; i < 8; ++i) corners[i] = trans(boxCorner(bbMin, bbMax, i));
	drawBoxEdges(*this, corners, color);
}

void btIDebugDraw::drawCapsule(btScalar radius, btScalar halfHeight, int upAxis, const btTransform& transform,
                               const btVector3& color)
{
	if (!validUpAxis(upAxis)) return;
	radius = btFabs(radius);
	halfHeight = btFabs(halfHeight);
	btVector3 up, a, b;
	shapeAxes(transform, upAxis, up, a, b);
	const int halfTurnSegments = segmentCount(SIMD_PI, kDefaultStepDegrees);
	for (int side = -1; side <= 1; side += 2)
	{
		const btVector3 capCenter = transform.getOrigin() + up * (btScalar(side) * halfHeight);
		const btVector3 outward = up * (btScalar(side) * radius);
		// The equator where the cap meets the side, and two half circles over the pole.
		drawCircle(*this, capCenter, a, b, radius, color);
		drawEllipticArc(*this, capCenter, a * radius, outward, btScalar(0), SIMD_PI, halfTurnSegments, color);
		drawEllipticArc(*this, capCenter, b * radius, outward, btScalar(0), SIMD_PI, halfTurnSegments, color);
	}
	const btVector3 top = transform.getOrigin() + up * halfHeight;
	const btVector3 bottom = transform.getOrigin() - up * halfHeight;
	const btVector3 spokes[4] = {a * radius, b * radius, a * -radius, b * -radius};
	for (const btVector3& spoke : spokes) drawLine(bottom + spoke, top + spoke, color);
}

void btIDebugDraw::drawCylinder(btScalar radius, btScalar halfHeight, int upAxis, const btTransform& transform,
                                const btVector3& color)
{
	if (!validUpAxis(upAxis)) return;
	radius = btFabs(radius);
	halfHeight = btFabs(halfHeight);
	btVector3 up, a, b;
	shapeAxes(transform, upAxis, up, a, b);
	const btVector3 top = transform.getOrigin() + up * halfHeight;
	const btVector3 bottom = transform.getOrigin() - up * halfHeight;
	drawCircle(*this, top, a, b, radius, color);
	drawCircle(*this, bottom, a, b, radius, color);
	const btVector3 spokes[4] = {a * radius, b * radius, a * -radius, b * -radius};
	for (const btVector3& spoke : spokes) drawLine(bottom + spoke, top + spoke, color);
}

void btIDebugDraw::drawCone(btScalar radius, btScalar height, int upAxis, const btTransform& transform,
                            const btVector3& color)
{
	if (!validUpAxis(upAxis)) return;
	radius = btFabs(radius);
	btVector3 up, a, b;
	shapeAxes(transform, upAxis, up, a, b);
	const btVector3 apex = transform.getOrigin() + up * (height * btScalar(0.5));
	const btVector3 baseCenter = transform.getOrigin() - up * (height * btScalar(0.5));
	drawCircle(*this, baseCenter, a, b, radius, color);
	const btVector3 spokes[4] = {a * radius, b * radius, a * -radius, b * -radius};
	for (const btVector3& spoke : spokes) drawLine(apex, baseCenter + spoke, color);
}

void btIDebugDraw::drawPlane(const btVector3& planeNormal, btScalar planeConst, const btTransform& transform,
                             const btVector3& color)
{
	const btScalar normalLength2 = planeNormal.length2();
	if (!(normalLength2 > btScalar(0)) || !btIsFinite(normalLength2) || !btIsFinite(planeConst)) return;
	// The point of the plane closest to the origin; exact for normals of any length.
	const btVector3 planeOrigin = planeNormal * (planeConst / normalLength2);
	btVector3 u, v;
	perpendicularBasis(planeNormal / btSqrt(normalLength2), u, v);
	const btVector3 tips[4] = {planeOrigin + u * kPlaneHalfSize, planeOrigin + v * kPlaneHalfSize,
	                           planeOrigin - u * kPlaneHalfSize, planeOrigin - v * kPlaneHalfSize};
	drawLine(transform(tips[0]), transform(tips[2]), color);
	drawLine(transform(tips[1]), transform(tips[3]), color);
	for (int i = 0; i < 4; ++i) drawLine(transform(tips[i]), transform(tips[(i + 1) % 4]), color);
}
