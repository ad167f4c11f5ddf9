// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
//
// btTriangleInfoMap in .bullet files (btTriangleInfoMapData): the hash table, links and keys as int
// arrays, the values as btTriangleInfoData, the tolerances. Reading inserts the entries anew: the stored
// hash table belongs to the writer's hash function (Bullet's differs from Caliber's) and a file is not
// trusted to link its entries within bounds.
#include "BulletCollision/CollisionShapes/btTriangleInfoMap.h"
#include "LinearMath/btSerializer.h"
#include "LinearMath/btWarningHook.h"

#include <string>

namespace
{
// Writes count ints as a plain "int" array chunk identified by id; the id written (0 for none).
int* writeInts(btSerializer* serializer, const int* values, int count, void* id)
{
	if (count <= 0) return 0;
	btChunk* chunk = serializer->allocate(sizeof(int), count);
	if (!chunk) return 0;
	int* out = static_cast<int*>(chunk->m_oldPtr);
	for (int i = 0; i < count; ++i) out[i] = values[i];
	serializer->finalizeChunk(chunk, "int", BT_ARRAY_CODE, id);
	return static_cast<int*>(serializer->getUniquePointer(id));
}
}  // namespace

int btTriangleInfoMap::calculateSerializeBufferSize() const { return int(sizeof(btTriangleInfoMapData)); }

const char* btTriangleInfoMap::serialize(void* dataBuffer, btSerializer* serializer) const
{
	btTriangleInfoMapData* d = static_cast<btTriangleInfoMapData*>(dataBuffer);
	d->m_convexEpsilon = float(m_convexEpsilon);
	d->m_planarEpsilon = float(m_planarEpsilon);
	d->m_equalVertexThreshold = float(m_equalVertexThreshold);
	d->m_edgeDistanceThreshold = float(m_edgeDistanceThreshold);
	d->m_zeroAreaThreshold = float(m_zeroAreaThreshold);
	d->m_hashTableSize = m_hashTable.size();
	d->m_nextSize = m_next.size();
	d->m_numValues = m_valueArray.size();
	d->m_numKeys = m_keyArray.size();
	for (char& c : d->m_padding) c = 0;

	d->m_hashTablePtr = d->m_hashTableSize ? writeInts(serializer, &m_hashTable[0], d->m_hashTableSize,
	                                                   const_cast<int*>(&m_hashTable[0]))
	                                       : 0;
	d->m_nextPtr = d->m_nextSize ? writeInts(serializer, &m_next[0], d->m_nextSize, const_cast<int*>(&m_next[0])) : 0;
	d->m_keyArrayPtr = 0;
	if (d->m_numKeys)
	{
		btAlignedObjectArray<int> keys;
		keys.resize(d->m_numKeys);
		for (int i = 0; i < d->m_numKeys; ++i) keys[i] = m_keyArray[i].getUid1();
		d->m_keyArrayPtr = writeInts(serializer, &keys[0], d->m_numKeys, const_cast<btHashInt*>(&m_keyArray[0]));
	}
	d->m_valueArrayPtr = 0;
	if (d->m_numValues)
	{
		void* id = const_cast<btTriangleInfo*>(&m_valueArray[0]);
		btChunk* chunk = serializer->allocate(sizeof(btTriangleInfoData), d->m_numValues);
		if (chunk)
		{
			btTriangleInfoData* out = static_cast<btTriangleInfoData*>(chunk->m_oldPtr);
			for (int i = 0; i < d->m_numValues; ++i)
			{
				const btTriangleInfo& in = m_valueArray[i];
				out[i].m_flags = in.m_flags;
				out[i].m_edgeV0V1Angle = float(in.m_edgeV0V1Angle);
				out[i].m_edgeV1V2Angle = float(in.m_edgeV1V2Angle);
				out[i].m_edgeV2V0Angle = float(in.m_edgeV2V0Angle);
			}
			serializer->finalizeChunk(chunk, "btTriangleInfoData", BT_ARRAY_CODE, id);
			d->m_valueArrayPtr = static_cast<btTriangleInfoData*>(serializer->getUniquePointer(id));
		}
	}
	return "btTriangleInfoMapData";
}

void btTriangleInfoMap::deSerialize(btTriangleInfoMapData& data)
{
	clear();
	const char* problem = 0;
	if (data.m_numKeys < 0 || data.m_numValues != data.m_numKeys)
		problem = "the key and value counts disagree";
	else if (data.m_numKeys > 0 && (!data.m_keyArrayPtr || !data.m_valueArrayPtr))
		problem = "the key or value array is missing";
	else if (!btIsFinite(data.m_convexEpsilon) || !btIsFinite(data.m_planarEpsilon) ||
	         !btIsFinite(data.m_equalVertexThreshold) || !btIsFinite(data.m_edgeDistanceThreshold) ||
	         !btIsFinite(data.m_zeroAreaThreshold))
		problem = "a non-finite tolerance";
	for (int i = 0; !problem && i < data.m_numValues; ++i)
	{
		const btTriangleInfoData& v = data.m_valueArrayPtr[i];
		if (!btIsFinite(v.m_edgeV0V1Angle) || !btIsFinite(v.m_edgeV1V2Angle) || !btIsFinite(v.m_edgeV2V0Angle))
			problem = "a non-finite edge angle";
	}
	if (problem)
	{
		btReportWarning(
		    (std::string("Caliber: btTriangleInfoMap::deSerialize: ") + problem + "; the map is left empty\n").c_str());
		return;
	}
	m_convexEpsilon = data.m_convexEpsilon;
	m_planarEpsilon = data.m_planarEpsilon;
	m_equalVertexThreshold = data.m_equalVertexThreshold;
	m_edgeDistanceThreshold = data.m_edgeDistanceThreshold;
	m_zeroAreaThreshold = data.m_zeroAreaThreshold;
	for (int i = 0; i < data.m_numKeys; ++i)
	{
		btTriangleInfo info;
		info.m_flags = data.m_valueArrayPtr[i].m_flags;
		info.m_edgeV0V1Angle = data.m_valueArrayPtr[i].m_edgeV0V1Angle;
		info.m_edgeV1V2Angle = data.m_valueArrayPtr[i].m_edgeV1V2Angle;
		info.m_edgeV2V0Angle = data.m_valueArrayPtr[i].m_edgeV2V0Angle;
		insert(btHashInt(data.m_keyArrayPtr[i]), info);
	}
}
