// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef BT_VEHICLE_RAYCASTER_H
#define BT_VEHICLE_RAYCASTER_H

#include "LinearMath/btVector3.h"

/// What a raycast vehicle asks of the world: the first surface along a ray (docs/actions.md).
struct btVehicleRaycaster
{
	virtual ~btVehicleRaycaster() {}

	/// The hit of one ray: point, unit normal and the fraction of the ray (-1 while nothing was hit).
	struct btVehicleRaycasterResult
	{
		btVehicleRaycasterResult() : m_distFraction(btScalar(-1.)) {}
		/// Where the ray hit, in world space.
		btVector3 m_hitPointInWorld;
		/// The surface normal there, unit length, in world space.
		btVector3 m_hitNormalInWorld;
		/// The hit's fraction of the way from `from` to `to`.
		btScalar m_distFraction;
	};

	/// Casts from `from` to `to`; returns the object hit (a btCollisionObject*) and fills result, or
	/// returns null when nothing was hit.
	virtual void* castRay(const btVector3& from, const btVector3& to, btVehicleRaycasterResult& result) = 0;
};

#endif  // BT_VEHICLE_RAYCASTER_H
