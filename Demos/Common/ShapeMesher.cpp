// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "ShapeMesher.h"

#include <cmath>
#include <vector>

#include "btBulletCollisionCommon.h"
#include "BulletCollision/CollisionShapes/btConvexPolyhedron.h"
#include "BulletCollision/CollisionShapes/btMultiSphereShape.h"
#include "LinearMath/btConvexHullComputer.h"

namespace caliber
{
namespace demo
{
namespace
{
// One point of a profile revolved about an axis: distance from the axis, height along it and the
// surface normal in the same (radial, axial) terms.
struct ProfilePoint
{
	btScalar radius, height, normalRadial, normalAxial;
};

// Revolves the profile (bottom to top) about local axis upAxis and adds the surface, smooth-shaded.
void addRevolved(Scene& scene, const std::vector<ProfilePoint>& profile, int upAxis, const btTransform& transform,
                 const MeshStyle& style)
{
	const int segments = btMax(6, style.segments);
	const int a = (upAxis + 1) % 3, b = (upAxis + 2) % 3;
	auto place = [&](const ProfilePoint& p, int segment, btVector3& position, btVector3& normal)
	{
		const btScalar angle = SIMD_2_PI * btScalar(segment) / btScalar(segments);
		const btScalar c = btCos(angle), s = btSin(angle);
		btVector3 local(0, 0, 0), localNormal(0, 0, 0);
		local[upAxis] = p.height;
		local[a] = p.radius * c;
		local[b] = p.radius * s;
		localNormal[upAxis] = p.normalAxial;
		localNormal[a] = p.normalRadial * c;
		localNormal[b] = p.normalRadial * s;
		position = transform(local);
		normal = transform.getBasis() * localNormal;
	};
	for (std::size_t i = 0; i + 1 < profile.size(); ++i)
		for (int k = 0; k < segments; ++k)
		{
			btVector3 p[4], n[4];
			place(profile[i], k, p[0], n[0]);
			place(profile[i], k + 1, p[1], n[1]);
			place(profile[i + 1], k + 1, p[2], n[2]);
			place(profile[i + 1], k, p[3], n[3]);
			const btVector3 first[3] = {p[0], p[1], p[2]}, firstNormals[3] = {n[0], n[1], n[2]};
			const btVector3 second[3] = {p[0], p[2], p[3]}, secondNormals[3] = {n[0], n[2], n[3]};
			scene.addSmoothTriangle(first, firstNormals, style.color);
			scene.addSmoothTriangle(second, secondNormals, style.color);
		}
}

// A half sphere of the given radius centred at height centre, from its equator towards side (+1 up, -1 down).
void appendHemisphere(std::vector<ProfilePoint>& profile, btScalar radius, btScalar centre, int side, int rings)
{
	for (int i = 0; i <= rings; ++i)
	{
		// Bottom half: from the pole (angle -90) to the equator; top half: from the equator to the pole.
		const btScalar angle = side < 0 ? -SIMD_HALF_PI + SIMD_HALF_PI * btScalar(i) / btScalar(rings)
		                                : SIMD_HALF_PI * btScalar(i) / btScalar(rings);
		const btScalar c = btCos(angle), s = btSin(angle);
		profile.push_back(ProfilePoint{radius * c, centre + radius * s, c, s});
	}
}

void addCapsule(Scene& scene, btScalar radius, btScalar halfHeight, int upAxis, const btTransform& transform,
                const MeshStyle& style)
{
	const int rings = btMax(3, style.segments / 4);
	std::vector<ProfilePoint> profile;
	appendHemisphere(profile, radius, -halfHeight, -1, rings);
	appendHemisphere(profile, radius, halfHeight, +1, rings);
	addRevolved(scene, profile, upAxis, transform, style);
}

// A cylinder is a core cylinder (radius and half height less the margin) rounded by the margin: its rim
// is a quarter circle of the margin's radius, which the profile follows.
void addCylinder(Scene& scene, btScalar radius, btScalar halfHeight, btScalar margin, int upAxis,
                 const btTransform& transform, const MeshStyle& style)
{
	const btScalar coreRadius = btMax(btScalar(0), radius - margin), coreHalf = btMax(btScalar(0), halfHeight - margin);
	std::vector<ProfilePoint> profile = {{0, -halfHeight, 0, -1}};
	const int arcSteps = 3;
	for (int side = -1; side <= 1; side += 2)
		for (int i = 0; i <= arcSteps; ++i)
		{
			// Bottom rim: from straight down (-90 degrees) to outwards (0); top rim: from 0 to straight up.
			const btScalar angle = side < 0 ? -SIMD_HALF_PI + SIMD_HALF_PI * btScalar(i) / arcSteps
			                                : SIMD_HALF_PI * btScalar(i) / arcSteps;
			const btScalar c = btCos(angle), s = btSin(angle);
			profile.push_back(ProfilePoint{coreRadius + margin * c, btScalar(side) * coreHalf + margin * s, c, s});
		}
	profile.push_back(ProfilePoint{0, halfHeight, 0, 1});
	addRevolved(scene, profile, upAxis, transform, style);
}

void addCone(Scene& scene, btScalar radius, btScalar height, int upAxis, const btTransform& transform,
             const MeshStyle& style)
{
	// The side's normal: perpendicular to the slant from the base rim up to the apex.
	btScalar radial = height, axial = radius;
	const btScalar length = btSqrt(radial * radial + axial * axial);
	if (length > 0)
	{
		radial /= length;
		axial /= length;
	}
	const btScalar half = height / 2;
	const std::vector<ProfilePoint> profile = {
	    {0, -half, 0, -1}, {radius, -half, 0, -1}, {radius, -half, radial, axial}, {0, half, radial, axial}};
	addRevolved(scene, profile, upAxis, transform, style);
}

// Adds the convex hull of points; with directions (one per point) the hull is shaded smoothly, each
// corner lit as if its surface normal were the direction that found it, else face by face.
void addHull(Scene& scene, const std::vector<btVector3>& points, const std::vector<btVector3>* directions,
             const btTransform& transform, const MeshStyle& style)
{
	if (points.empty()) return;
	std::vector<btScalar> coords;
	coords.reserve(points.size() * 3);
	for (const btVector3& p : points)
	{
		coords.push_back(p.x());
		coords.push_back(p.y());
		coords.push_back(p.z());
	}
	btConvexHullComputer hull;
	hull.compute(coords.data(), int(3 * sizeof(btScalar)), int(points.size()), 0, 0);
	for (int f = 0; f < hull.faces.size(); ++f)
	{
		std::vector<int> corners;
		const btConvexHullComputer::Edge* start = &hull.edges[hull.faces[f]];
		const btConvexHullComputer::Edge* edge = start;
		do
		{
			corners.push_back(edge->getTargetVertex());
			edge = edge->getNextEdgeOfFace();
		} while (edge != start && corners.size() <= std::size_t(hull.vertices.size()));
		for (std::size_t i = 1; i + 1 < corners.size(); ++i)
		{
			const int ids[3] = {corners[0], corners[i], corners[i + 1]};
			btVector3 p[3], n[3];
			for (int k = 0; k < 3; ++k)
			{
				p[k] = transform(hull.vertices[ids[k]]);
				if (directions)
					n[k] = transform.getBasis() * (*directions)[std::size_t(hull.original_vertex_index[ids[k]])];
			}
			if (directions)
				scene.addSmoothTriangle(p, n, style.color);
			else
				scene.addFlatTriangle(p[0], p[1], p[2], style.color, style.checker);
		}
	}
}

// Evenly spread unit directions (a Fibonacci sphere).
std::vector<btVector3> sphereDirections(int count)
{
	std::vector<btVector3> directions;
	const double golden = M_PI * (3 - std::sqrt(5.0));
	for (int i = 0; i < count; ++i)
	{
		const double y = 1 - 2 * (i + 0.5) / count;
		const double r = std::sqrt(1 - y * y);
		directions.emplace_back(btScalar(r * std::cos(golden * i)), btScalar(y), btScalar(r * std::sin(golden * i)));
	}
	return directions;
}

void addSupportHull(Scene& scene, const btConvexShape& shape, const btTransform& transform, const MeshStyle& style)
{
	const std::vector<btVector3> directions = sphereDirections(btMax(64, style.segments * style.segments / 4));
	std::vector<btVector3> points;
	points.reserve(directions.size());
	for (const btVector3& d : directions) points.push_back(shape.localGetSupportingVertex(d));
	addHull(scene, points, &directions, transform, style);
}

class TriangleAdder : public btTriangleCallback
{
public:
	TriangleAdder(Scene& scene, const btTransform& transform, const MeshStyle& style)
	    : m_scene(scene), m_transform(transform), m_style(style)
	{
	}
	void processTriangle(btVector3* triangle, int, int) override
	{
		m_scene.addFlatTriangle(m_transform(triangle[0]), m_transform(triangle[1]), m_transform(triangle[2]),
		                        m_style.color, m_style.checker);
	}

private:
	Scene& m_scene;
	const btTransform& m_transform;
	const MeshStyle& m_style;
};

void addPlanePatch(Scene& scene, const btStaticPlaneShape& plane, const btTransform& transform, const MeshStyle& style)
{
	const btVector3 normal = (transform.getBasis() * plane.getPlaneNormal()).normalized();
	const btVector3 onPlane = transform(plane.getPlaneNormal() * plane.getPlaneConstant());
	const btVector3 centre = style.planeCentre - normal * normal.dot(style.planeCentre - onPlane);
	btVector3 u, v;
	btPlaneSpace1(normal, u, v);
	u *= style.planeHalfSize;
	v *= style.planeHalfSize;
	scene.addFlatTriangle(centre - u - v, centre + u - v, centre + u + v, style.color, style.checker);
	scene.addFlatTriangle(centre - u - v, centre + u + v, centre - u + v, style.color, style.checker);
}
}  // namespace

bool addShape(Scene& scene, const btCollisionShape* shape, const btTransform& transform, const MeshStyle& style)
{
	if (!shape || !isFinite(transform.getOrigin()) || !isFinite(transform.getBasis()[0]) ||
	    !isFinite(transform.getBasis()[1]) || !isFinite(transform.getBasis()[2]))
		return false;
	switch (shape->getShapeType())
	{
		case EMPTY_SHAPE_PROXYTYPE:
			return true;
		case SPHERE_SHAPE_PROXYTYPE:
		{
			const btScalar radius = static_cast<const btSphereShape*>(shape)->getRadius();
			std::vector<ProfilePoint> profile;
			const int rings = btMax(3, style.segments / 4);
			appendHemisphere(profile, radius, 0, -1, rings);
			profile.pop_back();  // the equator is the first point of the top half too
			appendHemisphere(profile, radius, 0, +1, rings);
			addRevolved(scene, profile, 1, transform, style);
			return true;
		}
		case CAPSULE_SHAPE_PROXYTYPE:
		{
			const btCapsuleShape* capsule = static_cast<const btCapsuleShape*>(shape);
			addCapsule(scene, capsule->getRadius(), capsule->getHalfHeight(), capsule->getUpAxis(), transform, style);
			return true;
		}
		case CYLINDER_SHAPE_PROXYTYPE:
		{
			const btCylinderShape* cylinder = static_cast<const btCylinderShape*>(shape);
			const int up = cylinder->getUpAxis();
			addCylinder(scene, cylinder->getRadius(), cylinder->getHalfExtentsWithMargin()[up], cylinder->getMargin(),
			            up, transform, style);
			return true;
		}
		case CONE_SHAPE_PROXYTYPE:
		{
			const btConeShape* cone = static_cast<const btConeShape*>(shape);
			addCone(scene, cone->getRadius(), cone->getHeight(), cone->getConeUpIndex(), transform, style);
			return true;
		}
		case STATIC_PLANE_PROXYTYPE:
			addPlanePatch(scene, *static_cast<const btStaticPlaneShape*>(shape), transform, style);
			return true;
		case COMPOUND_SHAPE_PROXYTYPE:
		{
			const btCompoundShape* compound = static_cast<const btCompoundShape*>(shape);
			bool all = true;
			for (int i = 0; i < compound->getNumChildShapes(); ++i)
				all = addShape(scene, compound->getChildShape(i), transform * compound->getChildTransform(i), style) &&
				      all;
			return all;
		}
		default:
			break;
	}
	if (shape->isPolyhedral())
	{
		const btPolyhedralConvexShape* polyhedron = static_cast<const btPolyhedralConvexShape*>(shape);
		if (polyhedron->getNumVertices() > 0)
		{
			std::vector<btVector3> points(std::size_t(polyhedron->getNumVertices()));
			for (int i = 0; i < polyhedron->getNumVertices(); ++i) polyhedron->getVertex(i, points[std::size_t(i)]);
			addHull(scene, points, nullptr, transform, style);
			return true;
		}
	}
	if (shape->isConvex())
	{
		addSupportHull(scene, *static_cast<const btConvexShape*>(shape), transform, style);
		return true;
	}
	if (shape->isConcave())
	{
		btVector3 aabbMin, aabbMax;
		shape->getAabb(btTransform::getIdentity(), aabbMin, aabbMax);
		const btVector3 slack(1, 1, 1);
		TriangleAdder adder(scene, transform, style);
		static_cast<const btConcaveShape*>(shape)->processAllTriangles(&adder, aabbMin - slack, aabbMax + slack);
		return true;
	}
	return false;
}
}  // namespace demo
}  // namespace caliber
