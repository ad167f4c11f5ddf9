// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// The wide sweeps, written once for every lane count: btWideContactRows.cpp includes this file in one
// namespace per lane count, after defining there kLanes, Lanes and Mask with their operations (load,
// store, zero, +, -, *, negate, minBranchless, maxBranchless, frictionSkipped, allSet, select,
// horizontalSum) and gatherVectors/scatterVectors. No include guard: it is meant to be included more
// than once.

typedef caliber::WideRowBlockT<kLanes> Block;
typedef caliber::WideGroupT<kLanes> Group;

// The velocity changes of a group's bodies, one lane per manifold. The fourth scalar of each btVector3
// waits in memory (kept in registers, it would push the row data out of them) and is stored back as it was.
struct BodyLanes
{
	Lanes linear[3];
	Lanes angular[3];
};
struct BodyFourths
{
	btScalar linear[kLanes];
	btScalar angular[kLanes];
};

// Lanes that share a body (the fixed entry, or padding on it) store the same values, so the order of
// the stores does not matter.
SIMD_FORCE_INLINE void gatherBodies(const btSolverBody* bodies, const int* index, BodyLanes& lanes, BodyFourths& w)
{
	gatherVectors(bodies, index, offsetof(btSolverBody, m_deltaLinearVelocity), lanes.linear, w.linear);
	gatherVectors(bodies, index, offsetof(btSolverBody, m_deltaAngularVelocity), lanes.angular, w.angular);
}
SIMD_FORCE_INLINE void scatterBodies(btSolverBody* bodies, const int* index, const BodyLanes& lanes,
                                     const BodyFourths& w)
{
	scatterVectors(bodies, index, offsetof(btSolverBody, m_deltaLinearVelocity), lanes.linear, w.linear);
	scatterVectors(bodies, index, offsetof(btSolverBody, m_deltaAngularVelocity), lanes.angular, w.angular);
}

// A group's two bodies per lane, loaded for a pass over its blocks and stored back after it.
struct GroupBodies
{
	BodyLanes a;
	BodyLanes b;
	ATTRIBUTE_ALIGNED16(BodyFourths fourthsA);
	ATTRIBUTE_ALIGNED16(BodyFourths fourthsB);

	GroupBodies(const btSolverBody* bodies, const Group& group)
	{
		gatherBodies(bodies, group.bodyA, a, fourthsA);
		gatherBodies(bodies, group.bodyB, b, fourthsB);
	}
	void storeTo(btSolverBody* bodies, const Group& group) const
	{
		scatterBodies(bodies, group.bodyA, a, fourthsA);
		scatterBodies(bodies, group.bodyB, b, fourthsB);
	}
};

// rowDeltaVelocity of btSolverRowKernels.h, lane by lane, with its association.
SIMD_FORCE_INLINE Lanes deltaVelocity(const Block& block, const BodyLanes& a, const BodyLanes& b)
{
	Lanes sum[3];
	for (int c = 0; c < 3; ++c)
		sum[c] = ((load(block.normal1[c]) * a.linear[c] + load(block.relpos1CrossNormal[c]) * a.angular[c]) +
		          negate(load(block.normal1[c])) * b.linear[c]) +
		         load(block.relpos2CrossNormal[c]) * b.angular[c];
	return (sum[0] + sum[1]) + sum[2];
}

// btSolverBody::applyImpulse on both bodies of every lane.
SIMD_FORCE_INLINE void applyImpulses(const Block& block, const Group& group, Lanes deltaImpulse,
                                     BodyLanes& a, BodyLanes& b)
{
	for (int c = 0; c < 3; ++c)
	{
		a.linear[c] = a.linear[c] + (load(block.normal1[c]) * load(group.invMassA[c])) * deltaImpulse;
		a.angular[c] = a.angular[c] + load(block.angularA[c]) * (deltaImpulse * load(group.angularFactorA[c]));
		b.linear[c] = b.linear[c] + (negate(load(block.normal1[c])) * load(group.invMassB[c])) * deltaImpulse;
		b.angular[c] = b.angular[c] + load(block.angularB[c]) * (deltaImpulse * load(group.angularFactorB[c]));
	}
}

// resolveRow of btSolverRowKernels.h, lane by lane; returns the squared impulse changes.
SIMD_FORCE_INLINE Lanes resolveBlock(Block& block, const Group& group, Lanes lower, Lanes upper,
                                     BodyLanes& a, BodyLanes& b)
{
	const Lanes applied = load(block.applied);
	Lanes deltaImpulse =
	    (load(block.rhs) - applied * load(block.cfm)) - deltaVelocity(block, a, b) * load(block.jacDiagABInv);
	const Lanes clamped = maxBranchless(lower, minBranchless(upper, applied + deltaImpulse));
	deltaImpulse = clamped - applied;
	store(block.applied, clamped);
	applyImpulses(block, group, deltaImpulse, a, b);
	return deltaImpulse * deltaImpulse;
}

SIMD_FORCE_INLINE void storeImpulses(const Block& block, btConstraintArray& rows)
{
	for (int k = 0; k < kLanes; ++k)
		if (block.row[k] >= 0) rows[block.row[k]].m_appliedImpulse = block.applied[k];
}

btScalar sweepNormal(caliber::WideLayout<kLanes>& layout, int firstGroup, int endGroup, bool reverse,
                     btSolverBody* bodies, btConstraintArray* contacts)
{
	Lanes residual = zero();
	for (int i = firstGroup; i < endGroup; ++i)
	{
		const Group& group = layout.groups[reverse ? firstGroup + endGroup - 1 - i : i];
		GroupBodies lanes(bodies, group);
		BodyLanes& a = lanes.a;
		BodyLanes& b = lanes.b;
		for (int s = 0; s < group.numBlocks; ++s)
		{
			Block& block = layout.normalBlocks[group.firstBlock + (reverse ? group.numBlocks - 1 - s : s)];
			residual = residual + resolveBlock(block, group, load(block.lower), load(block.upper), a, b);
			if (contacts) storeImpulses(block, *contacts);
		}
		lanes.storeTo(bodies, group);
	}
	return horizontalSum(residual);
}

btScalar sweepFriction(caliber::WideLayout<kLanes>& layout, int firstGroup, int endGroup, bool reverse,
                       int frictionRowsPerContact, btSolverBody* bodies, btConstraintArray* friction)
{
	Lanes residual = zero();
	for (int i = firstGroup; i < endGroup; ++i)
	{
		const Group& group = layout.groups[reverse ? firstGroup + endGroup - 1 - i : i];
		GroupBodies lanes(bodies, group);
		BodyLanes& a = lanes.a;
		BodyLanes& b = lanes.b;
		for (int s = 0; s < group.numBlocks; ++s)
		{
			const int normalIndex = group.firstBlock + (reverse ? group.numBlocks - 1 - s : s);
			const Lanes normalImpulse = load(layout.normalBlocks[normalIndex].applied);
			for (int f = 0; f < frictionRowsPerContact; ++f)
			{
				Block& block = layout.frictionBlocks[normalIndex * frictionRowsPerContact + f];
				// solveFrictionRow: a row without normal impulse and without an impulse of its own is skipped.
				const Mask skipped = frictionSkipped(normalImpulse, load(block.applied));
				if (allSet(skipped)) continue;
				const Lanes bound = load(block.friction) * maxBranchless(zero(), normalImpulse);
				// resolveBlock with the skipped lanes' impulse change forced to zero: their bodies then gain
				// products with zero, which leave a sum unchanged (a velocity change, which starts at +0 and
				// only ever has numbers added to it, is never -0), and their impulse is put back.
				const Lanes applied = load(block.applied);
				Lanes deltaImpulse =
				    (load(block.rhs) - applied * load(block.cfm)) - deltaVelocity(block, a, b) * load(block.jacDiagABInv);
				const Lanes clamped = select(
				    skipped, applied, maxBranchless(negate(bound), minBranchless(bound, applied + deltaImpulse)));
				deltaImpulse = clamped - applied;
				store(block.applied, clamped);
				applyImpulses(block, group, deltaImpulse, a, b);
				const Lanes squared = deltaImpulse * deltaImpulse;
				residual = residual + squared;
				if (friction) storeImpulses(block, *friction);
			}
		}
		lanes.storeTo(bodies, group);
	}
	return horizontalSum(residual);
}

// Every block's impulses of groups [firstGroup, endGroup) into their rows.
void storeAllImpulses(caliber::WideLayout<kLanes>& layout, int firstGroup, int endGroup, int frictionRowsPerContact,
                      btConstraintArray& contacts, btConstraintArray& friction)
{
	for (int i = firstGroup; i < endGroup; ++i)
	{
		const Group& group = layout.groups[i];
		for (int s = 0; s < group.numBlocks; ++s)
		{
			storeImpulses(layout.normalBlocks[group.firstBlock + s], contacts);
			for (int f = 0; f < frictionRowsPerContact; ++f)
				storeImpulses(layout.frictionBlocks[(group.firstBlock + s) * frictionRowsPerContact + f], friction);
		}
	}
}
