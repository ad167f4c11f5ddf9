// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef BT_CONVEX_CAST_H
#define BT_CONVEX_CAST_H

/// btConvexCast: the interface of time-of-impact queries between two moving convex shapes.

#include "LinearMath/btScalar.h"
#include "LinearMath/btTransform.h"
#include "LinearMath/btVector3.h"

class btIDebugDraw;

#ifdef BT_USE_DOUBLE_PRECISION
/// Default iteration limit of btSubsimplexConvexCast (CastResult::m_subSimplexCastMaxIterations).
#define MAX_CONVEX_CAST_ITERATIONS 64
/// Default squared distance at which btSubsimplexConvexCast accepts a hit (CastResult::m_subSimplexCastEpsilon):
/// (1e-6)^2, a micrometre at metre scale.
#define MAX_CONVEX_CAST_EPSILON btScalar(1e-12)
#else
/// Default iteration limit of btSubsimplexConvexCast (CastResult::m_subSimplexCastMaxIterations).
#define MAX_CONVEX_CAST_ITERATIONS 64
/// Default squared distance at which btSubsimplexConvexCast accepts a hit (CastResult::m_subSimplexCastEpsilon):
/// (1e-3)^2, a millimetre at metre scale.
#define MAX_CONVEX_CAST_EPSILON btScalar(1e-6)
#endif

/// Finds the first fraction in [0, 1] of a motion (from -> to for both shapes) at which two convex
/// shapes touch. Implementations: btSubsimplexConvexCast, btGjkConvexCast, btContinuousConvexCollision.
/// Shapes that already touch at fraction 0 report a hit at fraction 0 (see docs).
class btConvexCast
{
public:
	/// Casts are deleted through base pointers.
	virtual ~btConvexCast();

	/// The result of a cast: written only when calcTimeOfImpact returns true.
	struct CastResult
	{
		/// Called with intermediate fractions when a debug drawer is set (no-op by default).
		virtual void DebugDraw(btScalar fraction) { (void)fraction; }
		/// Called with intermediate transforms when a debug drawer is set (no-op by default).
		virtual void drawCoordSystem(const btTransform& trans) { (void)trans; }
		/// Called when a cast gives up (errNo < 0, numIterations used); no-op by default.
		virtual void reportFailure(int errNo, int numIterations)
		{
			(void)errNo;
			(void)numIterations;
		}
		/// No hit yet: m_fraction is BT_LARGE_FLOAT.
		CastResult()
		    : m_normal(btScalar(0), btScalar(0), btScalar(0)),
		      m_hitPoint(btScalar(0), btScalar(0), btScalar(0)),
		      m_fraction(btScalar(BT_LARGE_FLOAT)),
		      m_debugDrawer(nullptr),
		      m_allowedPenetration(btScalar(0)),
		      m_subSimplexCastMaxIterations(MAX_CONVEX_CAST_ITERATIONS),
		      m_subSimplexCastEpsilon(MAX_CONVEX_CAST_EPSILON)
		{
			m_hitTransformA.setIdentity();
			m_hitTransformB.setIdentity();
		}
		/// Results are deleted through base pointers.
		virtual ~CastResult() {}

		/// Transform of shape A at the time of impact.
		btTransform m_hitTransformA;
		/// Transform of shape B at the time of impact.
		btTransform m_hitTransformB;
		/// Unit contact normal in world space, pointing from B towards A.
		btVector3 m_normal;
		/// Contact point on B in world space, at the time of impact.
		btVector3 m_hitPoint;
		/// Time of impact as a fraction of the motion, in [0, 1] (BT_LARGE_FLOAT until a hit).
		btScalar m_fraction;
		/// Optional debug drawer (not owned).
		btIDebugDraw* m_debugDrawer;
		/// How far the shapes may overlap at the reported hit (GJK and continuous casts; >= 0).
		btScalar m_allowedPenetration;
		/// Iteration limit of btSubsimplexConvexCast.
		int m_subSimplexCastMaxIterations;
		/// Squared distance between the shapes at which btSubsimplexConvexCast accepts a hit.
		btScalar m_subSimplexCastEpsilon;
	};

	/// Casts A from fromA to toA and B from fromB to toB. Returns true and fills result on a hit in
	/// [0, 1]; returns false (result unchanged) on a miss or bad input.
	virtual bool calcTimeOfImpact(const btTransform& fromA, const btTransform& toA, const btTransform& fromB,
	                              const btTransform& toB, CastResult& result) = 0;
};

#endif  // BT_CONVEX_CAST_H
