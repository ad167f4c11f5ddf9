// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef BT_DEFAULT_MOTION_STATE_H
#define BT_DEFAULT_MOTION_STATE_H

/// btDefaultMotionState: stores the graphics transform, with an optional centre-of-mass offset.

#include "LinearMath/btMotionState.h"

/// A motion state that keeps the last graphics transform, for programs that read it back each frame.
/// The graphics frame and the centre-of-mass frame are related by graphics = centreOfMass * offset.
ATTRIBUTE_ALIGNED16(struct)
btDefaultMotionState : public btMotionState
{
	/// The transform to draw the object with.
	btTransform m_graphicsWorldTrans;
	/// Offset of the graphics frame relative to the centre of mass: graphics = com * m_centerOfMassOffset.
	btTransform m_centerOfMassOffset;
	/// The graphics transform this state was created with.
	btTransform m_startWorldTrans;
	/// Free for the user.
	void* m_userPointer;

	BT_DECLARE_ALIGNED_ALLOCATOR();

	/// startTrans is the graphics transform; centerOfMassOffset as described above.
	btDefaultMotionState(const btTransform& startTrans = btTransform::getIdentity(),
	                     const btTransform& centerOfMassOffset = btTransform::getIdentity())
	    : m_graphicsWorldTrans(startTrans),
	      m_centerOfMassOffset(centerOfMassOffset),
	      m_startWorldTrans(startTrans),
	      m_userPointer(0)
	{
	}

	/// The centre-of-mass transform: graphics * offset^-1.
	void getWorldTransform(btTransform & centerOfMassWorldTrans) const override
	{
		centerOfMassWorldTrans = m_graphicsWorldTrans * m_centerOfMassOffset.inverse();
	}

	/// Stores graphics = centerOfMassWorldTrans * offset.
	void setWorldTransform(const btTransform& centerOfMassWorldTrans) override
	{
		m_graphicsWorldTrans = centerOfMassWorldTrans * m_centerOfMassOffset;
	}
};

#endif  // BT_DEFAULT_MOTION_STATE_H
