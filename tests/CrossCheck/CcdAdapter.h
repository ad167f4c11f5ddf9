// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef CALIBER_TESTS_CROSSCHECK_CCD_ADAPTER_H
#define CALIBER_TESTS_CROSSCHECK_CCD_ADAPTER_H

// Lets libccd (the reference) see a Caliber convex shape placed in the world. libccd only asks for
// world-space support points; they are built here as Caliber's GJK and EPA see the shape, as in
// Bullet: the margin-free core (localGetSupportingVertexWithoutMargin) swept by a sphere of radius
// getMargin(). For every shape but the box that is localGetSupportingVertex; a box's
// localGetSupportingVertex gives the sharp corners of its full extents (Bullet's convention), while
// its collision geometry is the core box with rounded edges.

#include <ccd/ccd.h>

#include <cmath>

#include "BulletCollision/CollisionShapes/btConvexShape.h"
#include "LinearMath/btTransform.h"
#include "LinearMath/btVector3.h"

namespace caliber_crosscheck
{
/// A Caliber convex shape at a world transform, as libccd's opaque object.
struct CcdObject
{
	/// The shape (not owned).
	const btConvexShape* shape;
	/// Where the shape is in the world.
	btTransform transform;
};

/// The world-space support point of obj's collision geometry (core plus margin) in a unit direction.
inline btVector3 worldSupport(const CcdObject& obj, const btVector3& worldDirection)
{
	// dir * basis is basis^T * dir: the direction in the shape's frame.
	const btVector3 localDirection = worldDirection * obj.transform.getBasis();
	const btVector3 core = obj.shape->localGetSupportingVertexWithoutMargin(localDirection);
	return obj.transform(core + localDirection * obj.shape->getMargin());
}

/// The support function h(dir) = max over the shape of x . dir, for a unit dir.
inline double supportHeight(const CcdObject& obj, const btVector3& worldDirection)
{
	return double(worldSupport(obj, worldDirection).dot(worldDirection));
}

/// How far b must move along -normalOnB (normalOnB points from b towards a) until the two just touch:
/// h_a(-n) + h_b(n), the depth of the Minkowski difference a - b in that direction. It is the
/// penetration depth exactly when n is a minimal separating direction, and larger otherwise.
inline double depthAlong(const CcdObject& a, const CcdObject& b, const btVector3& normalOnB)
{
	return supportHeight(a, -normalOnB) + supportHeight(b, normalOnB);
}

/// libccd's support callback.
inline void ccdSupport(const void* object, const ccd_vec3_t* direction, ccd_vec3_t* out)
{
	const CcdObject& obj = *static_cast<const CcdObject*>(object);
	// libccd's directions may be far shorter than SIMD_EPSILON (GJK's closest point nearing the origin),
	// and Bullet's shapes read such a vector as "no direction": normalise in double first.
	const double* d = direction->v;
	const double length = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
	const double scale = length > 0 && std::isfinite(length) ? 1 / length : 0;
	const btVector3 dir(btScalar(d[0] * scale), btScalar(d[1] * scale), btScalar(d[2] * scale));
	const btVector3 p = worldSupport(obj, dir);
	out->v[0] = p.x();
	out->v[1] = p.y();
	out->v[2] = p.z();
}

/// libccd's centre callback (MPR): the shape's origin, which is inside every shape used here.
inline void ccdCenter(const void* object, ccd_vec3_t* center)
{
	const btVector3& c = static_cast<const CcdObject*>(object)->transform.getOrigin();
	center->v[0] = c.x();
	center->v[1] = c.y();
	center->v[2] = c.z();
}

/// Centre-to-centre direction tilted by skew (times the centre distance): a libccd first direction.
inline void ccdTiltedCentreDirection(const void* object1, const void* object2, const double skew[3], ccd_vec3_t* dir)
{
	const btVector3 d = static_cast<const CcdObject*>(object2)->transform.getOrigin() -
	                    static_cast<const CcdObject*>(object1)->transform.getOrigin();
	const double length = double(d.length());
	for (int i = 0; i < 3; ++i) dir->v[i] = double(d[i]) + (length > 1e-6 ? length : 1.0) * skew[i];
}

/// The tilts of the first GJK directions ccdEpaPenetration tries, in order.
const double kFirstDirectionSkews[5][3] = {
    {0.13, 0.29, 0.41}, {-0.37, 0.23, -0.11}, {0.19, -0.43, 0.07}, {-0.05, -0.17, 0.47}, {0.44, 0.02, -0.31}};

/// libccd's first GJK direction number I: centre to centre, which avoids libccd's NaN-direction
/// defect on face-aligned boxes in many cases (libccd issue 25), tilted by kFirstDirectionSkews[I].
/// Untilted, GJK's second support point on two spheres lies on the line from the first through the
/// origin; libccd then sees the origin "on" a segment to within rounding and returns a ~1e-8 depth.
/// (libccd's default, the x axis, is not used: on concentric spheres it keeps libccd busy ~40 s.)
template <int I>
void ccdTiltedFirstDirection(const void* object1, const void* object2, ccd_vec3_t* dir)
{
	ccdTiltedCentreDirection(object1, object2, kFirstDirectionSkews[I], dir);
}

/// A libccd set-up for reference values: tight EPA tolerance (libccd compares it with a squared
/// distance, so the default 1e-4 stops ~1e-2 short on curved shapes) and bounded iterations.
inline ccd_t makeReferenceCcd()
{
	ccd_t ccd;
	CCD_INIT(&ccd);
	ccd.first_dir = ccdTiltedFirstDirection<0>;
	ccd.support1 = ccdSupport;
	ccd.support2 = ccdSupport;
	ccd.center1 = ccdCenter;
	ccd.center2 = ccdCenter;
	ccd.max_iterations = 300;
	ccd.epa_tolerance = 1e-10;
	ccd.mpr_tolerance = 1e-10;
	ccd.dist_tolerance = 1e-10;
	return ccd;
}

/// A libccd result is trusted only when its own normal reproduces its depth: h_a(-n) + h_b(n) is the
/// depth along n and at least the true depth, EPA's depth at most; a wider gap than this means
/// libccd stopped early or returned a wrong direction.
const double kReferenceConsistency = 1e-5;

/// libccd's answer for one pair.
struct CcdPenetration
{
	/// libccd's return value: 0 intersecting, -1 separated, -2 allocation failure.
	int status;
	/// Penetration depth (meaningful when status is 0).
	double depth;
	/// Contact normal on b pointing towards a, Bullet's convention (libccd's dir negated).
	btVector3 normalOnB;
	/// True when the values are usable: finite, positive depth, unit normal that reproduces the depth.
	bool valid;
};

/// One ccdGJKPenetration run with the given first direction.
inline CcdPenetration ccdEpaPenetrationFrom(const CcdObject& a, const CcdObject& b, ccd_first_dir_fn firstDirection)
{
	ccd_t ccd = makeReferenceCcd();
	ccd.first_dir = firstDirection;
	ccd_real_t depth = 0;
	ccd_vec3_t dir = {{0, 0, 0}};
	ccd_vec3_t pos = {{0, 0, 0}};
	CcdPenetration result;
	result.status = ccdGJKPenetration(&a, &b, &ccd, &depth, &dir, &pos);
	result.depth = depth;
	// libccd's dir points from a towards b (moving b by depth * dir separates them).
	result.normalOnB = btVector3(btScalar(-dir.v[0]), btScalar(-dir.v[1]), btScalar(-dir.v[2]));
	const double dirLength = std::sqrt(dir.v[0] * dir.v[0] + dir.v[1] * dir.v[1] + dir.v[2] * dir.v[2]);
	result.valid = result.status == 0 && std::isfinite(depth) && depth > 0 && std::isfinite(dirLength) &&
	               std::fabs(dirLength - 1) < 1e-6 &&
	               std::fabs(depthAlong(a, b, result.normalOnB) - depth) <= kReferenceConsistency;
	return result;
}

/// libccd's GJK+EPA penetration of a and b (ccdGJKPenetration): the first trusted result of runs
/// from five differently tilted centre directions. Where libccd's EPA stops short or mistakes deep
/// overlap for touching depends on where GJK starts, so other starts rescue most such failures.
inline CcdPenetration ccdEpaPenetration(const CcdObject& a, const CcdObject& b)
{
	const ccd_first_dir_fn starts[5] = {ccdTiltedFirstDirection<0>, ccdTiltedFirstDirection<1>,
	                                    ccdTiltedFirstDirection<2>, ccdTiltedFirstDirection<3>,
	                                    ccdTiltedFirstDirection<4>};
	const CcdPenetration first = ccdEpaPenetrationFrom(a, b, starts[0]);
	if (first.valid || first.status == -1) return first;
	for (int i = 1; i < 5; ++i)
	{
		const CcdPenetration retry = ccdEpaPenetrationFrom(a, b, starts[i]);
		if (retry.valid) return retry;
	}
	return first;
}

/// libccd's MPR yes/no (ccdMPRIntersect).
inline bool ccdMprIntersects(const CcdObject& a, const CcdObject& b)
{
	const ccd_t ccd = makeReferenceCcd();
	return ccdMPRIntersect(&a, &b, &ccd) != 0;
}

/// libccd's GJK yes/no (ccdGJKIntersect).
inline bool ccdGjkIntersects(const CcdObject& a, const CcdObject& b)
{
	const ccd_t ccd = makeReferenceCcd();
	return ccdGJKIntersect(&a, &b, &ccd) != 0;
}

}  // namespace caliber_crosscheck

#endif  // CALIBER_TESTS_CROSSCHECK_CCD_ADAPTER_H
