// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef BT_IDEBUG_DRAW__H
#define BT_IDEBUG_DRAW__H

/// btIDebugDraw: the interface a renderer implements to show the physics world as lines.
///
/// A renderer must implement drawLine, drawContactPoint, reportErrorWarning, draw3dText, setDebugMode
/// and getDebugMode; every other shape has a default built from drawLine alone. Curves are drawn as
/// segments of at most stepDegrees (10 by default); a stepDegrees that is not a positive finite
/// number means 10, and steps below 0.5 degrees are raised to 0.5, so a curve never has more than
/// 720 segments per turn. Shapes with non-finite angles, and shapes on an upAxis outside 0..2, draw
/// nothing. Zero sizes draw zero-length lines. Sphere, patch, capsule, cylinder and cone radii, and
/// capsule and cylinder half heights, are used by magnitude (a negative cone height points it down);
/// drawArc uses its radii and vectors exactly as given.

#include "LinearMath/btTransform.h"
#include "LinearMath/btVector3.h"

/// The debug drawing interface the physics world calls; subclass it for a renderer.
class btIDebugDraw
{
public:
	/// Colours used when the world draws objects in their various activation states.
	ATTRIBUTE_ALIGNED16(struct)
	DefaultColors
	{
		/// Awake bodies.
		btVector3 m_activeObject;
		/// Sleeping bodies.
		btVector3 m_deactivatedObject;
		/// Bodies about to sleep.
		btVector3 m_wantsDeactivationObject;
		/// Bodies that may never sleep.
		btVector3 m_disabledDeactivationObject;
		/// Bodies excluded from simulation.
		btVector3 m_disabledSimulationObject;
		/// Bounding boxes.
		btVector3 m_aabb;
		/// Contact points.
		btVector3 m_contactPoint;

		/// White active, green sleeping, cyan about to sleep, red never sleeping, yellow disabled,
		/// red boxes and yellow contacts.
		DefaultColors()
		    : m_activeObject(1, 1, 1),
		      m_deactivatedObject(0, 1, 0),
		      m_wantsDeactivationObject(0, 1, 1),
		      m_disabledDeactivationObject(1, 0, 0),
		      m_disabledSimulationObject(1, 1, 0),
		      m_aabb(1, 0, 0),
		      m_contactPoint(1, 1, 0)
		{
		}
	};

	/// Bits of the debug mode: what the world draws.
	enum DebugDrawModes
	{
		DBG_NoDebug = 0,                       ///< draw nothing
		DBG_DrawWireframe = 1,                 ///< collision shapes as wireframes
		DBG_DrawAabb = 2,                      ///< bounding boxes
		DBG_DrawFeaturesText = 4,              ///< feature labels as text
		DBG_DrawContactPoints = 8,             ///< contact points and normals
		DBG_NoDeactivation = 16,               ///< keep every body awake
		DBG_NoHelpText = 32,                   ///< hide the demo help text
		DBG_DrawText = 64,                     ///< allow text output
		DBG_ProfileTimings = 128,              ///< show profile timings
		DBG_EnableSatComparison = 256,         ///< compare SAT results (diagnostics)
		DBG_DisableBulletLCP = 512,            ///< disable the LCP solver path (diagnostics)
		DBG_EnableCCD = 1024,                  ///< enable continuous collision detection in demos
		DBG_DrawConstraints = (1 << 11),       ///< constraint frames
		DBG_DrawConstraintLimits = (1 << 12),  ///< constraint limits
		DBG_FastWireframe = (1 << 13),         ///< cheaper wireframes (fewer lines)
		DBG_DrawNormals = (1 << 14),           ///< triangle normals
		DBG_DrawFrames = (1 << 15),            ///< body frames (drawTransform)
		DBG_MAX_DEBUG_DRAW_MODE                ///< one past the highest bit
	};

	/// Nothing to release.
	virtual ~btIDebugDraw();

	/// The colours the world should use; those last given to setDefaultColors, else DefaultColors().
	virtual DefaultColors getDefaultColors() const;
	/// Replaces the colours getDefaultColors returns.
	virtual void setDefaultColors(const DefaultColors& colors);

	/// Draws one line segment in one colour.
	virtual void drawLine(const btVector3& from, const btVector3& to, const btVector3& color) = 0;
	/// Draws a line whose colour goes from fromColor to toColor; by default all in fromColor.
	virtual void drawLine(const btVector3& from, const btVector3& to, const btVector3& fromColor,
	                      const btVector3& toColor);

	/// Draws a wire sphere (three great circles in the transform's basis planes) around its origin.
	virtual void drawSphere(btScalar radius, const btTransform& transform, const btVector3& color);
	/// Draws a wire sphere (three great circles in the world axis planes) around p.
	virtual void drawSphere(const btVector3& p, btScalar radius, const btVector3& color);

	/// Draws a triangle with vertex normals; by default the normals are ignored and its edges drawn.
	virtual void drawTriangle(const btVector3& v0, const btVector3& v1, const btVector3& v2, const btVector3& n0,
	                          const btVector3& n1, const btVector3& n2, const btVector3& color, btScalar alpha);
	/// Draws a triangle; by default its three edges (alpha is ignored).
	virtual void drawTriangle(const btVector3& v0, const btVector3& v1, const btVector3& v2, const btVector3& color,
	                          btScalar alpha);

	/// Draws a contact point on B with its normal, penetration distance and age.
	virtual void drawContactPoint(const btVector3& PointOnB, const btVector3& normalOnB, btScalar distance,
	                              int lifeTime, const btVector3& color) = 0;
	/// Receives a warning the library wants the user to see.
	virtual void reportErrorWarning(const char* warningString) = 0;
	/// Draws text at a world position.
	virtual void draw3dText(const btVector3& location, const char* textString) = 0;
	/// Sets the DebugDrawModes bits.
	virtual void setDebugMode(int debugMode) = 0;
	/// The DebugDrawModes bits.
	virtual int getDebugMode() const = 0;

	/// Draws the 12 edges of the axis-aligned box [from, to].
	virtual void drawAabb(const btVector3& from, const btVector3& to, const btVector3& color);
	/// Draws the transform's basis axes as lines of length orthoLen from its origin: x red, y green, z blue.
	virtual void drawTransform(const btTransform& transform, btScalar orthoLen);

	/// Draws the elliptic arc center + axis*radiusA*cos(t) + (normal x axis)*radiusB*sin(t) for t from
	/// minAngle to maxAngle (radians; at most one turn), plus lines from the centre to both ends when
	/// drawSect. axis and normal should be perpendicular unit vectors.
	virtual void drawArc(const btVector3& center, const btVector3& normal, const btVector3& axis, btScalar radiusA,
	                     btScalar radiusB, btScalar minAngle, btScalar maxAngle, const btVector3& color, bool drawSect,
	                     btScalar stepDegrees = btScalar(10.f));

	/// Draws a latitude/longitude grid on the sphere of radius around center: latitude from minTh to
	/// maxTh (radians from the equator, clamped to [-pi/2, pi/2]) about the pole up, longitude from
	/// minPs to maxPs measured from axis towards up x axis (minPs > maxPs or a span of a full turn or
	/// more draws all longitudes). With drawCenter, lines join the centre to the patch's open edges.
	virtual void drawSpherePatch(const btVector3& center, const btVector3& up, const btVector3& axis, btScalar radius,
	                             btScalar minTh, btScalar maxTh, btScalar minPs, btScalar maxPs, const btVector3& color,
	                             btScalar stepDegrees = btScalar(10.f), bool drawCenter = true);

	/// Draws the 12 edges of the axis-aligned box [bbMin, bbMax].
	virtual void drawBox(const btVector3& bbMin, const btVector3& bbMax, const btVector3& color);
	/// Draws the 12 edges of the box [bbMin, bbMax] placed by trans.
	virtual void drawBox(const btVector3& bbMin, const btVector3& bbMax, const btTransform& trans,
	                     const btVector3& color);

	/// Draws a capsule along local axis upAxis (0, 1 or 2): hemispheres of radius centred at
	/// +-halfHeight, joined by four lines.
	virtual void drawCapsule(btScalar radius, btScalar halfHeight, int upAxis, const btTransform& transform,
	                         const btVector3& color);
	/// Draws a cylinder along local axis upAxis: end circles of radius at +-halfHeight and four side lines.
	virtual void drawCylinder(btScalar radius, btScalar halfHeight, int upAxis, const btTransform& transform,
	                          const btVector3& color);
	/// Draws a cone along local axis upAxis: apex at +height/2, base circle of radius at -height/2, four
	/// lines from the apex to the base.
	virtual void drawCone(btScalar radius, btScalar height, int upAxis, const btTransform& transform,
	                      const btVector3& color);
	/// Draws the plane planeNormal . x = planeConst (in the transform's frame) as a cross and a square of
	/// half-size 100 around its point closest to the origin. A zero normal draws nothing.
	virtual void drawPlane(const btVector3& planeNormal, btScalar planeConst, const btTransform& transform,
	                       const btVector3& color);

	/// Called by the world before it draws a frame; by default does nothing.
	virtual void clearLines() {}
	/// Called by the world after it drew a frame, for batching renderers; by default does nothing.
	virtual void flushLines() {}

private:
	DefaultColors m_defaultColors;
};

#endif  // BT_IDEBUG_DRAW__H
