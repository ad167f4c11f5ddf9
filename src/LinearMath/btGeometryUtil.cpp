// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "LinearMath/btGeometryUtil.h"

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

// Both conversions are brute force over triples (vertices -> planes is O(n^3 * n), planes ->
// vertices O(p^3 * p)); they run once when a shape is built, on tens of points. The arithmetic is
// done in double whatever btScalar is: float inputs are exact in double, so a float build's results
// are rounded only once, on output, and the tolerances below do not have to cover float arithmetic.

namespace
{
struct Vec3d
{
	double x, y, z;
};

inline Vec3d toDouble(const btVector3& v) { return Vec3d{double(v[0]), double(v[1]), double(v[2])}; }
inline Vec3d operator-(const Vec3d& a, const Vec3d& b) { return Vec3d{a.x - b.x, a.y - b.y, a.z - b.z}; }
inline Vec3d operator+(const Vec3d& a, const Vec3d& b) { return Vec3d{a.x + b.x, a.y + b.y, a.z + b.z}; }
inline Vec3d operator*(const Vec3d& a, double s) { return Vec3d{a.x * s, a.y * s, a.z * s}; }
inline double dot(const Vec3d& a, const Vec3d& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline Vec3d cross(const Vec3d& a, const Vec3d& b)
{
	return Vec3d{a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
inline double length(const Vec3d& a) { return std::sqrt(dot(a, a)); }

struct Plane
{
	Vec3d normal;
	double offset;
};

// Distances below this fraction of the problem's size count as zero: points that close to a plane
// lie on it. It is far above double rounding (1e-16) and above float input noise (about 1e-7), so
// faces of float meshes that are flat only up to rounding still come out as one face.
const double kRelativeTolerance = 1e-5;

// Three planes whose unit normals span less volume than this are treated as meeting in no single
// point. Solving in double, the corner's error is about 1e-16 / kMinTripleProduct of the problem's
// size, well inside kRelativeTolerance.
const double kMinTripleProduct = 1e-6;

// Two planes touching the same points can only be one face if their normals are this close; it
// keeps a sliver of nearly collinear points from merging faces that meet at a real angle.
const double kSameFaceCosine = 0.99;

// A point where three planes meet, with how well they pin it down (|det| of their unit normals).
struct CornerCandidate
{
	Vec3d corner;
	double conditioning;
	double tolerance;
	int planes[3];
};

// A face plane of the hull and the points lying on it (within tolerance).
struct Face
{
	Plane plane;
	std::vector<char> touches;
};

// True when every point touched by a is also touched by b.
bool touchesSubset(const std::vector<char>& a, const std::vector<char>& b)
{
	for (size_t i = 0; i < a.size(); ++i)
	{
		if (a[i] && !b[i]) return false;
	}
	return true;
}

// Adds a supporting plane as a face unless a known face already touches all its points. Points that
// are coplanar only within the tolerance produce several slightly different planes; keeping just the
// one that touches most of them avoids faces meeting at a crease too shallow to resolve, which
// would otherwise give spurious corners when converting back to vertices.
void addFace(const Plane& candidate, std::vector<Face>& faces, const std::vector<Vec3d>& points, double tolerance)
{
	Face face{candidate, std::vector<char>(points.size())};
	for (size_t i = 0; i < points.size(); ++i)
	{
		face.touches[i] = std::fabs(dot(candidate.normal, points[i]) + candidate.offset) <= tolerance;
	}
	for (const Face& known : faces)
	{
		if (dot(known.plane.normal, candidate.normal) >= kSameFaceCosine && touchesSubset(face.touches, known.touches))
		{
			return;
		}
	}
	size_t kept = 0;
	for (size_t i = 0; i < faces.size(); ++i)
	{
		const bool covered = dot(faces[i].plane.normal, candidate.normal) >= kSameFaceCosine &&
		                     touchesSubset(faces[i].touches, face.touches);
		if (!covered)
		{
			if (kept != i) faces[kept] = std::move(faces[i]);
			++kept;
		}
	}
	faces.resize(kept);
	faces.push_back(std::move(face));
}
}  // namespace

void btGeometryUtil::getPlaneEquationsFromVertices(btAlignedObjectArray<btVector3>& vertices,
                                                   btAlignedObjectArray<btVector3>& planeEquationsOut)
{
	const int count = vertices.size();
	if (count < 3) return;

	std::vector<Vec3d> points(static_cast<size_t>(count));
	Vec3d lo = toDouble(vertices[0]);
	Vec3d hi = lo;
	for (int i = 0; i < count; ++i)
	{
		const Vec3d p = toDouble(vertices[i]);
		if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) return;  // no hull to speak of
		points[static_cast<size_t>(i)] = p;
		lo = Vec3d{std::fmin(lo.x, p.x), std::fmin(lo.y, p.y), std::fmin(lo.z, p.z)};
		hi = Vec3d{std::fmax(hi.x, p.x), std::fmax(hi.y, p.y), std::fmax(hi.z, p.z)};
	}
	const double size = length(hi - lo);
	if (!(size > 0.0)) return;  // one repeated point
	const double tolerance = kRelativeTolerance * size;
	// Twice the triangle's area; thinner triangles give a normal too unreliable to try.
	const double minCrossLength = tolerance * size;

	std::vector<Face> faces;
	for (int i = 0; i < count; ++i)
	{
		const Vec3d& a = points[static_cast<size_t>(i)];
		for (int j = i + 1; j < count; ++j)
		{
			for (int k = j + 1; k < count; ++k)
			{
				const Vec3d c = cross(points[static_cast<size_t>(j)] - a, points[static_cast<size_t>(k)] - a);
				const double crossLength = length(c);
				if (!(crossLength > minCrossLength)) continue;
				const Vec3d normal = c * (1.0 / crossLength);

				// Signed distances of all points from the triangle's plane: the plane (or its flip)
				// is a face when no point lies beyond it by more than the tolerance.
				double above = 0.0, below = 0.0;
				for (const Vec3d& p : points)
				{
					const double s = dot(normal, p - a);
					if (s > above) above = s;
					if (s < below) below = s;
					if (above > tolerance && below < -tolerance) break;
				}
				// Each face plane is moved out to its outermost point, so every input vertex is
				// inside it exactly (before the output is rounded to btScalar).
				const double base = dot(normal, a);
				if (above <= tolerance) addFace(Plane{normal, -(base + above)}, faces, points, tolerance);
				if (below >= -tolerance)
				{
					addFace(Plane{normal * -1.0, base + below}, faces, points, tolerance);
				}
			}
		}
	}

	for (const Face& face : faces)
	{
		const Plane& p = face.plane;
		btVector3 plane(btScalar(p.normal.x), btScalar(p.normal.y), btScalar(p.normal.z));
		plane.setW(btScalar(p.offset));
		planeEquationsOut.push_back(plane);
	}
}

void btGeometryUtil::getVerticesFromPlaneEquations(const btAlignedObjectArray<btVector3>& planeEquations,
                                                   btAlignedObjectArray<btVector3>& verticesOut)
{
	const int count = planeEquations.size();
	if (count < 3) return;

	std::vector<Plane> planes(static_cast<size_t>(count));
	std::vector<double> normalLengths(static_cast<size_t>(count));
	double size = 0.0;  // the largest offset: the distance scale the planes were written at
	for (int i = 0; i < count; ++i)
	{
		const btVector3& source = planeEquations[i];
		Plane& plane = planes[static_cast<size_t>(i)];
		plane.normal = toDouble(source);
		plane.offset = double(source[3]);
		normalLengths[static_cast<size_t>(i)] = length(plane.normal);
		size = std::fmax(size, std::fabs(plane.offset));
	}

	// Every triple of planes meeting in a point inside all the others gives a candidate corner.
	std::vector<CornerCandidate> candidates;
	for (int i = 0; i < count; ++i)
	{
		const Plane& a = planes[size_t(i)];
		for (int j = i + 1; j < count; ++j)
		{
			const Plane& b = planes[size_t(j)];
			for (int k = j + 1; k < count; ++k)
			{
				const Plane& c = planes[size_t(k)];
				const Vec3d bc = cross(b.normal, c.normal);
				const double det = dot(a.normal, bc);
				const double lengths = normalLengths[size_t(i)] * normalLengths[size_t(j)] * normalLengths[size_t(k)];
				if (!(std::fabs(det) > kMinTripleProduct * lengths)) continue;  // also skips zero normals
				const double conditioning = std::fabs(det) / lengths;

				// Cramer's rule for n_a.x = -d_a, n_b.x = -d_b, n_c.x = -d_c.
				const Vec3d corner =
				    (bc * -a.offset + cross(c.normal, a.normal) * -b.offset + cross(a.normal, b.normal) * -c.offset) *
				    (1.0 / det);
				const double tolerance = kRelativeTolerance * std::fmax(size, length(corner));

				bool inside = true;
				for (int m = 0; m < count && inside; ++m)
				{
					const Plane& p = planes[size_t(m)];
					inside = dot(p.normal, corner) + p.offset <= tolerance * normalLengths[size_t(m)];
				}
				if (inside) candidates.push_back(CornerCandidate{corner, conditioning, tolerance, {i, j, k}});
			}
		}
	}

	// Corners where more than three planes meet are found once per triple; keep one. Where planes
	// meet at a shallow angle, the rounding of their coefficients moves that triple's solution
	// further than the tolerance. So the best conditioned triples go first, and a later candidate
	// is the same corner when a kept one lies on all three of its planes (a residual test, which is
	// well conditioned) or within the tolerance of it.
	std::stable_sort(candidates.begin(), candidates.end(),
	                 [](const CornerCandidate& x, const CornerCandidate& y)
	                 { return x.conditioning > y.conditioning; });
	std::vector<Vec3d> corners;
	for (const CornerCandidate& candidate : candidates)
	{
		bool known = false;
		for (const Vec3d& existing : corners)
		{
			known = length(existing - candidate.corner) <= candidate.tolerance;
			if (!known)
			{
				known = true;
				for (int t = 0; t < 3 && known; ++t)
				{
					const size_t q = size_t(candidate.planes[t]);
					known = std::fabs(dot(planes[q].normal, existing) + planes[q].offset) <=
					        candidate.tolerance * normalLengths[q];
				}
			}
			if (known) break;
		}
		if (!known) corners.push_back(candidate.corner);
	}

	for (const Vec3d& corner : corners)
	{
		verticesOut.push_back(btVector3(btScalar(corner.x), btScalar(corner.y), btScalar(corner.z)));
	}
}

bool btGeometryUtil::isInside(const btAlignedObjectArray<btVector3>& vertices, const btVector3& planeNormal,
                              btScalar margin)
{
	return areVerticesBehindPlane(planeNormal, vertices, margin);
}

bool btGeometryUtil::isPointInsidePlanes(const btAlignedObjectArray<btVector3>& planeEquations, const btVector3& point,
                                         btScalar margin)
{
	for (int i = 0; i < planeEquations.size(); ++i)
	{
		const btVector3& plane = planeEquations[i];
		// Written as !(<=) so that a NaN distance counts as outside.
		if (!(plane.dot(point) + plane[3] <= margin)) return false;
	}
	return true;
}

bool btGeometryUtil::areVerticesBehindPlane(const btVector3& planeNormal,
                                            const btAlignedObjectArray<btVector3>& vertices, btScalar margin)
{
	for (int i = 0; i < vertices.size(); ++i)
	{
		if (!(planeNormal.dot(vertices[i]) + planeNormal[3] <= margin)) return false;
	}
	return true;
}
