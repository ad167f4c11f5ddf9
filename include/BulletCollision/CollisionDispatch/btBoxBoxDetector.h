// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef BT_BOX_BOX_DETECTOR_H
#define BT_BOX_BOX_DETECTOR_H

/// btBoxBoxDetector: contact manifold of two boxes by the 15-axis separating-axis test and face clipping.

#include "BulletCollision/NarrowPhaseCollision/btDiscreteCollisionDetectorInterface.h"

class btBoxShape;

/// Box-box contacts. The axis of least penetration (or largest separation) among the 3 + 3 face normals
/// and the 9 edge cross products decides the contact: a face axis clips the other box's most opposed
/// face against the reference face and reports up to 4 points (the 4 spanning the largest area when
/// the clip leaves more); an edge axis reports the closest point pair of the two edges. Boxes are
/// their full size (getHalfExtentsWithMargin). Points are reported with the normal from box 2 (B)
/// towards box 1 (A), the point on B, and the signed distance, when that distance is at most
/// sqrt(input.m_maximumDistanceSquared); boxes separated by more along any axis report nothing.
/// Bad input: null boxes or non-finite transforms assert and report nothing in release builds. A
/// zero-size box is a point: it gets a single contact point (coincident clip points are merged).
struct btBoxBoxDetector : public btDiscreteCollisionDetectorInterface
{
	/// Box A (not owned).
	const btBoxShape* m_box1;
	/// Box B (not owned).
	const btBoxShape* m_box2;

public:
	/// A detector for the pair (box1 = A, box2 = B).
	btBoxBoxDetector(const btBoxShape* box1, const btBoxShape* box2);
	/// Nothing is owned.
	~btBoxBoxDetector() override {}

	/// Reports up to 4 contact points. With swapResults the pair is reported as (B, A): normals from A
	/// towards B and points on A.
	void getClosestPoints(const ClosestPointInput& input, Result& output, btIDebugDraw* debugDraw,
	                      bool swapResults = false) override;
};

#endif  // BT_BOX_BOX_DETECTOR_H
