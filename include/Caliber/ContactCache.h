// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef CALIBER_CONTACT_CACHE_H
#define CALIBER_CONTACT_CACHE_H

/// Caliber's contact cache (Bullet has none; Jolt's body pair cache is the model). When no point of a
/// body has moved by more than the cache distance relative to the other body of a pair since their
/// contacts were last found, and the pair does not close faster than that distance per step, the
/// narrowphase keeps the contacts it found then and only refreshes them (their world positions and
/// distances at the new poses), as btPersistentManifold::refreshContactPoints does. Resting and slowly
/// moving contacts, most of a settled pile's, then cost a refresh instead of a detection.
/// Which pairs use it, and what it changes: docs/collision-detection.md, "The contact cache".

#include "LinearMath/btScalar.h"

namespace caliber
{
/// Sets the cache distance in metres (default 0.001, as Jolt's): the most any point of a body may have
/// moved relative to the other body of a pair before the pair's contacts are found again. 0 turns the
/// cache off (every pair is detected every step, as in Bullet). A negative, NaN or infinite distance
/// asserts and is ignored in release builds, with a warning. Process-wide; set it between steps (a
/// step running on another thread meanwhile sees the old or the new value pair by pair).
void setContactCacheDistance(btScalar distance);
/// The cache distance in metres (0: off).
btScalar getContactCacheDistance();
}  // namespace caliber

#endif  // CALIBER_CONTACT_CACHE_H
