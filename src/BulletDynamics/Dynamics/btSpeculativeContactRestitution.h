// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef CALIBER_SPECULATIVE_CONTACT_RESTITUTION_H
#define CALIBER_SPECULATIVE_CONTACT_RESTITUTION_H

// What btDiscreteDynamicsWorld::setApplySpeculativeContactRestitution(true) does. In Bullet the world's
// predictive manifolds (m_predictiveManifolds, the contacts a CCD body's sweep finds ahead of it) carry
// no restitution, and the flag lets them bounce. Caliber's own speculative contacts come from the
// dispatcher and bounce like any other contact when they are met; its world makes no predictive
// manifolds, so the flag concerns those a subclass makes (docs/rigid-body-dynamics.md).

#include "LinearMath/btAlignedObjectArray.h"

class btPersistentManifold;

namespace caliber
{
/// Gives every point of the predictive manifolds its bodies' combined restitution
/// (gCalculateCombinedRestitutionCallback), so that the solver's restitution pass bounces the points
/// that are met this step. Null entries and manifolds without both bodies are skipped.
void giveSpeculativeContactsRestitution(const btAlignedObjectArray<btPersistentManifold*>& predictiveManifolds);
}  // namespace caliber

#endif  // CALIBER_SPECULATIVE_CONTACT_RESTITUTION_H
