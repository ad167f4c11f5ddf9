// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
//
// Internal to the importer libraries (not installed): checks of converted blocks shared by the rigid and
// the soft importer. Converted blocks have the reader's own layouts, described by the reader's DNA.
#ifndef CALIBER_IMPORTER_DNA_CHECKS_H
#define CALIBER_IMPORTER_DNA_CHECKS_H

#include "../../BulletFileLoader/bDNA.h"
#include "../../BulletFileLoader/bFile.h"
#include "LinearMath/btSerializer.h"
#include "LinearMath/btTransform.h"

#include <math.h>
#include <string.h>

namespace caliber
{
namespace importer
{
/// The reader's DNA (built once for the process): it names the struct of every converted block.
inline bParse::bDNA& memoryDna()
{
	static bParse::bDNA* dna = []
	{
		bParse::bDNA* parsed = new bParse::bDNA();  // built once, kept for the process
		parsed->init(const_cast<char*>(btDefaultSerializer::getMemoryDna()),
		             btDefaultSerializer::getMemoryDnaSizeInBytes(), false);
		return parsed;
	}();
	return *dna;
}

/// The chunk header the loader kept for each converted block (a protected member of bFile, reached
/// through a pointer to member: no Caliber member is added to Bullet's class).
inline const btHashMap<btHashPtr, bParse::bChunkInd>& blockInfo(const bParse::bFile& file)
{
	struct Access : bParse::bFile
	{
		static const btHashMap<btHashPtr, bParse::bChunkInd>& blocks(const bParse::bFile& f)
		{
			return f.*(&Access::m_chunkPtrPtrMap);
		}
	};
	return Access::blocks(file);
}

/// Every component of a vector struct (float or double) is finite.
template <class V>
bool finite(const V& v)
{
	for (int i = 0; i < 3; ++i)
		if (!isfinite(v.m_floats[i])) return false;
	return true;
}
template <class T>
bool finiteTransform(const T& t)
{
	return finite(t.m_origin) && finite(t.m_basis.m_el[0]) && finite(t.m_basis.m_el[1]) && finite(t.m_basis.m_el[2]);
}

/// The numbers of a block of the reader's struct memoryStruct (nested structs included): no NaN anywhere;
/// and finite where mustBeFinite, in transforms, frames, pivots, axes and gravity.
inline bool numbersSane(int memoryStruct, const char* p, bool mustBeFinite, int depth = 0)
{
	bParse::bDNA& dna = memoryDna();
	short* st = dna.getStruct(memoryStruct);
	if (!st || depth > 8) return false;
	int offset = 0;
	for (int f = 0; f < st[1]; ++f)
	{
		const short type = st[2 + 2 * f], name = st[3 + 2 * f];
		const char* fieldName = dna.getName(name);
		const int size = dna.getElementSize(type, name);
		const int count = dna.getArraySizeNew(name);
		if (fieldName[0] != '*' && count > 0)
		{
			const char* typeName = dna.getType(type);
			const int element = size / count;
			const bool strict = mustBeFinite || strstr(fieldName, "Frame") || strstr(fieldName, "Transform") ||
			                    strstr(fieldName, "m_pivotIn") || strstr(fieldName, "m_axisIn") ||
			                    strstr(fieldName, "m_gravity");
			const int sub = dna.getReverseType(typeName);
			for (int i = 0; i < count; ++i)
			{
				const char* q = p + offset + i * element;
				double v = 0;
				if (!strcmp(typeName, "btTransformFloatData") || !strcmp(typeName, "btTransformDoubleData"))
				{
					// Frames and transforms must be rotations, not just numbers.
					bool rotation;
					if (typeName[11] == 'F')
					{
						btTransformFloatData t;
						memcpy(&t, q, sizeof(t));
						rotation = finiteTransform(t);
					}
					else
					{
						btTransformDoubleData t;
						memcpy(&t, q, sizeof(t));
						rotation = finiteTransform(t);
					}
					if (!rotation) return false;
					continue;
				}
				if (sub >= 0)
				{
					if (!numbersSane(sub, q, strict, depth + 1)) return false;
					continue;
				}
				if (!strcmp(typeName, "float"))
				{
					float x;
					memcpy(&x, q, 4);
					v = x;
				}
				else if (!strcmp(typeName, "double"))
					memcpy(&v, q, 8);
				else
					continue;
				if (v != v || (strict && !isfinite(v))) return false;
			}
		}
		offset += size;
	}
	return true;
}

}  // namespace importer
}  // namespace caliber

#endif
