// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// Internal to the convex decomposition: a piece of a solid as an oriented triangle soup, and its split by
// a plane. Not installed; no public header includes it.
#ifndef CALIBER_EXTRAS_TRIANGLE_SOUP_H
#define CALIBER_EXTRAS_TRIANGLE_SOUP_H

#include <vector>

namespace caliber
{
namespace decomposition
{
struct Vec3
{
	double x, y, z;
};
inline Vec3 operator+(const Vec3& a, const Vec3& b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
inline Vec3 operator-(const Vec3& a, const Vec3& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
inline Vec3 operator*(const Vec3& a, double s) { return {a.x * s, a.y * s, a.z * s}; }
inline double dot(const Vec3& a, const Vec3& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline Vec3 cross(const Vec3& a, const Vec3& b)
{
	return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
inline double component(const Vec3& a, int axis) { return axis == 0 ? a.x : (axis == 1 ? a.y : a.z); }

/// A corner of a soup triangle. onSolid is true when the point is known to belong to the piece (a point of
/// the mesh's surface, or a cut point of it); false for cut points of cap triangles, which may lie outside
/// the solid (see splitSoup) until a point-in-solid test says otherwise.
struct SoupVertex
{
	Vec3 position;
	bool onSolid;
};

/// One triangle of a piece: from the mesh's surface, or from a cap that closes a cut.
struct SoupTriangle
{
	SoupVertex corner[3];
	bool cap;
};

/// A piece's boundary. It is a closed oriented surface whose winding number is 1 inside the piece and 0
/// outside, so the divergence theorem gives the piece's exact volume from it.
typedef std::vector<SoupTriangle> TriangleSoup;

/// Signed volume enclosed by soup (positive for an outward-wound closed surface).
double soupVolume(const TriangleSoup& soup);

/// Splits soup by the plane normal.x = offset (normal along an axis or not) into the part below
/// (normal.x < offset) and the part at or above it, and closes each cut with a cap: a fan from one cut
/// point over the cut's segments. A fan over a non-convex cut covers some of the plane outside the solid,
/// but with opposite windings that cancel, so volumes stay exact; its corners cut by later planes are the
/// "maybe outside" vertices (onSolid false). Points on the plane go above, so every point has one side.
void splitSoup(const TriangleSoup& soup, const Vec3& normal, double offset, TriangleSoup& below, TriangleSoup& above);
}  // namespace decomposition
}  // namespace caliber

#endif  // CALIBER_EXTRAS_TRIANGLE_SOUP_H
