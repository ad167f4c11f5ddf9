// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef CALIBER_DEMOS_COMMON_SCENE_H
#define CALIBER_DEMOS_COMMON_SCENE_H
// What the demo renderer draws: lit triangles, lines and points, all in world coordinates. The
// shape mesher and the debug drawer fill a Scene; Renderer turns it into pixels. Demo-side code, not
// part of the physics libraries.

#include <vector>

#include "LinearMath/btVector3.h"

namespace caliber
{
namespace demo
{
/// One solid triangle: corners, a normal per corner (for smooth shading) and a colour (0..1).
struct SceneTriangle
{
	btVector3 corner[3];
	btVector3 normal[3];
	btVector3 color;
	/// A floor-like surface gets a faint 1 m checker pattern, so that height and distance read.
	bool checker = false;
};

/// A line segment (debug drawing: joint frames and limits, AABBs, contact normals, wireframes).
struct SceneLine
{
	btVector3 from, to, color;
};

/// A marked point (a contact point), drawn as a small square.
struct ScenePoint
{
	btVector3 position, color;
};

/// Everything to draw, plus the box the camera should frame.
class Scene
{
public:
	/// Adds a triangle with one normal for the whole face (flat shading). Skipped, and counted in
	/// skippedNonFinite(), when a corner is NaN or infinite.
	void addFlatTriangle(const btVector3& a, const btVector3& b, const btVector3& c, const btVector3& color,
	                     bool checker = false);
	/// Adds a triangle with a normal per corner (smooth shading); non-finite input is skipped as above.
	void addSmoothTriangle(const btVector3 corner[3], const btVector3 normal[3], const btVector3& color);
	/// Adds a line; non-finite ends are skipped as above.
	void addLine(const btVector3& from, const btVector3& to, const btVector3& color);
	/// Adds a point; a non-finite point is skipped as above.
	void addPoint(const btVector3& position, const btVector3& color);

	/// Widens the box the camera frames (the focus) to hold these corners. Non-finite corners are ignored.
	void focusOn(const btVector3& aabbMin, const btVector3& aabbMax);
	/// True when focusOn() was called with a finite box.
	bool hasFocus() const { return m_hasFocus; }
	const btVector3& focusMin() const { return m_focusMin; }
	const btVector3& focusMax() const { return m_focusMax; }
	/// The box around every triangle, line and point (the focus's fallback).
	bool contentBounds(btVector3& aabbMin, btVector3& aabbMax) const;

	const std::vector<SceneTriangle>& triangles() const { return m_triangles; }
	const std::vector<SceneLine>& lines() const { return m_lines; }
	const std::vector<ScenePoint>& points() const { return m_points; }
	/// How many primitives were dropped because a coordinate was NaN or infinite.
	int skippedNonFinite() const { return m_skippedNonFinite; }
	/// Adds another scene's triangles, lines and points (not its focus), already checked when it was built.
	void append(const Scene& other);
	/// Empties the scene (keeps its memory for the next frame).
	void clear();

private:
	std::vector<SceneTriangle> m_triangles;
	std::vector<SceneLine> m_lines;
	std::vector<ScenePoint> m_points;
	btVector3 m_focusMin{0, 0, 0}, m_focusMax{0, 0, 0};
	bool m_hasFocus = false;
	int m_skippedNonFinite = 0;
};

/// True when every coordinate of v is finite.
bool isFinite(const btVector3& v);
}  // namespace demo
}  // namespace caliber

#endif
