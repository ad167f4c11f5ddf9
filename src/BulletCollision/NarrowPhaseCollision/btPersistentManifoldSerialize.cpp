// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
//
// btPersistentManifold in .bullet files (btPersistentManifoldFloatData / DoubleData, written with
// BT_SERIALIZE_CONTACT_MANIFOLDS): every point of the cache, field by field, the thresholds and the ids
// of the two objects. Reading fills the points and thresholds; the caller resolves the objects.
#include "BulletCollision/CollisionDispatch/btCollisionObject.h"
#include "BulletCollision/NarrowPhaseCollision/btPersistentManifold.h"
#include "LinearMath/btSerializer.h"
#include "LinearMath/btWarningHook.h"

#include <string.h>

#include <string>

namespace
{
// Only the build's precision is written; the other overload stays unused.
inline void writeVector(const btVector3& v, btVector3FloatData& out) { v.serializeFloat(out); }
inline void writeVector(const btVector3& v, btVector3DoubleData& out) { v.serializeDouble(out); }
void readVector(btVector3& v, const btVector3FloatData& in) { v.deSerializeFloat(in); }
void readVector(btVector3& v, const btVector3DoubleData& in) { v.deSerializeDouble(in); }

// One list of the point fields, used for writing, reading and checking alike.
template <class Data, class Op>
void forEachPointField(Data& d, btManifoldPoint& p, int i, Op op)
{
	op.vec(p.m_localPointA, d.m_pointCacheLocalPointA[i]);
	op.vec(p.m_localPointB, d.m_pointCacheLocalPointB[i]);
	op.vec(p.m_positionWorldOnA, d.m_pointCachePositionWorldOnA[i]);
	op.vec(p.m_positionWorldOnB, d.m_pointCachePositionWorldOnB[i]);
	op.vec(p.m_normalWorldOnB, d.m_pointCacheNormalWorldOnB[i]);
	op.vec(p.m_lateralFrictionDir1, d.m_pointCacheLateralFrictionDir1[i]);
	op.vec(p.m_lateralFrictionDir2, d.m_pointCacheLateralFrictionDir2[i]);
	op.num(p.m_distance1, d.m_pointCacheDistance[i]);
	op.num(p.m_appliedImpulse, d.m_pointCacheAppliedImpulse[i]);
	op.num(p.m_prevRHS, d.m_pointCachePrevRHS[i]);
	op.num(p.m_combinedFriction, d.m_pointCacheCombinedFriction[i]);
	op.num(p.m_combinedRollingFriction, d.m_pointCacheCombinedRollingFriction[i]);
	op.num(p.m_combinedSpinningFriction, d.m_pointCacheCombinedSpinningFriction[i]);
	op.num(p.m_combinedRestitution, d.m_pointCacheCombinedRestitution[i]);
	op.integer(p.m_partId0, d.m_pointCachePartId0[i]);
	op.integer(p.m_partId1, d.m_pointCachePartId1[i]);
	op.integer(p.m_index0, d.m_pointCacheIndex0[i]);
	op.integer(p.m_index1, d.m_pointCacheIndex1[i]);
	op.integer(p.m_contactPointFlags, d.m_pointCacheContactPointFlags[i]);
	op.num(p.m_appliedImpulseLateral1, d.m_pointCacheAppliedImpulseLateral1[i]);
	op.num(p.m_appliedImpulseLateral2, d.m_pointCacheAppliedImpulseLateral2[i]);
	op.num(p.m_contactMotion1, d.m_pointCacheContactMotion1[i]);
	op.num(p.m_contactMotion2, d.m_pointCacheContactMotion2[i]);
	op.num(p.m_contactCFM, d.m_pointCacheContactCFM[i]);
	op.num(p.m_combinedContactStiffness1, d.m_pointCacheCombinedContactStiffness1[i]);
	op.num(p.m_contactERP, d.m_pointCacheContactERP[i]);
	op.num(p.m_combinedContactDamping1, d.m_pointCacheCombinedContactDamping1[i]);
	op.num(p.m_frictionCFM, d.m_pointCacheFrictionCFM[i]);
	op.integer(p.m_lifeTime, d.m_pointCacheLifeTime[i]);
}

struct Write
{
	template <class V>
	void vec(const btVector3& v, V& out) const
	{
		writeVector(v, out);
	}
	template <class S>
	void num(btScalar v, S& out) const
	{
		out = S(v);
	}
	void integer(int v, int& out) const { out = v; }
};

struct Read
{
	template <class V>
	void vec(btVector3& v, const V& in) const
	{
		readVector(v, in);
	}
	template <class S>
	void num(btScalar& v, const S& in) const
	{
		v = btScalar(in);
	}
	void integer(int& v, int in) const { v = in; }
};

struct CheckFinite
{
	bool* ok;
	template <class V>
	void vec(btVector3&, const V& in) const
	{
		// Judged as read: a double too large for a float build is not finite there either.
		btVector3 v;
		readVector(v, in);
		*ok = *ok && caliber::isFinite(v);
	}
	template <class S>
	void num(btScalar&, const S& in) const
	{
		*ok = *ok && btIsFinite(btScalar(in));
	}
	void integer(int&, int) const {}
};

// Checks everything before changing the manifold, so bad data leaves it empty rather than half read.
template <class Data>
void readManifold(btPersistentManifold& m, const Data* d)
{
	m.clearManifold();
	const char* problem = 0;
	if (!d)
		problem = "no data";
	else if (d->m_numCachedPoints < 0 || d->m_numCachedPoints > MANIFOLD_CACHE_SIZE)
		problem = "a point count outside [0, 4]";
	else if (!btIsFinite(btScalar(d->m_contactBreakingThreshold)) ||
	         !btIsFinite(btScalar(d->m_contactProcessingThreshold)))
		problem = "a non-finite threshold";
	for (int i = 0; !problem && i < d->m_numCachedPoints; ++i)
	{
		bool ok = true;
		btManifoldPoint scratch;
		forEachPointField(*const_cast<Data*>(d), scratch, i, CheckFinite{&ok});
		if (!ok) problem = "a non-finite number in a point";
	}
	if (problem)
	{
		btReportWarning((std::string("Caliber: btPersistentManifold::deSerialize: ") + problem +
		                 "; the manifold is left without points\n")
		                    .c_str());
		return;
	}
	m.setContactBreakingThreshold(btScalar(d->m_contactBreakingThreshold));
	m.setContactProcessingThreshold(btScalar(d->m_contactProcessingThreshold));
	m.m_companionIdA = d->m_companionIdA;
	m.m_companionIdB = d->m_companionIdB;
	m.m_index1a = d->m_index1a;
	m.setNumContacts(d->m_numCachedPoints);
	for (int i = 0; i < d->m_numCachedPoints; ++i)
	{
		btManifoldPoint& p = m.getContactPoint(i);
		p = btManifoldPoint();
		forEachPointField(*const_cast<Data*>(d), p, i, Read());
	}
}
}  // namespace

int btPersistentManifold::calculateSerializeBufferSize() const { return int(sizeof(btPersistentManifoldData)); }

const char* btPersistentManifold::serialize(const btPersistentManifold* manifold, void* dataBuffer,
                                            btSerializer* serializer) const
{
	btPersistentManifoldData* d = static_cast<btPersistentManifoldData*>(dataBuffer);
	memset(d, 0, sizeof(*d));
	if (!manifold) manifold = this;
	d->m_body0 = static_cast<btCollisionObjectData*>(
	    serializer->getUniquePointer(const_cast<btCollisionObject*>(manifold->getBody0())));
	d->m_body1 = static_cast<btCollisionObjectData*>(
	    serializer->getUniquePointer(const_cast<btCollisionObject*>(manifold->getBody1())));
	d->m_contactBreakingThreshold = manifold->getContactBreakingThreshold();
	d->m_contactProcessingThreshold = manifold->getContactProcessingThreshold();
	d->m_numCachedPoints = manifold->getNumContacts();
	d->m_companionIdA = manifold->m_companionIdA;
	d->m_companionIdB = manifold->m_companionIdB;
	d->m_index1a = manifold->m_index1a;
	d->m_objectType = manifold->getObjectType();
	for (int i = 0; i < manifold->getNumContacts(); ++i)
	{
		btManifoldPoint p = manifold->getContactPoint(i);
		forEachPointField(*d, p, i, Write());
	}
	return btPersistentManifoldDataName;
}

void btPersistentManifold::deSerialize(const btPersistentManifoldDoubleData* manifoldDataPtr)
{
	readManifold(*this, manifoldDataPtr);
}

void btPersistentManifold::deSerialize(const btPersistentManifoldFloatData* manifoldDataPtr)
{
	readManifold(*this, manifoldDataPtr);
}
